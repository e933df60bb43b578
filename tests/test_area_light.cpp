// Area lights (core/area_light.h): a rectangle or a disk, each the grid of n1 × n2 point
// lights of colour color / (n1·n2), each shadowed as a point light.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include <refract/core/area_light.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/validation/pov_export.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr double kAlbedo = 0.5;

// A grey floor seen straight down by a 40 × 40 orthographic camera over [−2, 2]²:
// pixel (i, j) sees the floor at x = −2 + 4 (i + ½)/40, z = 2 − 4 (j + ½)/40.
json floor_scene(const json& light, const json& objects) {
    json all = {{{"type", "plane"}, {"name", "floor"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}};
    for (const auto& o : objects) all.push_back(o);
    return json{{"camera", {{"type", "orthographic"}, {"location", {0, 5, 0}}, {"look_at", {0, 0, 0}}, {"sky", {0, 0, 1}},
                            {"ortho_height", 4}, {"width", 40}, {"height", 40}}},
                {"background", {0, 0, 0}},
                {"materials", {{"floor", {{"type", "diffuse"}, {"color", {kAlbedo, kAlbedo, kAlbedo}}}},
                               {"black", {{"type", "diffuse"}, {"color", {0, 0, 0}}}}}},
                {"objects", all},
                {"lights", {light}},
                {"render", {{"max_depth", 2}}}};
}

Vec3 floor_point(int i, int j) { return {-2 + 4 * (i + 0.5) / 40, 0, 2 - 4 * (j + 0.5) / 40}; }

// Does the segment from p to q pass within r of c (the closed form of its nearest point)?
bool blocked(const Vec3& p, const Vec3& q, const Vec3& c, double r) {
    const Vec3 d = q - p;
    const double t = std::clamp((c - p).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (p + t * d - c).norm() < r;
}

}  // namespace

TEST_CASE("Rectangle area light: the penumbra of an opaque sphere is the sum over the grid points it leaves visible",
          "[light][area]") {
    const json light = {{"type", "rectangle"}, {"position", {0.3, 3, -0.2}}, {"axis1", {2, 0, 0}}, {"axis2", {0, 0, 1.5}},
                        {"size", {4, 3}}, {"color", {1, 1, 1}}};
    const Vec3 c(0, 1, 0);
    const double r = 0.5;
    const json ball = {{{"type", "sphere"}, {"name", "ball"}, {"center", {0, 1, 0}}, {"radius", r}, {"material", "black"}}};
    const Scene s = parse_scene(floor_scene(light, ball), "area.json");
    // The grid: POV-Ray's points i/(n−1) − ½ along each axis, edges included.
    std::vector<Vec3> grid;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) grid.push_back(Vec3(0.3, 3, -0.2) + (i / 3.0 - 0.5) * Vec3(2, 0, 0) + (j / 2.0 - 0.5) * Vec3(0, 0, 1.5));
    for (int k = 0; k < 12; ++k) CHECK((s.lights[0].grid_point(k) - grid[static_cast<size_t>(k)]).norm() < 1e-15);
    int partial = 0;
    for (int j = 0; j < 40; j += 3)
        for (int i = 0; i < 40; i += 3) {
            const Vec3 x = floor_point(i, j);
            if (std::hypot(x.x(), x.z()) < r + 0.05) continue;  // the ball itself, seen from above
            double expected = 0;
            int visible = 0;
            for (const Vec3& q : grid)
                if (!blocked(x, q, c, r)) {
                    expected += kAlbedo * (q - x).normalized().y() / 12.0;
                    ++visible;
                }
            partial += visible > 0 && visible < 12;
            INFO("pixel " << i << ", " << j << ": " << visible << " of 12 grid points visible");
            CHECK(render_pixel(s, i, j).x() == Approx(expected).margin(1e-14));
        }
    CHECK(partial >= 10);  // the penumbra was sampled
}

