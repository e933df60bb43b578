// Mesh files in scenes (OBJ, PLY, STL, glTF through Assimp), their closure check, the
// instancing cache, and the transforms of every object.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <refract/core/mesh_file.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/geometry/transform.h>
#include <refract/validation/random_scene.h>
#include <refract/validation/random_suite.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A unit cube [0, 1]³: 8 corners, 12 triangles counter-clockwise seen from outside.
const char* kCubeObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3
f 1 3 2
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 8 7
f 4 7 3
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
)";

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string scene_with(const std::string& object, const std::string& material = "glass") {
    return R"({"camera": {"location": [0.5, 0.5, -4], "look_at": [0.5, 0.5, 0.5], "angle": 40, "width": 16, "height": 12},
  "materials": {"glass": {"type": "dielectric", "ior": 1.5}, "white": {"type": "diffuse", "color": [1, 1, 1]}},
  "lights": [{"position": [2, 5, -4]}],
  "objects": [)" + object + R"(, "material": ")" + material + R"("}]})";
}

Scene load(const fs::path& dir, const std::string& text) {
    write(dir / "s.json", text);
    return load_scene((dir / "s.json").string());
}

std::string error_of(const fs::path& dir, const std::string& text) {
    try {
        load(dir, text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// The cube as an ASCII STL (every corner stored apart) and a binary PLY (indexed).
std::string cube_stl(const TriangleMesh& m) {
    std::string s = "solid cube\n";
    for (const auto& t : m.triangles) {
        s += "facet normal 0 0 0\nouter loop\n";
        for (int c = 0; c < 3; ++c) {
            const Vec3& v = m.vertices[static_cast<size_t>(t[c])];
            s += "vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
        }
        s += "endloop\nendfacet\n";
    }
    return s + "endsolid cube\n";
}

std::string cube_ply(const TriangleMesh& m) {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.vertices.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const Vec3& v : m.vertices)
        for (int c = 0; c < 3; ++c) {
            const float f = static_cast<float>(v[c]);
            s.append(reinterpret_cast<const char*>(&f), 4);
        }
    for (const auto& t : m.triangles) {
        s += '\3';
        for (int c = 0; c < 3; ++c) {
            const std::int32_t i = t[c];
            s.append(reinterpret_cast<const char*>(&i), 4);
        }
    }
    return s;
}

double volume(const TriangleMesh& m) { return mesh_closure(m).volume; }

fs::path data_dir() { return fs::path(REFRACT_SOURCE_DIR) / "tests" / "data"; }

}  // namespace

TEST_CASE("A mesh file reads as its triangles: OBJ, STL and binary PLY give the same closed cube", "[meshfile]") {
    const fs::path dir = test::fresh_dir("meshfile", "formats");
    write(dir / "cube.obj", kCubeObj);
    const TriangleMesh obj = read_mesh_file((dir / "cube.obj").string());
    CHECK(obj.vertices.size() == 8);  // the OBJ importer's per-corner copies joined again
    CHECK(obj.triangles.size() == 12);
    CHECK(mesh_closure(obj).closed_outward());
    CHECK(volume(obj) == Approx(1.0).epsilon(1e-15));
    write(dir / "cube.stl", cube_stl(obj));
    write(dir / "cube.ply", cube_ply(obj));
    for (const char* name : {"cube.stl", "cube.ply"}) {
        INFO(name);
        const TriangleMesh m = read_mesh_file((dir / name).string());
        CHECK(m.vertices.size() == 8);
        CHECK(m.triangles.size() == 12);
        CHECK(mesh_closure(m).closed_outward());
        CHECK(volume(m) == Approx(1.0).epsilon(1e-15));
        const auto b = bounds(m);
        CHECK(b->lo == Vec3(0, 0, 0));  // no change of axes
        CHECK(b->hi == Vec3(1, 1, 1));
    }
}

TEST_CASE("A transparent mesh file must be closed and consistently oriented: the open and misoriented edges counted",
          "[meshfile]") {
    const fs::path dir = test::fresh_dir("meshfile", "closure");
    std::string open = kCubeObj;
    open.erase(open.find("f 2 7 6\n"));  // one triangle gone: its three edges open
    write(dir / "open.obj", open);
    std::string flipped = kCubeObj;
    flipped.replace(flipped.find("f 2 7 6"), 7, "f 2 6 7");  // one triangle wound the wrong way
    write(dir / "flipped.obj", flipped);
    const std::string e_open = error_of(dir, scene_with(R"({"type": "mesh", "file": "open.obj")"));
    CHECK_THAT(e_open, Contains("s.json: /objects/0/file: ") && Contains("open.obj") &&
                           Contains("must be closed and consistently oriented: 3 open edges, 0 inconsistently oriented edges"));
    const std::string e_flip = error_of(dir, scene_with(R"({"type": "mesh", "file": "flipped.obj")"));
    CHECK_THAT(e_flip, Contains("flipped.obj") && Contains("0 open edges, 3 inconsistently oriented edges"));
    // Opaque meshes need not enclose anything.
    CHECK(std::get<TriangleMesh>(load(dir, scene_with(R"({"type": "mesh", "file": "open.obj")", "white")).objects[0].shape)
              .triangles.size() == 11);
    // Inside out (every triangle reversed): closed, consistent, but of negative volume.
    std::string inverted;
    for (std::size_t at = 0, next; at < std::string(kCubeObj).size(); at = next + 1) {
        next = std::string(kCubeObj).find('\n', at);
        std::string line = std::string(kCubeObj).substr(at, next - at);
        if (line[0] == 'f') std::swap(line[4], line[6]);
        inverted += line + "\n";
    }
    write(dir / "inverted.obj", inverted);
    CHECK_THAT(error_of(dir, scene_with(R"({"type": "mesh", "file": "inverted.obj")")),
               Contains("0 open edges, 0 inconsistently oriented edges, wound inside out (volume -1)"));
}

TEST_CASE("Bad mesh files are refused naming the file and the item", "[meshfile]") {
    const fs::path dir = test::fresh_dir("meshfile", "bad");
    const std::string glb = (data_dir() / "ring-gem.glb").string();
    std::ifstream in(glb, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write(dir / "truncated.glb", bytes.substr(0, bytes.size() / 2));
    write(dir / "empty.obj", "");
    write(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n");
    write(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    write(dir / "cube.fbx", "x");
    fs::copy_file(glb, dir / "ring-gem.glb");
    const auto refused = [&](const std::string& object, const std::string& field, const std::string& what) {
        const std::string e = error_of(dir, scene_with(object, "white"));
        INFO(e);
        CHECK_THAT(e, Contains("s.json: /objects/0/" + field + ": ") && Contains(what));
        CHECK(e.find('\n') == std::string::npos);
    };
    refused(R"({"type": "mesh", "file": "truncated.glb")", "file", "truncated.glb: cannot read the mesh");
    refused(R"({"type": "mesh", "file": "empty.obj")", "file", "empty.obj");
    refused(R"({"type": "mesh", "file": "nan.obj")", "file", "nan.obj: mesh 'defaultobject': vertex 2 is not finite");
    refused(R"({"type": "mesh", "file": "flat.obj")", "file", "flat.obj: mesh 'defaultobject': triangle 0 is degenerate");
    refused(R"({"type": "mesh", "file": "missing.ply")", "file", "missing.ply: cannot open the mesh file");
    refused(R"({"type": "mesh", "file": "cube.fbx")", "file", "unsupported mesh format '.fbx' (obj, ply, stl, gltf, glb)");
    refused(R"({"type": "mesh", "file": "ring-gem.glb", "node": "band")", "node",
            "ring-gem.glb: no node or mesh named 'band' (nodes: ");
    refused(R"({"type": "mesh", "file": "ring-gem.glb", "vertices": [[0, 0, 0]])", "file", "either a file or vertices");
    refused(R"({"type": "mesh", "node": "gem", "vertices": [[0, 0, 0]])", "node", "give the file too");
}

TEST_CASE("Bad mesh files exit 2 with one line on the command line", "[meshfile][cli]") {
    const fs::path dir = test::fresh_dir("meshfile", "cli");
    std::ifstream in(data_dir() / "ring-gem.glb", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write(dir / "truncated.glb", bytes.substr(0, 1000));
    write(dir / "s.json", scene_with(R"({"type": "mesh", "file": "truncated.glb")"));
    test::check_refused(test::run("render " + (dir / "s.json").string() + " -o " + (dir / "x.png").string(), dir),
                        "/objects/0/file: ");
    CHECK_FALSE(fs::exists(dir / "x.png"));
}

TEST_CASE("A mesh file used by many objects is read once (instancing)", "[meshfile]") {
    const fs::path dir = test::fresh_dir("meshfile", "instancing");
    write(dir / "cube.obj", kCubeObj);
    const std::uint64_t before = mesh_file_reads();
    const Scene s = load(dir, R"({"camera": {"location": [0, 0, -9], "look_at": [0, 0, 0], "width": 8, "height": 6},
      "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
      "objects": [{"type": "mesh", "file": "cube.obj", "material": "glass"},
                  {"type": "mesh", "file": "./cube.obj", "material": "glass", "transform": {"translate": [2, 0, 0]}},
                  {"type": "mesh", "file": "cube.obj", "material": "glass", "transform": {"translate": [-2, 0, 0]}}]})");
    CHECK(mesh_file_reads() - before == 1);
    REQUIRE(s.objects.size() == 3);
    // The untransformed mesh is kept once, shared by the transformed instances.
    CHECK(s.objects[1].placement->local == s.objects[2].placement->local);
    CHECK(std::get<TriangleMesh>(s.objects[1].shape).vertices[6] == Vec3(3, 1, 1));
    CHECK(std::get<TriangleMesh>(s.objects[2].shape).vertices[6] == Vec3(-1, 1, 1));
}

TEST_CASE("A transform is matrix, then scale, then rotate, then translate, whatever order it is written in",
          "[transform]") {
    const fs::path dir = test::fresh_dir("meshfile", "order");
    // The point (1, 0, 0) of the sphere's centre: matrix moves it to (1, 1, 0), scale 2 to
    // (2, 2, 0), a quarter turn about z to (−2, 2, 0), the translation to (−2, 2, 5).
    for (const char* t : {R"({"translate": [0, 0, 5], "rotate": [0, 0, 90], "scale": 2, "matrix": [[1, 0, 0, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]]})",
                          R"({"matrix": [1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1], "scale": [2, 2, 2], "rotate": [0, 0, 90], "translate": [0, 0, 5]})"}) {
        const Scene s = load(dir, scene_with(std::string(R"({"type": "sphere", "center": [1, 0, 0], "radius": 0.5, "transform": )") + t));
        const Sphere& sp = std::get<Sphere>(s.objects[0].shape);
        CHECK(sp.center.x() == Approx(-2).margin(1e-15));
        CHECK(sp.center.y() == Approx(2).margin(1e-15));
        CHECK(sp.center.z() == Approx(5).margin(1e-15));
        CHECK(sp.radius == Approx(1.0).epsilon(1e-15));
        CHECK(std::get<Sphere>(*s.objects[0].placement->local).center == Vec3(1, 0, 0));
    }
}

TEST_CASE("Transformed shapes: planes by the inverse transpose, meshes mirrored stay outward, spheres refuse shear",
          "[transform]") {
    Transform shear;
    shear.linear << 1, 0.5, 0, 0, 1, 0, 0, 0, 2;
    shear.translation = Vec3(0, 3, 0);
    // The plane y = 1 (points (x, 1, z)) moves to y' = 4 for every x, z: the plane y = 4.
    const Plane p = std::get<Plane>(*transformed(Plane{Vec3(0, 1, 0), 1}, shear));
    CHECK((p.normal - Vec3(0, 1, 0)).norm() < 1e-15);
    CHECK(p.offset == Approx(4).epsilon(1e-15));
    for (const Vec3& x : {Vec3(0, 1, 0), Vec3(2, 1, -3), Vec3(-5, 1, 7)})
        CHECK(p.normal.dot(shear.point(x)) == Approx(p.offset).margin(1e-14));
    // A polyhedron's planes hold the transformed corners of its mesh.
    ConvexPolyhedron cube;
    for (int a = 0; a < 3; ++a)
        for (double s : {1.0, -1.0}) {
            Vec3 n = Vec3::Zero();
            n[a] = s;
            cube.planes.push_back(Plane{n, 1});
        }
    set_bound(cube, vertices(cube));
    const auto moved = std::get<ConvexPolyhedron>(*transformed(cube, shear));
    for (const Vec3& v : vertices(cube)) {
        double worst = -1e300;
        for (const Plane& q : moved.planes) worst = std::max(worst, q.normal.dot(shear.point(v)) - q.offset);
        CHECK(worst == Approx(0).margin(1e-14));  // on the surface, inside every half-space
        CHECK((shear.point(v) - moved.bound_center).norm() <= moved.bound_radius);
    }
    // A mirror keeps the mesh closed and outward: each triangle rewound.
    Transform mirror;
    mirror.linear = Vec3(-1, 1, 1).asDiagonal();
    const TriangleMesh m = mesh_of(cube);
    const auto mirrored = std::get<TriangleMesh>(*transformed(m, mirror));
    CHECK(mesh_closure(mirrored).closed_outward());
    CHECK(volume(mirrored) == Approx(8).epsilon(1e-15));
    // A sphere takes rotation, mirror and uniform scale only.
    Transform uniform;
    uniform.linear = 3 * Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix() * mirror.linear;
    CHECK(std::get<Sphere>(*transformed(Sphere{Vec3(1, 0, 0), -2}, uniform)).radius == Approx(-6).epsilon(1e-14));
    CHECK_FALSE(transformed(Sphere{Vec3(0, 0, 0), 1}, shear));
}

TEST_CASE("Bad transforms are refused naming the field", "[transform]") {
    const fs::path dir = test::fresh_dir("meshfile", "badtransform");
    const auto refused = [&](const std::string& transform, const std::string& what) {
        const std::string e = error_of(dir, scene_with(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "transform": )" + transform));
        INFO(e);
        CHECK_THAT(e, Contains(what));
    };
    refused(R"({"scale": [1, 2, 1]})", "s.json: /objects/0/transform: a sphere takes only rotation, translation and uniform scale");
    refused(R"({"scale": 0})", "s.json: /objects/0/transform/scale: must be non-zero");
    refused(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]})",
            "s.json: /objects/0/transform/matrix: the last row must be [0, 0, 0, 1]");
    refused(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1]]})", "s.json: /objects/0/transform: the transform is singular");
    refused(R"({"matrix": [1, 0, 0]})", "s.json: /objects/0/transform/matrix: must be 4 rows of 4 finite numbers");
    refused(R"({"rotate": [0, "x", 0]})", "s.json: /objects/0/transform/rotate");
    refused(R"({"shear": 1})", "s.json: /objects/0/transform");
}

