// The grin experiment's studies (experiments/grin.h) in their quick configuration: real
// numbers from core/grin's advance(), against the closed forms and the published ranges the
// summary states.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <refract/experiments/grin.h>

using namespace refract::experiments::grin_media;

TEST_CASE("grin experiment: the lenses focus as their closed forms say and the parabolic rod does not",
          "[experiments][grin]") {
    const LuneburgStudy L = luneburg_study(true);
    INFO("Luneburg spot " << L.spot_radius << " R");
    CHECK(L.rays == 11);
    CHECK(L.spot_radius < 1e-9);
    CHECK(L.direction_error < 1e-9);
    const FishEyeStudy F = fisheye_study(true);
    INFO("fish-eye image " << F.image_error << ", circle " << F.circle_error);
    CHECK(F.image == -2.0);
    CHECK(F.image_error < 1e-8);
    CHECK(F.circle_error < 1e-8);
    const RodStudy R = rod_study(true);
    INFO("sech " << R.sech_spot << ", parabolic " << R.parabolic_spot);
    CHECK(R.sech_spot < 1e-9);
    CHECK(R.parabolic_spot > 1e-3);  // the parabolic rod's period depends on the angle
    const GridStudy G = grid_study(true);
    INFO("paraxial " << G.paraxial_magnification << ", axis " << G.axis_magnification << ", corner "
                     << G.corner_magnification);
    CHECK(G.points.size() == 9);
    CHECK(G.paraxial_magnification < 0);  // an inverted image
    CHECK(std::abs(G.axis_magnification / G.paraxial_magnification - 1) < 0.01);
}

TEST_CASE("grin experiment: the setting sun is flattened to about 0.8 and its green limb stands 10-20 arcsec above "
          "the red",
          "[experiments][grin]") {
    const SunStudy S = sun_study(true);
    REQUIRE(S.rows.size() == 3);
    INFO("ratio at the horizon " << S.rows[0].ratio << " (Bennett " << S.rows[0].ratio_bennett << ")");
    CHECK(S.rows[0].ratio > 0.75);
    CHECK(S.rows[0].ratio < 0.9);
    CHECK(std::abs(S.rows[0].ratio - S.rows[0].ratio_bennett) < 0.02);
    CHECK(S.rows[2].ratio > S.rows[0].ratio);
    CHECK(S.rows[0].horizontal_arcmin == Approx(2 * S.semidiameter_arcmin).epsilon(1e-3));
    REQUIRE(!S.limbs.empty());
    INFO("green - red at the horizon " << S.limbs[0].traced_arcsec << "\" against " << S.limbs[0].integral_arcsec << "\"");
    CHECK(S.limbs[0].traced_arcsec > 10);
    CHECK(S.limbs[0].traced_arcsec < 20);
    CHECK(std::abs(S.limbs[0].traced_arcsec - S.limbs[0].integral_arcsec) < 0.01);
}

TEST_CASE("grin experiment: a hot road shows an inverted image under an erect one, a cold sea's inversion lifts the "
          "hidden part of a ship into view",
          "[experiments][grin]") {
    const MirageStudy road = mirage_study(true, true);
    REQUIRE(road.branches.size() == 2);
    CHECK(road.branches[0].inverted());
    CHECK_FALSE(road.branches[1].inverted());
    INFO("vanishing line " << road.lowest_seen << " m, without the layer " << road.lowest_seen_standard << " m");
    CHECK(road.lowest_seen > 0.2);   // the fold: nothing lower is seen at 600 m
    CHECK(road.lowest_seen < 0.5);
    CHECK(road.ground_onset_deg < -0.3);  // only rays steeper than ~0.3 degrees meet the road
    const MirageStudy sea = mirage_study(false, true);
    bool inverted = false;
    for (const MirageBranch& b : sea.branches) inverted = inverted || b.inverted();
    CHECK(inverted);
    INFO("lowest seen " << sea.lowest_seen << " m, without the inversion " << sea.lowest_seen_standard << " m");
    CHECK(sea.lowest_seen < sea.lowest_seen_standard - 10);
}

