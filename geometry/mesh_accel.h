#pragma once
// Triangle meshes through Embree (Intel's ray-tracing kernels, Debian libembree-dev): a
// BVH built once per mesh, searched in single precision, with a refinement in double.
//
// Embree finds the nearest triangle in float (robust mode: its watertight test, no
// optimisation that can miss an edge); the refinement recomputes that triangle's t in
// double with the project's own triangle test (triangle_t in geometry/shapes.h,
// barycentric bounds not re-tested: Embree decided the triangle). When that t is at or
// before t_min (the surface the ray starts on, which float can place just after it) the
// search goes on beyond it; past t_max there is no hit. The hit returned, its t, point and
// normal are therefore the double-precision ones of the linear search
// (intersect(const TriangleMesh&, ...)) for the same triangle. The two can pick different
// triangles only where float decides differently: a ray through an edge or a vertex
// shared by triangles (the same t to rounding, a different facet index and normal),
// triangles whose t differ by less than float resolution (~1e-7 relative), and hits
// nearer than half of t_min to the origin. The tests measure how often, on random rays.
//
// Embree types never leave this file's implementation. One Embree device serves the
// process, created on first use; searches are thread-safe once built.
#include <cstddef>
#include <memory>
#include <optional>

#include <refract/geometry/shapes.h>

namespace refract {

class MeshAccel {
public:
    // `refined`: the search above. `plain`: Embree as its own examples set it up (default
    // scene flags and build quality, no filter), for intersect_float only: the benchmark
    // of Embree's own throughput.
    enum class Mode { refined, plain };
    // Builds the BVH. The mesh must outlive the MeshAccel and stay unchanged.
    explicit MeshAccel(const TriangleMesh& mesh, Mode mode = Mode::refined);
    ~MeshAccel();
    MeshAccel(const MeshAccel&) = delete;
    MeshAccel& operator=(const MeshAccel&) = delete;

    // Nearest hit with t in (t_min, t_max), as intersect(const TriangleMesh&, ...).
    // Mode::refined only (a plain MeshAccel throws std::logic_error).
    std::optional<Hit> intersect(const Ray& r, double t_min, double t_max) const;

    // Embree alone (Mode::plain only; a refined MeshAccel throws std::logic_error), for
    // benchmarks of Embree's own throughput on the same rays: the nearest triangle's index
    // and float t, −1 when none.
    struct FloatHit {
        int triangle;
        float t;
    };
    FloatHit intersect_float(const Ray& r, double t_min, double t_max) const;

    // The memory this search holds: Embree's allocations for its scene (measured through
    // the device's memory monitor over the build) and the refinement's data.
    std::size_t bytes() const;

    // Meshes with fewer triangles are searched linearly by the tracer (cheaper than a BVH
    // query; measured in docs/performance.md).
    static constexpr std::size_t kMinTriangles = 16;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace refract
