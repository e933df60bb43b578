#pragma once
// Vectors and rays: double precision throughout (Eigen).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace refract {

using Vec3 = Eigen::Vector3d;

struct Ray {
    Vec3 origin;
    Vec3 dir;  // unit length by convention
    Vec3 at(double t) const { return origin + t * dir; }
};

}  // namespace refract
