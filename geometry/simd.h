#pragma once
// The vectorised kernels of geometry/ and the choice of their variant.
//
// SIMD through one library, xsimd (Debian's libxsimd-dev, header-only). Each kernel is written
// once, as a template over xsimd's architecture A on xsimd::batch<double, A>
// (geometry/simd/*.cpp), and compiled once per instruction set, each time in its own object
// with that set's flags (geometry/CMakeLists.txt): SSE2 (the x86-64 baseline), AVX2
// (-mavx2) and AVX-512F (-mavx512f -mfma). `variant` below picks one at run time from the CPU.
// Why xsimd rather than Highway (libhwy-dev): Debian 12's Highway (1.0.3) has no SSE2
// target (on the x86-64 baseline its static target is EMU128, plain C++ loops), so the lane
// type of geometry/lanes.h, compiled at the baseline in every file of core/, could not keep
// its packed comparisons and blends; xsimd::batch<double, xsimd::sse2> is the SSE2 register.
// xsimd's variants are also exactly the three instruction sets the kernels had (Highway's
// AVX-512 target needs BW, DQ and VL besides F), and a kernel compiled with its set's flags
// can instantiate the project's own templates (sphere_quadratic) on its batches.
// The CPU is asked through the compiler's __builtin_cpu_supports (plane_set.cpp), which
// also checks that the OS saves the registers; xsimd 8.1's detection does not.
//
// A kernel file must not inline-define anything that does not depend on A: the linker keeps
// one copy of each inline function, and a copy compiled with -mavx512f must never be the
// one the rest of the program calls (the test geometry:simd-objects checks the objects).
#include <cstddef>
#include <cstdint>

#include <xsimd/xsimd.hpp>

#include <refract/geometry/plane_set.h>

namespace refract::simd {

#if defined(__x86_64__)
using Sse2 = xsimd::sse2;
using Avx2 = xsimd::avx2;
using Avx512f = xsimd::avx512f;
#else  // one variant, the compiler's default architecture, under the three names
using Sse2 = xsimd::default_arch;
using Avx2 = Sse2;
using Avx512f = Sse2;
#endif

// The variant of a kernel for `isa`: the baseline where the CPU cannot run it.
template <class F>
F variant(SlabIsa isa, F baseline, F avx2, F avx512f) {
    if (!slab_isa_supported(isa)) return baseline;
    if (isa == SlabIsa::avx512f) return avx512f;
    if (isa == SlabIsa::avx2) return avx2;
    return baseline;
}

// ---- The kernels (geometry/simd/*.cpp), instantiated for Sse2, Avx2 and Avx512f. ---------
// Rays are passed as plain doubles (o: origin x, y, z; v: direction), lanes of a packet as
// their arrays of kLanes doubles (geometry/lanes.h), lane masks as their bits.

// The slab pass of plane_set.h over the planes {n_x, n_y, n_z, offset} from `planes`.
template <class A>
SlabSpan slab_kernel(const double* planes, std::size_t n, const double* o, const double* v);

// Per sphere of the (padded) lists: its nearer root in (t_min, t_max), else its farther one,
// else +inf, into t_out; its b = oc·v into b_out (sphere_set.cpp).
template <class A>
void sphere_roots(const double* cx, const double* cy, const double* cz, const double* radius, std::size_t n,
                  const double* o, const double* v, double t_min, double t_max, double* t_out, double* b_out);

// SphereSet::nearest_lanes over the first n spheres: per lane of `active`, best_io and
// index_io narrowed to the nearest root in (t_min, best_io), skipping sphere leaving[lane]
// where b > 0; returns the lanes that found one, and for them point_io and normal_io
// (x, y, z arrays of kLanes doubles, one after another) as sphere_hit's.
template <class A>
std::uint32_t sphere_lanes(const double* cx, const double* cy, const double* cz, const double* radius,
                           std::size_t n, const double* ox, const double* oy, const double* oz, const double* vx,
                           const double* vy, const double* vz, std::uint32_t active, double t_min, double* best_io,
                           double* index_io, const double* leaving, double* point_io, double* normal_io);

// normalize_lanes (lanes_wide.h) on the lane arrays x, y, z.
template <class A>
void normalize_lanes(double* x, double* y, double* z, std::uint32_t mask);

// Whether one of n planes (coordinates and indices in arrays, n a multiple of 8)
// contradicts the candidate leaving hit at t_g on plane g (facet_graph.cpp).
template <class A>
bool contradicts(const double* nx, const double* ny, const double* nz, const double* d, const double* index,
                 std::size_t n, const double* o, const double* v, double t_min, double t_g, double g);

// The same on kLanes rays (lane arrays): the lanes of `mask` that one of the n planes
// contradicts.
template <class A>
std::uint32_t contradicts_lanes(const double* nx, const double* ny, const double* nz, const double* d,
                                const double* index, std::size_t n, const double* ox, const double* oy,
                                const double* oz, const double* vx, const double* vy, const double* vz, double t_min,
                                const double* t_g, const double* g, std::uint32_t mask);

}  // namespace refract::simd
