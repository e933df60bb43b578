// Exact polarisation in the renderer (render.polarisation "exact"): the walker carries
// Stokes vectors through Mueller matrices; checked on scenes against closed forms.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/integrators/fresnel_tree.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/optics.h>
#include <refract/core/polarisation_state.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include "tests/render_options.h"

using namespace refract;
using refract::testing::threads;
using nlohmann::json;

namespace {

// A camera looking down at a glass floor (filter 0: only its reflection is seen) under a
// white sky, the centre pixel's ray meeting the floor at `incidence` degrees.
json glass_floor(double incidence_deg, const json& polarisation) {
    const double a = incidence_deg * M_PI / 180.0;
    return json{{"camera", {{"location", {0, 5 * std::cos(a), -5 * std::sin(a)}}, {"look_at", {0, 0, 0}},
                            {"angle", 10}, {"width", 9}, {"height", 9}}},
                {"background", {1, 1, 1}},
                {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}, {"filter", {0, 0, 0}}}}}},
                {"objects", {{{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "glass"}}}},
                {"render", {{"max_depth", 4}, {"threshold", 0}, {"polarisation", polarisation}}}};
}

}  // namespace

TEST_CASE("Brewster's law: natural light reflected at tan(theta) = n is fully s-polarised", "[polarisation]") {
    const double theta_b = optics::brewster_angle(1.5) * 180.0 / M_PI;
    const Scene s = parse_scene(glass_floor(theta_b, "exact"), "brewster.json");
    const StokesRGB S = render_pixel_stokes(s, 4, 4);
    const auto f = optics::fresnel(std::cos(optics::brewster_angle(1.5)), 1.5);
    REQUIRE(f);
    CHECK(f->Rp < 1e-30);
    for (int c = 0; c < 3; ++c) {
        CHECK(S(0, c) == Approx(0.5 * f->Rs).epsilon(1e-12));
        // ŝ is horizontal, the image's right: S1 = +S0, S2 = S3 = 0.
        CHECK(S(1, c) / S(0, c) == Approx(1.0).epsilon(1e-12));
        CHECK(std::abs(S(2, c)) < 1e-12);
        CHECK(std::abs(S(3, c)) < 1e-12);
    }
    const LinearPolarisation lp = linear_polarisation(S, s, s.camera.ray(4.5, 4.5));
    CHECK(lp.dolp == Approx(1.0).epsilon(1e-12));
    CHECK(std::abs(lp.aolp) < 1e-12);
}

TEST_CASE("Malus's law: an analyser at angle theta passes cos^2 theta of the Brewster reflection", "[polarisation]") {
    const double theta_b = optics::brewster_angle(1.5) * 180.0 / M_PI;
    const double I = render_pixel_stokes(parse_scene(glass_floor(theta_b, "exact"), "b.json"), 4, 4)(0, 0);
    for (double t : {0.0, 20.0, 45.0, 60.0, 90.0, 135.0}) {
        const json pol = {{"model", "exact"}, {"analyser", {{"type", "linear"}, {"angle", t}}}};
        const StokesRGB S = render_pixel_stokes(parse_scene(glass_floor(theta_b, pol), "malus.json"), 4, 4);
        const double c = std::cos(t * M_PI / 180.0);
        CHECK(S(0, 1) == Approx(I * c * c).margin(1e-14));
    }
    // A circular analyser passes half of any linear state.
    const json circ = {{"model", "exact"}, {"analyser", {{"type", "circular"}, {"handedness", "right"}}}};
    CHECK(render_pixel_stokes(parse_scene(glass_floor(theta_b, circ), "c.json"), 4, 4)(0, 2) == Approx(0.5 * I).epsilon(1e-12));
}

