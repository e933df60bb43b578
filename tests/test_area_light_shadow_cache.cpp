// POV-Ray's shadow cache between an area light's grid points (docs/validation.md D7): the
// export writes a scene with an area light as one light_group, whose lights use no cache, so
// POV-Ray's shadow test is the one refract's POV-Ray mode copies. The reproducer: random seed
// 500 with --area-lights --mesh-files --size 64 48, shrunk to its minimal case.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/scene_json.h>
#include <refract/validation/pov_export.h>
#include <refract/validation/random_suite.h>

#include "tests/temp_dir.h"

using namespace refract;
using namespace refract::validation;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A 2 × 2 rectangle light outside an opaque sphere around the camera: inside it, near where
// the light's grid points pass from facing the surface to behind it, a grid point's shadow
// ray grazes the sphere and meets it again 2.2e-4 from its start (pixel (7, 10)).
json sphere_around_camera(bool area) {
    json light = {{"position", {-3.61743, 7.99031, 0.453709}}, {"color", {0.607, 0.337, 0.542}}};
    if (area) {
        light["type"] = "rectangle";
        light["axis1"] = {0.237224, 0.41405, 0.358743};
        light["axis2"] = {0.5001, -0.32328, 0.0424216};
        light["size"] = {2, 2};
    }
    json s = json::parse(R"({
      "background": {"type": "gradient", "bottom": [0.915, 0.804, 0.727], "top": [0.658, 0.582, 0.403]},
      "camera": {"angle": 69.2, "width": 16, "height": 12, "location": [-0.519417, 5.40843, 5.36218],
                 "look_at": [-0.670584, 1.50277, 0.657956]},
      "materials": {"paint": {"type": "diffuse", "ambient": 0.102, "color": [0.619, 0.35, 0.601], "diffuse": 0.67}},
      "objects": [{"type": "sphere", "name": "sphere around the camera", "center": [-0.487433, 5.45075, 5.35278],
                   "radius": 0.278291, "material": "paint"}],
      "render": {"compat": "povray", "integrator": "fresnel-tree", "max_depth": 0, "threshold": 0.0639}
    })");
    s["lights"] = json::array({light});
    return s;
}

}  // namespace

TEST_CASE("Area light shadow cache: a scene with an area light is exported as one light_group (its lights use no "
          "shadow cache), one with point lights only as before",
          "[light][area][export]") {
    const std::string area = export_pov(parse_scene(sphere_around_camera(true), "a.json"));
    const auto group = area.find("light_group {\n");
    REQUIRE(group != std::string::npos);
    CHECK(group < area.find("light_source {"));
    CHECK(area.find("light_source {") < area.find("\nsphere {"));
    CHECK(area.substr(area.size() - 2) == "}\n");
    CHECK(area.find("} }\n}\n") == area.size() - 6);  // the sphere's brace, then the group's
    const std::string point = export_pov(parse_scene(sphere_around_camera(false), "p.json"));
    CHECK(point.find("light_group") == std::string::npos);
}

TEST_CASE("Area light shadow cache: a grid point's grazing shadow ray within 1e-3 of its start is not shadowed by the "
          "occluder of the grid point before it, in POV-Ray as in refract (random seed 500's minimal case)",
          "[povray]") {
    const fs::path dir = test::fresh_dir("area-light", "shadow-cache");
    const Comparison r = compare_with_povray(sphere_around_camera(true), (dir / "scene.json").string(), Targets{},
                                             PovrayOptions{}, 1);
    INFO(r.reason);
    REQUIRE(r.outcome == Comparison::Outcome::Pass);
    CHECK(r.diff.rmse < 2e-5);            // 2.55e-4 with POV-Ray's cache
    CHECK(r.diff.max_error < 1e-4);       // 3.9e-3 at pixel (7, 10)
    CHECK(r.knife_edge_pixels == 0);
    fs::remove_all(dir);
}
