#include "core/tracer.h"

#include <cmath>
#include <limits>

#include "core/optics.h"

namespace refract {

SceneTracer::SceneTracer(const Scene& scene) : scene_(scene) {}

std::optional<SurfaceHit> SceneTracer::intersect(const Ray& ray, RenderStats& stats) const {
    ++stats.segments;
    std::optional<SurfaceHit> best;
    double t_max = std::numeric_limits<double>::infinity();
    for (const Object& obj : scene_.objects) {
        const auto hit = std::visit([&](const auto& shape) { return refract::intersect(shape, ray, kEpsilon, t_max); },
                                    obj.shape);
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
    const double e = 1e-9;
    const long long k = static_cast<long long>(std::floor(p.x() / s + e)) +
                        static_cast<long long>(std::floor(p.y() / s + e)) +
                        static_cast<long long>(std::floor(p.z() / s + e));
    return (k & 1) ? m.checker->color2 : m.color;
}

Vec3 SceneTracer::light_transmittance(const Vec3& from, const Vec3& to, RenderStats& stats) const {
    // Shadow ray. Opaque objects block. Dielectrics: in physical mode light does not go
    // straight through a refracting surface (that light arrives as a caustic, which only
    // a light pass computes), so they block; in POV-Ray mode the ray goes straight on and
    // each crossing multiplies by the filter colour (clear glass casts no shadow).
    // Emissive highlight spheres never cast shadows (POV-Ray looks_like).
    ++stats.shadow_rays;
    const Vec3 delta = to - from;
    const double dist = delta.norm();
    const Ray ray{from, delta / dist};
    Vec3 t(1, 1, 1);
    for (const Object& obj : scene_.objects) {
        const Material& m = scene_.materials[obj.material];
        if (m.kind == MaterialKind::Emissive) continue;
        const bool pass = m.kind == MaterialKind::Dielectric && scene_.settings.compat == Compat::PovRay;
        double t_min = kEpsilon;
        while (true) {
            const auto hit = std::visit([&](const auto& s) { return refract::intersect(s, ray, t_min, dist); }, obj.shape);
            if (!hit) break;
            if (!pass) return Vec3(0, 0, 0);
            t = t.cwiseProduct(m.filter);
            t_min = hit->t;
        }
    }
    return t;
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

Node SceneTracer::node(const SurfaceHit& h, const Ray& ray, RenderStats& stats) const {
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
            n.branch[0] = Branch{Ray{h.hit.point, optics::reflect(ray.dir, h.normal)}, m.color, m.color.maxCoeff()};
            n.branches = 1;
            n.reflectance = m.color.maxCoeff();
            return n;
        case MaterialKind::Dielectric: break;
    }
    ++stats.tree_nodes;
    const double eta = h.entering ? m.ior : 1.0 / m.ior;
    const double cos_i = std::fmin(-ray.dir.dot(h.normal), 1.0);
    const auto refr = optics::refract(ray.dir, h.normal, eta);
    // Constant reflectivity (Whitted, Fig. 9) keeps its ks even where the direction
    // computation finds total internal reflection; then all light goes the mirror way.
    const double R = refr ? reflectance(m, cos_i, eta) : 1.0;
    n.reflectance = R;
    const Ray reflected{h.hit.point, optics::reflect(ray.dir, h.normal)};
    n.branch[0] = Branch{reflected, Vec3::Constant(R), R};
    n.branches = 1;
    if (refr && R < 1.0) {
        const Vec3 factor = (1.0 - R) * m.filter;
        // POV-Ray's adc weight for refraction is the filter alone, without (1 − R).
        const double bail = pov ? m.filter.cwiseAbs().maxCoeff() : factor.maxCoeff();
        n.branch[1] = Branch{Ray{h.hit.point, refr->normalized()}, factor, bail};
        n.branches = 2;
    }
    return n;
}

}  // namespace refract
