#include "core/integrators/stochastic.h"

namespace refract {

Vec3 stochastic_radiance(const SceneTracer& tracer, const Ray& primary, Rng& rng, RenderStats& stats) {
    const RenderSettings& s = tracer.settings();
    Ray ray = primary;
    Vec3 throughput(1, 1, 1);
    Vec3 radiance(0, 0, 0);
    for (int depth = 0;; ++depth) {
        const auto hit = tracer.intersect(ray, stats);
        if (!hit) return radiance + throughput.cwiseProduct(tracer.background(ray.dir));
        if (const auto a = tracer.absorption(*hit, 0.0)) throughput = throughput.cwiseProduct(*a);  // Beer–Lambert
        const Material& m = *hit->material;
        const bool random_scatter = m.is<material::Lambertian>() || m.is<material::Metal>();
        if (depth + 1 > s.max_depth) {
            // The ray after the last bounce: its hit's own light counts (emissive, direct
            // light on a diffuse surface), as in the tree integrators; nothing scatters on.
            ++stats.depth_limited;
            if (!random_scatter) radiance += throughput.cwiseProduct(tracer.local_light(*hit, stats));
            // The path would have gone on from anything but a leaf (diffuse, emissive).
            if (random_scatter || !(m.diffuse_surface() || m.is<material::Emissive>())) stats.lost_depth += throughput.mean();
            return radiance;
        }
        std::optional<Scatter> next;
        if (const auto* l = m.as<material::Lambertian>()) {
            next = scatter(*l, tracer.pigment(l->pigment, hit->hit.point), *hit, rng);
        } else if (const auto* metal = m.as<material::Metal>()) {
            next = scatter(*metal, *hit, ray, rng);
        } else {
            // Every other material: sample one branch of its interaction (RTIOW), keeping
            // a leaf's light.
            const Interaction in = tracer.interact(*hit, ray, stats);
            if (in.leaf) radiance += throughput.cwiseProduct(tracer.local_light(*hit, stats));
            next = sample_branch(m, in, rng);
        }
        if (!next) return radiance;
        throughput = throughput.cwiseProduct(next->factor);
        ray = Ray{hit->hit.point, next->dir.normalized()};
    }
}

}  // namespace refract
