// The observer and lighting models of the light return (experiments/gem_observer.h).
#include <refract/experiments/gem_observer.h>

#include <cmath>
#include <limits>

#include <refract/experiments/gem_observation.h>
#include <refract/geometry/error.h>

namespace refract::gem_metrics {

namespace {
constexpr double kDeg = M_PI / 180.0;
}

const std::vector<Observer>& observers() {
    static const std::vector<Observer> o{
        {"aset", kHeadDeg, false, {0.0},
         "one eye within viewer_cone_deg of the axis, a 15 deg head cone: ASET's blocked zone (AGS), diffuse "
         "hemispherical light after Hemphill et al., G&G 34(3) 1998; the single eye is refract's own"},
        {"sasian", 40.0, false, {0.0},
         "a 40 deg head obscuration: Sasian, Quick, Sheffield, Caudill & Yantzer, Opt. Eng. 46(9) 093604, 2007; "
         "the eye and diffuse light as in aset"},
        {"hemisphere", 0.0, true, {0.0},
         "light returned into the whole upper hemisphere, no head: the quantity the Moscow State University "
         "'Brill' model separates from the light reaching the eye; the eye rays as in aset"},
        {"tilt", kHeadDeg, false, {0.0, 10.0, 20.0, 30.0},
         "the stone tilted 0, 10, 20 and 30 deg and the light return averaged, as GIA's WLR averages over "
         "positions (Hemphill et al., G&G 34(3) 1998); the tilts and the aset head are refract's own choice"},
        {"binocular", kHeadDeg, false, {0.0},
         "two eyes 64 mm apart (about the adult mean interpupillary distance, 63 mm in Dodgson, Proc. SPIE 5291, "
         "2004) at 250 mm (the conventional least distance of distinct vision), each eye with ASET's 15 deg head "
         "cone, the light return averaged over the two eyes; the head as the union of the two cones is refract's own",
         eye_half_angle_deg(64.0, 250.0)},
    };
    return o;
}

std::string observer_names_text() {
    const auto& o = observers();
    std::string s;
    for (size_t i = 0; i < o.size(); ++i) s += (i == 0 ? "" : i + 1 == o.size() ? " or " : ", ") + o[i].name;
    return s;
}

const Observer& find_observer(const std::string& name) {
    for (const Observer& o : observers())
        if (o.name == name) return o;
    throw InputError("observer '" + name + "': expected " + observer_names_text());
}

double head_cosine(const Observer& o) {
    return o.whole_hemisphere ? std::numeric_limits<double>::infinity() : std::cos(o.head_deg * kDeg);
}

double observer_radiance(const Vec3& d, const Vec3& up, const Vec3& viewer, double cos_head) {
    return d.dot(up) > 0.0 && d.dot(viewer) < cos_head ? 1.0 : 0.0;
}

double observer_radiance(const Vec3& d, const Vec3& up, const Vec3& eye, const Vec3& other_eye, double cos_head) {
    return d.dot(up) > 0.0 && d.dot(eye) < cos_head && d.dot(other_eye) < cos_head ? 1.0 : 0.0;
}

double eye_half_angle_deg(double separation_mm, double distance_mm) {
    return std::atan(0.5 * separation_mm / distance_mm) / kDeg;
}

bool traces_own_rays(const Observer& o) { return o.tilts_deg.size() != 1 || o.eye_half_angle_deg > 0; }

}  // namespace refract::gem_metrics
