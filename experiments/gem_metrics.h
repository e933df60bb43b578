#pragma once
// Gem optics metrics of one round brilliant (issue 15; docs/gem-metrics.md): light
// return (brilliance), dispersed coloured light return (fire), leakage through the
// pavilion, and a scintillation measure, each with its statistical error, from the exact
// cut under the documented observation set-ups. `measure` is single-threaded and
// deterministic for a given gem and options: a sweep runs many cuts at once and its CSV is
// byte-identical for any number of threads or MPI ranks.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/gem/brilliant.h"

namespace refract::gem_metrics {

struct MetricOptions {
    std::string material = "diamond";  // catalogue name (core/spectrum/dispersion.h)
    int rays = 4096;                    // eye rays per metric (the documented count)
    int wavelengths = 31;               // spectral bands, 400..700 nm
    bool exact_polarisation = true;     // Stokes–Mueller along every path
    std::uint64_t seed = 1;             // the cut's own stream: results do not depend on order
};

// A measured value and its standard error (one sigma, from the ray statistics).
struct Metric {
    double value = 0;
    double error = 0;
};

struct GemMetrics {
    Metric light_return;   // brilliance
    Metric fire;           // dispersed coloured light return
    Metric leakage;        // light lost through the pavilion
    Metric scintillation;  // pattern change under small tilts
    // Leakage per facet kind ("pavilion main", "lower half", ...), facet_kind() names.
    std::vector<std::pair<std::string, double>> leakage_by_kind;
};

GemMetrics measure(const Gem& gem, const MetricOptions& options);

}  // namespace refract::gem_metrics
