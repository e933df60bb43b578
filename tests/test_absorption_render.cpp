// Beer–Lambert absorption inside dielectrics (material "absorption"), rendered, against
// the closed forms of a slab and a sphere with all their internal reflections.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/integrators/fresnel_tree.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/optics.h>
#include <refract/core/polarisation_state.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include "tests/render_options.h"
#include <refract/geometry/error.h>

using namespace refract;
using refract::testing::threads;
using nlohmann::json;

namespace {

// Transmittance of a plate with interface reflectance R and one-pass internal
// transmittance tau, all internal reflections summed: (1 − R)² τ / (1 − R² τ²).
double plate(double R, double tau) { return (1 - R) * (1 - R) * tau / (1 - R * R * tau * tau); }

// An orthographic camera looking down through a horizontal glass plate (y in [−d, 0]) at
// `incidence` degrees; black sky, a white emitting floor below, so a pixel sees only the
// light the plate transmits from the floor.
json plate_scene(double incidence_deg, double d, double alpha, const json& polarisation) {
    const double a = incidence_deg * M_PI / 180.0;
    const double big = 1000;
    return json{
        {"camera", {{"type", "orthographic"}, {"location", {0, 2 * std::cos(a), -2 * std::sin(a)}}, {"look_at", {0, 0, 0}},
                    {"ortho_height", 0.01}, {"width", 3}, {"height", 3}}},
        {"background", {0, 0, 0}},
        {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}, {"absorption", {{"coefficients", {alpha, alpha, alpha}}}}}},
                       {"floor", {{"type", "emissive"}, {"color", {1, 1, 1}}}}}},
        {"objects", {{{"type", "polyhedron"}, {"material", "glass"},
                      {"planes", {{0, 1, 0, 0}, {0, -1, 0, d}, {1, 0, 0, big}, {-1, 0, 0, big}, {0, 0, 1, big}, {0, 0, -1, big}}}},
                     {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", -5}, {"material", "floor"}}}},
        {"render", {{"max_depth", 80}, {"threshold", 0}, {"polarisation", polarisation}}}};
}

}  // namespace

TEST_CASE("Beer-Lambert slab: transmittance with all internal reflections, per polarisation, against the closed form",
          "[absorption]") {
    const double d = 0.7, alpha = 0.9, theta = 30.0;
    const double cos_i = std::cos(theta * M_PI / 180.0);
    const auto f = optics::fresnel(cos_i, 1.5);
    REQUIRE(f);
    const double tau = optics::beer_lambert(alpha, d / f->cos_t);  // one pass along the refracted ray
    // ŝ is the image's right (the plane of incidence is vertical): an analyser at 0°
    // passes the s component of the (natural) sky, at 90° the p component.
    for (const auto& [angle, R] : {std::pair{0.0, f->Rs}, std::pair{90.0, f->Rp}}) {
        const json pol = {{"model", "exact"}, {"analyser", {{"type", "linear"}, {"angle", angle}}}};
        const StokesRGB S = render_pixel_stokes(parse_scene(plate_scene(theta, d, alpha, pol), "slab.json"), 1, 1);
        CHECK(S(0, 0) == Approx(0.5 * plate(R, tau)).epsilon(1e-12));
    }
    // Natural light at every node uses R = (Rs + Rp)/2 in the same series: a different,
    // wrong number (the series is not linear in R).
    const Scene nat = parse_scene(plate_scene(theta, d, alpha, "natural"), "slab.json");
    const Vec3 v = render_pixel(nat, 1, 1);
    const double exact = 0.5 * (plate(f->Rs, tau) + plate(f->Rp, tau));
    CHECK(v.x() == Approx(plate(f->R(), tau)).epsilon(1e-12));
    CHECK(std::abs(v.x() - exact) > 1e-6);
}

TEST_CASE("Beer-Lambert sphere: transmittance along the axis against the closed form", "[absorption]") {
    // A ray along a diameter meets both surfaces at normal incidence and its internal
    // reflections stay on the axis: a plate of thickness 2r.
    const double r = 0.8, alpha = 0.6;
    const json j = {{"camera", {{"type", "orthographic"}, {"location", {0, 3, 0}}, {"look_at", {0, 0, 0}}, {"sky", {0, 0, 1}},
                                {"ortho_height", 0.001}, {"width", 1}, {"height", 1}}},
                    {"background", {0, 0, 0}},
                    {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}, {"absorption", {{"coefficients", {alpha, 2 * alpha, 0}}}}}},
                                   {"floor", {{"type", "emissive"}, {"color", {1, 1, 1}}}}}},
                    {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", r}, {"material", "glass"}},
                                 {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", -5}, {"material", "floor"}}}},
                    {"render", {{"max_depth", 60}, {"threshold", 0}}}};
    const Vec3 v = render_pixel(parse_scene(j, "sphere.json"), 0, 0);
    const double R = optics::fresnel_reflectance(1.0, 1.5);
    CHECK(v.x() == Approx(plate(R, std::exp(-alpha * 2 * r))).epsilon(1e-12));
    CHECK(v.y() == Approx(plate(R, std::exp(-2 * alpha * 2 * r))).epsilon(1e-12));
    CHECK(v.z() == Approx(plate(R, 1.0)).epsilon(1e-12));  // clear channel: 2n/(n² + 1)
}

