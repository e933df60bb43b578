// Energy conservation with the lost-weight channel: in a white furnace (a lossless glass
// in a uniformly white background) every branch either reaches the background or is
// dropped, so per pixel the image plus the dropped weight is exactly 1.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>

using namespace refract;
using nlohmann::json;

namespace {

json furnace(const json& glass, const json& render) {
    return json{{"camera", {{"location", {0, 0.4, -3.5}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 20}, {"height", 16}}},
                {"background", {1, 1, 1}},
                {"materials", {{"glass", glass}}},
                {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
                {"render", render}};
}

// Max over pixels of |mean(pixel) + dropped − 1|, and the total dropped per primary ray.
std::pair<double, double> balance(const RenderResult& r) {
    double worst = 0;
    const size_t n = r.lost.size() / 3;
    for (size_t p = 0; p < n; ++p) {
        const double v = (r.image.rgb[3 * p] + r.image.rgb[3 * p + 1] + r.image.rgb[3 * p + 2]) / 3.0;
        worst = std::fmax(worst, std::abs(v + r.lost[3 * p] + r.lost[3 * p + 1] + r.lost[3 * p + 2] - 1.0));
    }
    const RenderStats& s = r.stats;
    return {worst, (s.lost_depth + s.lost_limits + s.lost_threshold) / static_cast<double>(s.primary_rays)};
}

RenderOptions one_thread() {
    RenderOptions o;
    o.threads = 1;
    o.lost_energy = true;
    return o;
}

}  // namespace

TEST_CASE("White furnace: image plus the weight dropped by the depth limit and the threshold is 1", "[lost]") {
    const json glass = {{"type", "dielectric"}, {"ior", 1.5}};
    const RenderResult depth = render(parse_scene(furnace(glass, {{"max_depth", 3}, {"threshold", 0}}), "d.json"), one_thread());
    const auto [worst_d, lost_d] = balance(depth);
    CHECK(worst_d < 1e-12);
    CHECK(depth.stats.lost_depth > 0);
    CHECK(depth.stats.lost_threshold == 0);
    CHECK(lost_d > 1e-3);
    const RenderResult thr = render(parse_scene(furnace(glass, {{"max_depth", 40}, {"threshold", 0.05}}), "t.json"), one_thread());
    const auto [worst_t, lost_t] = balance(thr);
    CHECK(worst_t < 1e-12);
    CHECK(thr.stats.lost_threshold > 0);
    CHECK(lost_t > 1e-3);
    // The warning names what dropped most, past 1 % of the image's light.
    CHECK_THAT(depth.stats.lost_warning(1e-4), Catch::Contains("render.max_depth"));
    CHECK_THAT(thr.stats.lost_warning(1e-4), Catch::Contains("render.threshold"));
    CHECK(depth.stats.lost_warning(0.99).empty());
}

TEST_CASE("White furnace, spectral: the paper's reflection/transmission limits drop light, counted per band",
          "[lost]") {
    // A dispersive diamond sphere with the 1998 paper's kind of limits (here 2 and 2):
    // each band's dropped weight is scaled by its RGB weight, so the balance holds.
    const json glass = {{"type", "dielectric"}, {"dispersion", "diamond"}};
    const json settings = {{"max_depth", 30}, {"threshold", 0},
                           {"spectral", {{"pipeline", "cie-rgb"}, {"max_reflections", 2}, {"max_transmissions", 2}}}};
    const RenderResult r = render(parse_scene(furnace(glass, settings), "s.json"), one_thread());
    const auto [worst, lost] = balance(r);
    CHECK(worst < 1e-9);
    CHECK(r.stats.lost_limits > 0);
    CHECK(lost > 1e-3);
    CHECK_THAT(r.stats.lost_warning(1e-3), Catch::Contains("max_reflections"));
}

TEST_CASE("Per-pixel images past 2^28 values are refused before any work, naming the option", "[lost]") {
    // The scene reader stops images at 2^26 pixels; a scene built in code meets these bounds.
    json j = furnace({{"type", "dielectric"}, {"ior", 1.5}}, {{"max_depth", 3}});
    Scene s = parse_scene(j, "big.json");
    s.camera.width = 16384;
    s.camera.height = 8192;
    RenderOptions o;
    o.lost_energy = true;
    CHECK_THROWS_WITH(render(s, o), Catch::Contains("/camera: the image"));
    s.camera.width = 8192;
    s.camera.height = 4096;  // 2^25 pixels: 3 values each fit, 14 do not
    j["render"]["polarisation"] = "exact";
    Scene p = parse_scene(j, "big.json");
    p.camera = s.camera;
    CHECK_THROWS_WITH(render(p), Catch::Contains("/render/polarisation"));
}
