#pragma once
// Facet-local intersection of a ray that starts on a facet of a convex plane set: the
// result of intersect(const ConvexPolyhedron&, ...) (geometry/shapes.h) to the last bit,
// from the planes around two facets instead of all of them.
//
// A ray leaving a hit on facet s of a bounded convex polyhedron (a reflection or a
// refraction inside a gem, a ray escaping it) is decided by few planes:
// - outward (n_s·v > 0): the leaving plane is at most s's own t, which is at or before
//   the window's start when the origin lies on s; then the full slab pass finds no hit
//   either (its t_exit <= t_s <= t_min), whatever the other planes;
// - inward, with a guess g of the facet it leaves through: the candidate is g's t, t_g.
//   It is the full pass's result when no plane touching s or g (s and g included)
//   contradicts it: no entering plane with t past t_min, no leaving plane with t before
//   t_g or equal to it with a smaller index, no plane parallel to the ray. Every other
//   plane k keeps a distance of at least `gap` > 0 from the facets s and g (their
//   polygons, computed once), so its t lies before s's (entering: t_k <= −gap) or after
//   t_g (leaving: t_k >= t_g + gap) by far more than rounding: the full pass's largest
//   entering t is at most t_min and its smallest leaving t is t_g, first attained by g. A
//   wrong guess, or any other doubt, leaves the ray undecided, and the caller runs the
//   full pass.
// Planes touching a facet are those within `tolerance` (1e-7 of the polyhedron's size)
// of one of its polygon's corners; a facet whose polygon is empty, degenerate or unbounded
// is not used (its rays take the full pass).
//
// The arithmetic of each plane is the slab loop's ((n_x v_x + n_y v_y) + n_z v_z, d − n·o,
// their quotient) without contraction into FMA (the files are compiled with
// -ffp-contract=off), so equal inputs give equal bits; the test over a facet's planes is
// vectorised (geometry/simd/facet_graph.cpp: AVX-512F, AVX2 or the SSE2 baseline, the best
// the CPU runs, chosen at run time).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <refract/geometry/lanes.h>
#include <refract/geometry/plane_set.h>
#include <refract/geometry/shapes.h>

namespace refract {

class FacetGraph {
public:
    // The polygons of every plane of c, clipped by all the others (O(n²) small clips),
    // within c's bounding sphere (one is found from the polygons when c has none). When c
    // is unbounded no facet is usable.
    explicit FacetGraph(const ConvexPolyhedron& c);
    // Every facet graph of the process from now on runs this variant of its vectorised test
    // (an unsupported one: the baseline); by default the best the CPU runs (tests compare
    // the variants).
    static void use_isa(SlabIsa isa);

    int facets() const { return static_cast<int>(neighbours_.size()); }
    bool usable(int f) const { return f >= 0 && f < facets() && usable_[static_cast<size_t>(f)]; }
    // The planes within tolerance of facet f's polygon, f excluded, in increasing index.
    const std::vector<std::int32_t>& neighbours(int f) const { return neighbours_[static_cast<size_t>(f)]; }
    // The smallest distance of another, non-neighbouring plane from facet f's polygon.
    double gap(int f) const { return gap_[static_cast<size_t>(f)]; }
    double tolerance() const { return tolerance_; }

    struct Local {
        bool decided = false;  // hit holds intersect(c, r, t_min, t_max)
        std::optional<Hit> hit;
    };
    // For a ray r whose origin is the point of a hit on facet `from` of c (the one c this
    // graph was built from), with `guess` the facet it is expected to leave through (-1:
    // none). t_min must be >= 0. Undecided when the ray runs along `from`, when a facet is
    // not usable, or when the guess is not the leaving facet.
    Local intersect(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max, int from, int guess) const;

    // The same on kLanes rays at once (a packet, geometry/lanes.h), all leaving facet `from`,
    // each with its own guess and window end t_max[lane]: in every lane of `active`,
    // intersect()'s answer bit for bit (`decided`; where decided, `hit` and the hit's t,
    // point and facet, whose outward normal is that facet's plane's).
    struct LocalLanes {
        LaneMask decided, hit;
        Lanes t;
        LaneVec3 point;
        std::array<std::int32_t, kLanes> facet;
    };
    LocalLanes intersect_lanes(const ConvexPolyhedron& c, const LaneVec3& origin, const LaneVec3& dir,
                               const LaneMask& active, double t_min, const Lanes& t_max, int from,
                               const std::array<std::int32_t, kLanes>& guess) const;
    // Its body, compiled once per instruction set A (geometry/simd/facet_graph.cpp), so that
    // the lane loops are as wide as the CPU's registers.
    template <class A>
    LocalLanes intersect_lanes_on(const ConvexPolyhedron& c, const LaneVec3& origin, const LaneVec3& dir,
                                  const LaneMask& active, double t_min, const Lanes& t_max, int from,
                                  const std::array<std::int32_t, kLanes>& guess) const;
    // The same as a plain function (a pointer to it is one word).
    template <class A>
    static LocalLanes intersect_lanes_of(const FacetGraph& g, const ConvexPolyhedron& c, const LaneVec3& origin,
                                         const LaneVec3& dir, const LaneMask& active, double t_min, const Lanes& t_max,
                                         int from, const std::array<std::int32_t, kLanes>& guess) {
        return g.intersect_lanes_on<A>(c, origin, dir, active, t_min, t_max, from, guess);
    }

private:
    std::vector<std::vector<std::int32_t>> neighbours_;
    // Per facet: its neighbours' planes and its own (in this order, then copies of its own
    // up to a multiple of 8 for the test vectorised over planes), by coordinate, with their
    // indices in c; `neighbours` of them are its neighbours'.
    struct Block {
        std::vector<double> nx, ny, nz, d, index;
        size_t neighbours = 0;
    };
    std::vector<Block> blocks_;
    std::vector<double> gap_;
    std::vector<char> usable_;
    double tolerance_ = 0;
};

}  // namespace refract
