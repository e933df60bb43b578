#include "core/light_pass.h"

#include <atomic>
#include <chrono>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/random.h"
#include "core/ray_tree.h"

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
        if (!h.material->diffuse_surface()) return;
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

    bool intercept(RayTreeWalkerT<P>& w, const Entry& e, const SurfaceHit& h, typename RayTreeWalkerT<P>::List& list) {
        const size_t mi = static_cast<size_t>(h.object->material);
        if (e.band >= 0 || !ctx.dispersive[mi]) return false;
        // First transparent hit: one ray per band, each with the band's weight.
        for (const int k : ctx.split_bands[mi]) {
            const Interaction in = w.tracer().interact(h, e.ray, stats, ctx.index[static_cast<size_t>(k)][mi]);
            for (int b = 0; b < in.branches; ++b) w.push(e, h, in, b, b == 1, list, ctx.weights[static_cast<size_t>(k)], k);
        }
        return true;
    }
};

// A light's polarisation as a photon leaving along `dir` carries it (S0 = 1).
LightStokes emitted(const PolarisationState& p, const Vec3& dir) {
    Vec3 ref = p.reference - p.reference.dot(dir) * dir;
    if (ref.norm() < 1e-9) ref = Vec3(1, 0, 0) - dir.x() * dir;  // the beam runs along the reference
    LightStokes s;
    s.x = ref.normalized();
    switch (p.kind) {
        case PolarisationState::Kind::Unpolarised: s.S = polar::unpolarised(1.0); break;
        case PolarisationState::Kind::Linear: s.S = polar::linear(1.0, p.angle_deg * M_PI / 180.0); break;
        case PolarisationState::Kind::Circular: s.S = polar::circular(1.0, p.handedness); break;
    }
    return s;
}

// The illumination map each shape gets: planes (a square under the transparent objects)
// and meshes; none for spheres and polyhedra.
std::unique_ptr<IlluminationMap> map_for(const Plane& p, const Vec3& centre, double half, double element) {
    return std::make_unique<IlluminationMap>(IlluminationMap::for_plane(p, centre, half, element));
}
std::unique_ptr<IlluminationMap> map_for(const TriangleMesh& m, const Vec3&, double, double element) {
    return std::make_unique<IlluminationMap>(IlluminationMap::for_mesh(m, element));
}
std::unique_ptr<IlluminationMap> map_for(const Sphere&, const Vec3&, double, double) { return nullptr; }
std::unique_ptr<IlluminationMap> map_for(const ConvexPolyhedron&, const Vec3&, double, double) { return nullptr; }

}  // namespace

