// Nested transparent spheres in the POV-Ray export (validation/pov_nesting.h): each
// surface's relative index in refract, the product of the ratios as POV-Ray's index.
#include <catch2/catch.hpp>

#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/validation/pov_export.h>

using namespace refract;
using namespace refract::validation;
using Catch::Matchers::Contains;

namespace {

// Three concentric spheres of ratios 1.25, 1.2, 1.1: absolute 1.25, 1.5, 1.65.
std::string nest(const std::string& reflectance = R"("reflectance": "constant", "reflectivity": 0)",
                 const std::string& camera = "[0, 0, -5]", const std::string& extra = "") {
    return R"({"camera": {"location": )" + camera + R"(, "look_at": [0, 0, 0], "angle": 40, "width": 16, "height": 12},
      "background": [0.5, 0.6, 0.7],
      "materials": {"a": {"type": "dielectric", "ior": 1.25, )" + reflectance + R"(},
                    "b": {"type": "dielectric", "ior": 1.2, )" + reflectance + R"(},
                    "c": {"type": "dielectric", "ior": 1.1, )" + reflectance + R"(}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a"},
                  {"type": "sphere", "center": [0, 0, 0], "radius": 0.6, "material": "b"},
                  {"type": "sphere", "center": [0.1, 0, 0], "radius": 0.3, "material": "c"})" + extra + R"(],
      "render": {"max_depth": 16, "compat": "povray"}})";
}

std::string exported(const std::string& text) {
    return export_pov(parse_scene(nlohmann::json::parse(text), "nest.json"));
}

std::string refusal(const std::string& text) {
    try {
        exported(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(exported)";
}

}  // namespace

TEST_CASE("Nested transparent spheres export POV-Ray indices that are the products of the ratios around them",
          "[validation]") {
    const std::string pov = exported(nest());
    CHECK_THAT(pov, Contains("sphere { <0, 0, 0>, 1 texture") && Contains("interior { ior 1.25 }"));
    CHECK_THAT(pov, Contains("interior { ior 1.5 }"));                 // 1.2 x 1.25
    CHECK_THAT(pov, Contains("interior { ior 1.6500000000000001 }"));  // 1.1 x 1.2 x 1.25 in double
}

TEST_CASE("Nested transparent spheres are refused with Fresnel reflection, a hollow sphere or the camera inside",
          "[validation]") {
    CHECK_THAT(refusal(nest(R"("reflectance": "fresnel")")), Contains("constant reflectivity") && Contains("Fresnel"));
    CHECK_THAT(refusal(nest(R"("reflectance": "constant", "reflectivity": 0)", "[0, 0, -0.5]")),
               Contains("camera inside a sphere with transparent spheres nested in it"));
    CHECK_THAT(refusal(nest(R"("reflectance": "constant", "reflectivity": 0)", "[0, 0, -5]",
                            R"(, {"type": "sphere", "center": [3, 0, 0], "radius": 0.5, "material": "a"},
                                 {"type": "sphere", "center": [3, 0, 0], "radius": -0.4, "material": "a"})")),
               Contains("hollow sphere in a scene with nested transparent spheres"));
    // Partly overlapping spheres stay refused.
    CHECK_THAT(refusal(nest(R"("reflectance": "constant", "reflectivity": 0)", "[0, 0, -5]",
                            R"(, {"type": "sphere", "center": [1.2, 0, 0], "radius": 0.5, "material": "a"})")),
               Contains("overlap"));
}
