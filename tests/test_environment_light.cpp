// The environment light (background "environment"): a constant radiance or an
// equirectangular map looked up as POV-Ray 3.7's spherical image map (bilinear between
// pixel centres), scaled and turned about +y.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <refract/core/environment_map.h>
#include <refract/core/image.h>
#include <refract/core/image_io.h>
#include <refract/geometry/atomic_file.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include "render_options.h"
#include <refract/validation/pov_export.h>

using namespace refract;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 8, kH = 4;

// A distinct value per pixel of the hand-made 8 × 4 map (row 0 at the top).
Vec3 texel(int i, int j) { return {1.0 + i + 10.0 * j, 0.5 * i + j * j, 0.25 + ((i * 3 + j * 5) % 7)}; }

struct TempDir {
    fs::path path;
    TempDir() : path(fs::temp_directory_path() / ("refract-environment-" + std::to_string(::getpid()))) {
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

std::string write_map(const TempDir& dir, const std::string& name, const Vec3& override_00 = Vec3(-1, -1, -1)) {
    Image img(kW, kH);
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) img.set(i, j, texel(i, j));
    if (override_00 != Vec3(-1, -1, -1)) img.set(0, 0, override_00);
    const std::string path = (dir.path / name).string();
    // Float OpenEXR (the values above are exact in float), through the image module itself:
    // refract's writer refuses the NaN and negative pixels the reader is tested with here.
    const std::vector<float> buf(img.rgb.begin(), img.rgb.end());
    TempFile tmp(path);
    REQUIRE(image_io().write(tmp.fd(), path, kW, kH, 3, PixelType::float32, buf.data(), {}, {}, {}).ok());
    tmp.commit();
    return path;
}

// A scene of `objects` (of material "clear", index 1) in `background`.
json scene_with(const json& background, const json& objects = json::array()) {
    json j{{"camera", {{"location", {0, 0, -4}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 8}, {"height", 6}}},
           {"background", background},
           {"objects", objects},
           {"render", {{"max_depth", 4}, {"threshold", 0}}}};
    if (!objects.empty()) j["materials"] = {{"clear", {{"type", "dielectric"}, {"ior", 1.0}}}};
    return j;
}

json map_background(const std::string& path, double rotation_deg = 0) {
    return {{"type", "environment"}, {"map", path}, {"rotation_deg", rotation_deg}};
}

// The unit direction at continuous map coordinates (x, y), y from the top: azimuth
// θ = 2πx/W from +x towards +z, elevation π(½ − y/H).
Vec3 map_direction(double x, double y) {
    const double theta = 2.0 * M_PI * x / kW;
    const double elevation = M_PI * (0.5 - y / kH);
    return {std::cos(elevation) * std::cos(theta), std::sin(elevation), std::cos(elevation) * std::sin(theta)};
}

// The mean of the four pixels in columns i0, i1 and rows j0, j1.
Vec3 mean4(int i0, int i1, int j0, int j1) {
    return 0.25 * (texel(i0, j0) + texel(i1, j0) + texel(i0, j1) + texel(i1, j1));
}

void check_close(const Vec3& got, const Vec3& want, double tol) {
    for (int c = 0; c < 3; ++c) CHECK(got[c] == Approx(want[c]).margin(tol));
}

}  // namespace

TEST_CASE("Environment light: a constant environment is seen unchanged through an index-1 sphere and with no objects",
          "[environment]") {
    const json constant = {{"type", "environment"}, {"color", {0.3, 0.5, 0.7}}, {"scale", 2}};
    const json sphere = {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1.2}, {"material", "clear"}}};
    for (const json& objects : {json::array(), sphere}) {
        const Scene s = parse_scene(scene_with(constant, objects), "constant.json");
        const RenderResult r = render(s, testing::threads(1));
        for (int j = 0; j < r.image.height; ++j)
            for (int i = 0; i < r.image.width; ++i) check_close(r.image.at(i, j), Vec3(0.6, 1.0, 1.4), 1e-12);
    }
}

