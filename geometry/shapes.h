#pragma once
// Shapes and their ray intersections. Every intersection returns the nearest hit with
// t in (t_min, t_max) and the *outward* geometric normal of the surface (for a sphere of
// negative radius the outward normal points to the centre: RTIOW's hollow sphere).
#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <refract/geometry/lanes.h>
#include <refract/geometry/ray.h>

namespace refract {

struct Hit {
    double t = 0;
    Vec3 point;
    Vec3 normal;    // outward unit normal of the surface at the hit
    int facet = -1; // facet / triangle index where the shape has facets, else -1
};

struct Sphere {
    Vec3 center{0, 0, 0};
    double radius = 1;  // negative: normals flipped (hollow sphere, RTIOW)
};

// Infinite plane {x : normal·x = offset}; outward side is where normal·x > offset.
struct Plane {
    Vec3 normal{0, 1, 0};  // unit
    double offset = 0;
};

struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside
};

// Convex polyhedron as an intersection of half-spaces normal_i·x <= offset_i
// (unit outward normals). This is the representation gems use: the tracer sees only
// plain double planes, whatever built them.
struct ConvexPolyhedron {
    std::vector<Plane> planes;
    std::vector<std::string> labels;  // one per plane (facet names), may be empty
    // Optional bounding sphere (radius > 0): rays that miss it skip the plane loop.
    Vec3 bound_center{0, 0, 0};
    double bound_radius = 0;
};

// Bounding sphere of a convex polyhedron from its vertices (the builder knows them).
void set_bound(ConvexPolyhedron& c, const std::vector<Vec3>& vertices);
// Whether the ray certainly misses c's bounding sphere (none set: false); the first test of
// every intersect(const ConvexPolyhedron&, ...).
bool misses_bound(const ConvexPolyhedron& c, const Ray& r);

// Every shape has the full set of operations below, one overload per shape; the
// Shape-level functions dispatch with std::visit, so a shape missing one fails to compile.
using Shape = std::variant<Sphere, Plane, TriangleMesh, ConvexPolyhedron>;

std::optional<Hit> intersect(const Sphere& s, const Ray& r, double t_min, double t_max);
// The hit of ray r on sphere s at its root t: point, outward normal (the sphere test's own,
// shared with the sphere set, geometry/sphere_set.h).
Hit sphere_hit(const Sphere& s, const Ray& r, double t);

// The sphere's quadratic |o + t d − c|² = ρ² for |d| = 1, oc = o − c, in half-b form
// t² + 2 b t + c = 0: b and the discriminant b² − c (no hit where it is negative). Over the
// vector type V (Vec3, LaneVec3).
template <class V>
struct SphereQuadratic {
    typename V::Scalar b, disc;
};
template <class V>
SphereQuadratic<V> sphere_quadratic(const V& oc, const V& dir, typename V::Scalar radius) {
    using S = typename V::Scalar;
    const S b = oc.dot(dir);
    const S c = oc.squaredNorm() - radius * radius;
    return {b, b * b - c};
}

// A shape's test on kLanes rays at once (geometry/lanes.h): in each lane of `active`, the
// hit of intersect(shape, ray, t_min, t_max[lane]) bit for bit: `hit` where there is one,
// with its t, point and outward normal (other lanes: unspecified).
struct LaneShapeHits {
    LaneMask hit;
    Lanes t;
    LaneVec3 point, normal;
};
// `leaving`: the lanes whose rays start on this sphere; those moving away from its centre
// (b = oc·d > 0) do not meet it again.
LaneShapeHits intersect_lanes(const Sphere& s, const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                              double t_min, const Lanes& t_max, const LaneMask& leaving = LaneMask::Constant(false));
LaneShapeHits intersect_lanes(const Plane& p, const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                              double t_min, const Lanes& t_max);
std::optional<Hit> intersect(const Plane& p, const Ray& r, double t_min, double t_max);
std::optional<Hit> intersect(const TriangleMesh& m, const Ray& r, double t_min, double t_max);
std::optional<Hit> intersect(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max);
// The same, with the original scalar plane loop (the reference the vectorised kernel in
// geometry/plane_set.h is tested against, bit for bit).
std::optional<Hit> intersect_scalar(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max);
std::optional<Hit> intersect(const Shape& s, const Ray& r, double t_min, double t_max);

// Möller–Trumbore for triangle k of a mesh, in double: the ray's t at the triangle's
// plane and the barycentrics (u, v) of the point (inside: u, v >= 0, u + v <= 1); empty
// when the ray is parallel to the plane. The one triangle test of the project (the linear
// search above and the Embree refinement in geometry/mesh_accel.h both use it).
struct TriangleT {
    double t, u, v;
};
std::optional<TriangleT> triangle_t(const TriangleMesh& m, std::size_t k, const Ray& r);
// The same for the triangle with corner a and edges e1 = b − a, e2 = c − a.
std::optional<TriangleT> triangle_t(const Vec3& a, const Vec3& e1, const Vec3& e2, const Ray& r);
Vec3 triangle_normal(const TriangleMesh& m, std::size_t k);  // outward unit normal

// Axis-aligned bounds (used for culling and for export); empty optional when unbounded.
struct Bounds {
    Vec3 lo, hi;
};
std::optional<Bounds> bounds(const Sphere& s);
std::optional<Bounds> bounds(const Plane& p);
std::optional<Bounds> bounds(const TriangleMesh& m);
std::optional<Bounds> bounds(const ConvexPolyhedron& c);
std::optional<Bounds> bounds(const Shape& s);

// A sphere enclosing the shape (the light pass aims its photons at it); empty when the
// shape is unbounded.
struct BoundingSphere {
    Vec3 centre;
    double radius;
};
std::optional<BoundingSphere> bounding_sphere(const Sphere& s);
std::optional<BoundingSphere> bounding_sphere(const Plane& p);
std::optional<BoundingSphere> bounding_sphere(const TriangleMesh& m);
std::optional<BoundingSphere> bounding_sphere(const ConvexPolyhedron& c);
std::optional<BoundingSphere> bounding_sphere(const Shape& s);

// Corner points (for export and bounds): the mesh's vertices, the polyhedron's vertices
// (every triple of planes meeting in a point inside all half-spaces); none for a sphere
// or a plane.
std::vector<Vec3> vertices(const Sphere& s);
std::vector<Vec3> vertices(const Plane& p);
std::vector<Vec3> vertices(const TriangleMesh& m);
std::vector<Vec3> vertices(const ConvexPolyhedron& c);
std::vector<Vec3> vertices(const Shape& s);

// The surface an illumination map can cover (core/illumination_map.h, the light pass's
// caustics): none, a plane (a square under the transparent objects) or a triangle mesh (its
// triangles). A shape that should receive caustics says which here.
using MapSurface = std::variant<std::monostate, const Plane*, const TriangleMesh*>;
MapSurface map_surface(const Sphere& s);
MapSurface map_surface(const Plane& p);
MapSurface map_surface(const TriangleMesh& m);
MapSurface map_surface(const ConvexPolyhedron& c);
MapSurface map_surface(const Shape& s);

// A bounded convex polyhedron as a closed triangle mesh: its corners once each, every
// face fanned from one corner, counter-clockwise seen from outside (the same solid for
// renderers that take meshes, e.g. POV-Ray's mesh2). Empty when unbounded.
TriangleMesh mesh_of(const ConvexPolyhedron& c);

}  // namespace refract