TEST_CASE("Disk area light: POV-Ray's circular grid, each point lighting the floor as a point light", "[light][area]") {
    const json light = {{"type", "disk"}, {"position", {0, 2, 0}}, {"normal", {0, -1, 0}}, {"radius", 0.8},
                        {"size", {5, 5}}, {"color", {1, 1, 1}}};
    const Scene s = parse_scene(floor_scene(light, json::array()), "disk.json");
    const Light& l = s.lights[0];
    REQUIRE(l.samples() == 25);
    CHECK(l.axis1.norm() == Approx(1.6).epsilon(1e-15));
    CHECK(l.axis2.norm() == Approx(1.6).epsilon(1e-15));
    CHECK(std::abs(l.axis1.dot(l.axis2)) < 1e-15);
    CHECK(std::abs(l.axis1.dot(l.normal)) < 1e-15);
    // (s, t) = (i/4 − ½ + 0.001, j/4 − ½ + 0.001), scaled onto the circle of radius max(|s|, |t|).
    std::vector<Vec3> grid;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            double a = i / 4.0 - 0.5 + 0.001, b = j / 4.0 - 0.5 + 0.001;
            const double ring = std::max(std::abs(a), std::abs(b)), scale = ring / std::hypot(a, b);
            a *= scale;
            b *= scale;
            grid.push_back(l.position + a * l.axis1 + b * l.axis2);
            const Vec3 p = l.grid_point(j * 5 + i);
            CHECK((p - grid.back()).norm() < 1e-15);
            CHECK((p - l.position).norm() == Approx(1.6 * ring).epsilon(1e-14));  // on its shell's circle
            CHECK(std::abs((p - l.position).dot(l.normal)) < 1e-15);
        }
    for (const auto& [i, j] : {std::pair{20, 20}, std::pair{3, 35}, std::pair{39, 0}}) {
        const Vec3 x = floor_point(i, j);
        double expected = 0;
        for (const Vec3& q : grid) expected += kAlbedo * (q - x).normalized().y() / 25.0;
        CHECK(render_pixel(s, i, j).x() == Approx(expected).margin(1e-14));
    }
}

TEST_CASE("Area lights in the light pass: light through an index-1 sphere lands as the grid's continuum would",
          "[light][area][statistical]") {
    // A small, far rectangle: its grid's and its continuum's light on the floor differ by
    // under 1e-4; photons through an index-1 sphere fill its shadow with that light.
    const json light = {{"type", "rectangle"}, {"position", {0, 6, 0}}, {"axis1", {0.4, 0, 0}}, {"axis2", {0, 0, 0.4}},
                        {"size", {2, 2}}, {"color", {1, 1, 1}}};
    const json ball = {{{"type", "sphere"}, {"name", "ball"}, {"center", {0, 1, 0}}, {"radius", 0.5}, {"material", "clear"}}};
    json j = floor_scene(light, ball);
    j["materials"]["clear"] = {{"type", "dielectric"}, {"ior", 1.0}};
    j["render"] = {{"max_depth", 4}, {"light_pass", {{"photons", 400000}, {"element_size", 0.1}, {"region", 3}}}};
    const Scene s = parse_scene(j, "area-caustic.json");
    RenderOptions o;
    o.threads = 2;
    const RenderResult res = render(s, o);
    // Lit: the eye pass's four grid points; in the (physical-mode) shadow: photons only.
    const Vec3 lit = res.image.at(20, 5), shadow = res.image.at(20, 20);
    double expected = 0;
    for (int k = 0; k < 4; ++k) expected += kAlbedo * (s.lights[0].grid_point(k) - floor_point(20, 5)).normalized().y() / 4;
    CHECK(lit.x() == Approx(expected).epsilon(1e-12));
    CHECK(shadow.x() == Approx(lit.x()).epsilon(0.03));
    CHECK(res.stats.deposits > 100000);
}

