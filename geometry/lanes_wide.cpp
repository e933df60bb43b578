// Whole-packet operations on the widest vector instructions (see lanes_wide.h): the choice
// of the variant. The kernel is in geometry/simd/lanes_wide.cpp.
#include <refract/geometry/lanes_wide.h>

#include <atomic>

#include <refract/geometry/plane_set.h>
#include <refract/geometry/simd.h>

namespace refract {

namespace {

using NormalizeFn = decltype(&simd::normalize_lanes<simd::Sse2>);

NormalizeFn normalize_function(SlabIsa isa) {
    return simd::variant<NormalizeFn>(isa, simd::normalize_lanes<simd::Sse2>, simd::normalize_lanes<simd::Avx2>,
                                      simd::normalize_lanes<simd::Avx512f>);
}

std::atomic<NormalizeFn> in_use{nullptr};

}  // namespace

void use_wide_isa(SlabIsa isa) { in_use.store(normalize_function(isa), std::memory_order_relaxed); }

void normalize_lanes(LaneVec3& v, const LaneMask& m) {
    NormalizeFn f = in_use.load(std::memory_order_relaxed);
    if (!f) in_use.store(f = normalize_function(slab_isa()), std::memory_order_relaxed);
    f(v.x.v, v.y.v, v.z.v, m.bits);
}

}  // namespace refract
