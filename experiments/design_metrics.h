#pragma once
// The gem metrics of any faceting design (issue 28; docs/gems.md, "Metrics of a design"): a
// GemCad design (geometry/gem/gemcad.h) built exactly and scaled so that its width W is 2,
// the round brilliant's girdle diameter, then measured by gem_metrics::measure and drawn by
// gem_metrics::render_view with the options' frame covering the whole outline; and the
// sweep of one tier's angle (`refract sweep design`), one CSV row per angle.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <refract/core/image.h>
#include <refract/experiments/gem_metrics.h>
#include <refract/experiments/gem_sweep.h>
#include <refract/geometry/gem/gemcad.h>

namespace refract::experiments::design_metrics {

// The design built exactly at width 2: its distances times 2/W, built again (the second
// build is the stone measured; its volume and extents are at W = 2).
DesignGem build_at_width_2(const GemcadDesign& design);

// The options for a built stone: `frame` the largest distance of a vertex from the origin
// (the brilliant keeps 1, its girdle radius).
gem_metrics::MetricOptions options_for(const Gem& gem, gem_metrics::MetricOptions options);

gem_metrics::GemMetrics measure(const DesignGem& stone, const gem_metrics::MetricOptions& options);
Image render_view(const DesignGem& stone, const std::string& view, int size, int samples,
                  const gem_metrics::MetricOptions& options);

// The sweep of one tier's angle: each angle replaces the tier's |angle| (the tier keeps its
// side, crown or pavilion), each of its facets turned about the level line through its
// outermost point on the design as given (the highest point of a pavilion facet, the lowest
// of a crown facet: where it meets the girdle or the row outside it), so that the outline
// stays and the depth changes, as a cutter changes a row's angle; a facet the design lists
// but its stone has not keeps its distance. A design that cuts one row as several tiers of one name (the catalogue's
// outlines, each azimuth its own distance) has every tier of the name swept together. The design is built at width 2 and measured
// with the same seed for every angle (common random numbers: neighbouring rows differ by
// the cut, not by the draws). A design the angle makes impossible (the tier cuts the stone
// away, a degenerate stone) is a row with its one-line reason.
struct TierSweep {
    GemcadDesign design;
    std::string name;                // as --tier gave it
    std::vector<std::size_t> tiers;  // indices into design.tiers, all of one name and side
    // Per swept tier, per index: the facet's pivot (its outermost point on the design as
    // given, the design's unit), or NaN when the stone has no such facet.
    std::vector<std::vector<Vec3>> pivots;
    gem_sweep::Axis angles;    // degrees, 0 to 90
    gem_metrics::MetricOptions metric;
};

// "NAME:FROM:TO:STEP" or "NAME:VALUE" (NAME a tier's name as GemcadTier::name gives it, or
// "tier N", the N-th tier alone); InputError naming --tier for an unknown name, one naming
// tiers of both the crown and the pavilion,
// a malformed range (gem_sweep::parse_axis) or an angle outside 0 to 90 degrees.
TierSweep parse_tier_sweep(const GemcadDesign& design, const std::string& text,
                           const gem_metrics::MetricOptions& metric);

struct TierRow {
    std::int64_t index = 0;
    double angle = 0;
    bool possible = false;
    std::string reason;
    DesignGem stone;  // at width 2
    gem_metrics::GemMetrics metrics;
};

TierRow evaluate(const TierSweep& sweep, std::int64_t index);
// Every angle on `threads` worker threads (0: all cores); `done` after each row, serialised.
std::vector<TierRow> run(const TierSweep& sweep, int threads, const std::function<void(const TierRow&)>& done = {});

// The CSV: a header and one line per row, numbers in shortest round-trip form.
std::string csv_text(const TierSweep& sweep, const std::vector<TierRow>& rows);

}  // namespace refract::experiments::design_metrics
