#include <refract/geometry/facet_graph.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <refract/geometry/plane_set.h>
#include <refract/geometry/simd.h>

namespace refract {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Sutherland–Hodgman: the part of polygon `poly` (in one plane) where n·x <= d.
std::vector<Vec3> clip(const std::vector<Vec3>& poly, const Plane& p) {
    std::vector<Vec3> out;
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % n];
        const double da = p.offset - p.normal.dot(a), db = p.offset - p.normal.dot(b);
        if (da >= 0) out.push_back(a);
        if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

// The test of a block of planes against a candidate hit (FacetGraph::intersect and
// intersect_lanes): the kernels of geometry/simd/facet_graph.cpp, on the widest vector
// instructions the CPU runs, or the ones a test asked for (FacetGraph::use_isa).
using ContradictsFn = decltype(&simd::contradicts<simd::Sse2>);
using ContradictsLanesFn = decltype(&FacetGraph::intersect_lanes_of<simd::Sse2>);
struct Kernels {
    ContradictsFn one;
    ContradictsLanesFn lanes;
};
Kernels kernels_for(SlabIsa isa) {
    return {simd::variant<ContradictsFn>(isa, simd::contradicts<simd::Sse2>, simd::contradicts<simd::Avx2>,
                                         simd::contradicts<simd::Avx512f>),
            simd::variant<ContradictsLanesFn>(isa, &FacetGraph::intersect_lanes_of<simd::Sse2>,
                                              &FacetGraph::intersect_lanes_of<simd::Avx2>,
                                              &FacetGraph::intersect_lanes_of<simd::Avx512f>)};
}
std::atomic<ContradictsFn> one_in_use{nullptr};
std::atomic<ContradictsLanesFn> lanes_in_use{nullptr};
ContradictsFn contradicts_fn() {
    ContradictsFn f = one_in_use.load(std::memory_order_relaxed);
    if (!f) one_in_use.store(f = kernels_for(slab_isa()).one, std::memory_order_relaxed);
    return f;
}
ContradictsLanesFn lanes_fn() {
    ContradictsLanesFn f = lanes_in_use.load(std::memory_order_relaxed);
    if (!f) lanes_in_use.store(f = kernels_for(slab_isa()).lanes, std::memory_order_relaxed);
    return f;
}

}  // namespace

namespace {

// The polygon of plane g of c: a square of half-size h around the section of the sphere
// (centre, ·) clipped by every other plane; `unbounded` when it still touches the square.
struct Polygon {
    std::vector<Vec3> corners;
    bool unbounded = false;
};
Polygon facet_polygon(const ConvexPolyhedron& c, size_t g, const Vec3& centre, double h, double tolerance) {
    const Plane& pg = c.planes[g];
    const Vec3 nz = pg.normal;
    const Vec3 u = (std::abs(nz.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)).cross(nz).normalized();
    const Vec3 w = nz.cross(u);
    const Vec3 p0 = centre + (pg.offset - nz.dot(centre)) * nz;
    Polygon out;
    std::vector<Vec3> poly{p0 - h * u - h * w, p0 + h * u - h * w, p0 + h * u + h * w, p0 - h * u + h * w};
    for (size_t k = 0; k < c.planes.size() && !poly.empty(); ++k) {
        if (k == g) continue;
        const Plane& pk = c.planes[k];
        if (pk.normal.dot(nz) > 1 - 1e-12) {  // parallel, same side: coincident or one redundant
            if (pk.offset < pg.offset - tolerance) return out;
            continue;
        }
        poly = clip(poly, pk);
    }
    for (const Vec3& v : poly)
        out.unbounded = out.unbounded || !(std::abs((v - p0).dot(u)) < h * (1 - 1e-9) && std::abs((v - p0).dot(w)) < h * (1 - 1e-9));
    out.corners = std::move(poly);
    return out;
}

}  // namespace

