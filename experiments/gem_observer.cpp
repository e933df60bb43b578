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

}  // namespace refract::gem_metrics