TEST_CASE("Exact polarisation equals natural light where light meets a single interface", "[polarisation]") {
    // A black-inside glass sphere (filter 0) under a white sky: every path is one
    // reflection, where Yasuda's eq. 7 is exact; the two models agree to 1e-12.
    json j = {{"camera", {{"location", {0, 0.3, -4}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 24}, {"height", 18}}},
              {"background", {1, 1, 1}},
              {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.7}, {"filter", {0, 0, 0}}}}}},
              {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
              {"render", {{"max_depth", 6}, {"threshold", 0}, {"polarisation", "natural"}}}};
    const RenderResult natural = render(parse_scene(j, "n.json"), threads(1));
    j["render"]["polarisation"] = "exact";
    const RenderResult exact = render(parse_scene(j, "e.json"), threads(1));
    REQUIRE(exact.polarisation);
    double max_err = 0, max_dolp = 0;
    for (size_t k = 0; k < natural.image.rgb.size(); ++k)
        max_err = std::fmax(max_err, std::abs(natural.image.rgb[k] - exact.image.rgb[k]));
    for (double d : exact.polarisation->dolp) max_dolp = std::fmax(max_dolp, d);
    CHECK(max_err < 1e-12);
    CHECK(max_dolp > 0.5);  // the rim reflects strongly polarised light
}

TEST_CASE("Exact polarisation: a multi-bounce glass sphere differs from per-node natural light", "[polarisation]") {
    // With the inside visible, paths cross two and more interfaces; after the first the
    // light is partly polarised, and eq. 7 at every node weighs it wrongly.
    json j = {{"camera", {{"location", {0, 0.3, -4}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 24}, {"height", 18}}},
              {"background", {{"type", "gradient"}}},
              {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.7}}}}},
              {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
              {"render", {{"max_depth", 8}, {"threshold", 0}, {"polarisation", "natural"}}}};
    const RenderResult natural = render(parse_scene(j, "n.json"), threads(1));
    j["render"]["polarisation"] = "exact";
    const RenderResult exact = render(parse_scene(j, "e.json"), threads(1));
    double max_err = 0;
    for (size_t k = 0; k < natural.image.rgb.size(); ++k)
        max_err = std::fmax(max_err, std::abs(natural.image.rgb[k] - exact.image.rgb[k]));
    CHECK(max_err > 1e-4);
    CHECK(max_err < 0.1);
}

TEST_CASE("Exact polarisation in the light pass: the caustic of natural light is the mean of two crossed linear states",
          "[polarisation]") {
    auto scene = [](const json& light_pol) {
        json j = {{"camera", {{"location", {0, 3, -3}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 12}, {"height", 12}}},
                  {"background", {0, 0, 0}},
                  {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}}, {"floor", {{"type", "diffuse"}, {"color", {1, 1, 1}}}}}},
                  {"objects", {{{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 0.6}, {"material", "glass"}},
                               {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}}},
                  {"lights", {{{"position", {2, 6, -1}}, {"polarisation", light_pol}}}},
                  {"render", {{"max_depth", 6}, {"polarisation", "exact"},
                              {"light_pass", {{"photons", 20000}, {"element_size", 0.1}}}}}};
        return parse_scene(j, "caustic.json");
    };
    const Image u = render(scene({{"type", "unpolarised"}}), threads(2)).image;
    const Image a = render(scene({{"type", "linear"}, {"angle", 0}}), threads(2)).image;
    const Image b = render(scene({{"type", "linear"}, {"angle", 90}}), threads(2)).image;
    double max_err = 0, max_diff = 0;
    for (size_t k = 0; k < u.rgb.size(); ++k) {
        max_err = std::fmax(max_err, std::abs(u.rgb[k] - 0.5 * (a.rgb[k] + b.rgb[k])));
        max_diff = std::fmax(max_diff, std::abs(a.rgb[k] - b.rgb[k]));
    }
    CHECK(max_err < 1e-7);   // Stokes vectors add linearly (up to the fixed-point deposits)
    CHECK(max_diff > 1e-3);  // polarised light makes a different caustic
}

