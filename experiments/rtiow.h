#pragma once
// "Ray Tracing in One Weekend", dielectric chapter (Japanese edition, listings 1.50-1.58,
// figures 1.27-1.29): the chapter's scene in its stages, Schlick against exact Fresnel,
// and the 1/√spp convergence of the stochastic integrator to the Fresnel tree.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/image.h>
#include <refract/core/scene.h>
#include <refract/experiments/common.h>
#include <refract/experiments/experiment.h>

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

// What the summary states beside its tables, each from the numbers (`judge`).
struct Findings {
    bool solid_without_tir = false;  // every stage but the hollow sphere: 0 TIR nodes
    bool hollow_with_tir = false;    // the hollow sphere: TIR nodes
    bool schlick_one_at_tir = false; // every row whose exact Fresnel is 1 has Schlick 1 too (TIR folded in)
    bool slope_one_half = false;     // the convergence slope within 0.1 of −1/2
};

struct Result {
    bool quick = false;
    std::vector<StageResult> stages;
    std::vector<SchlickCase> schlick;
    Convergence convergence;
    Findings findings;  // judge(*this), set by compute
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

// The findings from a Result's numbers (pure; compute stores them in Result::findings) and
// the summary's sentences that state them, worded by r.findings.
Findings judge(const Result& r);
std::string tir_text(const Result& r);          // the solid sphere: listings 1.51 and 1.54 alike?
std::string hollow_text(const Result& r);       // the hollow sphere's TIR
std::string schlick_text(const Result& r);      // both 1 beyond the critical angle?
std::string convergence_text(const Result& r);  // the slope against 1/√spp

}  // namespace refract::experiments::rtiow

namespace refract {

template <>
struct Fields<experiments::rtiow::StageResult> {
    static auto list() {
        using S = experiments::rtiow::StageResult;
        return std::make_tuple(derived<S>("id", [](const S& s) { return s.stage.id; }),
                               derived<S>("caption", [](const S& s) { return s.stage.caption; }),
                               field("scene", &S::scene), field("rgb", &S::image), field("tir_nodes", &S::tir_nodes));
    }
};
template <>
struct Fields<experiments::rtiow::SchlickRow> {
    static auto list() {
        using R = experiments::rtiow::SchlickRow;
        return std::make_tuple(field("angle_deg", &R::angle_deg), field("fresnel", &R::fresnel),
                               field("schlick", &R::schlick),
                               derived<R>("error", [](const R& r) { return r.schlick - r.fresnel; }).csv_only());
    }
};
template <>
struct Fields<experiments::rtiow::SchlickCase> {
    static auto list() {
        using C = experiments::rtiow::SchlickCase;
        return std::make_tuple(field("name", &C::name).csv("case"), field("eta", &C::eta),
                               field("use_cos_t", &C::use_cos_t).python_only(), field("rows", &C::rows).table(),
                               field("max_error", &C::max_error).python_only(),
                               field("max_error_at", &C::max_error_at).python_only(),
                               field("mean_error", &C::mean_error).python_only());
    }
};
template <>
struct Fields<experiments::rtiow::ConvergenceRow> {
    static auto list() {
        using R = experiments::rtiow::ConvergenceRow;
        return std::make_tuple(field("spp", &R::spp), field("rmse", &R::rmse), field("seconds", &R::seconds).digits(4));
    }
};
template <>
struct Fields<experiments::rtiow::Findings> {
    static auto list() {
        using F = experiments::rtiow::Findings;
        return std::make_tuple(field("solid_without_tir", &F::solid_without_tir),
                               field("hollow_with_tir", &F::hollow_with_tir),
                               field("schlick_one_at_tir", &F::schlick_one_at_tir),
                               field("slope_one_half", &F::slope_one_half));
    }
};
template <>
struct Fields<experiments::rtiow::Result> {
    static auto list() {
        using R = experiments::rtiow::Result;
        return std::make_tuple(field("quick", &R::quick), field("stages", &R::stages), field("schlick", &R::schlick),
                               derived<R>("convergence", [](const R& r) { return r.convergence.rows; }),
                               derived<R>("slope", [](const R& r) { return r.convergence.fit.slope; }),
                               derived<R>("intercept", [](const R& r) { return r.convergence.fit.intercept; }),
                               field("findings", &R::findings));
    }
};

}  // namespace refract
