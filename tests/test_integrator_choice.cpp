// Integrators as one abstraction (core/integrators/integrator.h): a combination of
// integrator, spectral pass and polarisation that cannot be honoured is refused with one
// line naming the setting, never replaced by another; Whitted's tree is the one walker's,
// stored, and now accounts for the light its depth limit drops.
#include <catch2/catch.hpp>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

#include <nlohmann/json.hpp>

using namespace refract;

namespace {

// A dispersive glass sphere in front of a grey background.
Scene dispersive_sphere(const std::string& integrator) {
    const auto j = nlohmann::json::parse(R"({
        "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 30, "width": 12, "height": 10},
        "materials": {"flint": {"type": "dielectric", "dispersion": "diamond"}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "flint"}],
        "background": [0.5, 0.5, 0.5],
        "render": {"integrator": ")" + integrator + R"(", "max_depth": 4}
    })");
    return parse_scene(j, "sphere.json");
}

}  // namespace

TEST_CASE("Integrators: the stochastic integrator with a dispersive material is refused with one line naming "
          "/render/integrator, not rendered by the spectral tree",
          "[integrators]") {
    const Scene s = dispersive_sphere("stochastic");
    REQUIRE(s.settings.spectral.enabled);
    try {
        render(s);
        FAIL("rendered");
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK(what.find("sphere.json: /render/integrator: \"stochastic\" cannot render a spectral pass") == 0);
        CHECK(what.find('\n') == std::string::npos);
    }
}

TEST_CASE("Integrators: Whitted with a dispersive material is the spectral pass under Whitted's rule: split, never "
          "pruned, its depth limit's dropped light counted",
          "[integrators]") {
    const Scene s = dispersive_sphere("whitted");
    const RenderResult r = render(s);
    CHECK(r.stats.spectral_splits > 0);
    CHECK(r.stats.pruned == 0);
    CHECK(r.stats.depth_limited > 0);
    CHECK(r.stats.lost_depth > 0.0);
}

TEST_CASE("Integrators: Whitted's stored tree counts the light its depth limit drops, as the Fresnel tree does for "
          "the same tree",
          "[integrators]") {
    Scene s = dispersive_sphere("whitted");
    s.settings.spectral.enabled = false;
    s.materials[0].kind = material::Dielectric{};
    const RenderResult whitted = render(s);
    s.settings.integrator = IntegratorKind::FresnelTree;
    s.settings.requested_polarisation = PolarisationModel::Natural;  // Whitted's model
    s.settings.threshold = 0;
    const RenderResult tree = render(s);
    REQUIRE(whitted.stats.depth_limited > 0);
    CHECK(whitted.stats.segments == tree.stats.segments);
    CHECK(whitted.stats.depth_limited == tree.stats.depth_limited);
    CHECK(whitted.stats.lost_depth == Approx(tree.stats.lost_depth).epsilon(1e-12));
    for (int j = 0; j < s.camera.height; ++j)
        for (int i = 0; i < s.camera.width; ++i)
            CHECK((whitted.image.at(i, j) - tree.image.at(i, j)).norm() < 1e-12);
}

TEST_CASE("Integrators: exact polarisation with the Whitted integrator is refused with one line naming "
          "/render/polarisation",
          "[integrators]") {
    Scene s = dispersive_sphere("whitted");
    s.settings.spectral.enabled = false;
    s.materials[0].kind = material::Dielectric{};
    s.settings.requested_polarisation = PolarisationModel::Exact;
    CHECK_THROWS_WITH(render(s), Catch::StartsWith("sphere.json: /render/polarisation: \"exact\" needs the fresnel-tree"));
}
