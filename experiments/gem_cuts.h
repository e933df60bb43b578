#pragma once
// gem-cuts (issue 15; docs/gem-metrics.md, "Sweep"): where in crown angle × pavilion angle
// the round brilliant's light return (brilliance) and fire are best, how far Tolkowsky's
// 1919 proportions lie from that optimum, and how much the star and lower-half lengths
// matter. Two sweeps (experiments/gem_sweep.h): the crown × pavilion map, and star ×
// lower half at the GIA default crown and pavilion. `compute` evaluates them into a
// Result, `write` draws the contour maps and writes the CSVs and summary.md.
#include <string>
#include <vector>

#include <refract/experiments/experiment.h>
#include <refract/experiments/gem_sweep.h>

namespace refract::experiments::gem_cuts {

void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// The metrics, in column order: light return, fire, leakage, scintillation.
struct MetricInfo {
    std::string key;    // "light_return", ...
    std::string title;  // "light return (brilliance)"
    bool maximise;      // leakage is best when smallest
};
const std::vector<MetricInfo>& metrics();
const gem_metrics::Metric& metric_of(const gem_metrics::GemMetrics& g, const std::string& key);

// The two grids: reproduce's resolution, or a few cuts (quick); and the full grid of the
// benchmark (>= 26 000 cuts) as the `refract sweep` command that runs it.
gem_sweep::Sweep crown_pavilion_sweep(bool quick);
gem_sweep::Sweep star_lower_half_sweep(bool quick);
gem_sweep::Sweep full_sweep();
std::string command_of(const gem_sweep::Sweep& sweep, const std::string& output);

struct Optimum {
    std::string metric;
    gem_sweep::Row best;                   // the grid's best cut for this metric
    std::vector<gem_sweep::Row> top;       // the five best, best first
    gem_metrics::Metric tolkowsky;         // Tolkowsky's cut, evaluated alike
    double d_crown = 0, d_pavilion = 0;    // best − Tolkowsky, degrees
    double sigmas = 0;                     // (best − Tolkowsky) / combined standard error
};

struct Sensitivity {
    std::string metric;
    double min = 0, max = 0;  // over the star × lower-half grid's possible cuts
    double mean_error = 0;    // mean standard error of one cut
    double crown_pavilion_spread = 0;  // max − min over the crown × pavilion map, for scale
};

// What the summary states beside its tables, each from the numbers (`judge`).
struct Findings {
    bool presets_share_angles = false;  // Tolkowsky and GIA default: the same crown and pavilion angles
};

struct Result {
    Findings findings;  // judge(*this), set by compute
    bool quick = false;
    gem_sweep::Sweep main, detail;
    std::vector<gem_sweep::Row> main_rows, detail_rows;  // in cut order
    std::vector<std::pair<std::string, gem_sweep::Row>> presets;  // tolkowsky, gia-default
    std::vector<Optimum> optima;                        // metrics() order
    std::vector<Sensitivity> sensitivity;               // metrics() order
    int impossible = 0;
    double seconds = 0;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

// The findings from a Result's numbers (pure; compute stores them in Result::findings) and
// the summary's words about the two reference cuts' marks, worded by r.findings.
Findings judge(const Result& r);
std::string marks_text(const Result& r);

}  // namespace refract::experiments::gem_cuts
