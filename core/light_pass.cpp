#include <refract/core/light_pass.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/emitters.h>
#include <refract/geometry/error.h>
#include <refract/core/ray_tree.h>
#include <refract/core/threads.h>

namespace refract {

namespace {

constexpr double kFixedScale = 1099511627776.0;  // 2^40 units per unit of scaled power

struct Accumulator {
    std::vector<std::vector<std::atomic<std::int64_t>>> sums;  // per object, 3 per element
    double scale = 1;
};

// Where a photon's branch ends: on a diffuse surface with a map, after at least one
// specular interaction, it is deposited; an RGB photon splits into bands at its first
// dispersive hit, each band carrying its weight.
template <class P>
struct PhotonEnds {
    using Entry = TreeEntryT<P>;
    const Scene& scene;
    const SpectralContext& ctx;
    const IlluminationMaps& maps;
    Accumulator& acc;
    double dref;
    RenderStats& stats;
    std::uint64_t& deposits;

    void background(const Entry&) {}

    // The photon's power: its colour weight, times S0 when it carries a Stokes vector.
    static Vec3 power(const TreeEntryT<NaturalLight>& e) { return e.weight; }
    static Vec3 power(const TreeEntryT<LightStokes>& e) { return e.weight * e.pol.S[0]; }

    void leaf(const Entry& e, const SurfaceHit& h) {
        if (!lit_surface(*h.material)) return;
        const size_t obj = static_cast<size_t>(h.object - scene.objects.data());
        if (e.depth == 0 || !maps.by_object[obj]) return;
        const int el = maps.by_object[obj]->element(h.hit);
        if (el < 0) return;
        // Irradiance counts the power arriving on the surface, whatever the angle.
        // Point lights have no distance falloff (POV-Ray's default, and refract's
        // direct lighting): a photon's power grows with the square of the path
        // length, so that light passing through an index-1 object lands exactly
        // as the direct light would.
        const double D = e.travelled + h.hit.t;
        // A directional light (dref 0) has parallel photons and no falloff.
        const double falloff = dref > 0 ? (D * D) / (dref * dref) : 1.0;
        const Vec3 pw = power(e);
        for (int c = 0; c < 3; ++c)
            acc.sums[obj][3 * static_cast<size_t>(el) + c].fetch_add(
                static_cast<std::int64_t>(std::llround(pw[c] * falloff * acc.scale)), std::memory_order_relaxed);
        ++deposits;
    }

    double wavelength(const Entry& e) const {
        return e.band < 0 ? 0.0 : ctx.all_wavelengths[static_cast<size_t>(e.band)];
    }

    double band_ior(const Entry& e, const SurfaceHit& h) const {
        return e.band < 0 ? 0.0 : ctx.index[static_cast<size_t>(e.band)][static_cast<size_t>(h.object->material)];
    }

    // A packet walk's lanes all deposit here (fixed point: in any order).
    PhotonEnds& lane(int) { return *this; }

    bool intercept(RayTreeWalkerT<P>& w, const Entry& e, const SurfaceHit& h, typename RayTreeWalkerT<P>::List&) {
        const size_t mi = static_cast<size_t>(h.object->material);
        if (e.band >= 0 || !ctx.dispersive[mi]) return false;
        // First transparent hit: one ray per band, each with the band's weight, the bands kLanes
        // at a time where the tracer walks packets (the same deposits, whose sums do not depend
        // on the order).
        const std::vector<int>& bands = ctx.split_bands[mi];
        w.walk_bands(
            static_cast<int>(bands.size()),
            [&](auto& s, int i) {
                const int k = bands[static_cast<size_t>(i)];
                const size_t kb = static_cast<size_t>(k);
                const Interaction in =
                    w.tracer().interact(h, e.ray, stats, ctx.index[kb][mi], false, e.wave, ctx.all_wavelengths[kb]);
                for (int b = 0; b < in.branches; ++b) s.push(e, h, in, b, ctx.weights[kb], k);
            },
            *this,
            [&](int, const LossesT<double>& lost) {
                stats.lost_depth += lost.depth;
                stats.lost_limits += lost.limits;
                stats.lost_threshold += lost.threshold;
            });
        return true;
    }
};

// The illumination map of each kind of surface a shape offers (geometry/shapes.h
// map_surface): a square of a plane under the transparent objects, a mesh's triangles.
std::unique_ptr<IlluminationMap> map_for(std::monostate, const Vec3&, double, double) { return nullptr; }
std::unique_ptr<IlluminationMap> map_for(const Plane* p, const Vec3& centre, double half, double element) {
    return std::make_unique<IlluminationMap>(IlluminationMap::for_plane(*p, centre, half, element));
}
std::unique_ptr<IlluminationMap> map_for(const TriangleMesh* m, const Vec3&, double, double element) {
    return std::make_unique<IlluminationMap>(IlluminationMap::for_mesh(*m, element));
}

double elements_for(std::monostate, double, double) { return 0; }
double elements_for(const Plane*, double half, double element) { return IlluminationMap::plane_elements(half, element); }
double elements_for(const TriangleMesh* m, double, double element) { return IlluminationMap::mesh_elements(*m, element); }

// The maps' square region: centred on the transparent objects, half-size region × extent.
struct MapRegion {
    Vec3 centre{0, 0, 0};
    double half = 0;
};

MapRegion map_region(const std::vector<BoundingSphere>& targets, const LightPassSettings& lp) {
    MapRegion r;
    double extent = 0;
    for (const auto& t : targets) r.centre += t.centre / static_cast<double>(targets.size());
    for (const auto& t : targets) extent = std::fmax(extent, (t.centre - r.centre).norm() + t.radius);
    r.half = lp.region * extent;
    return r;
}

}  // namespace

double illumination_elements(const Scene& scene) {
    const std::vector<BoundingSphere> targets = transparent_targets(scene);
    if (targets.empty()) return 0;
    const LightPassSettings& lp = scene.settings.light_pass;
    const MapRegion region = map_region(targets, lp);
    double total = 0;
    for (const Object& o : scene.objects)
        if (lit_surface(scene.materials[static_cast<size_t>(o.material)]))
            total += std::visit([&](const auto& surface) { return elements_for(surface, region.half, lp.element_size); },
                                map_surface(o.shape));
    return total;
}

std::shared_ptr<IlluminationMaps> light_pass(const Scene& scene, const SpectralContext& ctx, int threads,
                                             const std::atomic<bool>* cancel, const TraceOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    const LightPassSettings& lp = scene.settings.light_pass;
    const RenderSettings& rs = scene.settings;
    auto maps = std::make_shared<IlluminationMaps>();
    const std::vector<BoundingSphere> targets = transparent_targets(scene);
    maps->by_object.resize(scene.objects.size());
    if (targets.empty()) return maps;
    const MapRegion region = map_region(targets, lp);
    const Vec3& centre = region.centre;
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        const Object& o = scene.objects[k];
        const Material& m = scene.materials[o.material];
        if (!lit_surface(m)) continue;
        try {
            maps->by_object[k] = std::visit(
                [&](const auto& surface) { return map_for(surface, centre, region.half, lp.element_size); },
                map_surface(o.shape));
        } catch (const InputError& e) {
            throw InputError((scene.source.empty() ? std::string("scene") : scene.source) + ": " + e.what() +
                             " (object '" + clip_echo(o.name) + "')");
        }
    }
    Accumulator acc;
    acc.sums.resize(scene.objects.size());
    for (size_t k = 0; k < scene.objects.size(); ++k)
        if (maps->by_object[k])
            acc.sums[k] = std::vector<std::atomic<std::int64_t>>(3 * static_cast<size_t>(maps->by_object[k]->elements()));
    for (auto& v : acc.sums)
        for (auto& a : v) a.store(0, std::memory_order_relaxed);

