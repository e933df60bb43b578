// POV-Ray 3.7's dispersion rules in compat mode (trace.cpp, Trace::ComputeRefraction):
// an interior splits a ray only when its single-precision dispersion differs from 1, each
// interior splits into its own dispersion_samples bands, and a band ray meeting another
// dispersive interior keeps its wavelength (GetDispersionIOR). [povray] tests run POV-Ray.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <refract/core/integrators/spectral.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/validation/random_suite.h>

using namespace refract;

namespace {

std::string pov_dispersion(double ior, const std::string& D, int samples) {
    return R"({"model": "povray", "ior": )" + std::to_string(ior) + R"(, "dispersion": )" + D +
           R"(, "samples": )" + std::to_string(samples) + "}";
}

std::string dielectric(double ior, const std::string& dispersion_json) {
    std::string m = R"({"type": "dielectric", "ior": )" + std::to_string(ior);
    if (!dispersion_json.empty()) m += R"(, "dispersion": )" + dispersion_json;
    return m + "}";
}

// Two disjoint glass spheres on a checker floor under a point light, the one behind
// ("back") seen through the one in front ("front"); `extra_*` add one more material and
// object. Compat mode, max_depth 10.
nlohmann::json two_spheres(const std::string& front, const std::string& back, int width = 80, int height = 60,
                           const std::string& extra_material = "", const std::string& extra_object = "") {
    std::string materials =
        R"("floor": {"type": "diffuse", "color": [0.9, 0.9, 0.85],
                     "checker": {"color2": [0.15, 0.25, 0.55], "size": 0.4}},
           "front": )" + front + R"(, "back": )" + back;
    std::string objects = R"({"type": "plane", "normal": [0, 1, 0], "offset": 0, "material": "floor"},
           {"type": "sphere", "center": [-0.2, 0.75, -1.2], "radius": 0.75, "material": "front"},
           {"type": "sphere", "center": [0.5, 0.9, 1.2], "radius": 0.9, "material": "back"})";
    if (!extra_material.empty()) materials += ", " + extra_material;
    if (!extra_object.empty()) objects += ", " + extra_object;
    return nlohmann::json::parse(R"({
      "camera": {"location": [0, 1.4, -5], "look_at": [0.1, 0.8, 0], "angle": 40, "width": )" +
                                 std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(},
      "background": [0.55, 0.7, 0.9],
      "materials": {)" + materials + R"(},
      "objects": [)" + objects + R"(],
      "lights": [{"position": [3, 6, -4]}],
      "render": {"max_depth": 10, "compat": "povray"}})");
}

int material_index(const Scene& s, const std::string& name) {
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name) return static_cast<int>(i);
    FAIL("no material " << name);
    return -1;
}

double max_difference(const Image& a, const Image& b) {
    double m = 0;
    for (int j = 0; j < a.height; ++j)
        for (int i = 0; i < a.width; ++i) m = std::fmax(m, (a.at(i, j) - b.at(i, j)).cwiseAbs().maxCoeff());
    return m;
}

const std::string kPlainBack = dielectric(1.9, "");
const std::string kFront5 = dielectric(1.5, pov_dispersion(1.5, "1.08", 5));
const std::string kBack13 = dielectric(1.9, pov_dispersion(1.9, "1.15", 13));

// A sphere under the (opaque) floor: no ray reaches it.
std::string under_floor(const std::string& material) {
    return R"({"type": "sphere", "center": [0, -5, 0], "radius": 1, "material": ")" + material + R"("})";
}

}  // namespace

TEST_CASE("POV-Ray compat: a dispersion that is 1 in single precision never splits (|D - 1| >= 1e-10 splits)",
          "[spectral]") {
    const Scene plain = parse_scene(two_spheres(dielectric(1.5, ""), kPlainBack, 40, 30), "plain.json");
    const RenderResult reference = render(plain);
    REQUIRE_FALSE(plain.settings.spectral.enabled);
    // D = 1 exactly; 1 + 1e-9 and 1 + 2e-8 are 1.0f; a constant index has no dispersion.
    for (const std::string& disp : {pov_dispersion(1.5, "1", 7), pov_dispersion(1.5, "1.000000001", 7),
                                    pov_dispersion(1.5, "1.00000002", 7), std::string("1.5")}) {
        INFO(disp);
        const Scene s = parse_scene(two_spheres(dielectric(1.5, disp), kPlainBack, 40, 30), "one.json");
        REQUIRE(s.settings.spectral.enabled);
        const SpectralContext ctx = SpectralContext::build(s);
        CHECK(ctx.dispersive[static_cast<size_t>(material_index(s, "front"))] == 0);
        CHECK(ctx.bands() == 0);
        const RenderResult r = render(s);
        CHECK(r.stats.spectral_splits == 0);
        CHECK(r.stats.wavelength_segments == 0);
        CHECK(max_difference(r.image, reference.image) == 0.0);
    }
    // The next float above 1 (1 + 2^-23) splits, and the band colours (mean hue
    // (0.9938, 1, 0.9962)) tint what is seen through the sphere.
    const Scene next = parse_scene(
        two_spheres(dielectric(1.5, pov_dispersion(1.5, "1.00000011920928955", 7)), kPlainBack, 40, 30), "next.json");
    const RenderResult r = render(next);
    CHECK(r.stats.spectral_splits > 100);
    CHECK(max_difference(r.image, reference.image) > 1e-3);
}

