#pragma once
// `refract experiment gem-metrics`: the gem metrics (experiments/gem_metrics.h,
// docs/gem-metrics.md) of the presets "tolkowsky" and "gia-default" with their statistical
// errors, under exact polarisation and natural light; the images of the observation
// set-ups (ASET, ideal-scope, arrows, hearts, brilliance); the convergence of each
// metric's error with the ray count; and the cost of one cut (construction and metrics).
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/image.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/gem_metrics.h>

namespace refract::experiments::gem_metrics_experiment {

void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

struct PresetResult {
    std::string preset;
    Gem gem;
    gem_metrics::GemMetrics exact, natural;  // the same rays, the two polarisation models
    double build_seconds = 0;                // CGAL construction of the cut
    double exact_seconds = 0, natural_seconds = 0;  // measure(), one thread
    std::vector<std::pair<std::string, Image>> views;  // view name, image
};

struct ConvergenceRow {
    std::string preset;
    int rays = 0;
    gem_metrics::GemMetrics metrics;
};

// One cut of the pavilion-angle scan: GIA's default proportions with this pavilion angle.
struct ScanRow {
    double pavilion_angle = 0;
    gem_metrics::GemMetrics metrics;  // exact polarisation
};

struct Result {
    bool quick = false;
    gem_metrics::MetricOptions options;  // of the metric table (exact; natural differs only there)
    int image_size = 0, image_samples = 0;
    std::vector<PresetResult> presets;
    std::vector<ConvergenceRow> convergence;  // Tolkowsky's cut at growing ray counts
    // Least-squares slope of log standard error against log rays, per metric (light return,
    // fire, leakage, scintillation).
    std::vector<std::pair<std::string, double>> convergence_slopes;
    std::vector<ScanRow> pavilion_scan;       // the metrics against the pavilion angle
    // The viewers as files (the same as scenes/gems/): environment maps (file, image) and scenes.
    std::vector<std::pair<std::string, Image>> viewer_map_images;
    std::vector<std::pair<std::string, nlohmann::json>> viewer_scene_files;
};

// A viewer as a scene file for `refract render` (scenes/gems/): the preset's stone
// (diameter 2, its axis the scene's +y) in the view's environment map `map_file`
// (gem_observation.h viewer_environment, beside the scene), seen from 12 units above (from
// below for "hearts"), spectral with diamond's dispersion and exact polarisation.
nlohmann::json viewer_scene(const std::string& preset, const std::string& view, const std::string& map_file, int size);
// The scene files scenes/gems/ holds, as the experiment writes them: (file name, scene),
// and the maps: (file name, view).
std::vector<std::pair<std::string, nlohmann::json>> viewer_scenes(int size);
std::vector<std::pair<std::string, std::string>> viewer_maps();
constexpr int kViewerMapWidth = 360;

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::gem_metrics_experiment

namespace refract {

template <>
struct Fields<experiments::gem_metrics_experiment::ConvergenceRow> {
    static auto list() {
        using C = experiments::gem_metrics_experiment::ConvergenceRow;
        return std::make_tuple(field("rays", &C::rays),
                               derived<C>("light_return_error", [](const C& c) { return c.metrics.light_return.error; }),
                               derived<C>("fire_error", [](const C& c) { return c.metrics.fire.error; }),
                               derived<C>("leakage_error", [](const C& c) { return c.metrics.leakage.error; }),
                               derived<C>("scintillation_error", [](const C& c) { return c.metrics.scintillation.error; }));
    }
};
template <>
struct Fields<experiments::gem_metrics_experiment::ScanRow> {
    static auto list() {
        using S = experiments::gem_metrics_experiment::ScanRow;
        return std::make_tuple(field("pavilion_angle", &S::pavilion_angle),
                               derived<S>("light_return", [](const S& s) { return s.metrics.light_return.value; }),
                               derived<S>("light_return_error", [](const S& s) { return s.metrics.light_return.error; }),
                               derived<S>("fire", [](const S& s) { return s.metrics.fire.value; }),
                               derived<S>("fire_error", [](const S& s) { return s.metrics.fire.error; }),
                               derived<S>("leakage", [](const S& s) { return s.metrics.leakage.value; }),
                               derived<S>("leakage_error", [](const S& s) { return s.metrics.leakage.error; }),
                               derived<S>("scintillation", [](const S& s) { return s.metrics.scintillation.value; }),
                               derived<S>("scintillation_error", [](const S& s) { return s.metrics.scintillation.error; }));
    }
};

}  // namespace refract
