#pragma once
// A sphere as a triangle mesh: the regular icosahedron with each triangle cut into four,
// `subdivisions` times (20·4^s triangles: 80 at s = 1 … 327 680 at s = 7), the new
// vertices pushed out to the sphere; counter-clockwise seen from outside, shared
// vertices (a closed mesh). Test and benchmark geometry for the mesh search.
#include <refract/geometry/shapes.h>

namespace refract {

TriangleMesh icosphere(int subdivisions, const Vec3& centre = Vec3(0, 0, 0), double radius = 1.0);

}  // namespace refract
