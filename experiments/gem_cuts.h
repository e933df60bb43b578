#pragma once
// gem-cuts (issue 15; docs/gem-metrics.md, "Sweep"): where in crown angle × pavilion angle
// the round brilliant's light return (brilliance) and fire are best, how far Tolkowsky's
// 1919 proportions lie from that optimum, and how much the star and lower-half lengths
// matter. Two sweeps (experiments/gem_sweep.h): the crown × pavilion map, and star ×
// lower half at the GIA default crown and pavilion. `compute` evaluates them into a
// Result, `write` draws the contour maps and writes the CSVs and summary.md.
#include <ostream>
#include <string>
#include <vector>

#include <refract/core/image.h>
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
// Also "nail_head", "fish_eye" and "obstruction" (the detectors, not in metrics()).
const gem_metrics::Metric& metric_of(const gem_metrics::GemMetrics& g, const std::string& key);

// The two grids: reproduce's resolution, or a few cuts (quick); and the full grid of the
// benchmark (>= 26 000 cuts) as the `refract sweep` command that runs it.
gem_sweep::Sweep crown_pavilion_sweep(bool quick);
gem_sweep::Sweep star_lower_half_sweep(bool quick);
gem_sweep::Sweep full_sweep();
std::string command_of(const gem_sweep::Sweep& sweep, const std::string& output);

// Which edges of a crown × pavilion grid a cut lies on (within 1e-9 of the first or last value).
struct Edge {
    bool crown_low = false, crown_high = false, pavilion_low = false, pavilion_high = false;
    bool any() const { return crown_low || crown_high || pavilion_low || pavilion_high; }
};
Edge edge_of(const gem_sweep::Grid& grid, const BrilliantCut& cut);
// Of the edges e marks, those where the grid ends at the cut builder's limit: the cut one
// grid step beyond (crown or pavilion) is refused by validate (the builder's domain).
Edge builder_limits(const gem_sweep::Grid& grid, const BrilliantCut& cut, const Edge& e);

