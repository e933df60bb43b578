#pragma once
// The observer and lighting models of the light return (issue 31; docs/gem-metrics.md,
// "Observer models"): named set-ups, each with its source, chosen by
// MetricOptions::observer. The default "aset" is the model the metrics always had (one eye
// drawn within viewer_cone_deg of the axis, a 15° head cone, the stone face-up); the
// others change only the light return (fire, scintillation, leakage, the ASET shares and
// the energy balance are measured as before).
#include <string>
#include <vector>

#include <refract/geometry/ray.h>

namespace refract::gem_metrics {

struct Observer {
    std::string name;
    // The observer's head: directions within head_deg of the direction to the eye give no
    // light (the diffuse set-up's obstruction). Ignored when whole_hemisphere.
    double head_deg = 15.0;
    // What counts as returned: false, the light reaching the eye (above the horizon,
    // outside the head); true, every direction above the horizon (the light returned into
    // the upper hemisphere, no head).
    bool whole_hemisphere = false;
    // The stone tilted by each of these angles (degrees, about a horizontal axis at a
    // random azimuth per eye ray, viewer and lights fixed) and the light return averaged
    // over them; {0}: face-up only.
    std::vector<double> tilts_deg{0.0};
    std::string source;  // the publication the set-up follows, and what is refract's own
};

// The named set-ups, "aset" (the default) first: aset, sasian, hemisphere, tilt.
const std::vector<Observer>& observers();
// "aset, sasian, hemisphere or tilt".
std::string observer_names_text();
// The set-up called `name`; InputError "observer 'NAME': expected aset, sasian,
// hemisphere or tilt" for any other (callers prefix their option or field).
const Observer& find_observer(const std::string& name);

// The cosine the head test compares with: cos(head_deg) for an eye, +infinity (nothing
// blocked) for the whole hemisphere.
double head_cosine(const Observer& o);
// The diffuse light return's radiance along exit direction d (unit, in the stone's frame):
// 1 above the horizon of `up` (the world's vertical as the stone sees it) unless within
// the head cone about `viewer` (d·viewer >= cos_head), else 0 (gem_observation.h
// diffuse_with_head with the model's head).
double observer_radiance(const Vec3& d, const Vec3& up, const Vec3& viewer, double cos_head);

}  // namespace refract::gem_metrics
