// The lane type of a packet (geometry/lanes.h): every operation gives, in every lane, the
// scalar operation's result bit for bit (comparisons false where a lane is NaN, blends and
// square roots of -0, +0, infinities and NaN included), and a mask's lane i is its bit i.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <refract/geometry/lanes.h>
#include "tests/hit_bits.h"

using namespace refract;

namespace {

// Doubles with the awkward values often: ±0, ±inf, NaN, equal neighbours.
double awkward(std::mt19937_64& rng) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double special[] = {0.0, -0.0, inf, -inf, std::numeric_limits<double>::quiet_NaN(), 1.0, -1.0, 2.0};
    std::uniform_int_distribution<int> pick(0, 15);
    std::normal_distribution<double> n(0, 3);
    const int k = pick(rng);
    return k < 8 ? special[k] : n(rng);
}

}  // namespace

TEST_CASE("Lanes: comparisons, blends, square roots and the rest equal the scalar operations in every lane",
          "[geometry]") {
    using test::bits;
    std::mt19937_64 rng(26);
    long mismatches = 0, lanes = 0;
    for (int n = 0; n < 20000; ++n) {
        Lanes a, b;
        LaneMask m;
        for (int l = 0; l < kLanes; ++l) {
            a[l] = awkward(rng);
            b[l] = awkward(rng);
            m[l] = (rng() & 1) != 0;
        }
        const LaneMask lt = a < b, gt = a > b, ge = a >= b;
        const Lanes sel = select(m, a, b), root = sqrt(a), hi = max_of(a, b), lo = min_of(a, b), mag = abs(a),
                    minus = -a, quot = a / b;
        for (int l = 0; l < kLanes; ++l) {
            ++lanes;
            const double x = a[l], y = b[l];
            mismatches += lt[l] != (x < y) || gt[l] != (x > y) || ge[l] != (x >= y);
            mismatches += bits(sel[l]) != bits(m[l] ? x : y);
            mismatches += bits(root[l]) != bits(std::sqrt(x)) && !(std::isnan(root[l]) && std::isnan(std::sqrt(x)));
            mismatches += bits(hi[l]) != bits(x < y ? y : x) || bits(lo[l]) != bits(x < y ? x : y);
            mismatches += bits(mag[l]) != bits(std::abs(x)) || bits(minus[l]) != bits(-x);
            mismatches += bits(quot[l]) != bits(x / y) && !(std::isnan(quot[l]) && std::isnan(x / y));
        }
        // The bit layout: lane i is bit i, no bit beyond the lanes.
        std::uint32_t want = 0;
        for (int l = 0; l < kLanes; ++l) want |= (a[l] < b[l] ? 1u : 0u) << l;
        mismatches += lt.bits != want;
        mismatches += (lt.bits & ~LaneMask::kAll) != 0 || (ge.bits & ~LaneMask::kAll) != 0;
    }
    CHECK(lanes == 160000);
    CHECK(mismatches == 0);
}
