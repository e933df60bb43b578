// The sphere set's kernels (see geometry/sphere_set.h): written once over xsimd's batch of W
// doubles (geometry/simd/batch.h), compiled once per instruction set (geometry/simd.h). The
// arithmetic is the scalar test's: b and the discriminant are sphere_quadratic's
// (geometry/shapes.h, instantiated here on the batches), the roots −b ∓ √disc, the point
// r.at(t) and the normal ((p − c) / radius).normalized() of sphere_hit, operation by
// operation, without contraction into FMA.
#include <limits>

#include <refract/geometry/shapes.h>
#include <refract/geometry/simd.h>
#include <refract/geometry/simd/batch.h>

namespace refract::simd {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

// W spheres a step: the nearer root in (t_min, t_max), else the farther one, else +inf (a
// negative discriminant gives NaN roots, which no window accepts).
template <class A>
void sphere_roots(const double* cx, const double* cy, const double* cz, const double* radius, std::size_t n,
                  const double* o, const double* v, double t_min, double t_max, double* t_out, double* b_out) {
    using B = Batch<A>;
    constexpr std::size_t W = B::size;
    const Vec3Batch<A> origin{B(o[0]), B(o[1]), B(o[2])}, dir{B(v[0]), B(v[1]), B(v[2])};
    const B lo(t_min), hi(t_max), inf(kInfinity);
    for (std::size_t i = 0; i < n; i += W) {
        const Vec3Batch<A> centre{B::load_unaligned(cx + i), B::load_unaligned(cy + i), B::load_unaligned(cz + i)};
        const auto [b, disc] = sphere_quadratic(origin - centre, dir, B::load_unaligned(radius + i));
        const B sq = xsimd::sqrt(disc);
        const B near = neg(b) - sq, far = neg(b) + sq;
        const B t = xsimd::select((near > lo) & (near < hi), near, far);
        xsimd::select((t > lo) & (t < hi), t, inf).store_unaligned(t_out + i);
        b.store_unaligned(b_out + i);
    }
}

// The lanes' search, W lanes at a time, over every sphere in list order: per sphere the
// arithmetic of sphere_roots, with each lane's window ending at its best t so far, as the
// scalar search narrows it.
template <class A>
std::uint32_t sphere_lanes(const double* cx, const double* cy, const double* cz, const double* radius,
                           std::size_t n, const double* ox, const double* oy, const double* oz, const double* vx,
                           const double* vy, const double* vz, std::uint32_t active, double t_min, double* best_io,
                           double* index_io, const double* leaving, double* point_io, double* normal_io) {
    using B = Batch<A>;
    constexpr std::size_t W = B::size;
    static_assert(kLanes % W == 0, "whole batches of lanes");
    const B lo(t_min), zero(0.0);
    std::uint32_t won_bits = 0;
    for (std::size_t l = 0; l < kLanes; l += W) {
        const Mask<A> on = mask_of<A>(active >> l);
        if (!xsimd::any(on)) continue;
        const Vec3Batch<A> origin{B::load_unaligned(ox + l), B::load_unaligned(oy + l), B::load_unaligned(oz + l)};
        const Vec3Batch<A> dir{B::load_unaligned(vx + l), B::load_unaligned(vy + l), B::load_unaligned(vz + l)};
        const B leave = B::load_unaligned(leaving + l);
        B best = B::load_unaligned(best_io + l), idx = B::load_unaligned(index_io + l);
        Mask<A> won(false);
        for (std::size_t k = 0; k < n; ++k) {
            const Vec3Batch<A> centre{B(cx[k]), B(cy[k]), B(cz[k])};
            const auto [b, disc] = sphere_quadratic(origin - centre, dir, B(radius[k]));
            const B sq = xsimd::sqrt(disc);
            const B near = neg(b) - sq, far = neg(b) + sq;
            const B t = xsimd::select((near > lo) & (near < best), near, far);
            const B kd(static_cast<double>(k));
            const Mask<A> ok = on & (t > lo) & (t < best) & ~((leave == kd) & (b > zero));
            best = xsimd::select(ok, t, best);
            idx = xsimd::select(ok, kd, idx);
            won = won | ok;
        }
        best.store_unaligned(best_io + l);
        idx.store_unaligned(index_io + l);
        if (!xsimd::any(won)) continue;
        const std::uint32_t won_here = bits_of<A>(won);
        won_bits |= won_here << l;
        // sphere_hit: the point r.at(t), the normal ((p − c) / radius).normalized().
        alignas(64) double qx[W], qy[W], qz[W], rad[W];
        for (std::size_t j = 0; j < W; ++j) {
            const std::size_t k = (won_here >> j) & 1u ? static_cast<std::size_t>(index_io[l + j]) : 0;
            qx[j] = cx[k];
            qy[j] = cy[k];
            qz[j] = cz[k];
            rad[j] = radius[k];
        }
        const B r = B::load_aligned(rad);
        const Vec3Batch<A> p{origin.x + best * dir.x, origin.y + best * dir.y, origin.z + best * dir.z};
        const Vec3Batch<A> d = p - Vec3Batch<A>{B::load_aligned(qx), B::load_aligned(qy), B::load_aligned(qz)};
        const Vec3Batch<A> u{d.x / r, d.y / r, d.z / r};
        const B len = xsimd::sqrt(u.squaredNorm());
        p.x.store_unaligned(point_io + l);
        p.y.store_unaligned(point_io + kLanes + l);
        p.z.store_unaligned(point_io + 2 * kLanes + l);
        (u.x / len).store_unaligned(normal_io + l);
        (u.y / len).store_unaligned(normal_io + kLanes + l);
        (u.z / len).store_unaligned(normal_io + 2 * kLanes + l);
    }
    return won_bits;
}

template void sphere_roots<REFRACT_SIMD_ARCH>(const double*, const double*, const double*, const double*,
                                              std::size_t, const double*, const double*, double, double, double*,
                                              double*);
template std::uint32_t sphere_lanes<REFRACT_SIMD_ARCH>(const double*, const double*, const double*, const double*,
                                                       std::size_t, const double*, const double*, const double*,
                                                       const double*, const double*, const double*, std::uint32_t,
                                                       double, double*, double*, const double*, double*, double*);

}  // namespace refract::simd