std::shared_ptr<IlluminationMaps> light_pass(const Scene& scene, const SpectralContext& ctx, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    const LightPassSettings& lp = scene.settings.light_pass;
    const RenderSettings& rs = scene.settings;
    auto maps = std::make_shared<IlluminationMaps>();
    // Targets: the transparent objects' bounding spheres.
    std::vector<BoundingSphere> targets;
    for (const Object& o : scene.objects)
        if (scene.materials[o.material].is<material::Dielectric>())
            if (auto b = bounding_sphere(o.shape)) targets.push_back(*b);
    maps->by_object.resize(scene.objects.size());
    if (targets.empty() || scene.lights.empty()) return maps;
    Vec3 centre(0, 0, 0);
    double extent = 0;
    for (const auto& t : targets) centre += t.centre / static_cast<double>(targets.size());
    for (const auto& t : targets) extent = std::fmax(extent, (t.centre - centre).norm() + t.radius);
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        const Object& o = scene.objects[k];
        const Material& m = scene.materials[o.material];
        if (!m.diffuse_surface()) continue;
        maps->by_object[k] = std::visit([&](const auto& shape) { return map_for(shape, centre, lp.region * extent, lp.element_size); },
                                        o.shape);
    }
    Accumulator acc;
    acc.sums.resize(scene.objects.size());
    for (size_t k = 0; k < scene.objects.size(); ++k)
        if (maps->by_object[k])
            acc.sums[k] = std::vector<std::atomic<std::int64_t>>(3 * static_cast<size_t>(maps->by_object[k]->elements()));
    for (auto& v : acc.sums)
        for (auto& a : v) a.store(0, std::memory_order_relaxed);

    // Emitters: (light, target) pairs, photons split evenly over the targets.
    // A point light shoots into the cone around a target; a directional light shoots
    // parallel photons through the disk of the target's radius across its direction.
    struct Emitter {
        Vec3 origin, axis, power;  // power: flux of one photon at the reference distance
        double cos_max, dref;      // dref 0: directional
        std::uint64_t photons, stream;
        size_t light;
        double radius = 0;         // directional: the disk's radius
    };
    std::vector<Emitter> emitters;
    double max_power = 0;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& L = scene.lights[l];
        if (L.kind == Light::Kind::Directional) {
            for (size_t t = 0; t < targets.size(); ++t) {
                const double R = targets[t].radius;
                const std::uint64_t n = std::max<std::uint64_t>(1, lp.photons / targets.size());
                const Vec3 power = L.color * (M_PI * R * R / static_cast<double>(n));  // irradiance × disk area
                const Vec3 origin = targets[t].centre - (R * 1.01 + 1e-6) * L.direction;
                emitters.push_back({origin, L.direction, power, 1.0, 0.0, n, l * targets.size() + t, l, R});
                max_power = std::fmax(max_power, power.cwiseAbs().maxCoeff() * static_cast<double>(n));
            }
            continue;
        }
        const double dref = (centre - L.position).norm();
        for (size_t t = 0; t < targets.size(); ++t) {
            const Vec3 to = targets[t].centre - L.position;
            const double d = to.norm();
            if (d <= targets[t].radius) continue;  // light inside the bounds
            const double sin_max = targets[t].radius / d;
            const double cos_max = std::sqrt(1.0 - sin_max * sin_max);
            const double omega = 2.0 * M_PI * (1.0 - cos_max);
            const std::uint64_t n = std::max<std::uint64_t>(1, lp.photons / targets.size());
            const Vec3 power = L.color * (dref * dref * omega / static_cast<double>(n));
            emitters.push_back({L.position, to / d, power, cos_max, dref, n, l * targets.size() + t, l, 0.0});
            max_power = std::fmax(max_power, power.cwiseAbs().maxCoeff() * static_cast<double>(n));
        }
    }
    // Fixed point: 2^40 units for the largest emitter's total power.
    acc.scale = max_power > 0 ? kFixedScale / max_power : 1.0;
    std::atomic<std::uint64_t> photons{0}, deposits{0}, segments{0};
    SceneTracer tracer(scene);
    const TreeLimits limits = ctx.limits(rs);
    const bool exact = rs.polarisation == PolarisationModel::Exact;

    auto trace_photon = [&](const Emitter& em, std::uint64_t p, RenderStats& st, std::uint64_t& dep) {
        Rng rng(lp.seed, em.stream, p);
        const double xi = rng.uniform();
        const double phi = 2.0 * M_PI * rng.uniform();
        const Vec3 a = std::abs(em.axis.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        const Vec3 u = em.axis.cross(a).normalized(), v = em.axis.cross(u);
        Vec3 origin = em.origin, dir = em.axis;
        if (em.dref > 0) {  // uniform in the cone's solid angle
            const double cos_t = 1.0 - xi * (1.0 - em.cos_max);
            const double sin_t = std::sqrt(std::fmax(0.0, 1.0 - cos_t * cos_t));
            dir = (cos_t * em.axis + sin_t * (std::cos(phi) * u + std::sin(phi) * v)).normalized();
        } else {  // uniform over the disk's area
            origin += em.radius * std::sqrt(xi) * (std::cos(phi) * u + std::sin(phi) * v);
        }
        if (exact) {
            RayTreeWalkerT<LightStokes> walker(tracer, limits, st);
            PhotonEnds<LightStokes> ends{scene, ctx, *maps, acc, em.dref, st, dep};
            RayTreeWalkerT<LightStokes>::List list{TreeEntryT<LightStokes>{Ray{origin, dir}, em.power}};
            list.front().pol = emitted(scene.lights[em.light].polarisation, dir);
            walker.walk(list, ends);
        } else {
            RayTreeWalker walker(tracer, limits, st);
            PhotonEnds<NaturalLight> ends{scene, ctx, *maps, acc, em.dref, st, dep};
            RayTreeWalker::List list{TreeEntry{Ray{origin, dir}, em.power}};
            walker.walk(list, ends);
        }
    };

    constexpr std::uint64_t kChunk = 1024;
    const int nthreads = threads > 0 ? threads : tbb::this_task_arena::max_concurrency();
    tbb::task_arena arena(nthreads);
    for (const Emitter& em : emitters) {
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, em.photons, kChunk),
                              [&](const tbb::blocked_range<std::uint64_t>& r) {
                                  RenderStats st;
                                  std::uint64_t dep = 0;
                                  for (std::uint64_t p = r.begin(); p != r.end(); ++p) trace_photon(em, p, st, dep);
                                  photons += r.size();
                                  deposits += dep;
                                  segments += st.segments;
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
    maps->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return maps;
}

}  // namespace refract
