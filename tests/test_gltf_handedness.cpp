// glTF's right-handed frame against refract's left-handed (POV-Ray's) camera (docs/gltf.md,
// "Handedness"): the import mirrors z so that refract's image is a glTF viewer's, and
// export-gltf mirrors back, so that a glTF viewer sees refract's image.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/gltf_scene.h>
#include <refract/core/mesh_file.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>

#include "tests/temp_dir.h"

using namespace refract;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A unit cube (counter-clockwise seen from outside) as a .gltf with its buffer embedded, the
// cube's node translated by `at` (and mirrored in x when `mirror`), a camera at the origin
// looking along glTF's −z (its default) and a point light at the camera.
std::string cube_gltf(const std::array<double, 3>& at, bool mirror) {
    const float v[8][3] = {{-0.5f, -0.5f, -0.5f}, {0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f},
                           {-0.5f, -0.5f, 0.5f},  {0.5f, -0.5f, 0.5f},  {0.5f, 0.5f, 0.5f},  {-0.5f, 0.5f, 0.5f}};
    const std::uint32_t t[12][3] = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                    {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    std::string buf(sizeof v + sizeof t, '\0');
    std::memcpy(&buf[0], v, sizeof v);
    std::memcpy(&buf[sizeof v], t, sizeof t);
    json node = {{"name", "cube"}, {"mesh", 0}, {"translation", at}};
    if (mirror) node["scale"] = {-1, 1, 1};
    const json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1, 2}}}}},
        {"nodes", {node, {{"name", "camera"}, {"camera", 0}},
                   {{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}},
        {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"aspectRatio", 4.0 / 3.0}, {"znear", 0.01}}}}}},
        {"extensions", {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 1.0}}}}}}}},
        {"extensionsUsed", {"KHR_lights_punctual"}},
        {"materials", {{{"name", "white"}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}}},
        {"meshes", {{{"name", "cube"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
        {"buffers", {{{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", sizeof v}},
                         {{"buffer", 0}, {"byteOffset", sizeof v}, {"byteLength", sizeof t}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 8}, {"type", "VEC3"},
                        {"min", {-0.5, -0.5, -0.5}}, {"max", {0.5, 0.5, 0.5}}},
                       {{"bufferView", 1}, {"componentType", 5125}, {"count", 36}, {"type", "SCALAR"}}}}};
    return doc.dump();
}

// The image's light in its left and right halves.
std::pair<double, double> halves(const Image& im) {
    double left = 0, right = 0;
    for (int j = 0; j < im.height; ++j)
        for (int i = 0; i < im.width; ++i) (2 * i < im.width ? left : right) += im.at(i, j).sum();
    return {left, right};
}

Image imported_image(const fs::path& dir, const std::array<double, 3>& at, bool mirror) {
    std::ofstream(dir / "cube.gltf") << cube_gltf(at, mirror);
    const GltfImport im = import_gltf((dir / "cube.gltf").string(), "cube.gltf", 32, 24);
    return render(parse_scene(im.scene, (dir / "imported.json").string())).image;
}

}  // namespace

TEST_CASE("glTF handedness: an object on a glTF viewer's left is on the left of the imported scene's image, above "
          "on top",
          "[gltf][handedness]") {
    const fs::path dir = test::fresh_dir("gltf", "handedness");
    // glTF's default camera looks along −z with +x to the right: x = −1.5 is on the left.
    const auto [left, right] = halves(imported_image(dir, {-1.5, 0, -5}, false));
    CHECK(left > 1);
    CHECK(right == 0);
    const auto [l2, r2] = halves(imported_image(dir, {1.5, 0, -5}, false));
    CHECK(l2 == 0);
    CHECK(r2 > 1);
    const Image up = imported_image(dir, {0, 1.2, -5}, false);
    double top = 0, bottom = 0;
    for (int j = 0; j < up.height; ++j)
        for (int i = 0; i < up.width; ++i) (2 * j < up.height ? top : bottom) += up.at(i, j).sum();
    CHECK(top > 1);
    CHECK(bottom == 0);
    // A mirrored node (scale −1 in x) is read turned round: still closed, outward and lit.
    const TriangleMesh m = read_mesh_file((dir / "cube.gltf").string(), "cube");
    CHECK(mesh_closure(m).volume == Approx(1).epsilon(1e-12));
    std::ofstream(dir / "cube.gltf") << cube_gltf({-1.5, 0, -5}, true);
    const TriangleMesh mirrored = read_mesh_file((dir / "cube.gltf").string(), "cube");
    const MeshClosure c = mesh_closure(mirrored);
    CHECK(c.open_edges == 0);
    CHECK(c.inconsistent_edges == 0);
    CHECK(c.volume == Approx(1).epsilon(1e-12));
    const auto [ml, mr] = halves(imported_image(dir, {-1.5, 0, -5}, true));
    CHECK(ml == Approx(left).epsilon(1e-12));
    CHECK(mr == 0);
    fs::remove_all(dir);
}

TEST_CASE("glTF handedness: export-gltf writes the scene so that a glTF camera sees an object on the left of refract's "
          "image on its left (its −x), and the import brings it back",
          "[gltf][handedness]") {
    const fs::path dir = test::fresh_dir("gltf", "handedness-export");
    std::ofstream(dir / "s.json") << R"({
  "camera": {"location": [0, 0, -5], "look_at": [0, 0, 0], "angle": 50, "width": 32, "height": 24},
  "materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
  "objects": [{"type": "polyhedron", "name": "box", "material": "white",
               "planes": [[1, 0, 0, 0.5], [-1, 0, 0, 0.5], [0, 1, 0, 0.5], [0, -1, 0, 0.5], [0, 0, 1, 0.5], [0, 0, -1, 0.5]],
               "transform": {"translate": [-1.5, 0, 0]}}],
  "lights": [{"position": [0, 0, -5], "color": [1, 1, 1]}]
})";
    const Scene s = load_scene((dir / "s.json").string());
    const auto [left, right] = halves(render(s).image);
    REQUIRE(left > 1);
    REQUIRE(right == 0);
    const GltfExport ex = export_gltf(s, false);
    const json doc = json::parse(ex.bytes);
    // The camera node's +x (a glTF viewer's image right) and the box's centre seen from it.
    Vec3 cam_x = Vec3::Zero(), cam_at = Vec3::Zero(), box_at = Vec3::Zero();
    for (const json& n : doc["nodes"]) {
        const auto& m = n["matrix"];
        if (n.contains("camera")) {
            cam_x = Vec3(m[0].get<double>(), m[1].get<double>(), m[2].get<double>());
            cam_at = Vec3(m[12].get<double>(), m[13].get<double>(), m[14].get<double>());
        } else if (n.contains("mesh")) {
            box_at = Vec3(m[12].get<double>(), m[13].get<double>(), m[14].get<double>());
        }
    }
    CHECK((box_at - cam_at).dot(cam_x) == Approx(-1.5).epsilon(1e-12));
    std::ofstream(dir / "out.gltf", std::ios::binary) << ex.bytes;
    const GltfImport im = import_gltf((dir / "out.gltf").string(), "out.gltf");
    const auto [l2, r2] = halves(render(parse_scene(im.scene, (dir / "back.json").string())).image);
    CHECK(l2 == Approx(left).epsilon(1e-3));
    CHECK(r2 == 0);
    fs::remove_all(dir);
}
