// The slab pass over a convex plane set (see plane_set.h): the choice of its variant. The
// kernel, and why its result is the scalar loop's bit for bit, is in
// geometry/simd/plane_set.cpp.
#include <refract/geometry/plane_set.h>

#include <refract/geometry/simd.h>

namespace refract {

static_assert(sizeof(Plane) == 4 * sizeof(double), "the slab kernel reads a Plane as {n_x, n_y, n_z, offset}");

namespace {

using SlabFn = SlabSpan (*)(const double*, std::size_t, const double*, const double*);

SlabFn slab_function(SlabIsa isa) {
    return simd::variant<SlabFn>(isa, simd::slab_kernel<simd::Sse2>, simd::slab_kernel<simd::Avx2>,
                                 simd::slab_kernel<simd::Avx512f>);
}

SlabSpan run(SlabFn fn, const Plane* planes, std::size_t n, const Ray& r) {
    const double o[3] = {r.origin.x(), r.origin.y(), r.origin.z()};
    const double v[3] = {r.dir.x(), r.dir.y(), r.dir.z()};
    return fn(reinterpret_cast<const double*>(planes), n, o, v);
}

}  // namespace

const char* slab_isa_name(SlabIsa isa) {
    switch (isa) {
        case SlabIsa::avx512f: return "AVX-512F";
        case SlabIsa::avx2: return "AVX2";
        case SlabIsa::baseline: break;
    }
#if defined(__x86_64__)
    return "baseline (SSE2)";
#else
    return "baseline";
#endif
}

bool slab_isa_supported(SlabIsa isa) {
    if (isa == SlabIsa::baseline) return true;
#if defined(__x86_64__)
    __builtin_cpu_init();  // harmless when already done; needed if called before main
    // libgcc's and compiler-rt's checks include the OS's support for the register state.
    if (isa == SlabIsa::avx2) return __builtin_cpu_supports("avx2");
    // The AVX-512F variant is compiled with -mfma too (geometry/CMakeLists.txt).
    if (isa == SlabIsa::avx512f) return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma");
#endif
    return false;
}

SlabIsa slab_isa() {
    static const SlabIsa best = slab_isa_supported(SlabIsa::avx512f) ? SlabIsa::avx512f
                                : slab_isa_supported(SlabIsa::avx2)  ? SlabIsa::avx2
                                                                     : SlabIsa::baseline;
    return best;
}

SlabSpan slab_span(const Plane* planes, std::size_t n, const Ray& r) {
    static const SlabFn fn = slab_function(slab_isa());
    return run(fn, planes, n, r);
}

SlabSpan slab_span(SlabIsa isa, const Plane* planes, std::size_t n, const Ray& r) {
    return run(slab_function(isa), planes, n, r);
}

}  // namespace refract
