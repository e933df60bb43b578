#pragma once
// Illumination maps (Chattopadhyay & Fujimoto 1987; Ohtsuka & Kawai 1998 §2): the light
// that reaches a diffuse surface by way of specular surfaces (caustics), stored per
// element. A plane's map covers a square region (the part of the infinite plane under
// the transparent objects) cut into square elements of edge `element_size`; a mesh's map
// cuts every triangle into k² similar triangles (k = ceil(longest edge / element_size)).
// The light pass fills `irradiance` (RGB, the units of the direct lighting: a point light
// of colour c gives irradiance c·cosθ at the transparent objects' distance).
#include <memory>
#include <optional>
#include <vector>

#include "core/scene.h"

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

    std::vector<Vec3> irradiance;  // per element

private:
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
    double seconds = 0;
    // Irradiance at a hit on object `object`; 0 without a map or outside it.
    Vec3 irradiance(int object, const Hit& hit) const;
    size_t elements() const;
};

}  // namespace refract
