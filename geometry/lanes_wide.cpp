// Whole-packet operations on the widest vector instructions (see lanes_wide.h). The
// arithmetic is LaneVec3's: the squared norm added x, y, z left to right, the correctly
// rounded square root, three divisions; compiled without contraction into FMA.
#include "geometry/lanes_wide.h"

#include <atomic>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "geometry/plane_set.h"
#include "geometry/simd.h"

namespace refract {

namespace {

using simd::Lane8;
using simd::Mask8;
static_assert(kLanes == 8, "eight lanes");

#define REFRACT_NORMALIZE(TYPE, SQRT)                                                   \
    Lane8 x, y, z;                                                                      \
    std::memcpy(&x, v.x.v, sizeof x);                                                   \
    std::memcpy(&y, v.y.v, sizeof y);                                                   \
    std::memcpy(&z, v.z.v, sizeof z);                                                   \
    Lane8 n2 = x * x + y * y;                                                           \
    n2 = n2 + z * z;                                                                    \
    Lane8 len;                                                                          \
    REFRACT_SQRT8(TYPE, SQRT, n2, len)                                                  \
    Mask8 on;                                                                           \
    for (int l = 0; l < 8; ++l) on[l] = ((mask >> l) & 1u) ? -1 : 0;                    \
    on = on & (n2 > Lane8{});                                                           \
    x = on ? x / len : x;                                                               \
    y = on ? y / len : y;                                                               \
    z = on ? z / len : z;                                                               \
    std::memcpy(v.x.v, &x, sizeof x);                                                   \
    std::memcpy(v.y.v, &y, sizeof y);                                                   \
    std::memcpy(v.z.v, &z, sizeof z);

using NormalizeFn = void (*)(LaneVec3&, std::uint32_t);

#if defined(__x86_64__)
void normalize_baseline(LaneVec3& v, std::uint32_t mask) { REFRACT_NORMALIZE(__m128d, _mm_sqrt_pd) }
__attribute__((target("avx2"))) void normalize_avx2(LaneVec3& v, std::uint32_t mask) {
    REFRACT_NORMALIZE(__m256d, _mm256_sqrt_pd)
}
REFRACT_AVX512_BEGIN
__attribute__((target("avx512f"))) void normalize_avx512f(LaneVec3& v, std::uint32_t mask) {
    REFRACT_NORMALIZE(__m512d, _mm512_sqrt_pd)
}
REFRACT_AVX512_END
#else
void normalize_baseline(LaneVec3& v, std::uint32_t mask) { REFRACT_NORMALIZE(double, std::sqrt) }
#endif
#undef REFRACT_NORMALIZE

#if defined(__x86_64__)
NormalizeFn normalize_function(SlabIsa isa) {
    return simd::variant<NormalizeFn>(isa, normalize_baseline, normalize_avx2, normalize_avx512f);
}
#else
NormalizeFn normalize_function(SlabIsa) { return normalize_baseline; }
#endif

std::atomic<NormalizeFn> in_use{nullptr};

}  // namespace

void use_wide_isa(SlabIsa isa) { in_use.store(normalize_function(isa), std::memory_order_relaxed); }

void normalize_lanes(LaneVec3& v, const LaneMask& m) {
    NormalizeFn f = in_use.load(std::memory_order_relaxed);
    if (!f) in_use.store(f = normalize_function(slab_isa()), std::memory_order_relaxed);
    f(v, m.bits);
}

}  // namespace refract
