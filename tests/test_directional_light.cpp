// A directional light (a sun of no angular size): parallel light of irradiance `color`.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

using namespace refract;
using nlohmann::json;

namespace {

json floor_scene(const json& extra_objects, const json& render) {
    json objects = {{{"type", "plane"}, {"name", "floor"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}};
    for (const auto& o : extra_objects) objects.push_back(o);
    return json{{"camera", {{"type", "orthographic"}, {"location", {0, 5, 0}}, {"look_at", {0, 0, 0}}, {"sky", {0, 0, 1}},
                            {"ortho_height", 4}, {"width", 40}, {"height", 40}}},
                {"background", {0, 0, 0}},
                {"materials", {{"floor", {{"type", "diffuse"}, {"color", {0.5, 0.5, 0.5}}}},
                               {"clear", {{"type", "dielectric"}, {"ior", 1.0}}}}},
                {"objects", objects},
                {"lights", {{{"type", "directional"}, {"direction", {0, -1, -1}}, {"color", {1, 1, 1}}}}},
                {"render", render}};
}

}  // namespace

TEST_CASE("Directional light: a diffuse floor receives irradiance color times cos(theta)", "[light]") {
    const Scene s = parse_scene(floor_scene(json::array(), {{"max_depth", 2}}), "sun.json");
    // POV-Ray's diffuse convention: pigment × diffuse × color × cos θ, θ = 45°.
    for (const auto& [i, j] : {std::pair{0, 0}, std::pair{20, 20}, std::pair{39, 7}})
        CHECK(render_pixel(s, i, j).x() == Approx(0.5 * std::sqrt(0.5)).epsilon(1e-14));
}

TEST_CASE("Directional light in the light pass: light through an index-1 sphere lands as the direct light would",
          "[light]") {
    // Fresnel R = 0 and no bending at n = 1: the photons through the sphere fill its
    // (physical-mode) shadow with the irradiance the floor has outside it.
    const json sphere = {{{"type", "sphere"}, {"name", "ball"}, {"center", {0, 1, 0}}, {"radius", 0.5}, {"material", "clear"}}};
    const json settings = {{"max_depth", 4}, {"light_pass", {{"photons", 400000}, {"element_size", 0.1}, {"region", 3}}}};
    const Scene s = parse_scene(floor_scene(sphere, settings), "sun-caustic.json");
    RenderOptions o;
    o.threads = 2;
    const RenderResult r = render(s, o);
    // The shadow's centre: the ball's centre moved along (0, −1, −1) to the floor, z = −1;
    // image row j ↔ z = 2 − 4 (j + 0.5)/40 (sky +z is up), so z = −1 is row 29.5.
    const Vec3 lit = r.image.at(20, 10), shadow = r.image.at(20, 29);
    CHECK(lit.x() == Approx(0.5 * std::sqrt(0.5)).epsilon(1e-14));
    CHECK(shadow.x() == Approx(lit.x()).epsilon(0.03));
    CHECK(r.stats.deposits > 100000);
}

TEST_CASE("Directional light: a zero or non-finite direction is refused, naming the field", "[light]") {
    json j = floor_scene(json::array(), {{"max_depth", 2}});
    j["lights"][0]["direction"] = {0, 0, 0};
    CHECK_THROWS_WITH(parse_scene(j, "bad.json"), Catch::Contains("/lights/0/direction"));
    j["lights"][0] = {{"type", "directional"}, {"direction", {0, -1, 0}}, {"position", {0, 1, 0}}};
    CHECK_THROWS_WITH(parse_scene(j, "bad.json"), Catch::Contains("position"));
}
