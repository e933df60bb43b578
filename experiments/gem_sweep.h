#pragma once
// The proportion sweep of the round brilliant (issue 15; docs/gem-metrics.md, "Sweep"): a
// grid over the cut's parameters, every cut validated and built exactly (CGAL), impossible
// cuts recorded with their one-line reason, possible ones measured back and evaluated by
// gem_metrics::measure with a seed derived from the cut's parameters only. One CSV row per
// cut, numbers in the shortest round-trip form (std::to_chars, locale-independent): the
// file is byte-identical for any number of threads or MPI ranks.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <refract/experiments/gem_metrics.h>
#include <refract/geometry/gem/brilliant.h>

namespace refract::experiments::gem_sweep {

// One swept parameter, START:STOP:STEP (inclusive when STOP lies on the grid) or a single
// value. The decimals are read exactly: value i = (start + i·step) / 10^decimals, integers
// throughout, so 38:43:0.1 gives 38.3 (the double nearest 38.3), never 38.300000000000004.
struct Axis {
    std::string name;        // "table", "crown_angle", "pavilion_angle", "star", "lower_half", "girdle"
    std::int64_t start = 0;  // in units of 10^-decimals
    std::int64_t step = 0;   // 0 for a single value
    int count = 1;
    int decimals = 0;
    double value(int i) const;
    std::string text() const;  // canonical START:STOP:STEP or VALUE
};

// The swept parameters, in the grid's order (the last varies fastest), and the option
// (--crown-angle, ...) naming each.
const std::vector<std::string>& parameter_names();
std::string option_name(const std::string& parameter);  // "crown_angle" -> "--crown-angle"

// Parses "START:STOP:STEP" or "VALUE" for `parameter`; InputError naming the option for a
// malformed number, a step <= 0, STOP < START, more than 6 decimals or more than 10^6 values.
Axis parse_axis(const std::string& parameter, const std::string& text);

struct Grid {
    BrilliantCut base;        // the parameters that are not swept (culet, girdle facets, ...)
    std::vector<Axis> axes;   // one per parameter_names() entry, in that order
    std::int64_t size() const;
    BrilliantCut cut(std::int64_t index) const;  // mixed radix, last axis fastest
};

// A grid from `base` with every parameter a single value of `base`, then `set` replaces one.
Grid single_cut_grid(const BrilliantCut& base);
void set_axis(Grid& grid, const Axis& axis);  // InputError if the grid exceeds 10^8 cuts

struct Sweep {
    Grid grid;
    gem_metrics::MetricOptions metric;  // metric.seed is the sweep's base seed
};

// One line naming everything that determines the rows (grid, base cut, material, rays,
// wavelengths, polarisation, seed): a journal is resumed only under the same fingerprint.
std::string fingerprint(const Sweep& sweep);

// The cut's own seed: SplitMix64 over the base seed and the bit patterns of its
// parameters, so a cut's result depends on nothing but the cut (not on its index, order,
// thread or rank).
std::uint64_t cut_seed(std::uint64_t base, const BrilliantCut& cut);

struct Row {
    std::int64_t index = 0;
    BrilliantCut cut;
    bool possible = false;
    std::string reason;  // validate/build_brilliant's one-line InputError when impossible
    BrilliantProportions measured;
    gem_metrics::GemMetrics metrics;
};

// Validates, builds and measures one cut; an impossible cut is a row, not an error.
Row evaluate(const Sweep& sweep, std::int64_t index);
Row evaluate_cut(const BrilliantCut& cut, const gem_metrics::MetricOptions& metric);

// Evaluates `indices` (any order) on `threads` worker threads (0: all cores); `done` is
// called once per finished row, serialised (journal appends), in completion order.
// Returns the rows in the order of `indices`.
std::vector<Row> run(const Sweep& sweep, const std::vector<std::int64_t>& indices, int threads,
                     const std::function<void(const Row&)>& done = {});
std::vector<std::int64_t> all_indices(const Sweep& sweep);

// The result cells of a row, one list feeding the CSV's header and lines (and any other
// reader: names as in the header), after index, the six parameters, status and reason:
// the measured proportions, the four metrics and their errors, leakage_by_kind
// ("kind:value;..."), the ASET shares (aset_red, _green, _blue, _white) and the energy
// balance (balance_crown, _girdle, _pavilion, _lost, _missed), GemMetrics' Aset and
// Balance. An impossible cut leaves them empty.
struct Field {
    const char* name;
    std::string (*cell)(const Row& row);
};
const std::vector<Field>& fields();

// The CSV: header, and one line per row (no newline); cells in shortest round-trip form.
std::string csv_header();
std::string csv_line(const Row& row);
// The shortest text that reads back as `v` (std::to_chars): the same digits as
// format_shortest (geometry/format.h) gives, but independent of the C locale, which a
// program embedding refract may change, so the sweep's bytes cannot depend on it.
std::string number(double v);

}  // namespace refract::experiments::gem_sweep
