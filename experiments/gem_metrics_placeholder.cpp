// TEMPORARY stand-in for gem_metrics::measure until the metrics (issue 15, part 1) land;
// deleted when they are merged. Not physics: smooth functions of the measured proportions
// plus a little seed-dependent noise, so that the sweep's mechanics can be exercised.
#include "experiments/gem_metrics.h"

#include <cmath>

namespace refract::gem_metrics {

GemMetrics measure(const Gem& gem, const MetricOptions& o) {
    const auto& m = gem.measured;
    const double noise = static_cast<double>((o.seed * 0x9E3779B97F4A7C15ull) >> 11) / 9007199254740992.0 - 0.5;
    const double e = 1 / std::sqrt(static_cast<double>(o.rays));
    const double lr = std::exp(-std::pow((m.pavilion_angle - 40.8) / 1.2, 2) - std::pow((m.crown_angle - 33) / 8, 2));
    const double fire = std::exp(-std::pow((m.pavilion_angle - 40.6) / 1.5, 2) - std::pow((m.crown_angle - 36) / 5, 2));
    GemMetrics g;
    g.light_return = {lr + e * noise, e};
    g.fire = {fire * (0.9 + 0.001 * m.star) + e * noise, e};
    g.leakage = {1 - lr + 0.001 * m.lower_half, e};
    g.scintillation = {0.5 * (lr + fire), e};
    g.leakage_by_kind = {{"pavilion main", 0.7 * g.leakage.value}, {"lower half", 0.3 * g.leakage.value}};
    return g;
}

}  // namespace refract::gem_metrics
