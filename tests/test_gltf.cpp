// glTF scenes as a whole: `refract import` (nodes, cameras, KHR_lights_punctual, the
// KHR_materials_* dielectrics) and `refract export-gltf`, both ways (docs/gltf.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <refract/core/gltf_scene.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

fs::path data_dir() { return fs::path(REFRACT_SOURCE_DIR) / "tests" / "data"; }

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const Material& material_named(const Scene& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return m;
    FAIL("no material " << name);
    throw;
}

// The camera's rays: its location and its unit D, R and U.
void check_same_camera(const Camera& a, const Camera& b) {
    const Camera::Basis p = a.basis(), q = b.basis();
    CHECK((a.location - b.location).norm() < 1e-12);
    CHECK((p.D.normalized() - q.D.normalized()).norm() < 1e-12);
    CHECK((p.R.normalized() - q.R.normalized()).norm() < 1e-12);
    CHECK((p.U.normalized() - q.U.normalized()).norm() < 1e-12);
    CHECK(a.angle_deg == Approx(b.angle_deg).epsilon(1e-12));
    CHECK(a.width == b.width);
    CHECK(a.height == b.height);
}

}  // namespace

TEST_CASE("The ring glTF imports with its gem a dispersive dielectric and renders as the scene written by hand",
          "[gltf]") {
    const GltfImport im = import_gltf((data_dir() / "ring-gem.glb").string(), "ring-gem.glb");
    CHECK(im.warnings.empty());
    // Read as the scene file it would be, beside the model.
    Scene imported = parse_scene(im.scene, (data_dir() / "imported.json").string());
    Scene by_hand = load_scene((data_dir() / "ring-gem-gltf.json").string());
    REQUIRE(imported.objects.size() == 2);
    const auto* gem = material_named(imported, "diamond").dielectric();
    REQUIRE(gem);
    REQUIRE(gem->dispersion);
    // KHR_materials_dispersion 20/V_d → the Abbe model through n_d and V_d.
    CHECK(gem->dispersion->nominal() == 2.417);
    CHECK(gem->dispersion->abbe_number() == Approx(55.3).epsilon(1e-9));
    CHECK(gem->dispersion->n(spectrum::fraunhofer::F) > gem->dispersion->n(spectrum::fraunhofer::C));
    // KHR_materials_volume: colour c after distance d → α = −ln(c)/d.
    REQUIRE(gem->absorption);
    CHECK(gem->absorption->rgb.x() == Approx(-std::log(0.9) / 2).epsilon(1e-12));
    CHECK(gem->absorption->rgb.z() == 0);
    CHECK(material_named(imported, "gold").is<material::Metal>());
    check_same_camera(imported.camera, by_hand.camera);
    CHECK(imported.camera.angle_deg == by_hand.camera.angle_deg);
    REQUIRE(imported.lights.size() == 1);
    CHECK(imported.lights[0].position == Vec3(2, 5, 4));  // the file's (2, 5, -4), mirrored in z
    CHECK(imported.settings.spectral.enabled);
    // Tiny and coarse, the same for both, under a sky (glTF has no background): the images
    // equal pixel for pixel.
    for (Scene* s : {&imported, &by_hand}) {
        s->background.color = Vec3(0.55, 0.7, 0.9);
        s->camera.width = 32;
        s->camera.height = 24;
        s->settings.max_depth = 6;
        s->settings.spectral.sampling.step_nm = 50;
    }
    const RenderResult a = render(imported), b = render(by_hand);
    CHECK(a.image.rgb == b.image.rgb);
    double sum = 0;
    for (double v : a.image.rgb) sum += v;
    CHECK(sum > 10);  // an image, not a black frame
}

