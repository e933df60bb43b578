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
    // Two eyes: each eye's direction eye_half_angle_deg from the drawn viewer direction on
    // either side (about the stone frame's y axis: the eyes side by side along x), each eye
    // ray traced from its own eye, the light return averaged over the two; the head blocks
    // the directions within head_deg of either eye. 0: one eye.
    double eye_half_angle_deg = 0.0;
};

// The named set-ups, "aset" (the default) first: aset, sasian, hemisphere, tilt, binocular.
const std::vector<Observer>& observers();
// "aset, sasian, hemisphere, tilt or binocular".
std::string observer_names_text();
// The set-up called `name`; InputError "observer 'NAME': expected aset, sasian,
// hemisphere, tilt or binocular" for any other (callers prefix their option or field).
const Observer& find_observer(const std::string& name);

// The cosine the head test compares with: cos(head_deg) for an eye, +infinity (nothing
// blocked) for the whole hemisphere.
double head_cosine(const Observer& o);
// The diffuse light return's radiance along exit direction d (unit, in the stone's frame):
// 1 above the horizon of `up` (the world's vertical as the stone sees it) unless within
// the head cone about `viewer` (d·viewer >= cos_head), else 0 (gem_observation.h
// diffuse_with_head with the model's head).
double observer_radiance(const Vec3& d, const Vec3& up, const Vec3& viewer, double cos_head);
// The binocular observer's: 1 above the horizon unless within the head cone about either
// eye (d·eye >= cos_head or d·other_eye >= cos_head), else 0.
double observer_radiance(const Vec3& d, const Vec3& up, const Vec3& eye, const Vec3& other_eye, double cos_head);
// The half-angle two eyes `separation_mm` apart subtend at a stone `distance_mm` away, in
// degrees: atan(separation / 2 / distance).
double eye_half_angle_deg(double separation_mm, double distance_mm);
// Whether the model's light return needs eye rays of its own (tilts, two eyes): such a
// model cannot share another model's rays (MetricOptions::also_observers).
bool traces_own_rays(const Observer& o);

}  // namespace refract::gem_metrics
