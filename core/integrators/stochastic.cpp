#include "core/integrators/stochastic.h"

#include "core/optics.h"

namespace refract {

Vec3 stochastic_radiance(const SceneTracer& tracer, const Ray& primary, Rng& rng, RenderStats& stats) {
    const RenderSettings& s = tracer.settings();
    Ray ray = primary;
    Vec3 throughput(1, 1, 1);
    Vec3 radiance(0, 0, 0);
    for (int depth = 0;; ++depth) {
        const auto hit = tracer.intersect(ray, stats);
        if (!hit) return radiance + throughput.cwiseProduct(tracer.background(ray.dir));
        const Material& m = *hit->material;
        if (depth + 1 > s.max_depth) {
            // The ray after the last bounce: its hit's own light counts (emissive, direct
            // light on a diffuse surface), as in the tree integrators; nothing scatters on.
            ++stats.depth_limited;
            if (m.kind != MaterialKind::Lambertian && m.kind != MaterialKind::Metal)
                radiance += throughput.cwiseProduct(tracer.node(*hit, ray, stats).local);
            return radiance;
        }
        const Vec3& p = hit->hit.point;
        Vec3 dir;
        if (m.kind == MaterialKind::Lambertian) {
            dir = hit->normal + rng.unit_vector();  // RTIOW lambertian scatter
            if (dir.squaredNorm() < 1e-16) dir = hit->normal;
            throughput = throughput.cwiseProduct(tracer.pigment(m, p));
        } else if (m.kind == MaterialKind::Metal) {
            dir = optics::reflect(ray.dir, hit->normal) + m.fuzz * rng.in_unit_sphere();
            if (dir.dot(hit->normal) <= 0) return radiance;  // absorbed
            throughput = throughput.cwiseProduct(m.color);
        } else {
            // Every other material is one tree node: sample one of its branches with
            // probability proportional to the reflectance (RTIOW), keeping leaves' light.
            const Node n = tracer.node(*hit, ray, stats);
            radiance += throughput.cwiseProduct(n.local);
            if (n.branches == 0) return radiance;
            if (m.kind == MaterialKind::Dielectric) {
                const bool refl = n.branches == 1 || rng.uniform() < n.reflectance;
                if (!refl) {
                    dir = n.branch[1].ray.dir;
                    throughput = throughput.cwiseProduct(m.filter);
                } else {
                    dir = n.branch[0].ray.dir;
                }
            } else {
                dir = n.branch[0].ray.dir;
                throughput = throughput.cwiseProduct(n.branch[0].factor);
            }
        }
        ray = Ray{p, dir.normalized()};
    }
}

}  // namespace refract
