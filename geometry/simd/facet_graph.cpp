// The facet graph's test of the planes around two facets (see geometry/facet_graph.h):
// written once over xsimd's batch of W doubles (geometry/simd/batch.h), compiled once per
// instruction set (geometry/simd.h). Each plane's arithmetic is the slab loop's
// ((n_x v_x + n_y v_y) + n_z v_z, d − n·o, their quotient) without contraction into FMA, so
// equal inputs give equal bits.
#include <refract/geometry/lanes.h>
#include <refract/geometry/simd.h>
#include <refract/geometry/simd/batch.h>

namespace refract::simd {

namespace {

// Whether plane (nx, ny, nz, d; index i) contradicts, in each lane, the candidate leaving hit
// at t_g on plane g of the ray (o, v): an entering plane whose t is past t_min, a leaving
// plane whose t is before t_g or equal to it with a smaller index, a plane parallel to the ray.
template <class A>
[[gnu::always_inline]] inline Mask<A> contradiction(const Batch<A>& nx, const Batch<A>& ny, const Batch<A>& nz,
                                                    const Batch<A>& d, const Batch<A>& i, const Vec3Batch<A>& o,
                                                    const Vec3Batch<A>& v, const Batch<A>& t_min,
                                                    const Batch<A>& t_g, const Batch<A>& g) {
    const Batch<A> zero(0.0);
    const Batch<A> denom = (nx * v.x + ny * v.y) + nz * v.z;
    const Batch<A> dist = d - ((nx * o.x + ny * o.y) + nz * o.z);
    const Batch<A> t = dist / denom;
    const Mask<A> entering = denom < zero, leaving = denom > zero;
    const Mask<A> parallel = ~(entering | leaving), enters_late = ~(t <= t_min), before_g = ~(t >= t_g),
                  leaves_early = before_g | ((t == t_g) & (i < g));
    return parallel | (entering & enters_late) | (leaving & leaves_early);
}

}  // namespace

// W planes a step (n is a multiple of 8).
template <class A>
bool contradicts(const double* nx, const double* ny, const double* nz, const double* d, const double* index,
                 std::size_t n, const double* o, const double* v, double t_min, double t_g, double g) {
    using B = Batch<A>;
    constexpr std::size_t W = B::size;
    const Vec3Batch<A> origin{B(o[0]), B(o[1]), B(o[2])}, dir{B(v[0]), B(v[1]), B(v[2])};
    const B lo(t_min), tg(t_g), gg(g);
    Mask<A> bad(false);
    for (std::size_t i = 0; i < n; i += W)
        bad = bad | contradiction<A>(B::load_unaligned(nx + i), B::load_unaligned(ny + i), B::load_unaligned(nz + i),
                                     B::load_unaligned(d + i), B::load_unaligned(index + i), origin, dir, lo, tg, gg);
    return xsimd::any(bad);
}

// W lanes a step, every plane for each.
template <class A>
std::uint32_t contradicts_lanes(const double* nx, const double* ny, const double* nz, const double* d,
                                const double* index, std::size_t n, const double* ox, const double* oy,
                                const double* oz, const double* vx, const double* vy, const double* vz, double t_min,
                                const double* t_g, const double* g, std::uint32_t mask) {
    using B = Batch<A>;
    constexpr std::size_t W = B::size;
    static_assert(kLanes % W == 0, "whole batches of lanes");
    const B lo(t_min);
    std::uint32_t bad_bits = 0;
    for (std::size_t l = 0; l < kLanes; l += W) {
        const Mask<A> on = mask_of<A>(mask >> l);
        if (!xsimd::any(on)) continue;
        const Vec3Batch<A> origin{B::load_unaligned(ox + l), B::load_unaligned(oy + l), B::load_unaligned(oz + l)};
        const Vec3Batch<A> dir{B::load_unaligned(vx + l), B::load_unaligned(vy + l), B::load_unaligned(vz + l)};
        const B tg = B::load_unaligned(t_g + l), gg = B::load_unaligned(g + l);
        Mask<A> bad(false);
        for (std::size_t i = 0; i < n; ++i)
            bad = bad | contradiction<A>(B(nx[i]), B(ny[i]), B(nz[i]), B(d[i]), B(index[i]), origin, dir, lo, tg, gg);
        bad_bits |= bits_of<A>(bad & on) << l;
    }
    return bad_bits;
}

template bool contradicts<REFRACT_SIMD_ARCH>(const double*, const double*, const double*, const double*,
                                             const double*, std::size_t, const double*, const double*, double, double,
                                             double);
template std::uint32_t contradicts_lanes<REFRACT_SIMD_ARCH>(const double*, const double*, const double*,
                                                            const double*, const double*, std::size_t, const double*,
                                                            const double*, const double*, const double*, const double*,
                                                            const double*, double, const double*, const double*,
                                                            std::uint32_t);

}  // namespace refract::simd
