// The facet graph's test of the planes around two facets (see geometry/facet_graph.h):
// written once over xsimd's batch of W doubles (geometry/simd/batch.h), compiled once per
// instruction set (geometry/simd.h). Each plane's arithmetic is the slab loop's
// ((n_x v_x + n_y v_y) + n_z v_z, d − n·o, their quotient) without contraction into FMA, so
// equal inputs give equal bits.
#include <refract/geometry/facet_graph.h>
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

}  // namespace refract::simd

namespace refract {

// FacetGraph::intersect_lanes on this instruction set: its lane loops as wide as A's
// registers, the planes' test above inline; every call inside inlined (flatten), so that
// nothing compiled here is called from elsewhere.
template <class A>
[[gnu::flatten]] FacetGraph::LocalLanes FacetGraph::intersect_lanes_on(const ConvexPolyhedron& c, const LaneVec3& o,
                                                                     const LaneVec3& v, const LaneMask& active,
                                                                     double t_min, const Lanes& t_max, int from,
                                                                     const std::array<std::int32_t, kLanes>& guess) const {
    LocalLanes out;
    out.decided = out.hit = LaneMask::Constant(false);
    out.facet.fill(-1);
    if (!usable(from) || !(t_min >= 0)) return out;
    // intersect()'s steps on every lane: the bounding sphere (misses_bound) ...
    LaneMask live = active;
    if (c.bound_radius > 0) {
        const LaneVec3 oc = o - LaneVec3::broadcast(c.bound_center);
        const Lanes b = oc.dot(v);
        const Lanes q = oc.squaredNorm() - Lanes(c.bound_radius * c.bound_radius);
        const LaneMask miss = (q > Lanes(0.0)) && ((b > Lanes(0.0)) || (q > b * b));
        out.decided = active && miss;
        live = active && !miss;
    }
    // ... the starting facet's own plane: outward rays are decided by it ...
    const Plane& ps = c.planes[static_cast<size_t>(from)];
    const LaneVec3 ns = LaneVec3::broadcast(ps.normal);
    const Lanes denom_s = ns.dot(v);
    const Lanes dist_s = Lanes(ps.offset) - ns.dot(o);
    const LaneMask outward = live && (denom_s > Lanes(0.0));
    out.decided = out.decided || (outward && (Lanes(t_min) >= dist_s / denom_s));
    // ... inward ones by their guess's t, unless a plane around `from` or the guess
    // contradicts it.
    const double near = 0.25 * tolerance_;
    alignas(64) double gx[kLanes], gy[kLanes], gz[kLanes], gd[kLanes], gi[kLanes];
    LaneMask cand = live && (denom_s < Lanes(0.0));
    for (int l = 0; l < kLanes; ++l) {
        const int g = guess[static_cast<size_t>(l)];
        cand[l] = cand[l] && std::abs(dist_s[l]) <= near && usable(g);
        const Plane& pg = c.planes[static_cast<size_t>(cand[l] ? g : from)];
        gx[l] = pg.normal.x();
        gy[l] = pg.normal.y();
        gz[l] = pg.normal.z();
        gd[l] = pg.offset;
        gi[l] = static_cast<double>(cand[l] ? g : from);
    }
    if (!cand.any()) return out;
    LaneVec3 ng;
    for (int l = 0; l < kLanes; ++l) {
        ng.x[l] = gx[l];
        ng.y[l] = gy[l];
        ng.z[l] = gz[l];
    }
    Lanes dg;
    for (int l = 0; l < kLanes; ++l) dg[l] = gd[l];
    const Lanes denom_g = ng.dot(v);
    const Lanes t_g = (dg - ng.dot(o)) / denom_g;
    cand = cand && (denom_g > Lanes(0.0)) && (t_g > Lanes(t_min));
    if (!cand.any()) return out;
    // The lanes of m against the first n planes of f's block (vectorised over the lanes: no
    // padding): those it contradicts.
    const auto contradicted = [&](int f, size_t n, std::uint32_t m) {
        const Block& b = blocks_[static_cast<size_t>(f)];
        return simd::contradicts_lanes<A>(b.nx.data(), b.ny.data(), b.nz.data(), b.d.data(), b.index.data(), n, o.x.v,
                                      o.y.v, o.z.v, v.x.v, v.y.v, v.z.v, t_min, t_g.v, gi, m);
    };
    std::uint32_t bad = contradicted(from, blocks_[static_cast<size_t>(from)].neighbours + 1, cand.bits);
    // Each guess's block, for the lanes that took it: its neighbours (g's own plane gives
    // t_g itself, the same arithmetic, which never contradicts it).
    for (std::uint32_t left = cand.bits; left != 0;) {
        const int g = guess[static_cast<size_t>(__builtin_ctz(left))];
        std::uint32_t same = 0;
        for (int k = 0; k < kLanes; ++k) same |= ((left >> k) & 1u) && guess[static_cast<size_t>(k)] == g ? 1u << k : 0u;
        left &= ~same;
        bad |= contradicted(g, blocks_[static_cast<size_t>(g)].neighbours, same);
    }
    LaneMask ok;
    ok.bits = cand.bits & ~bad;
    out.decided = out.decided || ok;
    out.hit = ok && (t_g < t_max);
    for (int l = 0; l < kLanes; ++l)
        if (ok[l]) out.facet[static_cast<size_t>(l)] = guess[static_cast<size_t>(l)];
    out.t = t_g;
    out.point = o + t_g * v;
    return out;
}


template FacetGraph::LocalLanes FacetGraph::intersect_lanes_on<REFRACT_SIMD_ARCH>(
    const ConvexPolyhedron&, const LaneVec3&, const LaneVec3&, const LaneMask&, double, const Lanes&, int,
    const std::array<std::int32_t, kLanes>&) const;

}  // namespace refract

namespace refract::simd {

template bool contradicts<REFRACT_SIMD_ARCH>(const double*, const double*, const double*, const double*,
                                             const double*, std::size_t, const double*, const double*, double, double,
                                             double);
template std::uint32_t contradicts_lanes<REFRACT_SIMD_ARCH>(const double*, const double*, const double*,
                                                            const double*, const double*, std::size_t, const double*,
                                                            const double*, const double*, const double*, const double*,
                                                            const double*, double, const double*, const double*,
                                                            std::uint32_t);

}  // namespace refract::simd
