#pragma once
// Yasuda, Yokoi, Toriwaki, Tsuruoka, Miyake (1984), "An Improved Ray Tracing Algorithm
// for Rendering Transparent Objects": Fig. 4, 7, 8, 9 and the cost claims of §5.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/render.h"
#include "experiments/experiment.h"
#include "experiments/op_count.h"

namespace refract::experiments::yasuda1984 {

void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// Fig. 7: the indices of refraction of panels (a) (n > 1) and (b) (n < 1).
const std::vector<double>& fig7_indices_a();
const std::vector<double>& fig7_indices_b();
// Fig. 8: the ten spheres (a) ... (j) and their names in the caption.
struct Fig8Sphere {
    char letter;
    double n;
    std::string label;  // "ice (0 °C)", "water", ...
};
const std::vector<Fig8Sphere>& fig8_spheres();
// Fig. 9: the constant reflectivities (a) ... (f).
const std::vector<double>& fig9_reflectivities();

// Transmissivity T(θ) = 1 − R(θ) for natural light at incidence angle θ (degrees).
double transmissivity(double angle_deg, double n);

// The largest T over 0–90° for index n, located to 1e-6°. `interior` is true when T
// rises above its normal-incidence value (a peak away from 0°).
struct TransmissivityPeak {
    double n = 0;
    double angle_deg = 0;
    double T = 0;
    double T0 = 0;  // at normal incidence
    bool interior = false;
};
TransmissivityPeak transmissivity_peak(double n);
// Smallest n (to 1e-6) for which T has an interior peak, and for which that peak lies
// at or beyond `angle_deg`.
double peak_onset_index();
double peak_beyond_index(double angle_deg);

// The scenes (built in code, saved as JSON under DIR/scenes/ and in the repository's
// scenes/yasuda1984/). `quick`: small images for tests.
nlohmann::json fig8_scene(double n, bool quick);
nlohmann::json fig9_scene(double reflectivity, bool quick);
nlohmann::json tree_growth_scene(int max_depth, double threshold, const std::string& integrator, bool quick);

// Cost of one branching node (§5): counted arithmetic per formulation and model.
struct NodeCost {
    std::string formulation;  // "yasuda1984" (eq. 2-5, 7) or "refract" (core/tracer.cpp)
    std::string model;        // "constant", "fresnel", "schlick"
    OpCounts ops;
};
std::vector<NodeCost> count_node_costs();
OpCounts count_sphere_test();  // one ray-sphere intersection test (geometry/shapes.cpp)
OpCounts count_plane_test();   // one ray-plane intersection test

// §5 measured: counted arithmetic per node and per intersection test, time per node and per
// search, whole renders with constant and Fresnel reflectivity, and the peak memory of the
// stored tree against the list as the depth limit grows.
struct MemoryRow {
    int max_depth = 0;
    RenderStats whitted, list_threshold0, list_threshold_1_255;  // peak_list: nodes / entries per pixel
};
struct CostResult {
    std::vector<NodeCost> node_costs;
    OpCounts sphere_test, plane_test;
    double ns_constant = 0, ns_fresnel = 0, ns_schlick = 0;  // SceneTracer::interact per node (fastest round)
    double ns_search = 0;                                    // one intersection search in the Fig. 8 scene
    double render_best[2] = {0, 0}, render_median[2] = {0, 0};  // [constant, fresnel], seconds, one thread
    RenderStats render_stats[2];
    std::vector<MemoryRow> memory;
};
CostResult compute_cost(const ExperimentOptions& opt);
// Writes cost.csv, cost_render.csv, memory.csv, the memory figure and scenes/tree_growth.json;
// returns the summary section.
std::string write_cost(const CostResult& c, bool quick, const std::string& dir);
std::string run_cost(const ExperimentOptions& opt);  // both


// ---- The whole experiment: `compute` measures into a Result (numbers and images in
// memory), `write` turns it into CSV, figures, images, scenes and summary.md; `run` does both.

struct Fig4Row {
    double angle_deg = 0, Rs = 0, Rp = 0, R = 0;  // n = 1.5
};
struct Fig7Row {
    double n = 0, angle_deg = 0, T = 0;
};
struct RenderedPanel {
    std::string file;     // "fig8_a", "fig9_c", ...
    std::string caption;
    double value = 0;     // the sphere's index (Fig. 8) or the reflectivity (Fig. 9)
    nlohmann::json scene;
    Image image;
    RenderStats stats;
};

struct Result {
    bool quick = false;
    std::vector<Fig4Row> fig4;                // 0–90° in 0.5° steps
    std::vector<Fig7Row> fig7;                // panels (a) and (b), 0.1° steps plus the critical angle
    std::vector<TransmissivityPeak> peaks;    // Fig. 7's indices and a few more, ascending
    double peak_onset = 0, peak_beyond_70 = 0;
    std::vector<RenderedPanel> fig8, fig9;
    CostResult cost;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::yasuda1984
