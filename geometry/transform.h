#pragma once
// Affine transforms of shapes (an object's "transform", docs/scene-format.md): x ↦ A x + t
// on points. Meshes and polyhedra transform exactly (vertices by A x + t; planes by the
// inverse transpose of A, renormalised); a sphere stays a sphere under rotation,
// reflection, translation and uniform scale, and takes no other transform.
#include <optional>
#include <string>

#include <refract/geometry/shapes.h>

namespace refract {

struct Transform {
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    Vec3 translation{0, 0, 0};

    Vec3 point(const Vec3& p) const { return linear * p + translation; }
    // This transform applied after `inner`.
    Transform after(const Transform& inner) const { return {linear * inner.linear, linear * inner.translation + translation}; }
};

// The shape moved by T. Empty when T cannot move it exactly (a sphere under a non-uniform
// scale or a shear: its A is not a multiple of an orthogonal matrix, to 1e-12). A mirroring
// T (det A < 0) rewinds each triangle so that normals stay outward.
std::optional<Shape> transformed(const Shape& s, const Transform& T);

// The uniform scale of A when A = s·Q with Q orthogonal (to 1e-12 relative), else empty.
std::optional<double> uniform_scale(const Eigen::Matrix3d& A);

}  // namespace refract
