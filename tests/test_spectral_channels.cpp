// Spectral images (render --spectral-channels): the light at every wavelength, which the
// RGB image is the weighted sum of.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

using namespace refract;
using nlohmann::json;

namespace {

json grey_diamond(const json& render) {
    return json{{"camera", {{"location", {0, 2.2, -3.5}}, {"look_at", {0, 0.5, 0}}, {"angle", 35}, {"width", 24}, {"height", 18}}},
                {"background", {0.6, 0.6, 0.6}},
                {"materials", {{"gem", {{"type", "dielectric"}, {"dispersion", "diamond"}}},
                               {"floor", {{"type", "diffuse"}, {"color", {0.7, 0.7, 0.7}}, {"ambient", 0.1}}}}},
                {"objects", {{{"type", "brilliant"}, {"name", "gem"}, {"diameter", 1.4}, {"position", {0, 0.7, 0}},
                              {"rotation", {20, 0, 0}}, {"material", "gem"}},
                             {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}}},
                {"lights", {{{"position", {2, 6, -2}}}}},
                {"render", render}};
}

}  // namespace

TEST_CASE("Spectral channels: the RGB image is the band-weighted sum of the wavelengths' light (grey scene)",
          "[spectral]") {
    const Scene s = parse_scene(grey_diamond({{"max_depth", 12}, {"spectral", {{"pipeline", "cie-rgb"}}}}), "grey.json");
    RenderOptions o;
    o.threads = 2;
    o.spectral_channels = true;
    const RenderResult r = render(s, o);
    const SpectralContext ctx = SpectralContext::build(s);
    REQUIRE(r.wavelengths.size() == ctx.bands());
    REQUIRE(r.spectral.size() == ctx.bands() * 24 * 18);
    int checked = 0;
    double worst = 0, spread = 0;
    for (size_t p = 0; p < 24 * 18; ++p) {
        Vec3 sum(0, 0, 0);
        double lo = 1e300, hi = -1e300;
        for (size_t k = 0; k < ctx.bands(); ++k) {
            const double v = r.spectral[p * ctx.bands() + k];
            sum += ctx.weights[k] * v;
            lo = std::fmin(lo, v);
            hi = std::fmax(hi, v);
        }
        const Vec3 px(r.image.rgb[3 * p], r.image.rgb[3 * p + 1], r.image.rgb[3 * p + 2]);
        if (px.minCoeff() <= 0) continue;  // cie-rgb clips negatives: compare unclipped pixels
        worst = std::fmax(worst, (sum - px).cwiseAbs().maxCoeff());
        spread = std::fmax(spread, hi - lo);
        ++checked;
    }
    CHECK(checked > 300);
    CHECK(worst < 1e-12);
    CHECK(spread > 1e-3);  // dispersion: the wavelengths differ in some pixels
}

TEST_CASE("Spectral channels are refused without the physical spectral pass", "[spectral]") {
    RenderOptions o;
    o.spectral_channels = true;
    json j = grey_diamond({{"max_depth", 4}});
    j["materials"]["gem"] = {{"type", "dielectric"}, {"ior", 2.4}};
    CHECK_THROWS_WITH(render(parse_scene(j, "rgb.json"), o), Catch::Contains("spectral channels"));
}

TEST_CASE("Spectral channels are never negative: a yellow light's light pass on the 1998 diamond (a fuzzer finding)",
          "[spectral]") {
    // The fuzzer's tiny render of scenes/examples/ohtsuka1998-diamond.json with the light's
    // colour changed to [1, 1, 0]: the band-weighted maps gave −0.0087 at 400 nm, which the
    // writer refused as an internal error.
    std::ifstream in(std::string(REFRACT_SOURCE_DIR) + "/scenes/examples/ohtsuka1998-diamond.json");
    json j = json::parse(in);
    j["lights"][0]["color"] = {1.0, 1.0, 0.0};
    j["camera"]["width"] = 8;
    j["camera"]["height"] = 6;
    j["render"]["max_depth"] = 6;
    j["render"]["light_pass"]["photons"] = 200;
    j["render"]["light_pass"]["element_size"] = 0.05;
    const Scene s = parse_scene(j, "yellow.json");
    RenderOptions o;
    o.threads = 1;
    o.spectral_channels = true;
    const RenderResult r = render(s, o);
    REQUIRE(r.spectral.size() == r.wavelengths.size() * 8 * 6);
    double lo = 1e300, hi = 0;
    for (double v : r.spectral) {
        lo = std::fmin(lo, v);
        hi = std::fmax(hi, v);
    }
    CHECK(lo >= 0.0);
    CHECK(hi > 0.0);
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("refract-yellow-" + std::to_string(::getpid()) + ".spectral.exr")).string();
    std::vector<std::string> names;
    for (double nm : r.wavelengths) names.push_back(std::to_string(static_cast<int>(nm)) + "nm");
    CHECK_NOTHROW(write_channels(path, 8, 6, names, r.spectral, {}));
    std::filesystem::remove(path);
}