TEST_CASE("POV-Ray compat: each dispersive material splits into its own dispersion_samples bands, and a band "
          "keeps its wavelength in another dispersive material",
          "[spectral]") {
    // "aux" shares front's 5 bands; "back" has 13.
    const Scene s = parse_scene(
        two_spheres(kFront5, kBack13, 40, 30, R"("aux": )" + dielectric(1.7, pov_dispersion(1.7, "1.2", 5)),
                    under_floor("aux")),
        "two.json");
    const SpectralContext ctx = SpectralContext::build(s);
    const int front = material_index(s, "front"), back = material_index(s, "back"), aux = material_index(s, "aux");
    const int floor = material_index(s, "floor");
    CHECK(ctx.bands() == 18);
    REQUIRE(ctx.split_bands[static_cast<size_t>(front)].size() == 5);
    REQUIRE(ctx.split_bands[static_cast<size_t>(back)].size() == 13);
    CHECK(ctx.split_bands[static_cast<size_t>(aux)] == ctx.split_bands[static_cast<size_t>(front)]);
    CHECK(ctx.split_bands[static_cast<size_t>(floor)].empty());
    for (const int m : {front, back}) {
        const std::vector<int>& bands = ctx.split_bands[static_cast<size_t>(m)];
        const int N = static_cast<int>(bands.size());
        Vec3 weight_sum(0, 0, 0);
        for (int i = 0; i < N; ++i) {
            const size_t b = static_cast<size_t>(bands[static_cast<size_t>(i)]);
            // Band i of N: 380 + 350·(i + ½)/N nm (single precision), weight hue_i/N.
            CHECK(ctx.wavelengths[b] == static_cast<float>(380.0 + 350.0 * (i + 0.5) / N));
            weight_sum += ctx.weights[b];
        }
        CHECK(weight_sum.x() == Approx(0.9938).margin(2e-4));
        CHECK(weight_sum.y() == Approx(1.0).margin(2e-4));
        CHECK(weight_sum.z() == Approx(0.9962).margin(2e-4));
    }
    // Every band has each dispersive material's index at its wavelength: n·D^((555 − λ)/350)
    // with n and D in single precision; the floor has none.
    for (size_t b = 0; b < ctx.bands(); ++b) {
        INFO("band " << b << " at " << ctx.wavelengths[b] << " nm");
        CHECK(ctx.index[b][static_cast<size_t>(front)] ==
              spectrum::povray_index(static_cast<float>(1.5), static_cast<float>(1.08), ctx.wavelengths[b]));
        CHECK(ctx.index[b][static_cast<size_t>(back)] ==
              spectrum::povray_index(static_cast<float>(1.9), static_cast<float>(1.15), ctx.wavelengths[b]));
        CHECK(ctx.index[b][static_cast<size_t>(floor)] == 0.0);
    }
    CHECK(ctx.index[ctx.split_bands[static_cast<size_t>(front)][0]][static_cast<size_t>(back)] ==
          Approx(1.9 * std::pow(1.15, (555.0 - 415.0) / 350.0)).epsilon(1e-6));

    // Rendering: a 13-band material listed first (unreachable, under the floor) does not
    // change the 5-band split of the front sphere.
    const Scene alone = parse_scene(two_spheres(kFront5, kPlainBack, 40, 30), "alone.json");
    const Scene with13 = parse_scene(
        two_spheres(kFront5, kPlainBack, 40, 30, R"("a13": )" + kBack13, under_floor("a13")), "with13.json");
    REQUIRE(material_index(with13, "a13") < material_index(with13, "front"));
    const Scene front13 =
        parse_scene(two_spheres(dielectric(1.5, pov_dispersion(1.5, "1.08", 13)), kPlainBack, 40, 30), "front13.json");
    const RenderResult a = render(alone), b = render(with13), c = render(front13);
    CHECK(a.stats.spectral_splits > 100);
    CHECK(b.stats.spectral_splits == a.stats.spectral_splits);
    CHECK(b.stats.wavelength_segments == a.stats.wavelength_segments);
    CHECK(max_difference(a.image, b.image) == 0.0);
    // 13 bands instead of 5: more band rays, and a visibly different image.
    CHECK(c.stats.wavelength_segments > 2 * a.stats.wavelength_segments);
    CHECK(max_difference(a.image, c.image) > 1e-2);
}

TEST_CASE("POV-Ray 3.7 agrees with compat mode on two dispersive spheres of different D and dispersion_samples, "
          "one seen through the other",
          "[povray]") {
    using namespace refract::validation;
    const Targets targets;  // the suite's: <= 0.1 % of pixels over 1e-3, RMSE <= 2e-4
    struct Case {
        const char* name;
        std::string front;
    };
    for (const Case& k : {Case{"front-5-bands", kFront5},
                          Case{"front-d-1", dielectric(1.5, pov_dispersion(1.5, "1", 7))},
                          Case{"front-d-1e-9", dielectric(1.5, pov_dispersion(1.5, "1.000000001", 7))}}) {
        INFO(k.name);
        const Comparison c = compare_with_povray(two_spheres(k.front, kBack13), k.name, targets, PovrayOptions{}, 2);
        INFO(c.reason);
        REQUIRE(c.outcome != Comparison::Outcome::Skip);
        INFO("rmse " << c.diff.rmse << ", pixels over 1e-3 " << c.diff.pixels_over << ", max " << c.diff.max_error);
        CHECK(c.outcome == Comparison::Outcome::Pass);
        CHECK(c.diff.pixels == 80 * 60);
        CHECK(c.diff.pixels_over == 0);
        CHECK(c.diff.rmse < 2e-5);  // about the 16-bit output step
    }
}
