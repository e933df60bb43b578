#include <refract/core/render_stats.h>

#include <algorithm>
#include <sstream>

namespace refract {

void RenderStats::merge(const RenderStats& o) { merge_fields(*this, o); }

std::string RenderStats::summary() const {
    std::ostringstream s;
    for_each_field(*this, [&](const auto& f, const auto& v) {
        if (!f.label || (f.when_nonzero && v == 0)) return;
        const std::string label = f.label;
        s << label << std::string(label.size() < 18 ? 18 - label.size() : 1, ' ') << v << "\n";
    });
    if (facet_local + facet_full > 0)
        s << "facet local (%)   " << 100.0 * static_cast<double>(facet_local) / static_cast<double>(facet_local + facet_full)
          << "\n";
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
