#include <refract/core/lighting.h>

#include <cmath>

namespace refract {

Vec3 Lighting::shade(const SurfaceHit& h, const Pigment& pigment, double diffuse, double ambient,
                     RenderStats& stats) const {
    const Vec3 pig = rules_.pigment(pigment, h.hit.point);
    Vec3 c = ambient * pig;
    // An area light: the sum of its grid's point lights, each shadowed as a point light;
    // in the POV-Ray mode as POV-Ray's area_illumination: the grid's mean shadow times the
    // sum of the points' unshadowed terms (the two agree where the shadow is uniform).
    const bool pov = scene_.settings.compat == Compat::PovRay;
    for (const Light& l : scene_.lights) {
        const Vec3 colour = l.sample_color();
        if (pov && l.samples() > 1) {
            Vec3 shadow(0, 0, 0);
            double cosines = 0;
            for (int k = 0; k < l.samples(); ++k) {
                const auto to = l.toward(h.hit.point, k);
                shadow += rules_.light_transmittance(search_, h.hit.point, to->end, stats);
                cosines += std::fmax(0.0, h.normal.dot(to->dir));
            }
            c += diffuse * cosines * pig.cwiseProduct(colour).cwiseProduct(shadow / static_cast<double>(l.samples()));
            continue;
        }
        for (int k = 0; k < l.samples(); ++k) {
            const auto to = l.toward(h.hit.point, k);
            if (!to) continue;
            const double cos_l = h.normal.dot(to->dir);
            if (cos_l <= 0) continue;
            const Vec3 tr = rules_.light_transmittance(search_, h.hit.point, to->end, stats);
            c += diffuse * cos_l * pig.cwiseProduct(colour).cwiseProduct(tr);
        }
    }
    return c;
}

Vec3 Lighting::leaf(const SurfaceHit& h, const LeafLight& l, RenderStats& stats) const {
    switch (l.kind) {
        case LeafLight::Kind::Lit: return shade(h, *l.pigment, l.diffuse, l.ambient, stats);
        case LeafLight::Kind::Emits: return l.emission;
        case LeafLight::Kind::None: break;
    }
    return Vec3(0, 0, 0);
}

}  // namespace refract
