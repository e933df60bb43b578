#pragma once
// What the vectorised kernels of geometry/ share (plane_set.cpp, sphere_set.cpp,
// lanes_wide.cpp): GNU vector types of W doubles, the choice of a kernel's variant by
// instruction set, and the silencing of GCC 12's AVX-512 headers. Each kernel writes its
// arithmetic once (a template or a macro) and compiles it in per-target functions
// (target attributes), so that each copy is compiled for its own instruction set; the files
// are compiled without contraction into FMA, so every variant gives the same bits.
#include <cstdint>
#include <cstring>

#include "geometry/plane_set.h"

namespace refract::simd {

template <int W>
struct Doubles;  // GCC does not take a template-dependent vector_size
template <>
struct Doubles<2> {
    typedef double type __attribute__((vector_size(2 * sizeof(double))));
};
template <>
struct Doubles<4> {
    typedef double type __attribute__((vector_size(4 * sizeof(double))));
};
template <>
struct Doubles<8> {
    typedef double type __attribute__((vector_size(8 * sizeof(double))));
};
// Eight lanes and their masks (comparisons give 0 or -1 per lane).
using Lane8 = Doubles<8>::type;
typedef std::int64_t Mask8 __attribute__((vector_size(8 * sizeof(std::int64_t))));

// The variant of a kernel for `isa`: the baseline where the CPU cannot run it.
template <class F>
F variant(SlabIsa isa, F baseline, F avx2, F avx512f) {
    if (!slab_isa_supported(isa)) return baseline;
    if (isa == SlabIsa::avx512f) return avx512f;
    if (isa == SlabIsa::avx2) return avx2;
    return baseline;
}

}  // namespace refract::simd

// GCC 12's avx512fintrin.h initialises some results from themselves (__m512d __Y = __Y),
// which -W(maybe-)uninitialized reports wherever they are inlined: silenced around the
// AVX-512 variants.
#if defined(__GNUC__) && !defined(__clang__)
#define REFRACT_AVX512_BEGIN                                      \
    _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wuninitialized\"") \
        _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"")
#define REFRACT_AVX512_END _Pragma("GCC diagnostic pop")
#else
#define REFRACT_AVX512_BEGIN
#define REFRACT_AVX512_END
#endif

// out = the correctly rounded square root of the eight lanes of `in` (Lane8), by the
// instruction SQRT on vectors of type TYPE (__m128d and _mm_sqrt_pd, __m256d and
// _mm256_sqrt_pd, __m512d and _mm512_sqrt_pd): a macro, so that it is compiled in the
// per-target function that uses it.
#define REFRACT_SQRT8(TYPE, SQRT, in, out)                                            \
    for (std::size_t sqrt8_i = 0; sqrt8_i < 8; sqrt8_i += sizeof(TYPE) / sizeof(double)) { \
        TYPE sqrt8_x;                                                                 \
        std::memcpy(&sqrt8_x, reinterpret_cast<const double*>(&(in)) + sqrt8_i, sizeof sqrt8_x); \
        sqrt8_x = SQRT(sqrt8_x);                                                      \
        std::memcpy(reinterpret_cast<double*>(&(out)) + sqrt8_i, &sqrt8_x, sizeof sqrt8_x); \
    }
