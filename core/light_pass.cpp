#include "core/light_pass.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/random.h"

namespace refract {

namespace {

std::optional<BoundingSphere> sphere_of_points(const std::vector<Vec3>& pts) {
    if (pts.empty()) return std::nullopt;
    Vec3 lo = pts[0], hi = pts[0];
    for (const Vec3& p : pts) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const Vec3 c = 0.5 * (lo + hi);
    double r = 0;
    for (const Vec3& p : pts) r = std::fmax(r, (p - c).norm());
    return BoundingSphere{c, r * (1 + 1e-9) + 1e-12};
}

}  // namespace

std::optional<BoundingSphere> bounding_sphere(const Shape& shape) {
    if (const auto* s = std::get_if<Sphere>(&shape)) return BoundingSphere{s->center, std::abs(s->radius)};
    if (const auto* m = std::get_if<TriangleMesh>(&shape)) return sphere_of_points(m->vertices);
    if (const auto* c = std::get_if<ConvexPolyhedron>(&shape)) {
        // Vertices: every triple of planes meeting in a point inside all half-spaces.
        std::vector<Vec3> v;
        const size_t n = c->planes.size();
        for (size_t i = 0; i < n; ++i)
            for (size_t j = i + 1; j < n; ++j)
                for (size_t k = j + 1; k < n; ++k) {
                    Eigen::Matrix3d A;
                    A.row(0) = c->planes[i].normal.transpose();
                    A.row(1) = c->planes[j].normal.transpose();
                    A.row(2) = c->planes[k].normal.transpose();
                    if (std::abs(A.determinant()) < 1e-12) continue;
                    const Vec3 p = A.partialPivLu().solve(Vec3(c->planes[i].offset, c->planes[j].offset, c->planes[k].offset));
                    bool inside = true;
                    for (const Plane& q : c->planes) inside = inside && q.normal.dot(p) <= q.offset + 1e-9;
                    if (inside) v.push_back(p);
                }
        // A polyhedron with no vertex, or unbounded, gets no bounding sphere: the
        // vertices found then do not enclose it, which the caller cannot detect; gems
        // are always closed.
        return sphere_of_points(v);
    }
    return std::nullopt;
}

namespace {

struct Photon {
    Ray ray;
    Vec3 power;
    double bailout;
    int band;  // −1: RGB, before the first dispersive hit
    int depth, refl, trans;
    bool specular;  // has met a specular surface
    double travelled;  // path length from the light to the ray's origin
};

constexpr double kFixedScale = 1099511627776.0;  // 2^40 units per unit of scaled power

struct Accumulator {
    std::vector<std::vector<std::atomic<std::int64_t>>> sums;  // per object, 3 per element
    double scale = 1;
};

}  // namespace

std::shared_ptr<IlluminationMaps> light_pass(const Scene& scene, const SpectralContext& ctx, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    const LightPassSettings& lp = scene.settings.light_pass;
    const RenderSettings& rs = scene.settings;
    auto maps = std::make_shared<IlluminationMaps>();
    // Targets: the transparent objects' bounding spheres.
    std::vector<BoundingSphere> targets;
    for (const Object& o : scene.objects)
        if (scene.materials[o.material].kind == MaterialKind::Dielectric)
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
        if (m.kind != MaterialKind::Diffuse && m.kind != MaterialKind::Lambertian) continue;
        if (const auto* p = std::get_if<Plane>(&o.shape))
            maps->by_object[k] = std::make_unique<IlluminationMap>(
                IlluminationMap::for_plane(*p, centre, lp.region * extent, lp.element_size));
        else if (const auto* mesh = std::get_if<TriangleMesh>(&o.shape))
            maps->by_object[k] = std::make_unique<IlluminationMap>(IlluminationMap::for_mesh(*mesh, lp.element_size));
    }
    Accumulator acc;
    acc.sums.resize(scene.objects.size());
    for (size_t k = 0; k < scene.objects.size(); ++k)
        if (maps->by_object[k])
            acc.sums[k] = std::vector<std::atomic<std::int64_t>>(3 * static_cast<size_t>(maps->by_object[k]->elements()));
    for (auto& v : acc.sums)
        for (auto& a : v) a.store(0, std::memory_order_relaxed);

