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

// The nearest hits of the paths' rays: one ray's, or a packet's (no ray leaves a known hit:
// the paths' rays are searched afresh, as RTIOW's).
std::optional<SurfaceHit> search(const SceneTracer& tracer, const Vec3& origin, const Vec3& dir, bool, RenderStats& stats) {
    return tracer.intersect(Ray{origin, dir}, stats);
}
SceneTracer::LaneHits search(const SceneTracer& tracer, const LaneVec3& origin, const LaneVec3& dir, const LaneMask& on,
                             RenderStats& stats) {
    return tracer.intersect_lanes(origin, dir, on, SceneTracer::LaneOrigins{}, stats);
}
bool met(const std::optional<SurfaceHit>& h, int) { return h.has_value(); }
bool met(const SceneTracer::LaneHits& h, int l) { return h.hit[l]; }
SurfaceHit hit_of(const SceneTracer&, const std::optional<SurfaceHit>& h, int) { return *h; }
SurfaceHit hit_of(const SceneTracer& tracer, const SceneTracer::LaneHits& h, int l) { return tracer.surface_hit(h, l); }
// Eigen's normalized() of the bounced directions (a zero vector stays as it is): one ray's,
// or every lane of a packet at once on the widest vector instructions.
void normalize(Vec3& dir, bool bounced) {
    if (bounced) dir = dir.normalized();
}
void normalize(LaneVec3& dir, const LaneMask& bounced) {
    if (bounced.any()) normalize_lanes(dir, bounced);
}

// The paths of n samples, one at a time (S = double) or kLanes at a time (S = Lanes): each
// step searches the paths' rays together, then each path takes its own bounce, so that the
// paths' dependency chains overlap; a lane whose path ends takes the next sample.
// `start(k, rng)` sets rng to sample k's stream and gives its primary ray; out[k] is
// sample k's light. Every path's light and random stream are the same whatever S.
template <class S>
void walk_paths(const SceneTracer& tracer, int n, const std::function<Ray(int, Rng&)>& start, std::vector<Vec3>& out,
                RenderStats& stats, Rng* last_rng = nullptr) {
    constexpr int W = Width<S>::kLanes;
    out.assign(static_cast<size_t>(std::max(n, 0)), Vec3::Zero());
    std::array<Path, W> p;
    std::array<Rng, W> rng;
    std::array<int, W> depth{}, sample{};
    VecOf<S> origin, dir;
    MaskOf<S> on = all_lanes<S>(false);
    int next_sample = 0;
    // Lane l takes the next sample (or goes idle when none is left).
    const auto fill = [&](int l) {
        const size_t i = static_cast<size_t>(l);
        const bool more = next_sample < n;
        if constexpr (kPacketOf<S>) {
            on[l] = more;
        } else {
            on = more;
        }
        if (!more) return;
        sample[i] = next_sample;
        const Ray r = start(next_sample++, rng[i]);
        p[i] = Path{};
        depth[i] = 0;
        set_lane(origin, l, r.origin);
        set_lane(dir, l, r.dir);
    };
    for (int l = 0; l < W; ++l) fill(l);
    while (any(on)) {
        const auto h = search(tracer, origin, dir, on, stats);
        MaskOf<S> bounced = all_lanes<S>(false);  // the lanes whose new direction is to be normalised
        for_each_lane(MaskOf<S>(on), [&](int l) {
            const size_t i = static_cast<size_t>(l);
            const Ray ray{lane_of(origin, l), lane_of(dir, l)};
            if (!met(h, l)) {
                out[static_cast<size_t>(sample[i])] = p[i].radiance + p[i].throughput.cwiseProduct(tracer.background(ray.dir));
                if (last_rng) *last_rng = rng[i];
                fill(l);
                return;
            }
            const SurfaceHit hl = hit_of(tracer, h, l);
            const auto next = bounce(tracer, hl, ray, depth[i], p[i], rng[i], stats);
            if (!next) {
                out[static_cast<size_t>(sample[i])] = p[i].radiance;
                if (last_rng) *last_rng = rng[i];
                fill(l);
                return;
            }
            ++depth[i];
            set_lane(origin, l, hl.hit.point);
            set_lane(dir, l, *next);
            if constexpr (kPacketOf<S>) {
                bounced[l] = true;
            } else {
                bounced = true;
            }
        });
        normalize(dir, bounced);
    }
}

}  // namespace

Vec3 stochastic_radiance(const SceneTracer& tracer, const Ray& primary, Rng& rng, RenderStats& stats) {
    std::vector<Vec3> out;
    walk_paths<double>(
        tracer, 1,
        [&](int, Rng& r) {
            r = rng;
            return primary;
        },
        out, stats, &rng);
    return out[0];
}

void stochastic_radiance_samples(const SceneTracer& tracer, int n, const std::function<Ray(int, Rng&)>& start,
                                 std::vector<Vec3>& out, RenderStats& stats) {
    if (tracer.packets()) {
        walk_paths<Lanes>(tracer, n, start, out, stats);
    } else {
        walk_paths<double>(tracer, n, start, out, stats);
    }
}

namespace {

// RTIOW's paths: the samples of a pixel walked one at a time, or kLanes paths at a time (the
// tracer's packets), summed in sample order (the same sum).
class Stochastic : public Integrator {
public:
    using Integrator::Integrator;
    Vec3 pixel(int i, int j, RenderStats& stats, std::vector<double>*) const override {
        const int n = tracer_.settings().samples;
        thread_local std::vector<Vec3> values;
        stochastic_radiance_samples(
            tracer_, n,
            [&](int k, Rng& rng) {
                ++stats.primary_rays;
                return sample_ray(i, j, k, rng);
            },
            values, stats);
        Vec3 sum(0, 0, 0);
        for (const Vec3& v : values) sum += v;
        return Vec3(sum / n);
    }
};

}  // namespace

std::unique_ptr<Integrator> stochastic_integrator(const SceneTracer& tracer, const SpectralContext*) {
    return std::make_unique<Stochastic>(tracer);
}

}  // namespace refract
