// Randomized cross-validation against POV-Ray 3.7 (docs/validation.md, "Random
// scenes"): a fixed batch of generated scenes must meet the suite's targets, and the
// shrinker must reduce a failing scene while keeping it failing.
#include <catch2/catch.hpp>

#include <filesystem>
#include <unistd.h>

#include <refract/core/scene_json.h>
#include <refract/validation/random_suite.h>

using namespace refract;
using namespace refract::validation;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() : path(fs::temp_directory_path() / ("refract-random-" + std::to_string(::getpid()))) {
        fs::remove_all(path);
    }
    ~TempDir() { fs::remove_all(path); }
};

}  // namespace

TEST_CASE("Random compat scenes (fixed seeds, dispersion included) agree with POV-Ray 3.7 to the suite's targets",
          "[povray]") {
    TempDir dir;
    RandomOptions opt;
    opt.count = 24;
    opt.seed = 1000;
    opt.out_dir = dir.path.string();
    opt.scene.width = 64;
    opt.scene.height = 48;
    opt.jobs = 2;
    opt.shrink = false;
    const RandomResult r = run_random(opt);
    INFO(format_random(r));
    CHECK(r.cases.size() == 24);
    CHECK(r.skipped == 0);
    CHECK(r.failed == 0);
    CHECK(r.passed == 24);
    int dispersive = 0;
    for (const RandomCase& c : r.cases) {
        dispersive += c.description.find("dispers") != std::string::npos;
        CHECK(c.diff.rmse < 2e-4);
    }
    CHECK(dispersive >= 3);
    CHECK(fs::exists(dir.path / "report.md"));
}

TEST_CASE("Shrinking keeps a failing scene failing and drops what the failure does not need", "[povray]") {
    // Targets below POV-Ray's 16-bit output step make every lit scene "fail": the
    // shrinker must then reach a scene with fewer objects, lights and pixels that fails too.
    Targets strict;
    strict.pixel_tolerance = 1e-9;
    strict.max_fraction_over = 0;
    strict.rmse = 1e-9;
    RandomSceneOptions so;
    so.width = 32;
    so.height = 24;
    so.dispersion = false;
    nlohmann::json scene;
    Comparison c;
    for (std::uint64_t seed = 1;; ++seed) {  // the first scene with three or more objects
        REQUIRE(seed < 200);
        scene = random_scene(seed, so);
        if (scene["objects"].size() < 3) continue;
        c = compare_with_povray(scene, "shrink-test", strict, PovrayOptions{}, 2);
        if (c.outcome == Comparison::Outcome::Fail) break;
    }
    const ShrinkResult s = shrink_failure(scene, c, strict, PovrayOptions{}, 2, 40);
    CHECK(s.accepted > 0);
    CHECK(s.attempts <= 40);
    CHECK(s.comparison.outcome == Comparison::Outcome::Fail);
    CHECK(s.scene["objects"].size() < scene["objects"].size());
    CHECK(s.scene["camera"]["width"].get<int>() * s.scene["camera"]["height"].get<int>() <=
          scene["camera"]["width"].get<int>() * scene["camera"]["height"].get<int>());
    // The minimal scene is a valid scene file and fails again when compared afresh.
    CHECK_NOTHROW(parse_scene(s.scene, "minimal.json"));
    CHECK(compare_with_povray(s.scene, "again", strict, PovrayOptions{}, 2).outcome == Comparison::Outcome::Fail);
}
