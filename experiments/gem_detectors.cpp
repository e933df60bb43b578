// Nail-head and fish-eye detectors (experiments/gem_detectors.h).
#include <refract/experiments/gem_detectors.h>

#include <algorithm>
#include <cmath>

#include <refract/geometry/shapes.h>

namespace refract::gem_metrics {

bool shows_nail_head(const Metric& m) { return m.value >= kNailHeadThreshold; }
bool nail_head_decided(const Metric& m) { return std::fabs(m.value - kNailHeadThreshold) >= 2 * m.error; }
bool shows_fish_eye(const Metric& m) { return m.value >= kFishEyeThreshold; }
bool shows_obstruction(const Metric& m) { return m.value >= kObstructionThreshold; }

Detectors::Detectors(const Gem& gem)
    : stone_(std::make_shared<const Shape>(tracing_shape(gem))), hit_facet_(hit_facets(gem)) {
    double best = 1 - 1e-9;
    for (size_t i = 0; i < gem.facets.size(); ++i) {
        const double nz = gem.facets[i].plane.normal.z();
        if (nz >= best) {
            best = nz;
            table_ = static_cast<int>(i);
        }
    }
    if (table_ >= 0)
        for (const Vec3& v : gem.facets[static_cast<size_t>(table_)].polygon) {
            table_radius_ = std::max(table_radius_, std::hypot(v.x(), v.y()));
            table_z_ = v.z();
        }
}

void Detectors::add(const Ray& eye_ray, double head_weight, double girdle_weight) {
    face_head_.add(head_weight);  // every eye ray meets the stone (gem_metrics.cpp eye_sample)
    if (table_ < 0) return;
    const auto hit = intersect(*stone_, eye_ray, 0.0, 1e30);
    if (!hit) return;
    const bool on_table = hit_facet_[static_cast<size_t>(hit->facet)] == table_;
    if (!(on_table && std::hypot(hit->point.x(), hit->point.y()) < kNailHeadZone * table_radius_))
        rest_head_.add(head_weight);
    if (on_table) table_girdle_.add(girdle_weight);
}

Ray Detectors::central_ray(const Vec3& viewer, double u1, double u2, double distance) const {
    const double r = kNailHeadZone * table_radius_ * std::sqrt(u1), phi = 2 * M_PI * u2;
    const Vec3 p(r * std::cos(phi), r * std::sin(phi), table_z_);
    return {p + distance * viewer, -viewer};
}

Metric Detectors::nail_head() const {
    // Two independent means: their errors add in quadrature.
    if (centre_head_.n == 0) return {};
    return {centre_head_.mean() - rest_head_.mean(),
            std::sqrt(centre_head_.variance_of_mean() + rest_head_.variance_of_mean())};
}

Metric Detectors::obstruction() const { return face_head_.metric(); }

Metric Detectors::fish_eye() const { return {table_girdle_.mean(), std::sqrt(table_girdle_.variance_of_mean())}; }

}  // namespace refract::gem_metrics