    // Emitters: (light, target) pairs, photons split evenly over the targets.
    struct Emitter {
        Vec3 origin, axis, power;  // power: flux of one photon at the reference distance
        double cos_max, dref;
        std::uint64_t photons, stream;
    };
    std::vector<Emitter> emitters;
    double max_power = 0;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const PointLight& L = scene.lights[l];
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
            emitters.push_back({L.position, to / d, power, cos_max, dref, n, l * targets.size() + t});
            max_power = std::fmax(max_power, power.cwiseAbs().maxCoeff() * static_cast<double>(n));
        }
    }
    // Fixed point: 2^40 units for the largest emitter's total power.
    acc.scale = max_power > 0 ? kFixedScale / max_power : 1.0;
    std::atomic<std::uint64_t> photons{0}, deposits{0}, segments{0};
    SceneTracer tracer(scene);

    auto trace_photon = [&](const Emitter& em, std::uint64_t p, RenderStats& st, std::uint64_t& dep) {
        Rng rng(lp.seed, em.stream, p);
        const double cos_t = 1.0 - rng.uniform() * (1.0 - em.cos_max);
        const double phi = 2.0 * M_PI * rng.uniform();
        const double sin_t = std::sqrt(std::fmax(0.0, 1.0 - cos_t * cos_t));
        const Vec3 a = std::abs(em.axis.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        const Vec3 u = em.axis.cross(a).normalized(), v = em.axis.cross(u);
        const Vec3 dir = (cos_t * em.axis + sin_t * (std::cos(phi) * u + std::sin(phi) * v)).normalized();
        std::deque<Photon> list;
        list.push_back({Ray{em.origin, dir}, em.power, 1.0, -1, 0, 0, 0, false, 0.0});
        while (!list.empty()) {
            const Photon ph = list.front();
            list.pop_front();
            const auto hit = tracer.intersect(ph.ray, st);
            if (!hit) continue;
            const Material& m = *hit->material;
            const int mi = hit->object->material;
            if (m.kind == MaterialKind::Diffuse || m.kind == MaterialKind::Lambertian) {
                const size_t obj = static_cast<size_t>(hit->object - scene.objects.data());
                if (!ph.specular || !maps->by_object[obj]) continue;
                const int e = maps->by_object[obj]->element(hit->hit);
                if (e < 0) continue;
                // Irradiance counts the power arriving on the surface, whatever the angle.
                // Point lights have no distance falloff (POV-Ray's default, and refract's
                // direct lighting): a photon's power grows with the square of the path
                // length, so that light passing through an index-1 object lands exactly
                // as the direct light would.
                const double D = ph.travelled + hit->hit.t;
                const double falloff = (D * D) / (em.dref * em.dref);
                for (int c = 0; c < 3; ++c)
                    acc.sums[obj][3 * static_cast<size_t>(e) + c].fetch_add(
                        static_cast<std::int64_t>(std::llround(ph.power[c] * falloff * acc.scale)),
                        std::memory_order_relaxed);
                ++dep;
                continue;
            }
            if (m.kind == MaterialKind::Emissive) continue;
            auto push_node = [&](const Node& n, const Vec3& tint, int band, bool only_refraction) {
                for (int b = only_refraction ? 1 : 0; b < n.branches; ++b) {
                    const Branch& br = n.branch[b];
                    const double bail = ph.bailout * br.bailout_factor;
                    if (bail <= 0 || bail < rs.pruning_threshold()) continue;
                    const bool tr = b == 1;
                    const int refl = ph.refl + (tr ? 0 : 1), trans = ph.trans + (tr ? 1 : 0);
                    if (ph.depth + 1 > rs.max_depth || refl > ctx.max_reflections || trans > ctx.max_transmissions)
                        continue;
                    list.push_back({br.ray, ph.power.cwiseProduct(br.factor).cwiseProduct(tint), bail, band,
                                    ph.depth + 1, refl, trans, true, ph.travelled + hit->hit.t});
                }
            };
            if (ph.band < 0 && ctx.dispersive[static_cast<size_t>(mi)]) {
                // First transparent hit: one ray per band, each with the band's weight.
                for (const int k : ctx.split_bands[static_cast<size_t>(mi)])
                    push_node(tracer.node(*hit, ph.ray, st, ctx.index[static_cast<size_t>(k)][static_cast<size_t>(mi)]),
                              ctx.weights[static_cast<size_t>(k)], k, false);
                continue;
            }
            const double band_ior = ph.band < 0 ? 0.0 : ctx.index[static_cast<size_t>(ph.band)][static_cast<size_t>(mi)];
            push_node(tracer.node(*hit, ph.ray, st, band_ior), Vec3(1, 1, 1), ph.band, false);
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
