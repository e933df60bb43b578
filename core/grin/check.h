#pragma once
// Parameter checks shared by the regions and the profiles (core/grin/): an InputError
// naming the field, in the scene reader's words.
#include <cmath>
#include <string>

#include <Eigen/Core>

#include <refract/geometry/error.h>

namespace refract::grin::detail {

using Vec3 = Eigen::Vector3d;

inline void finite_vec(const Vec3& v, const std::string& field) {
    if (!v.allFinite())
        throw InputError(field + ": (" + format_value(v.x()) + ", " + format_value(v.y()) + ", " + format_value(v.z()) +
                         ") must be finite");
}
inline void unit_in_place(Vec3& v, const std::string& field) {
    finite_vec(v, field);
    const double n = v.norm();
    if (!(n > 0) || !std::isfinite(n)) throw InputError(field + ": must be a non-zero vector");
    v /= n;
}
inline void finite(double v, const std::string& field) {
    if (!std::isfinite(v)) throw InputError(field + ": " + format_value(v) + " must be finite");
}

}  // namespace refract::grin::detail
