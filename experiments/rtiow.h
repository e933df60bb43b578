#pragma once
// "Ray Tracing in One Weekend", dielectric chapter (Japanese edition, listings 1.50-1.58,
// figures 1.27-1.29): the chapter's scene in its stages, Schlick against exact Fresnel,
// and the 1/√spp convergence of the stochastic integrator to the Fresnel tree.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "experiments/common.h"
#include "experiments/experiment.h"

namespace refract::experiments::rtiow {

void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// The stages in the chapter's order.
struct Stage {
    std::string id;       // file stem: "fig1_27_always_refract", ...
    std::string caption;  // figure caption
};
const std::vector<Stage>& stages();

// The chapter's scene (listing 1.55 / 1.58) for a stage, mirrored in z so that refract's
// POV-Ray camera (right = sky × direction) sees it as the book's right-handed camera does.
nlohmann::json stage_scene(const std::string& id, bool quick);

// The convergence scene: the "+ Schlick" stage with the Lambertian surfaces replaced by
// directly lit diffuse ones and no fuzz, so that `stochastic` and `fresnel-tree`
// estimate the same pixel values. spp = 0 gives the fresnel-tree reference.
nlohmann::json convergence_scene(int spp, bool quick);
std::vector<int> convergence_spp(bool quick);  // 1, 4, 16, ...

// Dielectric nodes with total internal reflection met by the ray trees of the pixel
// centres (branches of weight >= 1e-4, up to the scene's depth; Lambertian surfaces end
// a branch).
std::uint64_t count_tir_nodes(const Scene& scene);

// ---- The whole experiment: `compute` measures into a Result (numbers and images in
// memory), `write` turns it into PNGs, CSV, figures, scenes and summary.md; `run` does both.

struct StageResult {
    Stage stage;
    nlohmann::json scene;
    Image image;                 // Fig. 1.28 is Fig. 1.27's image (the same scene, see summary.md)
    std::uint64_t tir_nodes = 0;  // count_tir_nodes of the stage's scene
};

struct SchlickRow {
    double angle_deg = 0, fresnel = 0, schlick = 0;
};
struct SchlickCase {
    std::string name;
    double eta = 1;
    bool use_cos_t = false;  // Schlick with the transmitted cosine instead of RTIOW's incident one
    std::vector<SchlickRow> rows;  // 0–90° in 0.25° steps
    double max_error = 0, max_error_at = 0, mean_error = 0;
};

struct ConvergenceRow {
    int spp = 0;
    double rmse = 0, seconds = 0;
};
struct Convergence {
    nlohmann::json reference_scene, stochastic_scene;  // the latter at the largest spp
    Image reference, stochastic;
    std::vector<ConvergenceRow> rows;
    LineFit fit;  // log RMSE against log spp
};

struct Result {
    bool quick = false;
    std::vector<StageResult> stages;
    std::vector<SchlickCase> schlick;
    Convergence convergence;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::rtiow
