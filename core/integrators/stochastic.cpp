#include "core/integrators/stochastic.h"

#include "geometry/lanes_wide.h"

#include <algorithm>

namespace refract {

namespace {

// A path's light so far and the weight of what it gathers next.
struct Path {
    Vec3 throughput{1, 1, 1};
    Vec3 radiance{0, 0, 0};
};

// One bounce of a path whose ray `ray` met `hit` after `depth` bounces: the hit's own light,
// then the scattered ray's direction, to be normalised (none: the path ends); the ray leaves
// the hit point.
std::optional<Vec3> bounce(const SceneTracer& tracer, const SurfaceHit& hit, const Ray& ray, int depth, Path& p,
                          Rng& rng, RenderStats& stats) {
    const RenderSettings& s = tracer.settings();
    if (const auto a = tracer.absorption(hit, 0.0)) p.throughput = p.throughput.cwiseProduct(*a);  // Beer–Lambert
    const Material& m = *hit.material;
    const bool random_scatter = m.is<material::Lambertian>() || m.is<material::Metal>();
    if (depth + 1 > s.max_depth) {
        // The ray after the last bounce: its hit's own light counts (emissive, direct
        // light on a diffuse surface), as in the tree integrators; nothing scatters on.
        ++stats.depth_limited;
        if (!random_scatter) p.radiance += p.throughput.cwiseProduct(tracer.local_light(hit, stats));
        // The path would have gone on from anything but a leaf (diffuse, emissive).
        if (random_scatter || !(m.diffuse_surface() || m.is<material::Emissive>())) stats.lost_depth += p.throughput.mean();
        return std::nullopt;
    }
    std::optional<Scatter> next;
    if (const auto* l = m.as<material::Lambertian>()) {
        next = scatter(*l, tracer.pigment(l->pigment, hit.hit.point), hit, rng);
    } else if (const auto* metal = m.as<material::Metal>()) {
        next = scatter(*metal, hit, ray, rng);
    } else if (const auto* d = m.as<material::Dielectric>(); d && s.compat != Compat::PovRay) {
        ++stats.tree_nodes;  // as SceneTracer::interact counts a transparent node
        next = scatter(*d, hit, ray, rng);
    } else {
        // Every other material: sample one branch of its interaction (RTIOW), keeping
        // a leaf's light.
        const Interaction in = tracer.interact(hit, ray, stats);
        if (in.leaf) p.radiance += p.throughput.cwiseProduct(tracer.local_light(hit, stats));
        next = sample_branch(m, in, rng);
    }
    if (!next) return std::nullopt;
    p.throughput = p.throughput.cwiseProduct(next->factor);
    return next->dir;
}

}  // namespace

Vec3 stochastic_radiance(const SceneTracer& tracer, const Ray& primary, Rng& rng, RenderStats& stats) {
    Path p;
    Ray ray = primary;
    for (int depth = 0;; ++depth) {
        const auto hit = tracer.intersect(ray, stats);
        if (!hit) return p.radiance + p.throughput.cwiseProduct(tracer.background(ray.dir));
        const auto next = bounce(tracer, *hit, ray, depth, p, rng, stats);
        if (!next) return p.radiance;
        ray = Ray{hit->hit.point, next->normalized()};
    }
}

void stochastic_radiance_samples(const SceneTracer& tracer, int n, const std::function<Ray(int, Rng&)>& start,
                                 std::vector<Vec3>& out, RenderStats& stats) {
    out.assign(static_cast<size_t>(std::max(n, 0)), Vec3::Zero());
    std::array<Path, kLanes> p;
    std::array<Rng, kLanes> rng;
    std::array<int, kLanes> depth{}, sample{};
    LaneVec3 origin, dir;
    LaneMask on;
    int next_sample = 0;
    // Lane l takes the next sample (or goes idle when none is left).
    const auto fill = [&](int l) {
        const size_t i = static_cast<size_t>(l);
        on[l] = next_sample < n;
        if (!on[l]) return;
        sample[i] = next_sample;
        const Ray r = start(next_sample++, rng[i]);
        p[i] = Path{};
        depth[i] = 0;
        origin.set(l, r.origin);
        dir.set(l, r.dir);
    };
    for (int l = 0; l < kLanes; ++l) fill(l);
    SceneTracer::LaneIds none;
    none.fill(-1);
    while (on.any()) {
        const SceneTracer::LaneHits h = tracer.intersect_lanes(origin, dir, on, none, none, stats);
        LaneMask bounced;  // the lanes whose new direction is to be normalised
        for (int l = 0; l < kLanes; ++l) {
            if (!on[l]) continue;
            const size_t i = static_cast<size_t>(l);
            const Ray ray{origin.lane(l), dir.lane(l)};
            if (!h.hit[l]) {
                out[static_cast<size_t>(sample[i])] = p[i].radiance + p[i].throughput.cwiseProduct(tracer.background(ray.dir));
                fill(l);
                continue;
            }
            const auto next = bounce(tracer, tracer.surface_hit(h, l), ray, depth[i], p[i], rng[i], stats);
            if (!next) {
                out[static_cast<size_t>(sample[i])] = p[i].radiance;
                fill(l);
                continue;
            }
            ++depth[i];
            origin.set(l, h.point.lane(l));
            dir.set(l, *next);
            bounced[l] = true;
        }
        // Eigen's normalized() on every lane at once (a zero vector stays as it is).
        if (bounced.any()) normalize_lanes(dir, bounced);
    }
}

}  // namespace refract
