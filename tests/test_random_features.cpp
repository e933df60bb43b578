// The random scene generator's area lights and mesh files (RandomSceneOptions::area_lights,
// ::mesh_files): drawn from streams of their own (the scenes are otherwise unchanged), read
// back through the scene reader and the mesh-file reader, and exported to POV-Ray; a few
// such scenes compared with POV-Ray 3.7 ([povray]).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/scene_json.h>
#include <refract/validation/pov_export.h>
#include <refract/validation/random_scene.h>
#include <refract/validation/random_suite.h>

#include "tests/temp_dir.h"

using namespace refract;
using namespace refract::validation;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The scene with its files written into `dir`, read as dir/scene.json would be.
Scene load_case(const RandomSceneFiles& c, const fs::path& dir) {
    for (const auto& [name, text] : c.files) std::ofstream(dir / name) << text;
    return parse_scene(c.scene, (dir / "scene.json").string());
}

}  // namespace

TEST_CASE("Random scenes with area lights and mesh files: the same scenes otherwise, read back through the mesh-file "
          "reader, exported to POV-Ray with area_light and mesh2 (transforms on)",
          "[random]") {
    const fs::path dir = test::fresh_dir("random", "features");
    RandomSceneOptions moved, both;  // with transforms: mesh files placed by a matrix too
    moved.transforms = both.transforms = true;
    both.area_lights = both.mesh_files = true;
    int rectangles = 0, disks = 0, files = 0, seeds_with_both = 0;
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
        INFO("seed " << seed);
        const json plain = random_scene(seed, moved);
        CHECK(random_scene_files(seed, moved).scene == plain);  // off: nothing changes
        CHECK(random_scene_files(seed, moved).files.empty());
        const RandomSceneFiles c = random_scene_files(seed, both);
        // The objects as before, but for the meshes moved into files (same name and material).
        REQUIRE(c.scene["objects"].size() == plain["objects"].size());
        for (std::size_t k = 0; k < plain["objects"].size(); ++k) {
            json o = c.scene["objects"][k], p = plain["objects"][k];
            if (o.contains("file")) {
                CHECK(p["type"] == "mesh");
                for (json* x : {&o, &p}) {
                    x->erase("file");
                    x->erase("vertices");
                    x->erase("triangles");
                }
            }
            CHECK(o == p);
        }
        CHECK(c.scene["materials"] == plain["materials"]);
        CHECK(c.scene["lights"].size() == plain["lights"].size());
        int here = 0;
        for (const json& l : c.scene["lights"]) {
            rectangles += l["type"] == "rectangle";
            disks += l["type"] == "disk";
            here += l["type"] != "point";
        }
        Scene s;
        REQUIRE_NOTHROW(s = load_case(c, dir));
        std::string pov;
        REQUIRE_NOTHROW(pov = export_pov(s));
        if (here > 0) CHECK(pov.find("area_light") != std::string::npos);
        if (!c.files.empty()) CHECK(pov.find("mesh2") != std::string::npos);
        files += static_cast<int>(c.files.size());
        seeds_with_both += here > 0 && !c.files.empty();
        for (const auto& [name, text] : c.files) fs::remove(dir / name);
    }
    CHECK(rectangles >= 5);
    CHECK(disks >= 5);
    CHECK(files >= 5);
    CHECK(seeds_with_both >= 2);
    fs::remove_all(dir);
}

TEST_CASE("A random scene with area lights and mesh files agrees with POV-Ray 3.7 to the suite's targets: the "
          "first from seed 501 that holds both (a batch: validate --random --area-lights --mesh-files)",
          "[povray]") {
    const fs::path dir = test::fresh_dir("random", "features-povray");
    RandomSceneOptions o;
    o.width = 48;
    o.height = 36;
    o.area_lights = o.mesh_files = true;
    int compared = 0;
    for (std::uint64_t seed = 501; compared < 1 && seed < 600; ++seed) {
        const RandomSceneFiles c = random_scene_files(seed, o);
        bool area = false;
        for (const json& l : c.scene["lights"]) area = area || l["type"] != "point";
        if (!area || c.files.empty()) continue;
        INFO("seed " << seed << ": " << c.scene["description"].get<std::string>());
        for (const auto& [name, text] : c.files) std::ofstream(dir / name) << text;
        const Comparison r = compare_with_povray(c.scene, (dir / "scene.json").string(), Targets{}, PovrayOptions{}, 2);
        INFO(r.reason);
        CHECK(r.outcome == Comparison::Outcome::Pass);
        ++compared;
    }
    CHECK(compared == 1);
    fs::remove_all(dir);
}
