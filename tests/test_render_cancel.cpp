// RenderOptions::cancel: a render whose flag is set stops and throws RenderCancelled (the
// Python module's Ctrl-C); an unset flag changes nothing.
#include <catch2/catch.hpp>

#include <atomic>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>

using namespace refract;

namespace {

Scene small_sphere() {
    const nlohmann::json j = {
        {"camera", {{"location", {0, 0, -4}}, {"look_at", {0, 0, 0}}, {"width", 24}, {"height", 16}}},
        {"background", {0.4, 0.5, 0.8}},
        {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}}}},
        {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}}};
    return parse_scene(j, "cancel.json");
}

}  // namespace

TEST_CASE("a render whose cancel flag is set throws RenderCancelled", "[render]") {
    const Scene s = small_sphere();
    std::atomic<bool> cancel{true};
    RenderOptions opt;
    opt.cancel = &cancel;
    CHECK_THROWS_AS(render(s, opt), RenderCancelled);
}

TEST_CASE("an unset cancel flag leaves the image as it is", "[render]") {
    const Scene s = small_sphere();
    std::atomic<bool> cancel{false};
    RenderOptions opt;
    opt.cancel = &cancel;
    const RenderResult a = render(s, opt), b = render(s);
    CHECK(a.image.rgb == b.image.rgb);
    CHECK(a.stats.primary_rays == 24u * 16u);
}

TEST_CASE("a set cancel flag stops the light pass before its photons, and the render throws", "[render]") {
    Scene s = load_scene(std::string(REFRACT_SOURCE_DIR) + "/scenes/examples/ohtsuka1998-diamond.json");
    REQUIRE(s.settings.light_pass.enabled);
    s.camera.width = 8;
    s.camera.height = 6;
    s.settings.light_pass.photons = 2000;
    const SpectralContext ctx = SpectralContext::build(s);
    std::atomic<bool> cancel{true};
    CHECK(light_pass(s, ctx, 2, &cancel)->photons == 0);
    cancel = false;
    CHECK(light_pass(s, ctx, 2, &cancel)->photons == 2000);
    cancel = true;
    RenderOptions opt;
    opt.cancel = &cancel;
    CHECK_THROWS_AS(render(s, opt), RenderCancelled);
}
