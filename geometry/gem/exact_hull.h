#pragma once
// The exact convex polyhedron of a set of half-spaces, shared by the gem builders
// (brilliant.cpp, gemcad_build.cpp): CGAL's exact kernel (Exact_predicates_exact_constructions)
// and CGAL::halfspace_intersection_3, one polygon per plane, then the conversion to the
// double Gem (shared vertices, unit planes, fan triangles). Only geometry/gem/ includes this
// header: it brings CGAL's kernel with it.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <string>
#include <vector>

#include <refract/geometry/gem/brilliant.h>

namespace refract::exact {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using P3 = K::Point_3;
using V3 = K::Vector_3;
using Pl = K::Plane_3;
using Loop = std::vector<P3>;
// Exact points in lexicographic order (maps keyed by a vertex).
struct LessPoint {
    bool operator()(const P3& a, const P3& b) const { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; }
};

// The nearest double of an exact number (forces the exact value, so the lazy interval is tight).
double dbl(const FT& x);

// cos and sin of an angle in degrees, reduced to the first quadrant so that the four
// quadrants are exact mirror images and multiples of 90° are exact.
struct Dir {
    double c, s;
};
Dir unit(double deg);

// Called with a one-line reason when the construction is degenerate; must throw.
using Fail = void (*)(const std::string& why);

// The faces of the intersection of the planes' negative sides, `inside` strictly inside every
// one: loops[i] is plane i's face, counter-clockwise seen from outside, repeated and collinear
// vertices dropped; empty when the plane touches the solid in no polygon (or repeats an
// earlier plane). The solid must be bounded (callers add bounding planes when unsure).
std::vector<Loop> facet_loops(const std::vector<Pl>& planes, const P3& inside, Fail fail);

// Appends facet f (its vertex_ids and polygon filled) to `gem`: fanned into triangles, its
// plane and label added to the solid.
void append_facet(Gem& gem, GemFacet f);

// Appends the non-empty loops to `gem` as facets in plane order: exactly equal points become
// one vertex, planes become unit doubles, each facet is fanned into triangles.
void append_facets(Gem& gem, const std::vector<Pl>& planes, const std::vector<std::string>& labels,
                   const std::vector<Loop>& loops);

}  // namespace refract::exact
