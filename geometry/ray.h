#pragma once
// Vectors and rays: double precision throughout (Eigen).
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace refract {

using Vec3 = Eigen::Vector3d;

struct Ray {
    Vec3 origin;
    Vec3 dir;  // unit length by convention
    Vec3 at(double t) const { return origin + t * dir; }
};

// A vector's direction, safe to normalise: v itself when v·v is a normal double (so an
// ordinary vector gives Eigen's normalized() to the bit), else v times the power of two
// that brings its largest component into [1, 2) (exact: the direction is kept), so that
// components past 1.3e154 or below 1.5e-154 neither overflow nor underflow in the squares.
namespace detail {
inline bool normal_square(double z) {
    return z >= std::numeric_limits<double>::min() && z <= std::numeric_limits<double>::max();
}
}  // namespace detail

inline Vec3 rescaled(const Vec3& v) {
    if (detail::normal_square(v.squaredNorm())) return v;
    const double m = v.cwiseAbs().maxCoeff();
    if (!(m > 0) || !std::isfinite(m)) return v;
    const int e = std::ilogb(m);
    return v.unaryExpr([e](double x) { return std::scalbn(x, -e); });
}

// v/|v| without overflow or underflow (rescaled, then normalised): the one normalisation
// of the vectors a user gives (directions, normals, axes). Empty when v is zero or not
// finite.
inline std::optional<Vec3> unit_vector(const Vec3& v) {
    if (!v.allFinite()) return std::nullopt;
    const Vec3 w = rescaled(v);
    if (!(w.squaredNorm() > 0)) return std::nullopt;
    return Vec3(w.normalized());
}

// x/|v| computed the same way (a plane's offset over its normal's length): x / v.norm()
// for an ordinary v.
inline double over_norm(double x, const Vec3& v) {
    if (detail::normal_square(v.squaredNorm())) return x / v.norm();
    const double m = v.cwiseAbs().maxCoeff();
    if (!(m > 0) || !std::isfinite(m)) return x / v.norm();
    return std::scalbn(x, -std::ilogb(m)) / rescaled(v).norm();
}

}  // namespace refract
