#include <refract/core/integrators/stochastic.h>

#include <refract/core/integrators/integrator.h>

#include <refract/geometry/lanes_wide.h>

#include <algorithm>

namespace refract {

namespace {

// A path's light so far and the weight of what it gathers next.
struct Path {
    Vec3 throughput{1, 1, 1};
    Vec3 radiance{0, 0, 0};
};

// One bounce of a path whose ray `ray` met `hit` after `depth` bounces, by the material's
// rules (core/material_rules.h): Beer–Lambert over the segment, the hit's own light where it
// is a leaf, then the sampled continuation's direction, to be normalised (none: the path
// ends); the ray leaves the hit point.
std::optional<Vec3> bounce(const SceneTracer& tracer, const SurfaceHit& hit, const Ray& ray, int depth, Path& p,
                           Rng& rng, RenderStats& stats) {
    const RenderSettings& s = tracer.settings();
    if (const auto a = tracer.absorption(hit, 0.0)) p.throughput = p.throughput.cwiseProduct(*a);  // Beer–Lambert
    const Material& m = *hit.material;
    const StochasticRole role = stochastic_role(m);
    if (depth + 1 > s.max_depth) {
        // The ray after the last bounce: a leaf's own light counts (emissive, direct light
        // on a diffuse surface), as in the tree integrators; nothing scatters on, and the
        // light the path would have gathered from anything but a leaf is lost.
        ++stats.depth_limited;
        if (role == StochasticRole::Leaf) {
            p.radiance += p.throughput.cwiseProduct(tracer.local_light(hit, stats));
        } else {
            stats.lost_depth += p.throughput.mean();
        }
        return std::nullopt;
    }
    if (role == StochasticRole::Leaf) {
        p.radiance += p.throughput.cwiseProduct(tracer.local_light(hit, stats));
        return std::nullopt;
    }
    if (transparent(m)) ++stats.tree_nodes;  // a branching node, as SceneTracer::interact counts it
    const std::optional<Scatter> next = sample(m, hit, ray, tracer.context(), rng);
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
    const SceneTracer::LaneOrigins none{};
    while (on.any()) {
        const SceneTracer::LaneHits h = tracer.intersect_lanes(origin, dir, on, none, stats);
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

namespace {

// RTIOW's paths: each sample's path walked alone, or the samples of a pixel kLanes paths at
// a time (the tracer's packets), summed in sample order (the same sum).
class Stochastic : public Integrator {
public:
    using Integrator::Integrator;
    Vec3 pixel(int i, int j, RenderStats& stats, std::vector<double>*) const override {
        const int n = tracer_.settings().samples;
        Vec3 sum(0, 0, 0);
        if (tracer_.packets()) {
            thread_local std::vector<Vec3> values;
            stochastic_radiance_samples(
                tracer_, n,
                [&](int k, Rng& rng) {
                    ++stats.primary_rays;
                    return sample_ray(i, j, k, rng);
                },
                values, stats);
            for (const Vec3& v : values) sum += v;
            return Vec3(sum / n);
        }
        for (int k = 0; k < n; ++k) {
            Rng rng;
            const Ray ray = sample_ray(i, j, k, rng);
            ++stats.primary_rays;
            sum += stochastic_radiance(tracer_, ray, rng, stats);
        }
        return Vec3(sum / n);
    }
};

}  // namespace

std::unique_ptr<Integrator> stochastic_integrator(const SceneTracer& tracer, const SpectralContext*) {
    return std::make_unique<Stochastic>(tracer);
}

}  // namespace refract
