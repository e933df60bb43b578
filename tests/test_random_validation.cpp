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

TEST_CASE("Random scenes with triangle meshes that failed against POV-Ray 3.7 agree now: its interior list and its "
          "single-precision mesh2",
          "[povray]") {
    // Five of the six failures of a batch of 320 (seeds 20261127 to 20261446, 80x60): each
    // failed by one or two pixels (up to 0.385, RMSE 3e-4 to 4.2e-3) with meshes met in
    // double and entering decided by the normal (docs/validation.md, R6 and R7). The sixth,
    // seed 20261358, is POV-Ray's box-tree walk of an opaque mesh (R5, not copied).
    for (const std::uint64_t seed : {20261139u, 20261149u, 20261329u, 20261363u, 20261429u}) {
        INFO("seed " << seed);
        const Comparison c = compare_with_povray(random_scene(seed, RandomSceneOptions{}), "seed", Targets{}, PovrayOptions{}, 2);
        INFO(c.reason);
        REQUIRE(c.outcome != Comparison::Outcome::Skip);
        INFO("rmse " << c.diff.rmse << ", max " << c.diff.max_error << " at (" << c.diff.max_x << ", " << c.diff.max_y << ")");
        CHECK(c.outcome == Comparison::Outcome::Pass);
        CHECK(c.diff.pixels_over == 0);
        CHECK(c.diff.rmse < 1e-5);
    }
}
