// grin-layers: the layered Luneburg stack (compat mode) converges to the continuous grin
// lens (physical mode) as the number of shells grows; the modes' floor is negligible.
#include <catch2/catch.hpp>

#include <cmath>

#include <refract/experiments/grin_layers.h>

using namespace refract::experiments;

TEST_CASE("A Luneburg lens as N constant-index shells converges to the continuous grin lens", "[experiments]") {
    CHECK(grin_layers::shell_index(1, 1) == Approx(std::sqrt(2 - 0.25)));
    CHECK(grin_layers::shell_index(8, 8) == Approx(std::sqrt(2 - (7.5 / 8) * (7.5 / 8))));
    ExperimentOptions opt;
    opt.quick = true;
    opt.threads = 2;
    const auto r = grin_layers::compute(opt);
    REQUIRE(r.series.size() == 2);
    const auto& sky = r.series[0];
    REQUIRE(sky.backdrop == "sky");
    REQUIRE(sky.rows.size() == 4);  // N = 2, 4, 8, 16
    // The difference on the lens's disk falls at every doubling of N, as N^-0.35 (measured
    // -0.35 over 2..16, -0.43 over 4..16: the staircase's turning rays).
    for (size_t k = 1; k < sky.rows.size(); ++k) CHECK(sky.rows[k].disk_mean < sky.rows[k - 1].disk_mean);
    CHECK(sky.disk_fit.slope < -0.25);
    CHECK(sky.disk_fit.slope > -0.6);
    CHECK(sky.rows.back().disk_mean < 0.7 * sky.rows.front().disk_mean);
    // The floor: a constant-index sphere in both modes differs by the float index only.
    CHECK(sky.floor_disk < 1e-7);
    CHECK(r.series[1].floor_disk == 0);
}
