#pragma once
// grin-layers: a Luneburg lens (n = √(2 − (r/R)²), R = 1) as a stack of N nested
// constant-index spheres (the validation case scenes/validation/grin-stack.json for N = 8),
// rendered in the POV-Ray compatibility mode, against the continuous "grin" lens rendered
// in the physical mode, same camera and backdrop, for N = 2 … 64: the image difference
// (RMSE over the image, mean |Δ| over the lens's disk) against N and its fitted order.
// Two backdrops: a smooth gradient sky (the difference follows the rays' directions) and
// a self-lit checker of unit cells (it flips whole cells). The floor: a constant-index
// sphere rendered in both modes. `compute` measures into a Result; `write` turns it into
// CSV, a log-log figure and summary.md.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/experiments/common.h>
#include <refract/experiments/experiment.h>

namespace refract::experiments::grin_layers {

// Shell k of N (1 = innermost, between (k − 1)/N and k/N) takes the profile's index at its
// mid radius (the midpoint rule: off the shell's radial mean by O(1/N²)).
double shell_index(int k, int shells);

// The scene: `shells` = 0 is the continuous grin lens (physical mode); otherwise the
// stack, in the compatibility mode when `compat`. `backdrop`: "sky" or "checker".
// `constant_ior` > 0: one dielectric sphere of that index (the floor), `shells` ignored.
nlohmann::json lens_scene(int shells, const std::string& backdrop, bool compat, bool quick, double constant_ior = 0);

struct Row {
    int shells = 0;
    double rmse = 0;       // over every pixel and channel
    double disk_mean = 0;  // mean |Δ| over the pixels whose primary ray meets the lens, every channel
    double seconds = 0;    // the stack's render
};
struct Series {
    std::string backdrop;
    std::vector<Row> rows;
    LineFit rmse_fit, disk_fit;           // log-log over all rows
    LineFit tail_fit;                     // the disk mean over the last three rows
    double floor_rmse = 0, floor_disk = 0;  // constant-index sphere (n = 1.2), compat vs physical
    double continuous_seconds = 0;
};
struct Result {
    bool quick = false;
    int width = 0, height = 0, disk_pixels = 0;
    std::vector<Series> series;
    double seconds = 0;
};

std::vector<int> shell_counts(bool quick);
Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);

}  // namespace refract::experiments::grin_layers
