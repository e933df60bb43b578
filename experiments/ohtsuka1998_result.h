#pragma once
// ohtsuka1998 as data: `compute` measures the main image (full split and shortcut), the
// floor-map and shortcut studies and the light the limits drop into a Result (numbers and
// images in memory); `write` turns it into images, CSV, figures, scenes and summary.md.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/render.h"
#include "experiments/ohtsuka1998.h"
#include "experiments/ohtsuka1998_maps.h"

namespace refract::experiments::ohtsuka1998 {

// Two images compared: linear-RGB RMSE and max, CIEDE2000 of the values read as linear sRGB.
struct Diff {
    double rmse = 0, max = 0, de_mean = 0, de_max = 0;
};

struct StepRow {
    double step_nm = 0;
    Diff against_1nm;
    double light_s = 0, eye_s = 0;
};
struct ShortcutRow {
    std::string label;    // the threshold, or "paper" / "measured" for the wavelength choice
    double threshold = 0;
    double wavelengths[3] = {0, 0, 0};
    double taken_fraction = 0, speedup_time = 0, speedup_segments = 0;
    Diff against_full;
};
struct LostRow {
    bool paper_limits = false;
    int max_depth = 0;
    double threshold = 0;
    RenderStats stats;
    double worst_pixel = 0;       // the largest dropped fraction in one pixel
    double rmse_vs_deepest = 0;
};

struct Result {
    bool quick = false;
    int threads_used = 0;
    SceneParams base, shortcut, box, first, study;  // the main image's, its variants', the studies'
    // The main image: light pass + full split, the shortcut over the same maps, the box-read
    // floor, and the first version's floor (fewer photons, box elements).
    RenderResult full, fast;
    Image box_image, first_image;
    double light_s = 0, eye_s = 0;
    std::uint64_t map_elements = 0, map_photons = 0, map_deposits = 0;
    std::size_t gem_planes = 0;
    Diff shortcut_diff;
    std::vector<StepRow> steps;
    MapStudyPlan plan;
    MapStudies maps;
    std::vector<ShortcutRow> thresholds, peaks;
    std::vector<LostRow> lost;
    double seconds = 0;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::ohtsuka1998