FacetGraph::FacetGraph(const ConvexPolyhedron& c) {
    const size_t n = c.planes.size();
    neighbours_.resize(n);
    gap_.assign(n, 0.0);
    usable_.assign(n, 0);
    blocks_.resize(n);
    if (n < 4) return;
    Vec3 centre = c.bound_center;
    double R = c.bound_radius;
    if (!(R > 0)) {
        // No bounding sphere: the corners of every facet, from squares far larger than the
        // offsets, give one (an unbounded polyhedron has a facet that touches its square).
        double m = 1;
        for (const Plane& p : c.planes) m = std::max(m, std::abs(p.offset));
        const double h = 1e4 * m;
        std::vector<Vec3> corners;
        for (size_t g = 0; g < n; ++g) {
            const Polygon poly = facet_polygon(c, g, Vec3::Zero(), h, 1e-7 * h);
            if (poly.unbounded) return;
            corners.insert(corners.end(), poly.corners.begin(), poly.corners.end());
        }
        if (corners.empty()) return;
        Vec3 lo = corners.front(), hi = corners.front();
        for (const Vec3& v : corners) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        centre = 0.5 * (lo + hi);
        R = 0;
        for (const Vec3& v : corners) R = std::max(R, (v - centre).norm());
        R = R * (1 + 1e-6) + 1e-12;
    }
    const double scale = centre.norm() + R;
    tolerance_ = 1e-7 * scale;
    for (size_t g = 0; g < n; ++g) {
        const Polygon polygon = facet_polygon(c, g, centre, 2 * R, tolerance_);
        const std::vector<Vec3>& poly = polygon.corners;
        if (poly.size() < 3) continue;
        double extent = 0;
        for (const Vec3& v : poly) extent = std::max(extent, (v - poly[0]).norm());
        if (polygon.unbounded || extent < 100 * tolerance_) continue;
        double gap = kInf;
        for (size_t k = 0; k < n; ++k) {
            if (k == g) continue;
            double m = kInf;
            for (const Vec3& v : poly) m = std::min(m, c.planes[k].offset - c.planes[k].normal.dot(v));
            if (m <= tolerance_) neighbours_[g].push_back(static_cast<std::int32_t>(k));
            else gap = std::min(gap, m);
        }
        gap_[g] = gap;
        usable_[g] = 1;
        // The block: g and its neighbours, padded to a multiple of 8 with g itself (which
        // never contradicts a hit on g, nor a ray leaving g inward).
        std::vector<std::int32_t> closed = neighbours_[g];
        closed.push_back(static_cast<std::int32_t>(g));
        while (closed.size() % 8 != 0) closed.push_back(static_cast<std::int32_t>(g));
        Block& b = blocks_[g];
        b.neighbours = neighbours_[g].size();
        for (const std::int32_t k : closed) {
            const Plane& p = c.planes[static_cast<size_t>(k)];
            b.nx.push_back(p.normal.x());
            b.ny.push_back(p.normal.y());
            b.nz.push_back(p.normal.z());
            b.d.push_back(p.offset);
            b.index.push_back(static_cast<double>(k));
        }
    }
}

void FacetGraph::use_isa(SlabIsa isa) {
    const Kernels k = kernels_for(isa);
    one_in_use.store(k.one, std::memory_order_relaxed);
    lanes_in_use.store(k.lanes, std::memory_order_relaxed);
}

FacetGraph::Local FacetGraph::intersect(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max, int from,
                                        int guess) const {
    Local out;
    if (!usable(from) || !(t_min >= 0)) return out;
    if (misses_bound(c, r)) {
        out.decided = true;
        return out;
    }
    // The slab loop's arithmetic for one plane (shapes.cpp, intersect_scalar).
    const Plane& ps = c.planes[static_cast<size_t>(from)];
    const double denom_s = ps.normal.dot(r.dir);
    const double dist_s = ps.offset - ps.normal.dot(r.origin);
    if (denom_s > 0) {  // outward: the full pass's t_exit <= t_s
        out.decided = dist_s / denom_s <= t_min;
        return out;
    }
    if (!(denom_s < 0) || !(std::abs(dist_s) <= 0.25 * tolerance_) || !usable(guess)) return out;

    // The guess's own t, as the slab loop computes it: the candidate hit.
    const Plane& pg = c.planes[static_cast<size_t>(guess)];
    const double denom_g = pg.normal.dot(r.dir);
    const double t_g = (pg.offset - pg.normal.dot(r.origin)) / denom_g;
    if (!(denom_g > 0) || !(t_g > t_min)) return out;
    // No plane around `from` or `guess` may contradict it: an entering plane's t past the
    // window's start, a leaving plane's t before t_g or equal to it with a smaller index,
    // a plane parallel to the ray.
    const double o[3] = {r.origin.x(), r.origin.y(), r.origin.z()};
    const double v[3] = {r.dir.x(), r.dir.y(), r.dir.z()};
    for (const int f : {from, guess}) {
        const Block& b = blocks_[static_cast<size_t>(f)];
        if (contradicts_fn()(b.nx.data(), b.ny.data(), b.nz.data(), b.d.data(), b.index.data(), b.nx.size(), o, v,
                             t_min, t_g, static_cast<double>(guess)))
            return out;
    }
    out.decided = true;
    if (t_g < t_max) out.hit = Hit{t_g, r.at(t_g), pg.normal, guess};
    return out;
}

FacetGraph::LocalLanes FacetGraph::intersect_lanes(const ConvexPolyhedron& c, const LaneVec3& o, const LaneVec3& v,
                                                   const LaneMask& active, double t_min, const Lanes& t_max, int from,
                                                   const std::array<std::int32_t, kLanes>& guess) const {
    return lanes_fn()(*this, c, o, v, active, t_min, t_max, from, guess);
}

}  // namespace refract
