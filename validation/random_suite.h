#pragma once
// Randomized cross-validation (docs/validation.md, "Random scenes"): scenes from the
// generator (validation/random_scene.h) rendered by refract in compat mode and by
// POV-Ray 3.7, compared with the suite's targets; a failing scene is written out with
// both images and a difference map, then shrunk (objects, lights, depth, dispersion
// bands, resolution dropped one at a time while it still fails) to a minimal failing case.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/validation/compare.h>
#include <refract/validation/povray_runner.h>
#include <refract/validation/random_scene.h>

namespace refract::validation {

// One scene through both renderers.
struct Comparison {
    enum class Outcome { Pass, Fail, Skip } outcome = Outcome::Skip;
    std::string reason;       // Skip: why (not expressible, POV-Ray failed, ...)
    ImageDifference diff;     // Pass / Fail
    // A pass only with knife-edge pixels set aside (validation/knife_edge.h): their number
    // and the difference outside them; 0 when the rule is met as it stands.
    int knife_edge_pixels = 0;
    ImageDifference diff_outside_knife_edges;
    Image refract, povray;    // refract clipped to [0, 1] as POV-Ray's PNG is
    double refract_seconds = 0, povray_seconds = 0;
};

// Renders `scene_json` (a scene file as JSON; "compat" forced to "povray") with both.
// A scene that meets the fraction rule but not the RMSE passes when it does so with its
// knife-edge pixels set aside (validation/knife_edge.h). Never throws for a problem of the scene itself (that is a Skip with its reason).
Comparison compare_with_povray(const nlohmann::json& scene_json, const std::string& name, const Targets& targets,
                               const PovrayOptions& povray, int threads);

struct ShrinkResult {
    nlohmann::json scene;      // the smallest scene found that still fails
    Comparison comparison;     // its comparison
    int attempts = 0;          // candidate scenes tried
    int accepted = 0;          // reductions kept
};

// Greedy reduction of a failing scene: each step tries, in order, dropping one object,
// dropping one light, a lower max_depth, fewer dispersion bands (and no dispersion),
// a lower resolution, and keeps the first candidate that still fails; it stops when none
// does or after `max_attempts` candidates.
ShrinkResult shrink_failure(const nlohmann::json& scene, const Comparison& failing, const Targets& targets,
                            const PovrayOptions& povray, int threads, int max_attempts = 80,
                            const std::string& name = "shrink");  // the scene file's name: files it names are beside it

struct RandomOptions {
    int count = 10;                // scenes
    std::uint64_t seed = 1;        // scene k has generator seed `seed + k`
    std::string out_dir;           // failures and report.md (created)
    RandomSceneOptions scene;      // size, dispersion on/off
    Targets targets;
    PovrayOptions povray;          // timeout per POV-Ray run
    int jobs = 0;                  // scenes in flight at once (0: all cores), 1 thread each
    bool shrink = true;
    int max_shrink_attempts = 80;
};

struct RandomCase {
    std::uint64_t seed = 0;
    std::string description;
    Comparison::Outcome outcome = Comparison::Outcome::Skip;
    std::string reason;
    ImageDifference diff;
    int knife_edge_pixels = 0;            // a pass with these set aside
    ImageDifference diff_outside_knife_edges;
    std::optional<ShrinkResult> minimal;  // failures, when shrinking is on
    std::string dir;                      // failures: out_dir/seed-N
    double seconds = 0;                   // refract + POV-Ray (and shrinking)
};

struct RandomResult {
    std::vector<RandomCase> cases;  // in seed order
    int passed = 0, failed = 0, skipped = 0;
    int passed_with_knife_edges = 0;  // of `passed`
};

// Runs the batch; one line per scene to `progress` when given; writes
// out_dir/report.md and, per failure, out_dir/seed-N/{scene.json, refract.png,
// povray.png, diff.png, minimal.json, minimal-*.png}. InputError when out_dir cannot
// be created.
RandomResult run_random(const RandomOptions& opt, std::ostream* progress = nullptr);

// Plain-text summary: one line per failure or skip, then the counts.
std::string format_random(const RandomResult& r);

}  // namespace refract::validation
