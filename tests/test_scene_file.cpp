// Bad scene input: one clear message naming the file and the JSON path, never a crash.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

#include <cmath>

#include <refract/core/render.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

using namespace refract;
using Catch::Matchers::Contains;

namespace {

const char* kGood = R"({
  "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 40, "width": 8, "height": 6},
  "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
  "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"}]
})";

std::string error_of(const std::string& text) {
    try {
        parse_scene(nlohmann::json::parse(text), "s.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Where the material's name "glass" (quotes included) starts in kGood.
size_t glass_at() { return std::string(kGood).find("\"glass\": {"); }

std::string with(const std::string& from, const std::string& to) {
    std::string s = kGood;
    const auto pos = s.find(from);
    REQUIRE(pos != std::string::npos);
    return s.replace(pos, from.size(), to);
}

}  // namespace

TEST_CASE("A valid scene file parses into the scene it describes", "[scene]") {
    const Scene s = parse_scene(nlohmann::json::parse(kGood), "s.json");
    CHECK(s.camera.width == 8);
    CHECK(s.objects.size() == 1);
    CHECK(s.materials.at(0).dielectric()->ior == 1.5);
    CHECK(std::get<Sphere>(s.objects[0].shape).radius == 1.0);
}

TEST_CASE("Bad scene input names the file and the JSON path", "[scene][errors]") {
    CHECK_THAT(error_of(with("\"radius\": 1", "\"raduis\": 1")), Contains("s.json: /objects/0/raduis: unknown field"));
    CHECK_THAT(error_of(with("\"ior\": 1.5", "\"ior\": 0")), Contains("s.json: /materials/glass/ior: must be > 0"));
    CHECK_THAT(error_of(with("\"ior\": 1.5", "\"ior\": -2")), Contains("/materials/glass/ior"));
    nlohmann::json huge = nlohmann::json::parse(kGood);
    huge["objects"][0]["radius"] = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(parse_scene(huge, "s.json"), Contains("s.json: /objects/0/radius: must be a finite number"));
    CHECK_THAT(error_of(with("\"width\": 8", "\"width\": 0")), Contains("/camera/width: must be in"));
    CHECK_THAT(error_of(with("\"type\": \"dielectric\"", "\"type\": \"glassy\"")),
               Contains("/materials/glass/type: unknown material type 'glassy'"));
    CHECK_THAT(error_of(with("\"material\": \"glass\"", "\"material\": \"gold\"")),
               Contains("/objects/0/material: unknown material 'gold'"));
    CHECK_THAT(error_of(with("\"center\": [0, 0, 0]", "\"center\": [0, \"a\", 0]")),
               Contains("/objects/0/center/1: must be a number"));
    CHECK_THAT(error_of(with("\"type\": \"sphere\"", "\"type\": \"torus\"")),
               Contains("/objects/0/type: unknown object type 'torus'"));
}

TEST_CASE("Scene text echoed in a message is clipped to 64 bytes and its length: keys, names, values, and the "
          "description is a string",
          "[scene][errors][limits]") {
    const std::string big(1 << 20, 'k');
    const std::string clipped = std::string(64, 'k') + "\u2026(1048576 bytes)";
    std::string e = error_of(with("\"radius\": 1", "\"" + big + "\": 1"));
    CHECK_THAT(e, Contains("s.json: /objects/0/" + clipped + ": unknown field (expected one of:"));
    CHECK(e.size() < 300);
    e = error_of(with("\"type\": \"sphere\"", "\"type\": \"" + big + "\""));
    CHECK_THAT(e, Contains("/objects/0/type: unknown object type '" + clipped + "' (sphere,"));
    CHECK(e.size() < 300);
    // A material's name in its fields' paths.
    e = error_of(with("\"ior\": 1.5", "\"ior\": 1.5, \"x\": 1").replace(glass_at(), 7, "\"" + big + "\""));
    CHECK_THAT(e, Contains("s.json: /materials/" + clipped + "/x: unknown field"));
    CHECK(e.size() < 300);
    // Whole characters: a 2-byte character across the 64th byte is left out, not cut.
    CHECK(clip_echo(std::string(63, 'a') + "\u00e9" + "b") == std::string(63, 'a') + "\u2026(66 bytes)");
    CHECK(clip_echo(std::string(64, 'a')) == std::string(64, 'a'));
    for (const char* d : {"5", "[\"a\"]", "{}", "null", "true"})
        CHECK_THAT(error_of(with("{\n", std::string("{\"description\": ") + d + ",\n")),
                   Contains("s.json: /description: must be a string"));
    CHECK(error_of(with("{\n", "{\"description\": \"a sphere\",\n")).empty());
}

TEST_CASE("Missing and malformed scene files are refused with the file name", "[scene][errors]") {
    CHECK_THROWS_WITH(load_scene("no-such-scene.json"), Contains("no-such-scene.json: cannot open"));
    const auto path = std::filesystem::temp_directory_path() / "refract-malformed-scene.json";
    {
        std::ofstream f(path);
        f << "{\"camera\": {\"width\": NaN}}";
    }
    CHECK_THROWS_WITH(load_scene(path.string()), Contains("malformed JSON"));
    {
        std::ofstream f(path);
        f << "{\"camera\": {\"width\": 1e999}}";
    }
    CHECK_THROWS_WITH(load_scene(path.string()), Contains("malformed JSON: number overflow"));
    std::filesystem::remove(path);
}

TEST_CASE("A failed image write leaves no file behind", "[image][errors]") {
    Image img(4, 3);
    const auto dir = std::filesystem::temp_directory_path() / "refract-image-test";
    std::filesystem::create_directories(dir);
    CHECK_THROWS_AS(write_image((dir / "x.unknownext").string(), img), InputError);
    CHECK_THROWS_AS(write_image((dir / "missing-dir" / "x.png").string(), img), InputError);
    write_image((dir / "ok.exr").string(), img);
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
    CHECK(files == 1);  // only ok.exr: no temporary left over
    const Image back = read_image((dir / "ok.exr").string());
    CHECK(back.width == 4);
    CHECK(back.height == 3);
    std::filesystem::remove_all(dir);
}

TEST_CASE("Hardening: a Sellmeier pole between whole nanometres, an image over 2^26 pixels, a light at the targets' "
          "centre", "[scene][limits]") {
    using nlohmann::json;
    // n² = 1 + B λ²/(λ² − C) has its pole at λ = √C = 550.5 nm: sampled every nanometre, it
    // was missed.
    const double C = 0.5505 * 0.5505;
    CHECK_THROWS_WITH(spectrum::parse_dispersion(json{{"model", "sellmeier"}, {"B", {1.0}}, {"C", {C}}}, "s.json: /d"),
                      Catch::Contains("/d/C") && Catch::Contains("550.5"));
    json big = {{"camera", {{"width", 32768}, {"height", 32768}}}, {"objects", json::array()}};
    CHECK_THROWS_WITH(parse_scene(big, "big.json"), Catch::Contains("/camera/height") && Catch::Contains("2^26"));
    // A point light midway between two glass spheres: the targets' centre, where the light
    // pass's reference distance was 0 (0 · ∞ photons).
    json two = {{"camera", {{"location", {0, 6, -6}}, {"look_at", {0, 0, 0}}, {"width", 24}, {"height", 16}}},
                {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}}, {"floor", {{"type", "diffuse"}}}}},
                {"objects", {{{"type", "sphere"}, {"center", {-2, 1, 0}}, {"radius", 0.8}, {"material", "glass"}},
                             {{"type", "sphere"}, {"center", {2, 1, 0}}, {"radius", 0.8}, {"material", "glass"}},
                             {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}}},
                {"lights", {{{"position", {0, 1, 0}}}}},
                {"render", {{"light_pass", {{"photons", 20000}}}}}};
    RenderOptions o;
    o.threads = 2;
    const RenderResult r = render(parse_scene(two, "two.json"), o);
    double sum = 0;
    for (double v : r.image.rgb) sum += v;
    CHECK(std::isfinite(sum));
    CHECK(sum > 0);
}

