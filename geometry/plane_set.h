#pragma once
// The slab pass of intersect(const ConvexPolyhedron&, ...) over a convex plane set,
// vectorised, with results identical to the last bit to the scalar loop (intersect_scalar
// in geometry/shapes.h; the tests compare them ray by ray for every variant this CPU runs).
//
// For half-spaces n_k·x <= d_k and a ray o + t v it finds
//   t_enter = the largest t = dist/denom over planes with denom < 0, f_enter = the first
//             plane attaining it (-inf and -1 when none),
//   t_exit  = the smallest t over the other planes, f_exit = the first attaining it
//             (+inf and -1 when none),
// with denom = n·v, dist = d - n·o computed as the scalar loop does. The one difference in
// these fields: a plane parallel to the ray with the origin outside, where the scalar loop
// stops with a miss, here makes t_enter = +inf or t_exit = -inf, which no t window
// (t_min < t < t_max) accepts and which otherwise makes t_enter > t_exit: still a miss.
// The caller's test is the end of the scalar loop: no hit when t_enter > t_exit, else the
// entering plane if t_enter is in the window and f_enter >= 0, else the leaving plane.
//
// The kernel reads `planes` as they are (no copy that could go stale): blocks of W planes
// are transposed in registers into per-coordinate vectors, each lane keeps its running
// max/min and plane index, and a final reduction picks the largest (smallest) t and among
// equal t the smallest index. The kernel is written once over xsimd's batch of W doubles
// (geometry/simd/plane_set.cpp) and compiled per instruction set: AVX-512F (W = 8), AVX2
// (W = 4) and baseline x86-64 SSE2 (W = 2); slab_span picks the best one the CPU runs, once
// (geometry/simd.h). On other processors only the baseline variant, for the compiler's
// default architecture, exists.
#include <cstddef>
#include <optional>

#include <refract/geometry/shapes.h>

namespace refract {

struct SlabSpan {
    double t_enter;
    double t_exit;
    int f_enter;
    int f_exit;
};

enum class SlabIsa { baseline, avx2, avx512f };

const char* slab_isa_name(SlabIsa isa);  // "baseline (SSE2)", "AVX2", "AVX-512F"
bool slab_isa_supported(SlabIsa isa);    // can this CPU (and OS) run the variant?
SlabIsa slab_isa();                      // the variant slab_span dispatches to

// The dispatched kernel: the best variant this CPU supports.
SlabSpan slab_span(const Plane* planes, std::size_t n, const Ray& r);
// One variant by name (tests, benchmark); an unsupported one runs the baseline variant.
SlabSpan slab_span(SlabIsa isa, const Plane* planes, std::size_t n, const Ray& r);

// intersect(const ConvexPolyhedron&, ...) (geometry/shapes.h) with one variant's slab pass
// (tests, benchmark); defined in shapes.cpp next to the dispatched one.
std::optional<Hit> intersect(SlabIsa isa, const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max);

}  // namespace refract