TEST_CASE("Environment map: axis directions, poles and pixel centres look up POV-Ray's spherical map bilinearly",
          "[environment]") {
    const TempDir dir;
    const Scene s = parse_scene(scene_with(map_background(write_map(dir, "map.exr"))), "map.json");
    const Background& b = s.background;
    REQUIRE(b.map);
    CHECK(b.map->width == kW);
    CHECK(b.map->height == kH);
    // A pixel's centre gives that pixel (POV-Ray nudges coordinates by 1e-10 pixel).
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) check_close(b.radiance(map_direction(i + 0.5, j + 0.5)), texel(i, j), 1e-8);
    // On the horizon the axes fall between rows 1 and 2 and between two columns: +x on
    // the left edge (columns 7 and 0, wrapped), +z a quarter in, −x in the middle, −z at
    // three quarters.
    check_close(b.radiance({1, 0, 0}), mean4(7, 0, 1, 2), 1e-8);
    check_close(b.radiance({0, 0, 1}), mean4(1, 2, 1, 2), 1e-8);
    check_close(b.radiance({-1, 0, 0}), mean4(3, 4, 1, 2), 1e-8);
    check_close(b.radiance({0, 0, -1}), mean4(5, 6, 1, 2), 1e-8);
    // The poles: azimuth 0 (columns 7 and 0), and, as in POV-Ray, rows that wrap around:
    // both poles sit half a row from the top row and from the bottom row.
    check_close(b.radiance({0, 1, 0}), mean4(7, 0, 3, 0), 1e-8);
    check_close(b.radiance({0, -1, 0}), mean4(7, 0, 3, 0), 1e-8);
    // Between pixel centres: halfway along row 1, a quarter of the way down from row 1 to
    // row 2 (bilinear weights); the length of dir is moot.
    check_close(b.radiance(5.0 * map_direction(3.0, 1.5)), 0.5 * (texel(2, 1) + texel(3, 1)), 1e-8);
    check_close(b.radiance(map_direction(4.5, 1.75)), 0.75 * texel(4, 1) + 0.25 * texel(4, 2), 1e-8);
}

TEST_CASE("Environment map: rotation_deg 90 shows in R·d what the unturned map shows in d", "[environment]") {
    const TempDir dir;
    const std::string map = write_map(dir, "map.exr");
    const Scene plain = parse_scene(scene_with(map_background(map)), "plain.json");
    const Scene turned = parse_scene(scene_with(map_background(map, 90)), "turned.json");
    // R turns +z towards +x (POV-Ray's rotate y*90): what the map shows along +z is seen
    // along +x, and −x's along +z.
    check_close(turned.background.radiance({1, 0, 0}), mean4(1, 2, 1, 2), 1e-8);
    check_close(turned.background.radiance({0, 0, 1}), mean4(3, 4, 1, 2), 1e-8);
    for (const Vec3& d : {Vec3(0.3, 0.4, 0.5), Vec3(-0.7, 0.1, 0.2), Vec3(0.1, -0.9, -0.3), Vec3(0.2, 0.05, -1)})
        check_close(turned.background.radiance(rotate_about_y(d, 90)), plain.background.radiance(d), 1e-12);
}