TEST_CASE("A non-finite pixel is reported as an internal error naming the pixel, never returned", "[scene][limits]") {
    using nlohmann::json;
    json j = {{"camera", {{"location", {0, 0, -4}}, {"width", 4}, {"height", 3}}},
              {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", {{"type", "diffuse"}}}}}},
              {"lights", {{{"position", {0, 0, -5}}}}}};
    Scene s = parse_scene(j, "inf.json");
    s.lights[0].color = Vec3(std::numeric_limits<double>::infinity(), 1, 1);  // past the reader's checks
    CHECK_THROWS_WITH(render(s), Catch::Contains("internal error") && Catch::Contains("pixel ("));
}

TEST_CASE("A camera field that does not apply to its type is refused, naming it", "[scene][limits]") {
    using nlohmann::json;
    json p = {{"camera", {{"width", 4}, {"height", 3}, {"ortho_height", 2}}}, {"objects", json::array()}};
    CHECK_THROWS_WITH(parse_scene(p, "p.json"), Catch::Contains("/camera/ortho_height") && Catch::Contains("orthographic"));
    json o = {{"camera", {{"type", "orthographic"}, {"width", 4}, {"height", 3}, {"angle", 40}}}, {"objects", json::array()}};
    CHECK_THROWS_WITH(parse_scene(o, "o.json"), Catch::Contains("/camera/angle"));
    o["camera"].erase("angle");
    o["camera"]["ortho_height"] = 3;
    CHECK(parse_scene(o, "o.json").camera.ortho_height == 3);
}

TEST_CASE("A dispersive material's ior must agree with its dispersion model's nominal index", "[scene][limits]") {
    using nlohmann::json;
    auto scene = [](const json& material) {
        json sphere = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "w"}};
        json j = {{"camera", {{"width", 4}, {"height", 3}}}, {"objects", json::array({sphere})}};
        j["materials"]["w"] = material;
        return j;
    };
    const double water = spectrum::catalogue("water").nominal();  // n at the d line, 1.3334
    // A rounded n_d is accepted; the model's own index is used.
    const Scene ok = parse_scene(scene({{"type", "dielectric"}, {"ior", 1.333}, {"dispersion", "water"}}), "w.json");
    CHECK(ok.materials[0].dielectric()->ior == water);
    CHECK(parse_scene(scene({{"type", "dielectric"}, {"dispersion", "water"}}), "w.json").materials[0].dielectric()->ior ==
          water);
    CHECK_THROWS_WITH(parse_scene(scene({{"type", "dielectric"}, {"ior", 1.5}, {"dispersion", "water"}}), "w.json"),
                      Catch::Contains("w.json: /materials/w/ior") && Catch::Contains("contradicts") &&
                          Catch::Contains("1.333403"));
    CHECK_THROWS_WITH(parse_scene(scene({{"type", "dielectric"}, {"ior", water + 6e-4}, {"dispersion", "water"}}), "w.json"),
                      Catch::Contains("/materials/w/ior"));
    // POV-Ray's law carries its own ior: the two must be equal.
    const json pov = {{"model", "povray"}, {"ior", 2.42}, {"dispersion", 1.1}};
    CHECK(parse_scene(scene({{"type", "dielectric"}, {"ior", 2.42}, {"dispersion", pov}}), "p.json")
              .materials[0].dielectric()->ior == 2.42);
    CHECK_THROWS_WITH(parse_scene(scene({{"type", "dielectric"}, {"ior", 2.4201}, {"dispersion", pov}}), "p.json"),
                      Catch::Contains("/materials/w/ior"));
}

