// Image measurements (refract measure; the validation profiles sample through them).
#include <catch2/catch.hpp>

#include <cmath>

#include <refract/geometry/error.h>
#include <refract/validation/compare.h>
#include <refract/validation/measure.h>

using namespace refract;
using namespace refract::validation;

TEST_CASE("Region statistics: mean, sum, min and max over a rectangle and a mask", "[measure]") {
    Image img(4, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) img.set(x, y, Vec3(x, y, x + 10 * y));
    const RegionStats all = region_stats(img, {0, 0, 3, 2});
    CHECK(all.pixels == 12);
    CHECK(all.channel[0].mean == 1.5);
    CHECK(all.channel[1].sum == 12.0);
    CHECK(all.channel[2].min == 0.0);
    CHECK(all.channel[2].max == 23.0);
    const RegionStats corner = region_stats(img, {3, 2, 1, 1});  // corners in any order
    CHECK(corner.pixels == 6);
    CHECK(corner.channel[0].mean == 2.0);
    Image mask(4, 3);
    mask.set(2, 1, Vec3(1, 1, 1));
    const RegionStats one = region_stats(img, {0, 0, 3, 2}, &mask);
    CHECK(one.pixels == 1);
    CHECK(one.channel[2].mean == 12.0);
    CHECK_THROWS_AS(region_stats(img, {10, 10, 12, 12}), InputError);
    Image small(2, 2);
    CHECK_THROWS_WITH(region_stats(img, {0, 0, 3, 2}, &small), Catch::Contains("mask"));
}

TEST_CASE("Radial profile: rings of an image that holds its own distance from the centre", "[measure]") {
    Image img(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) img.set(x, y, Vec3::Constant(std::hypot(x + 0.5 - 32, y + 0.5 - 32)));
    const auto bins = radial_profile(img, 32, 32, 8, 32);
    REQUIRE(bins.size() == 8);
    for (const auto& b : bins) {
        CHECK(b.pixels > 0);
        CHECK(b.mean.x() >= b.r0);
        CHECK(b.mean.x() < b.r1);
    }
    // Ring areas grow with the radius: about π(r1² − r0²) pixels.
    CHECK(bins[7].pixels == Approx(M_PI * (32.0 * 32 - 28.0 * 28)).epsilon(0.05));
}

TEST_CASE("Line profile: the values along a line of pixels, outside pixels refused", "[measure]") {
    Image img(5, 5);
    for (int k = 0; k < 5; ++k) img.set(k, k, Vec3(k, 0, 0));
    const auto v = values_at(img, line_pixels(0, 0, 4, 4));
    REQUIRE(v.size() == 5);
    for (int k = 0; k < 5; ++k) CHECK(v[static_cast<size_t>(k)].x() == k);
    CHECK_THROWS_WITH(values_at(img, {{5, 0}}), Catch::Contains("(5, 0)"));
}

TEST_CASE("Angle histogram of a far-field map: the power is kept, and about the opposite axis the bins mirror",
          "[measure][far-field]") {
    // A synthetic equal-area map (12 azimuth × 10 polar bins about +z) whose intensity
    // grows with the row; each pixel spans 4π/120 sr.
    Channels map;
    map.width = 12;
    map.height = 10;
    map.names = {"total"};
    for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 12; ++i) map.data.push_back(1.0 + j);
    map.attributes = {{"refract:far_field", "sphere"}, {"refract:far_field_axis", "0 0 1"},
                      {"refract:far_field_reference", "1 0 0"}};
    double total = 0;
    for (double v : map.data) total += v * 4 * M_PI / 120;
    const auto up = angle_histogram(map, "map.exr", 7), down = angle_histogram(map, "map.exr", 7, Vec3(0, 0, -1));
    double sum = 0;
    for (size_t b = 0; b < up.size(); ++b) {
        sum += up[b].power[0];
        CHECK(up[b].power[0] == Approx(down[up.size() - 1 - b].power[0]).epsilon(1e-12));
        CHECK(up[b].intensity[0] == Approx(up[b].power[0] / up[b].solid_angle).epsilon(1e-12));
    }
    CHECK(sum == Approx(total).epsilon(1e-12));
    // About its own axis, whole rows land in a bin: row centres at θ = acos(0.9) = 25.8° and
    // acos(0.7) = 45.6° in the second bin (25.7°–51.4°), none in the first.
    CHECK(up[0].pixels == 0);
    CHECK(up[1].pixels == 24);
    CHECK(up[1].power[0] == Approx((1.0 + 2.0) * 12 * 4 * M_PI / 120).epsilon(1e-12));
    map.attributes[0].second = "axis";
    CHECK_THROWS_WITH(angle_histogram(map, "map.exr", 9), Catch::Contains("map.exr") && Catch::Contains("sphere"));
}