struct Optimum {
    std::string metric;
    std::string observer = "aset";         // the observer model the map was measured under
    Edge edge;                             // the grid edges the best cut lies on
    Edge builder_limit;                    // of those, where the cut builder's range ends
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

// The light return under each observer model (issue 31): the crown × pavilion map and the
// table scan measured again under the model, the light return only (the other metrics do
// not depend on it; gem_observer.h).
const std::vector<std::string>& map_observers();  // aset, sasian, hemisphere
// The map observers after the first: the main sweeps measure them on the same eye rays
// (MetricOptions::also_observers).
std::vector<std::string> other_observers();

// The nail-head, fish-eye and obstruction detectors (gem_detectors.h) over a grid wider in the pavilion
// angle than the map (the trade's limits lie outside it), under each map observer.
gem_sweep::Sweep phenomena_sweep(bool quick);
gem_sweep::Sweep table_sweep(bool quick);  // table at the GIA default crown and pavilion

// How often the obstruction detector fires over a detector grid, and its range.
struct ObstructionCount {
    int cuts = 0, firing = 0;  // possible cuts, and those that show obstruction
    int near = 0;              // cuts within two standard errors of the threshold
    double lo = 0, hi = 0;     // the smallest and largest value
};
ObstructionCount obstruction_count(const std::vector<gem_sweep::Row>& rows);

struct ObserverMap {
    std::string observer;
    std::vector<gem_sweep::Row> rows;        // the crown × pavilion map, in cut order
    std::vector<gem_sweep::Row> table_rows;  // the table scan
    std::vector<gem_sweep::Row> phenomena;   // the detector grid
    ObstructionCount obstruction;            // over the detector grid
    int nail_head_undecided = 0;             // detector-grid cuts within 2σ of the threshold
    gem_sweep::Row tolkowsky;                // Tolkowsky's cut under this observer
    Optimum light_return;                    // the map's best light return against Tolkowsky's
};

// Per observer and detector, where it fires along the pavilion angle at one crown angle.
struct Onset {
    double crown = 0;
    // nail-head: the smallest grid pavilion angle from which every steeper one fires;
    // fish-eye: the largest from which every shallower one fires; NaN: none in the grid.
    double pavilion = 0;
};

// A least-squares slope (value per degree or per table percent) and its standard error
// (from the residuals, so the fit's misfit counts).
struct Slope {
    double value = 0, error = 0;
    bool falls() const { return value < -2 * error; }
    bool rises() const { return value > 2 * error; }
};

// One published qualitative result and, per map observer, whether the numbers agree.
struct LiteratureRow {
    std::string key;      // "tolkowsky_among_best", ...
    std::string claim;    // the published result, with its source
    std::string measure;  // what refract compares, and the test
    bool observer_dependent = true;
    std::vector<bool> agrees;          // map_observers() order
    std::vector<std::string> numbers;  // the numbers behind each mark
};

// A cut rendered in the viewers beside the others (issue 31): a fish-eye, Tolkowsky's and
// a nail-head cut, tolkowsky_with_girdle at render_pavilions().
struct RenderedCut {
    std::string label;   // "fish-eye (pavilion 37.5°)", ...
    gem_sweep::Row row;  // measured as the map's cuts (aset), the detectors included
    std::vector<std::pair<std::string, Image>> views;  // render_views() order
    // Per view of render_tilt_views(), that view at render_tilts() (the stone tilted).
    std::vector<std::pair<std::string, std::vector<std::pair<double, Image>>>> tilts;
};
std::vector<double> render_tilts();  // 0, 10, 20, 30 degrees
const std::vector<std::string>& render_tilt_views();  // aset, ideal-scope
const std::vector<std::string>& render_views();  // aset, ideal-scope, brilliance
std::vector<double> render_pavilions();          // 37.25, 40.75, 43.75
// Tolkowsky's cut with the GIA default's girdle (3 %; his knife edge has no girdle to
// reflect: fish-eye 0 by definition) and the pavilion angle given.
BrilliantCut tolkowsky_with_girdle(double pavilion);

// What the summary states beside its tables, each from the numbers (`judge`).
struct Findings {
    bool presets_share_angles = false;  // Tolkowsky and GIA default: the same crown and pavilion angles
    double optimum_spread_deg = 0;      // largest distance between the observers' light-return optima
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
    std::vector<ObserverMap> observers;  // map_observers() order
    // Per observer (map_observers() order), per crown of the detector grid.
    std::vector<std::vector<Onset>> nail_head_onset, fish_eye_limit;
    std::vector<LiteratureRow> literature;
    std::vector<RenderedCut> renders;
    int render_size = 0;
    double observer_seconds = 0;  // of `seconds`, the observer maps, detector grids and renders
};

Result compute(const ExperimentOptions& opt);
// The best cut of `rows` for metric m against Tolkowsky's value, its grid edges marked.
Optimum optimum_of(const MetricInfo& m, const std::vector<gem_sweep::Row>& rows, const gem_sweep::Row& tolkowsky,
                   const gem_sweep::Grid& grid);
// The observer maps, the detector grids and their onsets (compute calls it after the
// main sweeps; experiments/gem_cuts_observers.cpp).
void add_observer_maps(Result& r, int threads);
void write(const Result& r, const std::string& dir);

// The findings from a Result's numbers (pure; compute stores them in Result::findings) and
// the summary's words about the two reference cuts' marks, worded by r.findings.
Findings judge(const Result& r);
// The detector onsets of one observer's detector grid (pure; Onset).
std::vector<Onset> nail_head_onsets(const gem_sweep::Sweep& sweep, const std::vector<gem_sweep::Row>& rows);
std::vector<Onset> fish_eye_limits(const gem_sweep::Sweep& sweep, const std::vector<gem_sweep::Row>& rows);
// Least-squares slopes: value = a + b·crown + c·pavilion over the possible rows (b, c), and
// value = a + b·table.
std::pair<Slope, Slope> crown_pavilion_slopes(const std::vector<gem_sweep::Row>& rows, const std::string& metric);
Slope table_slope(const std::vector<gem_sweep::Row>& rows, const std::string& metric);
// The comparison with the literature from a Result's numbers (pure; compute stores it).
std::vector<LiteratureRow> literature(const Result& r);
std::string marks_text(const Result& r);
// The observer maps, detector maps and literature sections of summary.md, with their
// CSVs and figures (experiments/gem_cuts_observers_report.cpp).
void write_observers(const Result& r, const std::string& dir, std::ostream& summary);
// "crown 23°, the grid's shallowest and ..." for the edges e marks (", the cut builder's
// limit" after those `limit` marks); and the sentence on an optimum, chosen by whether it
// lies on an edge and whether the builder's range ends there.
std::string edge_text(const Edge& e, const gem_sweep::Grid& grid, const Edge& limit = {});
std::string optimum_sentence(const Optimum& o, const gem_sweep::Grid& grid);

}  // namespace refract::experiments::gem_cuts