TEST_CASE("Resource limits of the scene reader and the light pass: file size (a device's too), nesting, photons, "
          "illumination-map elements",
          "[scene][limits]") {
    using nlohmann::json;
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("refract-limits-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    { std::ofstream{dir / "huge.json"} << "{}"; }
    fs::resize_file(dir / "huge.json", (std::uintmax_t{64} << 20) + 1);  // sparse: nothing is written
    CHECK_THROWS_WITH(load_scene((dir / "huge.json").string()), Catch::Contains("huge.json") && Catch::Contains("64 MiB"));
    CHECK_THROWS_WITH(load_scene(dir.string()), Catch::Contains("is a directory"));
    // A device or a pipe has no size: read in chunks and refused once past 64 MiB.
    CHECK_THROWS_WITH(load_scene("/dev/zero"),
                      Catch::Contains("/dev/zero: the scene file is longer than the limit of 64 MiB"));
    // Nesting costs the parser far more than its bytes: at most 64 levels.
    { std::ofstream{dir / "deep.json"} << "{\"a\": \"[[[[\", \"b\":\n" << std::string(64, '[') << std::string(64, ']') << "}"; }
    CHECK_THROWS_WITH(load_scene((dir / "deep.json").string()), Catch::Contains("deep.json: line 2: nested more than 64 levels deep"));
    { std::ofstream{dir / "deep.json"} << "{\"a\": \"[[[[\", \"b\":\n" << std::string(63, '[') << std::string(63, ']') << "}"; }
    CHECK_THROWS_WITH(load_scene((dir / "deep.json").string()), Catch::Contains("deep.json: /a: unknown field"));  // parsed
    fs::remove_all(dir);
    json s = {{"camera", {{"location", {0, 4, -4}}, {"look_at", {0, 0, 0}}, {"width", 8}, {"height", 6}}},
              {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}}, {"floor", {{"type", "diffuse"}}}}},
              {"objects", {{{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 1}, {"material", "glass"}},
                           {{"type", "plane"}, {"name", "floor"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}}},
              {"lights", {{{"position", {0, 8, 0}}}}},
              {"render", {{"light_pass", {{"photons", 1LL << 34}}}}}};
    CHECK_THROWS_WITH(parse_scene(s, "p.json"), Catch::Contains("/render/light_pass/photons") && Catch::Contains("2^31"));
    s["render"]["light_pass"] = {{"photons", 1000}, {"element_size", 1e-4}};
    // Past the memory budget (the default one here: 188 GiB of maps) ...
    CHECK_THROWS_WITH(render(parse_scene(s, "cells.json")),
                      Catch::Contains("cells.json") && Catch::Contains("/render/light_pass/element_size") &&
                          Catch::Contains("--max-memory"));
    // ... and past a map's element limit whatever the budget, naming the object.
    RenderOptions unbounded;
    unbounded.max_memory = std::uint64_t{1} << 60;
    CHECK_THROWS_WITH(render(parse_scene(s, "cells.json"), unbounded),
                      Catch::Contains("cells.json") && Catch::Contains("/render/light_pass/element_size") &&
                          Catch::Contains("floor") && Catch::Contains("4194304"));
}

TEST_CASE("Overflowing input: a camera at 1e308 and a width of 2^64 - 1 are refused, reported as given",
          "[scene][limits]") {
    using nlohmann::json;
    json j = {{"camera", {{"location", {0, 0, -1e308}}, {"width", 4}, {"height", 3}}}, {"objects", json::array()}};
    CHECK_THROWS_WITH(parse_scene(j, "c.json"), Catch::Contains("/camera/location"));
    j = json::parse(R"({"camera": {"width": 18446744073709551615, "height": 3}, "objects": []})");
    CHECK_THROWS_WITH(parse_scene(j, "w.json"), Catch::Contains("/camera/width") && Catch::Contains("18446744073709551615"));
}
