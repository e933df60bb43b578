#pragma once
// A convex preform minus a convex notch, exactly (CGAL's Nef polyhedra): the machinery of a
// design with a cleft (gemcad.h, gemcad_build.cpp). Only geometry/gem/ includes this header:
// it brings CGAL's kernel with it (exact_hull.h).
#include <array>
#include <vector>

#include <refract/geometry/gem/exact_hull.h>

namespace refract::exact {

struct Difference {
    std::vector<std::array<P3, 3>> triangles;  // the result's boundary, counter-clockwise seen from outside
    int pieces = 0;                            // connected solids the result falls into
};

// `solid` minus `notch`, both bounded convex polyhedra given by their facet loops
// (facet_loops: counter-clockwise seen from outside, empty loops skipped), regularised
// (no dangling faces, edges or points), its boundary triangulated without new vertices.
// Calls `fail` when the result is not a simple closed 2-manifold.
Difference convex_difference(const std::vector<Loop>& solid, const std::vector<Loop>& notch, Fail fail);

}  // namespace refract::exact
