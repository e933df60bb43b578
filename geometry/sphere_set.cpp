// A list of spheres tested together (see sphere_set.h).
#include "geometry/sphere_set.h"

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "geometry/plane_set.h"
#include "geometry/simd.h"

namespace refract {

namespace {

constexpr std::size_t kBlock = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();

using simd::Doubles;
using simd::Lane8;
using simd::Mask8;

// t of every sphere of the (padded) list, W spheres a step: its nearer root in (t_min,
// t_max), else its farther one, else +inf; and its b = oc·d. The arithmetic is
// sphere_quadratic's and intersect(const Sphere&)'s, operation by operation. Written once as
// a macro over the vector type and its square root, so that each per-target function below
// holds its own copy, compiled for its own instruction set.
#define REFRACT_SPHERE_ROOTS(W, SQRT)                                                          \
    using vd = Doubles<W>::type;                                                               \
    /* x - (+0) is exactly x for every x, -0 included. */                                      \
    const vd ox = r.origin.x() - vd{}, oy = r.origin.y() - vd{}, oz = r.origin.z() - vd{};     \
    const vd dx = r.dir.x() - vd{}, dy = r.dir.y() - vd{}, dz = r.dir.z() - vd{};              \
    const vd lo = t_min - vd{}, hi = t_max - vd{}, inf = kInf - vd{};                          \
    for (std::size_t i = 0; i < n; i += W) {                                                   \
        vd px, py, pz, q;                                                                      \
        std::memcpy(&px, cx + i, sizeof(vd));                                                  \
        std::memcpy(&py, cy + i, sizeof(vd));                                                  \
        std::memcpy(&pz, cz + i, sizeof(vd));                                                  \
        std::memcpy(&q, r2 + i, sizeof(vd));                                                   \
        const vd ocx = ox - px, ocy = oy - py, ocz = oz - pz;                                  \
        vd b = ocx * dx + ocy * dy;                                                            \
        b = b + ocz * dz;                                                                      \
        vd c = ocx * ocx + ocy * ocy;                                                          \
        c = c + ocz * ocz;                                                                     \
        c = c - q;                                                                             \
        const vd sq = SQRT(b * b - c); /* NaN where the discriminant is negative: no root */   \
        const vd near = -b - sq, far = -b + sq;                                                \
        const vd t = (near > lo) & (near < hi) ? near : far;                                   \
        const vd kept = (t > lo) & (t < hi) ? t : inf;                                         \
        std::memcpy(t_out + i, &kept, sizeof(vd));                                             \
        std::memcpy(b_out + i, &b, sizeof(vd));                                                \
    }

#define REFRACT_ROOTS_ARGS                                                                              \
    const double *cx, const double *cy, const double *cz, const double *r2, std::size_t n, const Ray &r, \
        double t_min, double t_max, double *t_out, double *b_out

using RootsFn = void (*)(REFRACT_ROOTS_ARGS);

#if defined(__x86_64__)
void roots_baseline(REFRACT_ROOTS_ARGS) { REFRACT_SPHERE_ROOTS(2, _mm_sqrt_pd) }
__attribute__((target("avx2"))) void roots_avx2(REFRACT_ROOTS_ARGS) { REFRACT_SPHERE_ROOTS(4, _mm256_sqrt_pd) }
REFRACT_AVX512_BEGIN
__attribute__((target("avx512f"))) void roots_avx512f(REFRACT_ROOTS_ARGS) { REFRACT_SPHERE_ROOTS(8, _mm512_sqrt_pd) }
REFRACT_AVX512_END
#else
Doubles<2>::type sqrt2(Doubles<2>::type v) { return Doubles<2>::type{std::sqrt(v[0]), std::sqrt(v[1])}; }
void roots_baseline(REFRACT_ROOTS_ARGS) { REFRACT_SPHERE_ROOTS(2, sqrt2) }
#endif
#undef REFRACT_SPHERE_ROOTS
#undef REFRACT_ROOTS_ARGS

// The lanes' search over every sphere, in list order (eight lanes, one vector of eight
// doubles; lowered to 2 or 4 registers where the instruction set is narrower). Per sphere
// the arithmetic of REFRACT_SPHERE_ROOTS, with each lane's window ending at its best t so
// far, as the scalar search narrows it.
static_assert(kLanes == 8, "the lane kernel holds eight lanes");

#define REFRACT_SPHERE_LANES(TYPE, SQRT)                                                              \
    Lane8 ox, oy, oz, dx, dy, dz, best, idx, leave;                                                \
    std::memcpy(&ox, origin.x.v, sizeof ox);                                                        \
    std::memcpy(&oy, origin.y.v, sizeof oy);                                                        \
    std::memcpy(&oz, origin.z.v, sizeof oz);                                                        \
    std::memcpy(&dx, dir.x.v, sizeof dx);                                                           \
    std::memcpy(&dy, dir.y.v, sizeof dy);                                                           \
    std::memcpy(&dz, dir.z.v, sizeof dz);                                                           \
    std::memcpy(&best, best_io, sizeof best);                                                       \
    std::memcpy(&idx, index_io, sizeof idx);                                                        \
    std::memcpy(&leave, leaving, sizeof leave);                                                     \
    Mask8 on, won = Mask8{};                                                                        \
    for (int l = 0; l < 8; ++l) on[l] = ((active >> l) & 1u) ? -1 : 0;                              \
    const Lane8 lo = t_min - Lane8{}, zero = Lane8{};                                               \
    for (std::size_t k = 0; k < n; ++k) {                                                           \
        const Lane8 ocx = ox - cx[k], ocy = oy - cy[k], ocz = oz - cz[k];                           \
        Lane8 b = ocx * dx + ocy * dy;                                                              \
        b = b + ocz * dz;                                                                           \
        Lane8 c = ocx * ocx + ocy * ocy;                                                            \
        c = c + ocz * ocz;                                                                          \
        c = c - r2[k];                                                                              \
        const Lane8 disc = b * b - c;                                                               \
        Lane8 sq;                                                                                   \
        REFRACT_SQRT8(TYPE, SQRT, disc, sq)                                                         \
        const Lane8 near = -b - sq, far = -b + sq;                                                  \
        const Lane8 t = (near > lo) & (near < best) ? near : far;                                   \
        const Lane8 kd = static_cast<double>(k) - Lane8{};                                          \
        const Mask8 ok = on & (t > lo) & (t < best) & ~((leave == kd) & (b > zero));                \
        best = ok ? t : best;                                                                       \
        idx = ok ? kd : idx;                                                                        \
        won = won | ok;                                                                             \
    }                                                                                               \
    std::memcpy(best_io, &best, sizeof best);                                                       \
    std::memcpy(index_io, &idx, sizeof idx);                                                        \
    std::uint32_t won_bits = 0;                                                                     \
    for (int l = 0; l < 8; ++l) won_bits |= won[l] ? 1u << l : 0u;                                  \
    if (won_bits) {                                                                                 \
        /* sphere_hit: the point r.at(t), the normal ((p − c)/radius).normalized() */               \
        Lane8 qx, qy, qz, rad;                                                                      \
        for (int l = 0; l < 8; ++l) {                                                               \
            const std::size_t k = won[l] ? static_cast<std::size_t>(idx[l]) : 0;                    \
            qx[l] = cx[k];                                                                          \
            qy[l] = cy[k];                                                                          \
            qz[l] = cz[k];                                                                          \
            rad[l] = radius[k];                                                                     \
        }                                                                                           \
        const Lane8 px = ox + best * dx, py = oy + best * dy, pz = oz + best * dz;                  \
        const Lane8 nx = (px - qx) / rad, ny = (py - qy) / rad, nz = (pz - qz) / rad;               \
        Lane8 len2 = nx * nx + ny * ny;                                                             \
        len2 = len2 + nz * nz;                                                                      \
        Lane8 len;                                                                                  \
        REFRACT_SQRT8(TYPE, SQRT, len2, len)                                                        \
        const Lane8 ux = nx / len, uy = ny / len, uz = nz / len;                                    \
        std::memcpy(point_io, &px, sizeof px);                                                      \
        std::memcpy(point_io + 8, &py, sizeof py);                                                  \
        std::memcpy(point_io + 16, &pz, sizeof pz);                                                 \
        std::memcpy(normal_io, &ux, sizeof ux);                                                     \
        std::memcpy(normal_io + 8, &uy, sizeof uy);                                                 \
        std::memcpy(normal_io + 16, &uz, sizeof uz);                                                \
    }                                                                                               \
    return won_bits;

#define REFRACT_LANES_ARGS                                                                               \
    const double *cx, const double *cy, const double *cz, const double *r2, std::size_t n,               \
        const double *radius, const LaneVec3 &origin, const LaneVec3 &dir, std::uint32_t active, double t_min, \
        double *best_io, double *index_io, const double *leaving, double *point_io, double *normal_io

using LanesFn = std::uint32_t (*)(REFRACT_LANES_ARGS);

#if defined(__x86_64__)
std::uint32_t lanes_baseline(REFRACT_LANES_ARGS) { REFRACT_SPHERE_LANES(__m128d, _mm_sqrt_pd) }
__attribute__((target("avx2"))) std::uint32_t lanes_avx2(REFRACT_LANES_ARGS) { REFRACT_SPHERE_LANES(__m256d, _mm256_sqrt_pd) }
REFRACT_AVX512_BEGIN
__attribute__((target("avx512f"))) std::uint32_t lanes_avx512f(REFRACT_LANES_ARGS) {
    REFRACT_SPHERE_LANES(__m512d, _mm512_sqrt_pd)
}
REFRACT_AVX512_END
#else
std::uint32_t lanes_baseline(REFRACT_LANES_ARGS) { REFRACT_SPHERE_LANES(double, std::sqrt) }
#endif
#undef REFRACT_SPHERE_LANES
#undef REFRACT_LANES_ARGS

#if defined(__x86_64__)
LanesFn lanes_function(SlabIsa isa) { return simd::variant<LanesFn>(isa, lanes_baseline, lanes_avx2, lanes_avx512f); }
RootsFn roots_function(SlabIsa isa) { return simd::variant<RootsFn>(isa, roots_baseline, roots_avx2, roots_avx512f); }
#else
LanesFn lanes_function(SlabIsa) { return lanes_baseline; }
RootsFn roots_function(SlabIsa) { return roots_baseline; }
#endif

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
    r2_.resize(padded, nan);
    r_.resize(padded, nan);
    cx_[n] = s.center.x();
    cy_[n] = s.center.y();
    cz_[n] = s.center.z();
    r2_[n] = s.radius * s.radius;
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
    roots_fn()(cx_.data(), cy_.data(), cz_.data(), r2_.data(), n, r, t_min, t_max, t, b);
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
    io.hit.bits = lanes_fn()(cx_.data(), cy_.data(), cz_.data(), r2_.data(), spheres_.size(), r_.data(), origin, dir,
                         active.bits, t_min, io.best.v, idx, leave, point, normal);
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
