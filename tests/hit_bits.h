#pragma once
// Bit-for-bit comparison of hits, for the tests that hold a faster intersection to the
// reference one's exact result (test_plane_set.cpp, test_facet_graph.cpp).
#include <cstdint>
#include <cstring>
#include <optional>

#include "geometry/shapes.h"

namespace refract::test {

inline std::uint64_t bits(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

// The same hit: t, point, normal and facet equal to the last bit, or both none.
inline bool identical(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    for (int i = 0; i < 3; ++i)
        if (bits(a->point[i]) != bits(b->point[i]) || bits(a->normal[i]) != bits(b->normal[i])) return false;
    return bits(a->t) == bits(b->t) && a->facet == b->facet;
}

}  // namespace refract::test
