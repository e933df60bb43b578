#pragma once
// The nearest of a list of spheres along one ray, the spheres tested together: their
// centres and radii by coordinate (structure of arrays), the quadratic of every sphere
// computed in one vectorised pass (geometry/simd/sphere_set.cpp: AVX-512F, AVX2 or the SSE2
// baseline, the best the CPU runs, chosen at run time), then the nearest root picked in
// list order.
//
// The answer is that of intersect(const Sphere&, ...) asked of each sphere in list order
// with the window narrowed to the best t so far, bit for bit: the same operations in the
// same order for b, c, the discriminant and the roots (sphere_quadratic itself, on the
// kernel's batches; the kernels are compiled without contraction into FMA, so every variant
// gives the same bits), the nearer root when it lies in the window, else the farther one,
// and on equal t the sphere listed first. A negative discriminant gives a NaN root, which no
// window accepts, as the scalar test's early miss.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <refract/geometry/plane_set.h>
#include <refract/geometry/shapes.h>

namespace refract {

class SphereSet {
public:
    SphereSet() = default;
    // Every sphere set of the process from now on runs this variant (an unsupported one:
    // the baseline); by default the best the CPU runs (tests compare the variants).
    static void use_isa(SlabIsa isa);
    void add(const Sphere& s);
    std::size_t size() const { return spheres_.size(); }
    const Sphere& sphere(std::size_t i) const { return spheres_[i]; }

    struct Nearest {
        double t;
        std::size_t index;  // in the order of add()
    };
    // The nearest root with t_min < t < t_max. `leaving`: the sphere the ray starts on
    // (SIZE_MAX: none), skipped when the ray moves away from its centre (b = oc·d > 0: it
    // cannot meet that sphere again).
    std::optional<Nearest> nearest(const Ray& r, double t_min, double t_max, std::size_t leaving = SIZE_MAX) const;

    // The same search for kLanes rays at once (geometry/lanes.h), each lane of `active`
    // asking with its own window (t_min, best[lane]): where a sphere's root lies in it, best
    // becomes that t, index that sphere's (in the order of add()), and point and normal
    // sphere_hit's at that t, and `hit` is set; other lanes keep their best and index (their
    // point and normal are unspecified). Each lane's answer is nearest()'s and sphere_hit's,
    // bit for bit. `leaving[lane]`: the sphere that lane's ray starts on (-1: none).
    struct LaneHits {
        LaneMask hit;
        Lanes best;
        std::array<std::int32_t, kLanes> index;
        LaneVec3 point, normal;
    };
    void nearest_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active, double t_min,
                       const std::array<std::int32_t, kLanes>& leaving, LaneHits& io) const;

private:
    std::vector<Sphere> spheres_;
    // Padded to a multiple of 8 with spheres of NaN radius (never a hit).
    std::vector<double> cx_, cy_, cz_, r_;
};

}  // namespace refract
