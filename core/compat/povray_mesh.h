#pragma once
// POV-Ray 3.7's mesh2 as it meets a ray, the compatibility mode's triangle mesh (sources:
// POV-Ray 3.7 source/backend/shape/mesh.cpp Compute_Mesh_Triangle,
// intersect_mesh_triangle, test_hit; mesh.h; parser/parse.cpp Parse_Mesh2; paraphrased in
// docs/validation.md, "Meshes"):
// - the vertices are stored in single precision;
// - each triangle's unit normal is computed in double from those vertices as
//   (P3 − P1) × (P2 − P1) (the inward normal of a counter-clockwise triangle), then stored
//   in single precision, and so is its plane's distance −n·P1;
// - a ray's t is the stored plane's, −(d + n·o)/(n·dir), no hit where |n·dir| < 1e-10 or t
//   outside [1e-6, 1e7]; the point o + t·dir is then tested against the triangle's three
//   edges in the plane of the two axes other than the normal's largest component, edges
//   and vertices included (after POV-Ray's reordering of the first two vertices);
// - the hit's normal is the stored single-precision one, not renormalised.
// In double, as POV-Ray computes (only the stored values are single precision).
#include <cstddef>
#include <optional>
#include <vector>

#include <refract/geometry/object_bvh.h>
#include <refract/geometry/shapes.h>

namespace refract::povray {

class Mesh {
public:
    explicit Mesh(const TriangleMesh& m);

    // The nearest hit with t in (t_min, t_max) and its outward normal (the stored one
    // negated, |n| = 1 to single precision), facet = the triangle's index in the mesh.
    std::optional<Hit> intersect(const Ray& r, double t_min, double t_max) const;
    // The triangles the ray meets with t in (0, t_max), but not `skip` (−1: none), ignoring
    // POV-Ray's own 1e-6: where the surface is crossed, one crossing per distinct t.
    int crossings(const Ray& r, double t_max, int skip) const;

    // Meshes from this many triangles are searched through a BVH over the triangles' boxes.
    static constexpr std::size_t kMinBvhTriangles = 16;

private:
    struct Triangle {
        Vec3 p1, p2, p3;  // POV-Ray's order (the first two swapped where it swaps them)
        Vec3 normal;      // stored: single precision, as POV-Ray's (inward for refract's winding)
        double distance;  // stored: single precision
        int axis;         // the normal's largest component
    };
    // Triangle k's t for ray r when the ray meets it, within [lo, 1e7].
    std::optional<double> hit_t(const Triangle& tr, const Ray& r, double lo) const;
    template <class Visit>
    void candidates(const Ray& r, double t_min, const double& t_cull, Visit&& visit) const;

    std::vector<Triangle> tri_;
    std::optional<ObjectBvh> bvh_;
};

}  // namespace refract::povray