TEST_CASE("grin experiment's rendered mirage: the ball 500 m down a hot road shows an inverted image under it, "
          "through the renderer's own walk",
          "[experiments][grin]") {
    const std::vector<ViewStudy> views = view_study(true, 2);
    REQUIRE(views.size() == 5);
    // The superior mirage's view: the ship over the cold sea seen upside down.
    REQUIRE(views[2].name == "sea_view");
    const ShipImage ship = ship_image(views[2]);
    INFO("ship rows: red " << ship.red_top << "-" << ship.red_bottom << ", white " << ship.white_top << "-"
                           << ship.white_bottom);
    CHECK(ship.seen);
    CHECK(ship.inverted);
    for (const ViewStudy& v : views) {
        CHECK(v.finite);
        CHECK(v.grin_exhausted == 0);
        CHECK(v.grin_evaluations > 10 * v.grin_segments);
    }
    // The road view's middle column, top to bottom: the red rows are the ball and, joined to it
    // at the mirage line, its inverted image: the red falls towards the ball's unlit underside
    // and rises again below, where the mirage shows that underside upside down, shorter.
    const refract::Image& im = views[1].image;
    std::vector<double> red;  // the red channel over the one run of red rows
    int runs = 0;
    bool in_run = false;
    for (int j = 0; j < im.height; ++j) {
        const refract::Vec3 c = im.at(im.width / 2, j);
        const bool is_red = c.x() > 4 * c.y() && c.x() > 0.05;
        if (is_red && !in_run) ++runs;
        if (is_red && runs == 1) red.push_back(c.x());
        in_run = is_red;
    }
    REQUIRE(runs == 1);
    REQUIRE(red.size() >= 6);
    const size_t k = static_cast<size_t>(std::min_element(red.begin() + 1, red.end() - 1) - red.begin());
    const double above = *std::max_element(red.begin(), red.begin() + static_cast<long>(k));
    const double below = *std::max_element(red.begin() + static_cast<long>(k) + 1, red.end());
    INFO("red rows " << red.size() << ", the minimum at row " << k << " of the run");
    CHECK(red[k] < 0.75 * above);
    CHECK(red[k] < 0.75 * below);
    CHECK(red.size() - k - 1 < k);  // the inverted image is compressed
}

TEST_CASE("grin experiment's heat shimmer: the target's apparent displacement is linear in the plume's temperature "
          "amplitude, and the field read back from OpenVDB is the one sampled",
          "[experiments][grin][grid]") {
    const ShimmerStudy s = shimmer_study(true, 2);
    REQUIRE(s.rows.size() >= 3);
    INFO("exponent " << s.exponent << ", rms at " << s.rows.front().amplitude_K << " K " << s.rows.front().rms_displacement
                     << " m");
    CHECK(std::abs(s.exponent - 1.0) < 0.05);
    // 0.1–1 mm on the target 55 m away per kelvin: tens of µrad, the size of real shimmer.
    CHECK(s.rows.front().rms_displacement > 1e-5);
    CHECK(s.rows.back().rms_displacement < 1e-2);
    CHECK(s.vdb_dims_match);
    CHECK(s.vdb_max_index_difference < 1e-12);
    CHECK(s.view.finite);
    CHECK(s.view.grin_exhausted == 0);
    CHECK(s.view.grin_segments > 0);
}

TEST_CASE("grin experiment's rendered sunset: the spectral eye pass from inside the air splits the sun's upper limb, "
          "blue above red by tens of arcseconds",
          "[experiments][grin]") {
    const std::vector<ViewStudy> views = sunset_views(true, 2);
    REQUIRE(views.size() == 2);
    REQUIRE(views[1].name == "sunset_limb_view");
    const SunsetLimb limb = sunset_limb(views[1]);
    INFO("top pixel " << limb.top_rgb.transpose() << ", rim " << limb.rim_arcsec << " arcsec");
    REQUIRE(limb.found);
    CHECK(limb.blue_on_top);
    // Near the horizon the air's refraction differs by about 30 arcseconds between 400 and
    // 700 nm (the sun study's 520-650 nm split alone is 10-20): the rim from the first blue
    // pixel to half-strength red is of that size, at 3.4 arcseconds a pixel.
    CHECK(limb.rim_arcsec > 15);
    CHECK(limb.rim_arcsec < 60);
}