    const std::vector<Emitter> emitters = make_emitters(scene, targets, centre, lp.photons);
    double max_power = 0;
    for (const Emitter& em : emitters)
        max_power = std::fmax(max_power, em.power.cwiseAbs().maxCoeff() * static_cast<double>(em.photons));
    // Fixed point: 2^40 units for the largest emitter's total power.
    acc.scale = max_power > 0 ? kFixedScale / max_power : 1.0;
    std::atomic<std::uint64_t> photons{0}, deposits{0}, segments{0}, facet_local{0}, facet_full{0};
    SceneTracer tracer(scene, options);
    const TreeLimits limits = ctx.limits(rs);
    const bool exact = tracer.exact();

    // A chunk of one emitter's photons, walked on one list.
    auto trace_photons = [&](auto payload, const Emitter& em, std::uint64_t begin, std::uint64_t end, RenderStats& st,
                             std::uint64_t& dep) {
        using P = decltype(payload);
        RayTreeWalkerT<P> walker(tracer, limits, st);
        PhotonEnds<P> ends{scene, ctx, *maps, acc, em.dref, st, dep};
        typename RayTreeWalkerT<P>::List list;
        for (std::uint64_t p = begin; p != end; ++p) {
            const auto [ray, power] = sample_photon(em, lp.seed, p);
            TreeEntryT<P> e{ray, power};
            if constexpr (std::is_same_v<P, LightStokes>) e.pol = emitted(emitter_polarisation(scene, em), ray.dir);
            list.push_back(e);
            walker.walk(list, ends);
        }
    };

    constexpr std::uint64_t kChunk = 1024;
    const int nthreads = worker_threads(threads);
    tbb::task_arena arena(nthreads);
    for (const Emitter& em : emitters) {
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, em.photons, kChunk),
                              [&](const tbb::blocked_range<std::uint64_t>& r) {
                                  if (cancel && cancel->load(std::memory_order_relaxed)) return;
                                  RenderStats st;
                                  std::uint64_t dep = 0;
                                  if (exact) trace_photons(LightStokes{}, em, r.begin(), r.end(), st, dep);
                                  else trace_photons(NaturalLight{}, em, r.begin(), r.end(), st, dep);
                                  photons += r.size();
                                  deposits += dep;
                                  segments += st.segments;
                                  facet_local += st.facet_local;
                                  facet_full += st.facet_full;
                              });
        });
    }
    // Irradiance = power / element area.
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        if (!maps->by_object[k]) continue;
        IlluminationMap& m = *maps->by_object[k];
        for (int e = 0; e < m.elements(); ++e)
            for (int c = 0; c < 3; ++c)
                m.irradiance[static_cast<size_t>(e)][c] =
                    static_cast<double>(acc.sums[k][3 * static_cast<size_t>(e) + c].load()) / acc.scale /
                    m.element_area(e);
    }
    maps->photons = photons;
    maps->deposits = deposits;
    maps->segments = segments;
    maps->facet_local = facet_local;
    maps->facet_full = facet_full;
    maps->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return maps;
}

}  // namespace refract
