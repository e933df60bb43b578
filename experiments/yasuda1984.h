#pragma once
// Yasuda, Yokoi, Toriwaki, Tsuruoka, Miyake (1984), "An Improved Ray Tracing Algorithm
// for Rendering Transparent Objects": Fig. 4, 7, 8, 9 and the cost claims of §5.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/experiment.h"
#include "experiments/op_count.h"

namespace refract::experiments::yasuda1984 {

void run(const ExperimentOptions& opt);

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

// Writes cost.csv, memory.csv, their figures, and returns the summary section.
std::string run_cost(const ExperimentOptions& opt);

}  // namespace refract::experiments::yasuda1984