TEST_CASE("The ring-holding-a-gem glTF renders identically to the same scene written inline", "[meshfile][transform]") {
    const Scene by_file = load_scene((data_dir() / "ring-gem.json").string());
    const Scene inline_ = load_scene((data_dir() / "ring-gem-inline.json").string());
    REQUIRE(by_file.objects.size() == 2);
    const auto& gem = std::get<TriangleMesh>(by_file.objects[1].shape);
    CHECK(gem.triangles.size() == 32);
    CHECK(mesh_closure(gem).closed_outward());
    CHECK(std::get<TriangleMesh>(by_file.objects[0].shape).vertices ==
          std::get<TriangleMesh>(inline_.objects[0].shape).vertices);
    CHECK(gem.vertices == std::get<TriangleMesh>(inline_.objects[1].shape).vertices);
    CHECK(by_file.settings.spectral.enabled);  // the gem is a dispersive dielectric
    const RenderResult a = render(by_file), b = render(inline_);
    CHECK(a.image.rgb == b.image.rgb);
    double sum = 0;
    for (double v : a.image.rgb) sum += v;
    CHECK(sum > 100);  // an image, not a black frame
}

namespace {

double shape_distance(const Shape& a, const Shape& b) {
    if (a.index() != b.index()) return 1e300;
    if (const auto* s = std::get_if<Sphere>(&a)) {
        const Sphere& t = std::get<Sphere>(b);
        return std::max((s->center - t.center).norm(), std::abs(s->radius - t.radius));
    }
    const auto plane = [](const Plane& p, const Plane& q) {
        return std::max((p.normal - q.normal).norm(), std::abs(p.offset - q.offset));
    };
    if (const auto* p = std::get_if<Plane>(&a)) return plane(*p, std::get<Plane>(b));
    double d = 0;
    if (const auto* m = std::get_if<TriangleMesh>(&a)) {
        const TriangleMesh& n = std::get<TriangleMesh>(b);
        if (m->triangles != n.triangles) return 1e300;
        for (size_t k = 0; k < m->vertices.size(); ++k) d = std::max(d, (m->vertices[k] - n.vertices[k]).norm());
        return d;
    }
    const auto& c = std::get<ConvexPolyhedron>(a);
    const auto& e = std::get<ConvexPolyhedron>(b);
    for (size_t k = 0; k < c.planes.size(); ++k) d = std::max(d, plane(c.planes[k], e.planes[k]));
    return d;
}

}  // namespace

