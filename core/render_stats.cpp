#include "core/render_stats.h"

#include <algorithm>
#include <sstream>

namespace refract {

void RenderStats::merge(const RenderStats& o) {
    primary_rays += o.primary_rays;
    segments += o.segments;
    shadow_rays += o.shadow_rays;
    tree_nodes += o.tree_nodes;
    pruned += o.pruned;
    depth_limited += o.depth_limited;
    lost_depth += o.lost_depth;
    lost_limits += o.lost_limits;
    lost_threshold += o.lost_threshold;
    peak_list = std::max(peak_list, o.peak_list);
    spectral_splits += o.spectral_splits;
    shortcut_tests += o.shortcut_tests;
    shortcut_taken += o.shortcut_taken;
    wavelength_segments += o.wavelength_segments;
    facet_local += o.facet_local;
    facet_full += o.facet_full;
    photons += o.photons;
    photon_segments += o.photon_segments;
    deposits += o.deposits;
    light_seconds += o.light_seconds;
}

std::string RenderStats::summary() const {
    std::ostringstream s;
    s << "primary rays      " << primary_rays << "\n"
      << "ray segments      " << segments << "\n"
      << "shadow rays       " << shadow_rays << "\n"
      << "tree nodes        " << tree_nodes << "\n"
      << "pruned branches   " << pruned << "\n"
      << "depth-limited     " << depth_limited << "\n"
      << "lost weight       depth " << lost_depth << ", limits " << lost_limits << ", threshold " << lost_threshold
      << " (of " << primary_rays << " primary rays)\n"
      << "peak list / tree  " << peak_list << "\n"
      << "wall time (s)     " << seconds << "\n";
    if (spectral_splits > 0 || shortcut_tests > 0)
        s << "spectral splits   " << spectral_splits << "\n"
          << "shortcut tests    " << shortcut_tests << "\n"
          << "shortcut taken    " << shortcut_taken << "\n"
          << "wavelength segs   " << wavelength_segments << "\n";
    if (facet_local + facet_full > 0)
        s << "facet segments    " << facet_local << " local, " << facet_full << " full ("
          << 100.0 * static_cast<double>(facet_local) / static_cast<double>(facet_local + facet_full) << " % local)\n";
    if (photons > 0)
        s << "photons           " << photons << "\n"
          << "photon segments   " << photon_segments << "\n"
          << "map deposits      " << deposits << "\n"
          << "light pass (s)    " << light_seconds << "\n";
    if (photons > 0 && light_seconds > 0) s << "photons/s         " << static_cast<double>(photons) / light_seconds << "\n";
    if (seconds > 0) s << "segments/s        " << static_cast<double>(segments) / seconds << "\n";
    return s.str();
}

std::string RenderStats::lost_warning(double fraction) const {
    const double total = lost_depth + lost_limits + lost_threshold;
    if (primary_rays == 0 || !(total > fraction * static_cast<double>(primary_rays))) return "";
    const double n = static_cast<double>(primary_rays);
    auto pct = [&](double v) {
        std::ostringstream s;
        s.precision(3);
        s << 100.0 * v / n << " %";
        return s.str();
    };
    std::string why;
    if (lost_depth >= lost_limits && lost_depth >= lost_threshold) why = "raise render.max_depth";
    else if (lost_threshold >= lost_limits) why = "lower render.threshold";
    else why = "raise render.spectral.max_reflections / max_transmissions";
    return "warning: " + pct(total) + " of the image's light was dropped (depth limit " + pct(lost_depth) +
           ", reflection/transmission limits " + pct(lost_limits) + ", threshold " + pct(lost_threshold) + "): " +
           why;
}

}  // namespace refract