TEST_CASE("Exact polarisation is refused where it has no meaning", "[polarisation]") {
    json j = glass_floor(50, "exact");
    j["render"]["compat"] = "povray";
    CHECK_THROWS_WITH(render(parse_scene(j, "p.json")), Catch::Contains("/render/polarisation"));
    j = glass_floor(50, "exact");
    j["render"]["integrator"] = "whitted";
    CHECK_THROWS_WITH(render(parse_scene(j, "w.json")), Catch::Contains("fresnel-tree"));
    j = glass_floor(50, "exact");
    j["materials"]["glass"]["reflectance"] = "schlick";
    CHECK_THROWS_WITH(render(parse_scene(j, "s.json")), Catch::Contains("material 'glass'"));
    j = glass_floor(50, {{"model", "natural"}, {"analyser", {{"type", "linear"}}}});
    CHECK_THROWS_WITH(parse_scene(j, "a.json"), Catch::Contains("analyser"));
    j = glass_floor(50, "sideways");
    CHECK_THROWS_WITH(parse_scene(j, "x.json"), Catch::Contains("unknown model"));
}

TEST_CASE("The physical mode defaults to exact polarisation wherever it is supported, compat, Whitted, stochastic "
          "and a non-Fresnel reflectance keep natural light",
          "[polarisation]") {
    json j = glass_floor(50, "exact");
    j["render"].erase("polarisation");
    const auto model = [](const json& scene) { return polarisation_model(parse_scene(scene, "d.json")); };
    CHECK(model(j) == PolarisationModel::Exact);  // physical, fresnel-tree, Fresnel reflectance
    json k = j;
    k["materials"]["glass"].erase("ior");
    k["materials"]["glass"]["dispersion"] = "N-BK7";  // the spectral eye pass
    CHECK(model(k) == PolarisationModel::Exact);
    k = j;
    k["render"]["compat"] = "povray";  // POV-Ray's model
    CHECK(model(k) == PolarisationModel::Natural);
    k = j;
    k["render"]["integrator"] = "whitted";
    CHECK(model(k) == PolarisationModel::Natural);
    k = j;
    k["render"]["integrator"] = "stochastic";
    CHECK(model(k) == PolarisationModel::Natural);
    for (const char* r : {"schlick", "fresnel-s", "constant"}) {
        k = j;
        k["materials"]["glass"]["reflectance"] = r;
        if (std::string(r) == "constant") k["materials"]["glass"]["reflectivity"] = 0.1;
        CHECK(model(k) == PolarisationModel::Natural);
    }
    k = j;
    k["render"]["polarisation"] = "natural";  // asked for explicitly
    CHECK(model(k) == PolarisationModel::Natural);
    // The scene that does not say renders exactly like the one asking for "exact" (with the
    // Stokes images), and a render flipped to compat "povray" after parsing falls back to
    // natural light rather than being refused.
    const RenderResult d = render(parse_scene(j, "d.json"), threads(1));
    const RenderResult e = render(parse_scene(glass_floor(50, "exact"), "e.json"), threads(1));
    REQUIRE(d.polarisation);
    CHECK(d.image.rgb == e.image.rgb);
    Scene pov = parse_scene(j, "p.json");
    pov.settings.compat = Compat::PovRay;
    CHECK(polarisation_model(pov) == PolarisationModel::Natural);
    CHECK_FALSE(render(pov, threads(1)).polarisation);
}

TEST_CASE("Spectral channels of a scene without render.polarisation are rendered with natural light", "[polarisation]") {
    json j = glass_floor(50, "natural");
    j["materials"]["glass"].erase("ior");
    j["materials"]["glass"]["dispersion"] = "N-BK7";
    RenderOptions o = threads(1);
    o.spectral_channels = true;
    const RenderResult natural = render(parse_scene(j, "n.json"), o);
    j["render"].erase("polarisation");
    const RenderResult by_default = render(parse_scene(j, "d.json"), o);
    CHECK(by_default.image.rgb == natural.image.rgb);
    CHECK(by_default.spectral == natural.spectral);
    CHECK_FALSE(by_default.polarisation);
    j["render"]["polarisation"] = "exact";  // asked for: refused, naming the reason
    CHECK_THROWS_WITH(render(parse_scene(j, "e.json"), o), Catch::Contains("natural light"));
}