TEST_CASE("Random scenes drawn with transforms keep every object where the generator placed it", "[transform]") {
    validation::RandomSceneOptions with;
    with.transforms = true;
    int transformed_objects = 0;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        INFO("seed " << seed);
        const nlohmann::json plain_json = validation::random_scene(seed), moved_json = validation::random_scene(seed, with);
        const Scene plain = parse_scene(plain_json, "plain.json"), moved = parse_scene(moved_json, "moved.json");
        REQUIRE(plain.objects.size() == moved.objects.size());
        for (size_t k = 0; k < plain.objects.size(); ++k) {
            transformed_objects += moved.objects[k].placement.has_value();
            INFO("object " << k << ": " << moved_json["objects"][k]["type"]);
            CHECK(shape_distance(plain.objects[k].shape, moved.objects[k].shape) < 1e-12);
        }
        // Everything but the objects is the scene drawn without transforms.
        nlohmann::json a = plain_json, b = moved_json;
        a.erase("objects");
        b.erase("objects");
        a.erase("description");
        b.erase("description");
        CHECK(a == b);
    }
    CHECK(transformed_objects > 100);
}

TEST_CASE("Random compat scenes drawn with transforms agree with POV-Ray 3.7, which applies them itself", "[povray]") {
    validation::RandomSceneOptions with;
    with.transforms = true;
    for (const std::uint64_t seed : {20261127u, 20261128u, 20261130u}) {
        INFO("seed " << seed);
        const nlohmann::json scene = validation::random_scene(seed, with);
        INFO(scene["description"].get<std::string>());
        const validation::Comparison c =
            validation::compare_with_povray(scene, "seed", validation::Targets{}, validation::PovrayOptions{}, 2);
        INFO(c.reason);
        REQUIRE(c.outcome != validation::Comparison::Outcome::Skip);
        INFO("rmse " << c.diff.rmse << ", max " << c.diff.max_error);
        CHECK(c.outcome == validation::Comparison::Outcome::Pass);
    }
}
