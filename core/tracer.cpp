#include "core/tracer.h"

#include <cmath>
#include <limits>

#include "core/optics.h"

namespace refract {

SceneTracer::SceneTracer(const Scene& scene) : scene_(scene) {
    // POV-Ray mode: the order of the exported scene (validation/pov_export.cpp writes the
    // opaque objects first, then the transparent ones), which is the order in which POV-Ray
    // tests them; this decides exact ties, e.g. a gem's facet lying in the floor plane,
    // where POV-Ray shades the floor.
    const bool pov = scene.settings.compat == Compat::PovRay;
    for (int pass = pov ? 0 : 1; pass < 2; ++pass)
        for (const Object& obj : scene.objects)
            if (!pov || (scene.materials[obj.material].kind == MaterialKind::Dielectric) == (pass == 1))
                order_.push_back(&obj);
}

std::optional<SurfaceHit> SceneTracer::intersect(const Ray& ray, RenderStats& stats) const {
    ++stats.segments;
    std::optional<SurfaceHit> best;
    // POV-Ray keeps hits with kPovMinDepth <= t < kPovMaxDistance (every ray, primary too).
    const bool pov = scene_.settings.compat == Compat::PovRay;
    const double t_min = pov ? kPovMinDepth : kEpsilon;
    double t_max = pov ? kPovMaxDistance : std::numeric_limits<double>::infinity();
    for (const Object* o : order_) {
        const Object& obj = *o;
        const auto hit = std::visit([&](const auto& s) { return refract::intersect(s, ray, t_min, t_max); }, obj.shape);
        if (!hit) continue;
        t_max = hit->t;
        best = SurfaceHit{*hit, &obj, &scene_.materials[obj.material], hit->normal, true};
    }
    if (best) {
        best->entering = best->hit.normal.dot(ray.dir) < 0;
        best->normal = best->entering ? best->hit.normal : Vec3(-best->hit.normal);
    }
    return best;
}

Vec3 SceneTracer::background(const Vec3& dir) const {
    const Background& b = scene_.background;
    if (b.kind == Background::Kind::Solid) return b.color;
    const double a = 0.5 * (dir.normalized().y() + 1.0);  // RTIOW ray_color sky
    return (1.0 - a) * b.bottom + a * b.top;
}

Vec3 SceneTracer::pigment(const Material& m, const Vec3& p) const {
    if (!m.checker) return m.color;
    // 3D checker (POV-Ray `checker`): parity of the sum of the cell indices. A small
    // offset keeps a surface lying on a cell boundary (a floor at y = 0) on one side.
    const double s = m.checker->size;
    long long k;
    if (scene_.settings.compat == Compat::PovRay) {
        // POV-Ray `checker ... scale s` (pattern.cpp checker_pattern): the point is taken
        // to pattern space by the inverse transform, a product with 1/s, then floor(v + 1e-10).
        const Vec3 q = p * (1.0 / s);
        k = static_cast<long long>(std::floor(q.x() + 1e-10)) + static_cast<long long>(std::floor(q.y() + 1e-10)) +
            static_cast<long long>(std::floor(q.z() + 1e-10));
    } else {
        const double e = 1e-9;
        k = static_cast<long long>(std::floor(p.x() / s + e)) + static_cast<long long>(std::floor(p.y() / s + e)) +
            static_cast<long long>(std::floor(p.z() / s + e));
    }
    return (k & 1) ? m.checker->color2 : m.color;
}

Vec3 SceneTracer::light_transmittance(const Vec3& from, const Vec3& to, RenderStats& stats) const {
    // Shadow ray. Opaque objects block. Dielectrics: in physical mode light does not go
    // straight through a refracting surface (that light arrives as a caustic, which only
    // a light pass computes), so they block; in POV-Ray mode the ray goes straight on and
    // each crossing multiplies by the filter colour (clear glass casts no shadow).
    // Emissive highlight spheres never cast shadows (POV-Ray looks_like).
    ++stats.shadow_rays;
    if (scene_.settings.compat == Compat::PovRay) return light_transmittance_pov(from, to);
    const Vec3 delta = to - from;
    const double dist = delta.norm();
    const Ray ray{from, delta / dist};
    for (const Object& obj : scene_.objects) {
        const Material& m = scene_.materials[obj.material];
        if (m.kind == MaterialKind::Emissive) continue;
        const auto hit = std::visit([&](const auto& s) { return refract::intersect(s, ray, kEpsilon, dist); }, obj.shape);
        if (hit) return Vec3(0, 0, 0);
    }
    return Vec3(1, 1, 1);
}

Vec3 SceneTracer::light_transmittance_pov(const Vec3& from, const Vec3& to) const {
    // POV-Ray 3.7 point-light shadow ray (trace.cpp TracePointLightShadowRay): a straight
    // ray; the nearest hit farther than kPovShadowTolerance from the current origin and
    // nearer than kPovShadowTolerance to the light is taken; an opaque object blocks, a
    // transparent one multiplies by its filter colour and the search goes on from that
    // hit. no_shadow objects (the emissive highlight spheres) are not seen.
    Vec3 origin = from;
    double remaining = (to - from).norm();
    const Vec3 dir = (to - from) / remaining;
    Vec3 t(1, 1, 1);
    while (true) {
        const Ray ray{origin, dir};
        std::optional<Hit> best;
        const Material* best_m = nullptr;
        double t_max = remaining;
        for (const Object* o : order_) {
            const Object& obj = *o;
            const Material& m = scene_.materials[obj.material];
            if (m.kind == MaterialKind::Emissive) continue;
            const auto hit = std::visit(
                [&](const auto& s) { return refract::intersect(s, ray, kPovShadowTolerance, t_max); }, obj.shape);
            if (!hit) continue;
            t_max = hit->t;
            best = hit;
            best_m = &m;
        }
        if (!best || best->t >= remaining - kPovShadowTolerance) return t;
        if (best_m->kind != MaterialKind::Dielectric) return Vec3(0, 0, 0);
        t = t.cwiseProduct(best_m->filter);
        origin = best->point;
        remaining -= best->t;
    }
}

Vec3 SceneTracer::shade_diffuse(const SurfaceHit& h, const Material& m, RenderStats& stats) const {
    const Vec3 pig = pigment(m, h.hit.point);
    Vec3 c = m.ambient * pig;
    for (const PointLight& l : scene_.lights) {
        const Vec3 to_light = l.position - h.hit.point;
        const double cos_l = h.normal.dot(to_light.normalized());
        if (cos_l <= 0) continue;
        const Vec3 tr = light_transmittance(h.hit.point, l.position, stats);
        c += m.diffuse * cos_l * pig.cwiseProduct(l.color).cwiseProduct(tr);
    }
    return c;
}

double SceneTracer::reflectance(const Material& m, double cos_i, double eta) {
    switch (m.reflectance) {
        case ReflectanceModel::Constant: return m.constant_reflectivity;
        case ReflectanceModel::Fresnel: return optics::fresnel_reflectance(cos_i, eta);
        case ReflectanceModel::FresnelS: {
            const auto f = optics::fresnel(cos_i, eta);
            return f ? f->Rs : 1.0;
        }
        case ReflectanceModel::FresnelP: {
            const auto f = optics::fresnel(cos_i, eta);
            return f ? f->Rp : 1.0;
        }
        case ReflectanceModel::Schlick:
            return optics::cos_transmitted(cos_i, eta) ? optics::schlick(cos_i, eta) : 1.0;
    }
    return 1.0;
}

Node SceneTracer::node(const SurfaceHit& h, const Ray& ray, RenderStats& stats, double band_ior, bool split) const {
    const Material& m = *h.material;
    const bool pov = scene_.settings.compat == Compat::PovRay;
    Node n;
    switch (m.kind) {
        case MaterialKind::Diffuse:
        case MaterialKind::Lambertian:  // tree integrators light RTIOW's Lambertian directly
            n.local = shade_diffuse(h, m, stats);
            return n;
        case MaterialKind::Emissive:
            n.local = m.color;
            return n;
        case MaterialKind::Mirror:
        case MaterialKind::Metal:  // fuzz needs sampling: the tree takes the mirror direction
            n.branch[0] = Branch{Ray{h.hit.point, optics::reflect(ray.dir, h.normal).normalized()}, m.color,
                                 m.color.maxCoeff()};
            n.branches = 1;
            n.reflectance = m.color.maxCoeff();
            return n;
        case MaterialKind::Dielectric: break;
    }
    ++stats.tree_nodes;
    // POV-Ray stores an interior's ior in single precision (frame.h, class Interior):
    // n = 1.333 refracts as 1.33299994..., which moves far-away hits by ~0.1 unit.
    const double nominal = pov ? static_cast<double>(static_cast<float>(m.ior)) : m.ior;
    const double ior = band_ior > 0 ? band_ior : nominal;
    const double eta = h.entering ? ior : 1.0 / ior;
    const double cos_i = std::fmin(-ray.dir.dot(h.normal), 1.0);
    const auto refr = optics::refract(ray.dir, h.normal, eta);
    if (pov) {
        n = dielectric_node_pov(h, ray, cos_i, h.entering ? nominal : 1.0 / nominal, refr, band_ior > 0, split);
        return n;
    }
    // Constant reflectivity (Whitted, Fig. 9) keeps its ks even where the direction
    // computation finds total internal reflection; then all light goes the mirror way.
    const double R = refr ? reflectance(m, cos_i, eta) : 1.0;
    n.reflectance = R;
    // Rays are unit length by convention: renormalise, or the rounding error of |dir|
    // grows about tenfold per bounce in a chain of internal reflections (the sphere
    // intersection assumes |dir| = 1, so the hit leaves the surface and the next normal
    // is off), and after ~10 bounces the path is wrong.
    const Ray reflected{h.hit.point, optics::reflect(ray.dir, h.normal).normalized()};
    n.branch[0] = Branch{reflected, Vec3::Constant(R), R};
    n.branches = 1;
    if (refr && R < 1.0) {
        const Vec3 factor = (1.0 - R) * m.filter;
        n.branch[1] = Branch{Ray{h.hit.point, refr->normalized()}, factor, factor.maxCoeff()};
        n.branches = 2;
    }
    return n;
}

Node SceneTracer::dielectric_node_pov(const SurfaceHit& h, const Ray& ray, double cos_i, double eta,
                                      const std::optional<Vec3>& refr, bool band, bool split) const {
    // POV-Ray 3.7 with `reflection { MIN, MAX fresnel on } conserve_energy` or
    // `reflection { ks } conserve_energy` and `pigment { rgbf <filter, 1> }`
    // (trace.cpp ComputeLightedTexture, ComputeReflectivity, ComputeRefraction):
    // - reflectivity R: the model's value; on total internal reflection Fresnel gives
    //   MAX = 1, a constant ks stays ks (dispersion: Fresnel with the nominal index, the
    //   TIR test with the band's);
    // - the surface's filter colour is filter·(1 − R), and a refracted ray is spawned only
    //   when its greyscale exceeds adc_bailout (a local test, not the cumulative weight);
    //   its adc weight is parent × max3(filter·(1 − R));
    // - if that refracted ray meets total internal reflection it becomes a mirror ray of
    //   colour factor 1 (unfiltered) with the refraction's adc weight, and replaces the
    //   reflection term;
    // - the reflected ray has colour factor R and adc weight parent × R; none when R = 0.
    // Dispersion (ComputeRefraction): an RGB ray splits into bands at its first refraction
    // whenever the refracted ray is spawned, even where the nominal index meets total
    // internal reflection (a constant ks); a band meeting total internal reflection there
    // (`split`) becomes a mirror ray filtered by filter·(1 − R) like the refraction (the
    // band loop discards the TIR flag), and the reflection term is kept; that mirror ray
    // is made from the incoming ray (TraceRefractionRay → ComputeReflection), so it is
    // not one band but a full ray that splits again at its next dispersive hit. A ray that is
    // already one band (`band`) follows the rule above with its own index.
    const Material& m = *h.material;
    const RenderSettings& s = scene_.settings;
    const double adc = s.pruning_threshold();
    double R = reflectance(m, cos_i, eta);
    // A band ray (dispersion) keeps the nominal index's R even where its own index meets
    // total internal reflection; the refracted ray then turns into the mirror ray below.
    if (!refr && !band && m.reflectance != ReflectanceModel::Constant) R = 1.0;
    const Vec3 filter = (1.0 - R) * m.filter;
    const double trans = std::fmin(1.0, std::abs(filter.dot(kPovGreyscale)));
    const Ray reflected{h.hit.point, optics::reflect(ray.dir, h.normal).normalized()};
    Node n;
    n.reflectance = R;
    if (trans > adc && !refr && split) {  // a band's total internal reflection at the split
        n.branch[0] = Branch{reflected, Vec3::Constant(R), R};
        n.branch[1] = Branch{reflected, filter, filter.cwiseAbs().maxCoeff()};
        n.branches = 2;
        n.split_mirror = true;
        return n;
    }
    if (trans > adc && !refr) {  // the refracted ray turns into total internal reflection
        n.branch[0] = Branch{reflected, Vec3(1, 1, 1), filter.cwiseAbs().maxCoeff()};
        n.branches = 1;
        n.reflectance = 1.0;
        return n;
    }
    n.branch[0] = Branch{reflected, Vec3::Constant(R), R};
    n.branches = 1;
    if (trans > adc) {
        n.branch[1] = Branch{Ray{h.hit.point, refr->normalized()}, filter, filter.cwiseAbs().maxCoeff()};
        n.branches = 2;
    }
    return n;
}

}  // namespace refract
