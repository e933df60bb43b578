// Whole-packet operations (see geometry/lanes_wide.h): written once over xsimd's batch of W
// doubles (geometry/simd/batch.h), compiled once per instruction set (geometry/simd.h). The
// arithmetic is LaneVec3's: the squared norm added x, y, z left to right, the correctly
// rounded square root, three divisions; compiled without contraction into FMA.
#include <refract/geometry/lanes.h>
#include <refract/geometry/simd.h>
#include <refract/geometry/simd/batch.h>

namespace refract::simd {

template <class A>
void normalize_lanes(double* x, double* y, double* z, std::uint32_t mask) {
    using B = Batch<A>;
    constexpr std::size_t W = B::size;
    static_assert(kLanes % W == 0, "whole batches of lanes");
    for (std::size_t l = 0; l < kLanes; l += W) {
        Mask<A> on = mask_of<A>(mask >> l);
        if (!xsimd::any(on)) continue;
        const Vec3Batch<A> v{B::load_unaligned(x + l), B::load_unaligned(y + l), B::load_unaligned(z + l)};
        const B n2 = v.squaredNorm();
        const B len = xsimd::sqrt(n2);
        on = on & (n2 > B(0.0));
        xsimd::select(on, v.x / len, v.x).store_unaligned(x + l);
        xsimd::select(on, v.y / len, v.y).store_unaligned(y + l);
        xsimd::select(on, v.z / len, v.z).store_unaligned(z + l);
    }
}

template void normalize_lanes<REFRACT_SIMD_ARCH>(double*, double*, double*, std::uint32_t);

}  // namespace refract::simd