TEST_CASE("Area lights: a zero or parallel axis, a grid of 0 or over 64, a non-finite field are refused, naming the field",
          "[light][area][errors]") {
    const json good = {{"type", "rectangle"}, {"position", {0, 3, 0}}, {"axis1", {1, 0, 0}}, {"axis2", {0, 0, 1}},
                       {"size", {2, 2}}};
    REQUIRE_NOTHROW(parse_scene(floor_scene(good, json::array()), "a.json"));
    const std::pair<json, std::string> cases[] = {
        {{{"axis1", {0, 0, 0}}}, "a.json: /lights/0/axis1: must be a non-zero vector"},
        {{{"axis2", {2, 0, 0}}}, "a.json: /lights/0/axis2: must not be parallel to axis1"},
        {{{"axis2", {0, 0, 1e300}}}, "a.json: /lights/0/axis2: must be a non-zero vector of length at most 1e15"},
        {{{"size", {0, 2}}}, "a.json: /lights/0/size/0: must be in [1, 64] (got 0)"},
        {{{"size", {2, 65}}}, "a.json: /lights/0/size/1: must be in [1, 64] (got 65)"},
        {{{"size", {2.5, 2}}}, "a.json: /lights/0/size/0: must be an integer in [1, 64]"},
        {{{"size", {2}}}, "a.json: /lights/0/size: must be [n1, n2]"},
        {{{"position", {0, 1e300, 0}}}, "a.json: /lights/0/position: must lie within 1e150"},
        {{{"type", "disk"}, {"normal", {0, -1, 0}}, {"radius", 1}, {"size", {1, 4}}},
         "a.json: /lights/0/size/0: must be in [2, 64] (got 1)"},
        {{{"type", "disk"}, {"normal", {0, 0, 0}}, {"radius", 1}}, "a.json: /lights/0/normal: must be a finite, non-zero vector"},
        {{{"type", "disk"}, {"normal", {0, 1, 0}}, {"radius", -1}}, "a.json: /lights/0/radius: must be in (0, 1e15]"},
    };
    for (const auto& [change, says] : cases) {
        json l = good;
        for (const auto& [k, v] : change.items()) l[k] = v;
        if (l["type"] == "disk") l.erase("axis1"), l.erase("axis2");
        INFO(l.dump());
        CHECK_THROWS_WITH(parse_scene(floor_scene(l, json::array()), "a.json"), Catch::Contains(says));
    }
    // A number past a double in the file (JSON has no infinity: 1e999) is refused by the reader,
    // naming the file, before any field sees it.
    const fs::path dir = refract::test::fresh_dir("area-light", "errors");
    std::string text = floor_scene(good, json::array()).dump();
    const std::string axis = "\"axis1\":[1,0,0]";
    REQUIRE(text.find(axis) != std::string::npos);
    text.replace(text.find(axis), axis.size(), "\"axis1\":[1e999,0,0]");
    std::ofstream{dir / "s.json"} << text;
    const refract::test::Run r = refract::test::run("render " + (dir / "s.json").string() + " -o " + (dir / "o.exr").string(), dir);
    refract::test::check_refused(r, "s.json: malformed JSON: number overflow parsing '1e999'");
    CHECK_FALSE(fs::exists(dir / "o.exr"));
    fs::remove_all(dir);
}

TEST_CASE("POV-Ray export: an area light is area_light with its axes and grid, circular for a disk", "[light][area][export]") {
    const json rect = {{"type", "rectangle"}, {"position", {0, 3, 0}}, {"axis1", {1, 0, 0}}, {"axis2", {0, 0, 2}},
                       {"size", {3, 4}}, {"color", {0.5, 0.5, 0.5}}};
    const std::string pov = validation::export_pov(parse_scene(floor_scene(rect, json::array()), "a.json"));
    CHECK(pov.find("light_source { <0, 3, 0> color rgb <0.5, 0.5, 0.5> area_light <1, 0, 0>, <0, 0, 2>, 3, 4 "
                   "area_illumination on }") != std::string::npos);
    const json disk = {{"type", "disk"}, {"position", {0, 3, 0}}, {"normal", {0, 1, 0}}, {"radius", 0.5}, {"size", {5, 5}}};
    const Scene ds = parse_scene(floor_scene(disk, json::array()), "d.json");
    const std::string dpov = validation::export_pov(ds);
    INFO(dpov);
    CHECK(dpov.find(", 5, 5 circular area_illumination on }") != std::string::npos);
    CHECK(dpov.find("area_light " ) != std::string::npos);
}