TEST_CASE("Environment light: a missing map, a directory, a device, a truncated PPM, a non-positive scale, a NaN or "
          "negative pixel are refused, naming the field",
          "[environment]") {
    const TempDir dir;
    const std::string good = write_map(dir, "good.exr");
    auto refused = [](const json& background) { return parse_scene(scene_with(background), "env.json"); };
    CHECK_THROWS_WITH(refused(map_background((dir.path / "missing.exr").string())),
                      Catch::Contains("env.json: /background/map:") && Catch::Contains("missing.exr: no such file"));
    json scaled = map_background(good);
    scaled["scale"] = -2;
    CHECK_THROWS_WITH(refused(scaled), Catch::Contains("env.json: /background/scale: must be > 0"));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(refused(map_background(write_map(dir, "nan.exr", Vec3(1, nan, 1)))),
                      Catch::Contains("/background/map:") && Catch::Contains("pixel (0, 0) is not finite"));
    CHECK_THROWS_WITH(refused(map_background(write_map(dir, "negative.exr", Vec3(1, 1, -0.5)))),
                      Catch::Contains("/background/map:") && Catch::Contains("pixel (0, 0) is -"));
    const std::string text = (dir.path / "not-an-image.exr").string();
    { std::ofstream(text) << "not an image"; }
    CHECK_THROWS_WITH(refused(map_background(text)), Catch::Contains("/background/map:") && Catch::Contains("not-an-image.exr"));
    // A directory, a device and a PPM shorter than its header: each its own reason, before
    // reading (the PPM's 8192 × 8192 pixels are never allocated).
    fs::create_directories(dir.path / "adir.exr");
    CHECK_THROWS_WITH(refused(map_background((dir.path / "adir.exr").string())),
                      Catch::Contains("/background/map:") && Catch::Contains("adir.exr: is a directory, not an image file"));
    CHECK_THROWS_WITH(refused(map_background("/dev/zero")),
                      Catch::Contains("/background/map: /dev/zero: not a regular file"));
    const std::string ppm = (dir.path / "short.ppm").string();
    { std::ofstream(ppm, std::ios::binary) << "P6\n# a comment\n8192 8192\n255\n" << std::string(1000, 'x'); }
    CHECK_THROWS_WITH(refused(map_background(ppm)),
                      Catch::Contains("/background/map:") &&
                          Catch::Contains("short.ppm: truncated: its header announces a 8192x8192 P6 image of "
                                          "201326592 bytes of pixels, the file holds 1000 after the header"));
    CHECK_THROWS_WITH(refused({{"type", "environment"}, {"map", good}, {"color", {1, 1, 1}}}),
                      Catch::Contains("/background: an environment needs either \"color\" or \"map\""));
    CHECK_THROWS_WITH(refused({{"type", "environment"}, {"color", {1, 1, 1}}, {"spectrum", "d65"}}),
                      Catch::Contains("/background/spectrum"));
}

TEST_CASE("Environment light: the map path is relative to the scene file's directory", "[environment]") {
    const TempDir dir;
    write_map(dir, "relative.exr");
    const Scene s = parse_scene(scene_with(map_background("relative.exr")), (dir.path / "scene.json").string());
    REQUIRE(s.background.map);
    CHECK(fs::equivalent(s.background.map->path, dir.path / "relative.exr"));
}

TEST_CASE("Environment light: the POV-Ray export is a sky_sphere with the map, its emission and rotation",
          "[environment]") {
    const TempDir dir;
    json bg = map_background(write_map(dir, "map.exr"), 30);
    bg["scale"] = 0.75;
    const Scene s = parse_scene(scene_with(bg), "env.json");
    validation::ExportOptions eo;
    eo.environment_map = "sky.exr";
    const std::string pov = validation::export_pov(s, eo);
    CHECK_THAT(pov, Catch::Contains("sky_sphere {\n  pigment { image_map { exr \"sky.exr\" map_type 1 interpolate 2 } }\n"
                                    "  emission rgb <0.75, 0.75, 0.75>\n  rotate y*30\n}"));
    const std::string written = (dir.path / "sky.exr").string();
    validation::write_environment_map(s, written);
    const Image back = read_image(written);
    CHECK(back.at(5, 2) == texel(5, 2));
    // A constant environment is POV-Ray's background colour, times its scale.
    const Scene c = parse_scene(scene_with({{"type", "environment"}, {"color", {0.2, 0.4, 0.5}}, {"scale", 2}}), "c.json");
    CHECK_THAT(validation::export_pov(c), Catch::Contains("background { rgb <0.4, 0.8, 1> }"));
    // POV-Ray reads OpenEXR in half precision: a value that is not a half is refused.
    const Scene fine = parse_scene(scene_with(map_background(write_map(dir, "fine.exr", Vec3(0.1, 1, 1)))), "fine.json");
    CHECK_THROWS_WITH(validation::export_pov(fine), Catch::Contains("/background/map") && Catch::Contains("half-precision"));
}