TEST_CASE("export-gltf then import gives the scene back: materials, transforms, camera and lights", "[gltf]") {
    const fs::path dir = test::fresh_dir("gltf", "roundtrip");
    write(dir / "s.json", R"({
  "camera": {"location": [1, 2, -5], "look_at": [0, 0.5, 0], "angle": 50, "width": 40, "height": 30},
  "materials": {
    "glass": {"type": "dielectric", "dispersion": {"model": "abbe", "nd": 1.5168, "Vd": 64.17},
              "absorption": {"coefficients": [0.1, 0.2, 0.3]}, "filter": [1, 0.9, 0.8]},
    "stone": {"type": "dielectric", "dispersion": "diamond"},
    "gold": {"type": "metal", "color": [0.9, 0.7, 0.3], "fuzz": 0.25},
    "white": {"type": "diffuse", "color": [0.8, 0.7, 0.6]}},
  "objects": [
    {"type": "polyhedron", "name": "cube", "material": "glass",
     "planes": [[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1], [0, 0, 1, 1], [0, 0, -1, 1]],
     "transform": {"translate": [0.5, 1, 2], "rotate": [10, 20, 30], "scale": [1, 2, 0.5]}},
    {"type": "mesh", "name": "tetra", "material": "stone",
     "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], "triangles": [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
     "transform": {"matrix": [[0, -1, 0, 3], [1, 0, 0, 0], [0, 0, 1, -1], [0, 0, 0, 1]]}},
    {"type": "mesh", "name": "band", "material": "gold",
     "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], "triangles": [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]},
    {"type": "sphere", "name": "ball", "material": "white", "center": [0, -1, 0], "radius": 0.5},
    {"type": "plane", "name": "floor", "material": "white", "normal": [0, 1, 0], "offset": -2}],
  "lights": [{"position": [3, 4, -5], "color": [2, 1, 0.5]},
             {"type": "directional", "direction": [1, -2, 0.5], "color": [0.5, 0.5, 0.5]}]
})");
    const Scene s = load_scene((dir / "s.json").string());
    const GltfExport ex = export_gltf(s, true);
    REQUIRE(ex.warnings.size() == 3);
    CHECK_THAT(ex.warnings[0], Contains("material 'stone'") && Contains("n_d and Abbe number"));
    CHECK_THAT(ex.warnings[1], Contains("object 'ball'") && Contains("sphere tessellated (1280 triangles)"));
    CHECK_THAT(ex.warnings[2], Contains("object 'floor'") && Contains("plane not exported"));
    write(dir / "out.glb", ex.bytes);
    const GltfImport im = import_gltf((dir / "out.glb").string(), "out.glb");
    CHECK(im.warnings.empty());
    const Scene back = parse_scene(im.scene, (dir / "back.json").string());

    // Materials: the index n_d, the Abbe number V_d, the absorption, the colours.
    for (const char* name : {"glass", "stone"}) {
        const auto* a = material_named(s, name).dielectric();
        const auto* b = material_named(back, name).dielectric();
        REQUIRE(b);
        REQUIRE(b->dispersion);
        CHECK(b->ior == Approx(a->ior).epsilon(1e-12));
        CHECK(b->dispersion->abbe_number() == Approx(a->dispersion->abbe_number()).epsilon(1e-9));
    }
    const auto* glass = material_named(back, "glass").dielectric();
    REQUIRE(glass->absorption);
    CHECK((glass->absorption->rgb - Vec3(0.1, 0.2, 0.3)).norm() < 1e-12);
    CHECK((glass->filter - Vec3(1, 0.9, 0.8)).norm() < 1e-15);
    CHECK_FALSE(material_named(back, "stone").dielectric()->absorption);
    const auto* gold = material_named(back, "gold").as<material::Metal>();
    REQUIRE(gold);
    CHECK(gold->color == Vec3(0.9, 0.7, 0.3));
    CHECK(gold->fuzz == 0.25);
    const auto* white = material_named(back, "white").as<material::Diffuse>();
    REQUIRE(white);
    CHECK(white->pigment.color == Vec3(0.8, 0.7, 0.6));

    // Objects: the plane left out, the rest placed where they were, corner by corner (the
    // mesh's coordinates in glTF's float32, the node's matrix as the file reader reads it).
    REQUIRE(back.objects.size() == 4);
    const auto world = [](const Object& o) {
        const Shape& local = o.placement ? *o.placement->local : o.shape;
        TriangleMesh m;
        if (const auto* c = std::get_if<ConvexPolyhedron>(&local)) m = mesh_of(*c);
        else m = std::get<TriangleMesh>(local);
        if (o.placement)
            for (Vec3& v : m.vertices) v = o.placement->transform.point(v);
        return m;
    };
    for (size_t k = 0; k < 3; ++k) {
        const TriangleMesh a = world(s.objects[k]);
        const auto& b = std::get<TriangleMesh>(back.objects[k].shape);
        CHECK(back.objects[k].name == s.objects[k].name);
        REQUIRE(a.triangles.size() == b.triangles.size());
        double d = 0;
        for (size_t t = 0; t < a.triangles.size(); ++t)
            for (int c = 0; c < 3; ++c)
                d = std::max(d, (a.vertices[static_cast<size_t>(a.triangles[t][c])] -
                                 b.vertices[static_cast<size_t>(b.triangles[t][c])]).norm());
        CHECK(d < 1e-6);
    }
    CHECK(std::get<TriangleMesh>(back.objects[3].shape).triangles.size() == 1280);

    check_same_camera(back.camera, s.camera);
    REQUIRE(back.lights.size() == 2);
    CHECK((back.lights[0].position - Vec3(3, 4, -5)).norm() < 1e-12);
    CHECK((back.lights[0].color - Vec3(2, 1, 0.5)).norm() < 1e-12);
    CHECK(back.lights[1].kind == Light::Kind::Directional);
    CHECK((back.lights[1].direction - s.lights[1].direction).norm() < 1e-12);
    CHECK((back.lights[1].color - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12);
}

TEST_CASE("What a glTF holds that refract cannot honour is named in one warning per item", "[gltf]") {
    const fs::path dir = test::fresh_dir("gltf", "warnings");
    std::string glb = read(data_dir() / "ring-gem.glb");
    // The ring-gem's JSON with a texture, an emissive colour, an unknown extension and a
    // spot light added, as a .gltf beside the .glb's buffer (never read by the import).
    const std::uint32_t n = static_cast<std::uint32_t>(static_cast<unsigned char>(glb[12])) |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(glb[13])) << 8;
    nlohmann::json j = nlohmann::json::parse(glb.substr(20, n));
    j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    j["materials"][0]["emissiveFactor"] = {1, 0, 0};
    j["materials"][1]["extensions"]["KHR_materials_clearcoat"] = nlohmann::json::object();
    j["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "spot";
    j["animations"] = {{{"name", "spin"}}};
    write(dir / "ring.gltf", j.dump());
    const GltfImport im = import_gltf((dir / "ring.gltf").string(), "ring.gltf");
    REQUIRE(im.warnings.size() == 5);
    const std::string all = im.warnings[0] + "\n" + im.warnings[1] + "\n" + im.warnings[2] + "\n" + im.warnings[3] +
                            "\n" + im.warnings[4];
    CHECK_THAT(all, Contains("ring.gltf: /animations/0 ('spin'): animations not honoured"));
    CHECK_THAT(all, Contains("ring.gltf: /materials/0 ('gold'): pbrMetallicRoughness/baseColorTexture not honoured"));
    CHECK_THAT(all, Contains("ring.gltf: /materials/0 ('gold'): emissiveFactor not honoured"));
    CHECK_THAT(all, Contains("ring.gltf: /materials/1 ('diamond'): extension KHR_materials_clearcoat not honoured"));
    CHECK_THAT(all, Contains("spot cone not honoured: a point light"));
}

TEST_CASE("A truncated or malformed glTF gives one line naming the file and exit 2, and no scene", "[gltf][cli]") {
    const fs::path dir = test::fresh_dir("gltf", "cli");
    const std::string glb = read(data_dir() / "ring-gem.glb");
    write(dir / "truncated.glb", glb.substr(0, 1000));
    const auto refused = [&](const std::string& model, const std::string& what) {
        test::check_refused(test::run("import " + (dir / model).string() + " -o " + (dir / "s.json").string(), dir), what);
        CHECK_FALSE(fs::exists(dir / "s.json"));
    };
    refused("truncated.glb", "truncated.glb: truncated: the GLB header gives " + std::to_string(glb.size()) +
                                 " bytes, the file has 1000");
    write(dir / "short.glb", glb.substr(0, 7));
    refused("short.glb", "short.glb: truncated: 7 bytes, shorter than the GLB header");
    write(dir / "cut.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0)");
    refused("cut.gltf", "cut.gltf: malformed JSON");
    write(dir / "index.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"name": "a", "mesh": 3}]})");
    refused("index.gltf", "index.gltf: /nodes/0/mesh: must be an index into /meshes");
    refused("missing.glb", "missing.glb: cannot open the glTF file");
}

TEST_CASE("import and export-gltf on the command line: warnings one line each, the files read back", "[gltf][cli]") {
    const fs::path dir = test::fresh_dir("gltf", "cli-ok");
    fs::copy_file(data_dir() / "ring-gem.glb", dir / "ring-gem.glb");
    auto r = test::run("import " + (dir / "ring-gem.glb").string() + " -o " + (dir / "s.json").string(), dir);
    INFO(r.err);
    CHECK(r.code == 0);
    CHECK(r.err.empty());
    const Scene s = load_scene((dir / "s.json").string());
    CHECK(s.objects.size() == 2);
    // A sphere added: one warning line; the .gltf (buffer embedded) imports again.
    nlohmann::json j = nlohmann::json::parse(read(dir / "s.json"));
    j["objects"].push_back({{"type", "sphere"}, {"center", {0, 3, 0}}, {"radius", 0.2}, {"material", "gold"}});
    write(dir / "t.json", j.dump());
    r = test::run("export-gltf " + (dir / "t.json").string() + " -o " + (dir / "out.gltf").string(), dir);
    CHECK(r.code == 0);
    CHECK(test::count_lines(r.err) == 1);
    CHECK_THAT(r.err, Contains("refract: warning: object 'object 2': sphere tessellated"));
    r = test::run("import " + (dir / "out.gltf").string() + " -o " + (dir / "back.json").string(), dir);
    CHECK(r.code == 0);
    CHECK(load_scene((dir / "back.json").string()).objects.size() == 3);
    test::check_refused(test::run("export-gltf " + (dir / "t.json").string() + " -o " + (dir / "out.obj").string(), dir),
                        "--output: '");
}