TEST_CASE("Beer-Lambert in the spectral eye pass: each wavelength absorbs with its own coefficient", "[absorption]") {
    // A dispersive plate (BK7) at normal incidence with a tabulated α(λ): the ray splits
    // at the plate into the sampled wavelengths, and each band's light is the plate's
    // closed form at its own index and its own α(λ); the pixel is their weighted sum.
    json j = plate_scene(0, 0.5, 0.0, "natural");
    j["camera"]["sky"] = {0, 0, 1};
    j["materials"]["glass"]["dispersion"] = "BK7";
    j["materials"]["glass"].erase("ior");  // the model's own index
    j["materials"]["glass"]["absorption"] = {{"spectrum", {{400, 3.0}, {560, 3.0}, {600, 0.0}, {700, 0.4}}}};
    j["render"]["spectral"] = {{"pipeline", "cie-rgb"}};
    const Scene s = parse_scene(j, "bands.json");
    const SpectralContext ctx = SpectralContext::build(s);
    const auto& glass = *s.materials.at(s.objects.at(0).material).dielectric();
    Vec3 expected(0, 0, 0);
    for (size_t k = 0; k < ctx.bands(); ++k) {
        const double n = glass.dispersion->n(ctx.wavelengths[k]);
        const double R = std::pow((n - 1) / (n + 1), 2);
        expected += ctx.weights[k] * plate(R, std::exp(-glass.absorption->at(ctx.wavelengths[k]) * 0.5));
    }
    const Vec3 v = render_pixel(s, 1, 1);
    for (int c = 0; c < 3; ++c) CHECK(v[c] == Approx(ctx.finish(expected)[c]).epsilon(1e-12));
    CHECK(v.x() > 3 * v.z());  // red passes, blue is absorbed
}

TEST_CASE("Absorption in a scene file: catalogue, transmittance colour, and clear errors", "[absorption]") {
    json j = plate_scene(20, 0.5, 1.0, "natural");
    j["materials"]["glass"]["absorption"] = {{"transmittance", {0.5, 0.25, 1.0}}, {"thickness", 2.0}};
    const Scene s = parse_scene(j, "t.json");
    const auto& a = *s.materials.at(s.objects.at(0).material).dielectric()->absorption;
    CHECK(a.rgb.x() == Approx(std::log(2.0) / 2).epsilon(1e-15));
    CHECK(a.rgb.y() == Approx(std::log(4.0) / 2).epsilon(1e-15));
    CHECK(a.rgb.z() == 0.0);
    j["materials"]["glass"]["absorption"] = "ruby";
    const Scene sr = parse_scene(j, "r.json");
    const auto& ruby = *sr.materials.at(sr.objects.at(0).material).dielectric()->absorption;
    CHECK(ruby.rgb.y() > 3 * ruby.rgb.x());  // ruby absorbs green, passes red
    j["materials"]["glass"]["absorption"] = {{"model", "ruby"}, {"unit_cm", 0.1}};
    const Scene sm = parse_scene(j, "r.json");
    CHECK(sm.materials.at(sm.objects.at(0).material).dielectric()->absorption->rgb.y() == Approx(0.1 * ruby.rgb.y()));
    j["materials"]["glass"]["absorption"] = "opal";
    CHECK_THROWS_WITH(parse_scene(j, "o.json"), Catch::Contains("/materials/glass/absorption") && Catch::Contains("ruby"));
    j["materials"]["glass"]["absorption"] = {{"transmittance", {0, 1, 1}}, {"thickness", 1}};
    CHECK_THROWS_WITH(parse_scene(j, "z.json"), Catch::Contains("transmittance/0"));
    j["materials"]["glass"]["absorption"] = {{"coefficients", {1, -1, 1}}};
    CHECK_THROWS_WITH(parse_scene(j, "n.json"), Catch::Contains("coefficients/1"));
}

TEST_CASE("Beer-Lambert: the stored Whitted tree and the FIFO walk agree on an absorbing glass", "[absorption]") {
    // Same tree (threshold 0), the absorption applied per node in the stored tree and per
    // list entry in the walk: the images agree to rounding.
    json j = {{"camera", {{"location", {0, 0.5, -4}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 16}, {"height", 12}}},
              {"background", {{"type", "gradient"}}},
              {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.6}, {"absorption", "emerald"}}}}},
              {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
              {"render", {{"max_depth", 7}, {"threshold", 0}, {"polarisation", "natural"}}}};  // Whitted's model
    const Image tree = render(parse_scene(j, "fifo.json"), threads(1)).image;
    j["render"]["integrator"] = "whitted";
    const Image stored = render(parse_scene(j, "whitted.json"), threads(1)).image;
    double max_err = 0, max_v = 0;
    for (size_t k = 0; k < tree.rgb.size(); ++k) {
        max_err = std::fmax(max_err, std::abs(tree.rgb[k] - stored.rgb[k]));
        max_v = std::fmax(max_v, tree.rgb[k]);
    }
    CHECK(max_err < 1e-12);
    CHECK(max_v > 0.1);
}
