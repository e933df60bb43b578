#pragma once
// Illumination maps (Chattopadhyay & Fujimoto 1987; Ohtsuka & Kawai 1998 §2): the light
// that reaches a diffuse surface by way of specular surfaces (caustics), stored per
// element. A plane's map covers a square region (the part of the infinite plane under
// the transparent objects) cut into square elements of edge `element_size`; a mesh's map
// cuts every triangle into k² similar triangles (k = ceil(longest edge / element_size)).
// The light pass fills `irradiance` (RGB, the units of the direct lighting: a point light
// of colour c gives irradiance c·cosθ at the transparent objects' distance): each
// element's mean over its area.
//
// Reconstruction (MapFilter, core/scene.h), what the eye pass reads at a point:
//   Box        the element's mean: a step at every element edge, error O(h) where the
//              irradiance has a gradient.
//   Bilinear   plane: bilinear interpolation between the four nearest element centres
//              (an element's mean is the irradiance at its centre to O(h²)), exact for a
//              linear field; outside the outermost centres the edge values are held
//              (clamped). Mesh: each triangle's k² elements are interpolated
//              barycentrically between values at their corners, a corner's value being
//              the mean of the elements of the same triangle that share it (six inside a
//              triangle, which makes it exact for a linear field there; fewer on the
//              triangle's edges, biased O(h) there as the box is). No smoothing across
//              triangles: a mesh's triangles may have different k.
// Both are pure functions of the stored means: deterministic like the light pass.
#include <memory>
#include <optional>
#include <vector>

#include <refract/core/scene.h>

namespace refract {

class IlluminationMap {
public:
    // The most elements a map may hold (docs/limits.md); more throws InputError naming
    // /render/light_pass/element_size.
    static constexpr long long kMaxCells = 1LL << 22;
    // Square of half-size `half` on plane p centred on the projection of `centre`.
    static IlluminationMap for_plane(const Plane& p, const Vec3& centre, double half, double element_size);
    static IlluminationMap for_mesh(const TriangleMesh& m, double element_size);
    // The elements those maps would hold, computed without allocating (memory estimates).
    static double plane_elements(double half, double element_size);
    static double mesh_elements(const TriangleMesh& m, double element_size);
    // Bytes a map holds per element (area, irradiance, the light pass's fixed-point sums).
    static constexpr double kBytesPerElement = 56;

    int elements() const { return static_cast<int>(area_.size()); }
    double element_area(int e) const { return area_[static_cast<size_t>(e)]; }
    // Element holding the hit (facet: the hit's triangle for meshes), −1 outside the map.
    int element(const Hit& hit) const;
    // The reconstructed irradiance at the hit; 0 outside the map.
    Vec3 value(const Hit& hit, MapFilter filter) const;
    // Plane maps: the element's centre, and the point (on the plane) at grid coordinates
    // (x, y) in element units from the square's corner (centres at half-integers).
    Vec3 centre(int e) const;
    Vec3 grid_point(double x, double y) const { return origin_ + (x * size_) * u_ + (y * size_) * v_; }
    int cells() const { return cells_; }

    std::vector<Vec3> irradiance;  // per element

private:
    // Plane grid coordinates (x, y) of a hit; false outside the square.
    bool grid(const Hit& hit, double& x, double& y) const;
    // Mesh: the triangle, its subdivision k and the hit's lattice coordinates (s, r),
    // s, r ≥ 0, s + r ≤ k; false when the hit has no facet of the map.
    bool lattice(const Hit& hit, int& facet, int& k, double& s, double& r) const;
    // The element of lattice point (s, r): cell (i, j) of the k×k grid, its upper or
    // lower triangle.
    static void cell(int k, double s, double r, int& i, int& j, bool& upper);
    Vec3 bilinear(double x, double y) const;
    Vec3 barycentric(int facet, int k, double s, double r) const;
    Vec3 corner_mean(int facet, int k, int a, int b) const;  // lattice vertex (a, b)
    int mesh_element(int facet, int k, int i, int j, bool upper) const;

    enum class Kind { Plane, Mesh } kind_ = Kind::Plane;
    // plane: origin of the square's corner, its axes, cells per side, cell size
    Vec3 origin_{0, 0, 0}, u_{1, 0, 0}, v_{0, 0, 1};
    int cells_ = 0;
    double size_ = 1;
    // mesh: per triangle, its vertices, subdivision k and first element index
    const TriangleMesh* mesh_ = nullptr;
    std::vector<int> k_, first_;
    std::vector<double> area_;
};

// One map per object (null for objects without one: non-diffuse, spheres, polyhedra).
struct IlluminationMaps {
    std::vector<std::unique_ptr<IlluminationMap>> by_object;
    std::uint64_t photons = 0, deposits = 0, segments = 0;
    std::uint64_t facet_local = 0, facet_full = 0;  // RenderStats' counts for the light pass
    double seconds = 0;
    // Irradiance at a hit on object `object`, reconstructed with `filter`; 0 without a
    // map or outside it.
    Vec3 irradiance(int object, const Hit& hit, MapFilter filter) const;
    size_t elements() const;
};

}  // namespace refract
