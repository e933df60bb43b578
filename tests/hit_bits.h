#pragma once
// Bit-for-bit comparison of hits, for the tests that hold a faster intersection to the
// reference one's exact result (test_plane_set.cpp, test_facet_graph.cpp), and the random
// directions their rays take.
#include <cstdint>
#include <cstring>
#include <optional>
#include <random>

#include <refract/geometry/shapes.h>

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

// A direction uniform on the unit sphere.
inline Vec3 random_direction(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    for (;;) {
        const Vec3 v(n(rng), n(rng), n(rng));
        if (v.norm() > 1e-6) return v.normalized();
    }
}

// Lane l of a packet test (geometry/shapes.h intersect_lanes) as the one-ray test returns it.
inline std::optional<Hit> lane_hit(const LaneShapeHits& h, int l) {
    if (!h.hit[l]) return std::nullopt;
    return Hit{h.t[l], h.point.lane(l), h.normal.lane(l), -1};
}

}  // namespace refract::test
