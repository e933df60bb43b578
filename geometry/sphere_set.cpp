// A list of spheres tested together (see sphere_set.h).
#include <refract/geometry/sphere_set.h>

#include <atomic>
#include <cstring>
#include <limits>

#include <refract/geometry/plane_set.h>
#include <refract/geometry/simd.h>

namespace refract {

namespace {

constexpr std::size_t kBlock = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The kernels (geometry/simd/sphere_set.cpp) and their variants.
using RootsFn = decltype(&simd::sphere_roots<simd::Sse2>);
using LanesFn = decltype(&simd::sphere_lanes<simd::Sse2>);
RootsFn roots_function(SlabIsa isa) {
    return simd::variant<RootsFn>(isa, simd::sphere_roots<simd::Sse2>, simd::sphere_roots<simd::Avx2>,
                                  simd::sphere_roots<simd::Avx512f>);
}
LanesFn lanes_function(SlabIsa isa) {
    return simd::variant<LanesFn>(isa, simd::sphere_lanes<simd::Sse2>, simd::sphere_lanes<simd::Avx2>,
                                  simd::sphere_lanes<simd::Avx512f>);
}

// The variants in use: the best the CPU runs, or the one a test asked for.
std::atomic<RootsFn> roots_in_use{nullptr};
std::atomic<LanesFn> lanes_in_use{nullptr};
RootsFn roots_fn() {
    RootsFn f = roots_in_use.load(std::memory_order_relaxed);
    if (!f) roots_in_use.store(f = roots_function(slab_isa()), std::memory_order_relaxed);
    return f;
}
LanesFn lanes_fn() {
    LanesFn f = lanes_in_use.load(std::memory_order_relaxed);
    if (!f) lanes_in_use.store(f = lanes_function(slab_isa()), std::memory_order_relaxed);
    return f;
}

}  // namespace

void SphereSet::use_isa(SlabIsa isa) {
    roots_in_use.store(roots_function(isa), std::memory_order_relaxed);
    lanes_in_use.store(lanes_function(isa), std::memory_order_relaxed);
}

void SphereSet::add(const Sphere& s) {
    const std::size_t n = spheres_.size();
    spheres_.push_back(s);
    const std::size_t padded = (n + kBlock) / kBlock * kBlock;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    cx_.resize(padded, 0.0);
    cy_.resize(padded, 0.0);
    cz_.resize(padded, 0.0);
    r_.resize(padded, nan);
    cx_[n] = s.center.x();
    cy_[n] = s.center.y();
    cz_[n] = s.center.z();
    r_[n] = s.radius;
}

std::optional<SphereSet::Nearest> SphereSet::nearest(const Ray& r, double t_min, double t_max,
                                                     std::size_t leaving) const {
    const std::size_t n = cx_.size();
    if (n == 0) return std::nullopt;
    constexpr std::size_t kMax = 64;
    alignas(64) double stack_t[kMax], stack_b[kMax];
    std::vector<double> heap;
    double* t = stack_t;
    double* b = stack_b;
    if (n > kMax) {
        heap.resize(2 * n);
        t = heap.data();
        b = t + n;
    }
    const double o[3] = {r.origin.x(), r.origin.y(), r.origin.z()};
    const double v[3] = {r.dir.x(), r.dir.y(), r.dir.z()};
    roots_fn()(cx_.data(), cy_.data(), cz_.data(), r_.data(), n, o, v, t_min, t_max, t, b);
    if (leaving < spheres_.size() && b[leaving] > 0) t[leaving] = kInf;
    // The first sphere attaining the smallest t (strictly smaller replaces: list order wins
    // ties, as the scalar search that narrows its window to the best t so far).
    std::size_t best = SIZE_MAX;
    double best_t = kInf;
    for (std::size_t i = 0; i < spheres_.size(); ++i)
        if (t[i] < best_t) {
            best_t = t[i];
            best = i;
        }
    if (best == SIZE_MAX) return std::nullopt;
    return Nearest{best_t, best};
}

void SphereSet::nearest_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active, double t_min,
                              const std::array<std::int32_t, kLanes>& leaving, LaneHits& io) const {
    double idx[kLanes], leave[kLanes];
    alignas(64) double point[3 * kLanes], normal[3 * kLanes];
    for (int l = 0; l < kLanes; ++l) {
        idx[l] = io.index[static_cast<std::size_t>(l)];
        leave[l] = leaving[static_cast<std::size_t>(l)];
    }
    io.hit.bits = lanes_fn()(cx_.data(), cy_.data(), cz_.data(), r_.data(), spheres_.size(), origin.x.v, origin.y.v,
                             origin.z.v, dir.x.v, dir.y.v, dir.z.v, active.bits, t_min, io.best.v, idx, leave, point,
                             normal);
    for (int l = 0; l < kLanes; ++l) io.index[static_cast<std::size_t>(l)] = static_cast<std::int32_t>(idx[l]);
    if (!io.hit.any()) return;
    std::memcpy(io.point.x.v, point, sizeof io.point.x.v);
    std::memcpy(io.point.y.v, point + kLanes, sizeof io.point.y.v);
    std::memcpy(io.point.z.v, point + 2 * kLanes, sizeof io.point.z.v);
    std::memcpy(io.normal.x.v, normal, sizeof io.normal.x.v);
    std::memcpy(io.normal.y.v, normal + kLanes, sizeof io.normal.y.v);
    std::memcpy(io.normal.z.v, normal + 2 * kLanes, sizeof io.normal.z.v);
}

}  // namespace refract
