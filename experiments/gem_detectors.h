#pragma once
// Detectors of the face-up phenomena the trade names (issue 31; docs/gem-metrics.md,
// "Nail-head and fish-eye", "Obstruction"): each a number per cut with its standard error, measured on the
// light-return eye rays (experiments/gem_metrics.cpp), and one threshold that decides
// whether the cut shows it. Defined here only.
//
// - Nail-head (a dark centre face-up): the share of the light of the eye rays entering
//   through the central zone of the table (within kNailHeadZone of the table's radius; rays
//   of its own, drawn uniformly over the zone, MetricOptions::centre_share of them) that
//   comes from the observer's head, the directions the observer model blocks (leaving
//   through the crown within its head cone of the eye), less the same share over the rest
//   of the face: the centre darker than the face by the head's reflection. In a deep pavilion the table's
//   central rays, after one reflection off each of two opposite pavilion mains, leave close
//   to the direction they came from (at α = 45° the two mains are a 90° retro-reflector)
//   and carry the observer's own head: a dark centre. A model without a head (the whole
//   hemisphere) has no nail-head by definition.
// - Fish-eye (the girdle's reflection ring seen through the table): the share of the light
//   of the eye rays entering through the table that leaves the stone through the girdle:
//   the girdle, seen by reflection off the pavilion, where the table should show returned
//   light. In a shallow pavilion a ray entering the table meets a pavilion main at α and
//   leaves it rising at 90° − 2α above the horizontal, steeply enough to reach the far
//   girdle above the far pavilion. A knife-edge girdle (Tolkowsky's 1919 preset) has no
//   girdle facets: its fish-eye is 0 by this definition.
// - Obstruction (the observer's head blocking the light the face would return): the share
//   of the light of all the face's eye rays (the light-return rays, the whole face) that
//   comes from the observer's head, the directions the model blocks. This is the light
//   ASET shows blue (AGS: the 75–90° zone about the eye, "obstruction") and Sasian et al.
//   2007's head obscuration; as one number per cut, its error and the threshold are
//   refract's own. A model without a head has no obstruction by definition.
//
// Thresholds: docs/gem-metrics.md gives the measured values behind them (the trade's
// limits, pavilion steeper than about 42–43° for a nail-head and shallower than about 39°
// for a fish-eye, are where the detectors cross them under the default observer). The
// nail-head's 0.35 lies between the largest value away from a nail-head at Tolkowsky's
// table (0.327 ± 0.006, pavilion 39.25°) and the smallest at 43.75° over the gem-cuts
// detector grid (0.373 ± 0.009), under aset; the obstruction's 0.25 (a quarter of the
// face's light from the head) is refract's own.
#include <memory>
#include <vector>

#include <refract/experiments/gem_metrics.h>
#include <refract/geometry/ray.h>

namespace refract::gem_metrics {

constexpr double kNailHeadZone = 0.3;       // the central zone: within 0.3 of the table's radius
constexpr double kNailHeadThreshold = 0.35;  // the centre's head share 0.35 above the face's
constexpr double kFishEyeThreshold = 0.025;  // 2.5 % of the table's light from the girdle
constexpr double kObstructionThreshold = 0.25;  // the face's head share

// "shows a nail-head / fish-eye / obstruction": the value at or above its threshold.
bool shows_nail_head(const Metric& nail_head);
// The nail-head's decision is taken at two standard errors: a value within 2σ of the
// threshold is undecided at that ray count (the maps draw it apart; more central-zone rays,
// MetricOptions::centre_share, decide it).
bool nail_head_decided(const Metric& nail_head);
bool shows_fish_eye(const Metric& fish_eye);
bool shows_obstruction(const Metric& obstruction);

// The sums of one cut's eye rays; add() per face-up eye ray.
class Detectors {
public:
    // The table: the facet whose outward normal is closest to +z (within 1e-9 of it; none:
    // both detectors 0), its radius the largest distance of its vertices from the axis.
    explicit Detectors(const Gem& gem);
    // One light-return eye ray (in the stone's frame) face-up: the weight of its exits
    // through the crown within the observer's head cone, and of its exits through the
    // girdle. Rays entering the central zone are left to add_centre.
    void add(const Ray& eye_ray, double head_weight, double girdle_weight);
    // The central zone's own eye rays (central_ray), which sample it far more densely than
    // the light-return rays (about 2 % of which fall in it): their head weight.
    bool has_table() const { return table_ >= 0; }
    // The eye ray along −viewer through the point of the central zone drawn from u1, u2 in
    // [0, 1) (uniform over the disc), starting `distance` from the table.
    Ray central_ray(const Vec3& viewer, double u1, double u2, double distance) const;
    void add_centre(double head_weight) { centre_head_.add(head_weight); }
    Metric nail_head() const;
    Metric fish_eye() const;
    Metric obstruction() const;

private:
    std::shared_ptr<const Shape> stone_;  // tracing_shape(gem)
    std::vector<int> hit_facet_;          // hit_facets(gem)
    int table_ = -1;
    double table_radius_ = 0, table_z_ = 0;
    Mean centre_head_, rest_head_, table_girdle_, face_head_;
};

}  // namespace refract::gem_metrics
