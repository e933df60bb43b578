#pragma once
// The regions a ray crosses a gradient-index medium in (docs/grin.md): a sphere, a box, a
// slab and a half-space, each as a signed distance (negative inside, zero on the boundary,
// positive outside; exact Euclidean distance for each kind) with its gradient, the outward
// normal. The kinds are plain structs in one std::variant; each has the overloads below,
// and the variant is visited over them, so a kind without them does not compile.
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

namespace refract::grin {

using Vec3 = Eigen::Vector3d;

struct Sphere {
    Vec3 centre = Vec3::Zero();
    double radius = 1.0;
};
// Axis-aligned: lo < hi componentwise.
struct Box {
    Vec3 lo = Vec3::Constant(-1.0), hi = Vec3::Constant(1.0);
};
// lo ≤ normal·x ≤ hi, `normal` unit.
struct Slab {
    Vec3 normal = Vec3::UnitZ();
    double lo = 0.0, hi = 1.0;
};
// normal·x ≤ offset, `normal` unit (the outward normal).
struct HalfSpace {
    Vec3 normal = Vec3::UnitZ();
    double offset = 0.0;
};
// A bounded convex polyhedron: the points inside every face's half-space, with its
// vertices (for its extent). Its signed distance is max over the faces of normal·x − offset:
// exact inside and on the boundary, a lower bound of the distance outside (zero exactly on
// the boundary, which is what the crossing's root finding needs).
struct Polyhedron {
    std::vector<HalfSpace> faces;
    std::vector<Vec3> vertices;
};

using Region = std::variant<Sphere, Box, Slab, HalfSpace, Polyhedron>;

double signed_distance(const Sphere& s, const Vec3& x);
double signed_distance(const Box& b, const Vec3& x);
double signed_distance(const Slab& s, const Vec3& x);
double signed_distance(const HalfSpace& h, const Vec3& x);
double signed_distance(const Polyhedron& q, const Vec3& x);
double signed_distance(const Region& r, const Vec3& x);

// The gradient of the signed distance (unit where it exists; at a sphere's centre, any
// unit vector).
Vec3 outward_normal(const Sphere& s, const Vec3& x);
Vec3 outward_normal(const Box& b, const Vec3& x);
Vec3 outward_normal(const Slab& s, const Vec3& x);
Vec3 outward_normal(const HalfSpace& h, const Vec3& x);
Vec3 outward_normal(const Polyhedron& q, const Vec3& x);
Vec3 outward_normal(const Region& r, const Vec3& x);

// The range of u·x over the region (u unit); ±infinity where it is unbounded.
std::pair<double, double> extent(const Sphere& s, const Vec3& u);
std::pair<double, double> extent(const Box& b, const Vec3& u);
std::pair<double, double> extent(const Slab& s, const Vec3& u);
std::pair<double, double> extent(const HalfSpace& h, const Vec3& u);
std::pair<double, double> extent(const Polyhedron& q, const Vec3& u);
std::pair<double, double> extent(const Region& r, const Vec3& u);

// The largest distance from the line through p along unit d over the region (infinity
// where it is unbounded).
double max_distance_from_line(const Sphere& s, const Vec3& p, const Vec3& d);
double max_distance_from_line(const Box& b, const Vec3& p, const Vec3& d);
double max_distance_from_line(const Slab& s, const Vec3& p, const Vec3& d);
double max_distance_from_line(const HalfSpace& h, const Vec3& p, const Vec3& d);
double max_distance_from_line(const Polyhedron& q, const Vec3& p, const Vec3& d);
double max_distance_from_line(const Region& r, const Vec3& p, const Vec3& d);

// The face of a polyhedron nearest to x from inside (its index in `faces`); −1 for the
// kinds without a face list.
int nearest_face(const Region& r, const Vec3& x);

// A length that sets the scale of the region (a sphere's radius, a box's half diagonal,
// a slab's thickness, 1 for a half-space): the unit of the boundary tolerance.
double length_scale(const Region& r);

// Finite parameters, radius > 0, lo < hi, normals non-zero (normalised in place); an
// InputError naming `path` and the field otherwise (e.g. "s.json: /objects/0/region/radius:
// -1 must be > 0").
void validate(Region& r, const std::string& path);

}  // namespace refract::grin
