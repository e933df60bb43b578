// Vectorised slab pass over a convex plane set (see plane_set.h).
//
// Why the result is the scalar loop's, bit for bit:
// - Per plane, the same operations in the same order: denom = (n_x v_x + n_y v_y) + n_z v_z
//   (Eigen's Vector3d dot), dist = d - ((n_x o_x + n_y o_y) + n_z o_z), t = dist / denom,
//   IEEE double in every lane. This file is compiled with -ffp-contract=off (see
//   geometry/CMakeLists.txt), so the AVX2/AVX-512 variants cannot fuse a*b+c.
// - Selection: each lane keeps, over its own planes in increasing order, the largest entering
//   t with strict > (so the first plane attaining it) and its plane index; likewise the
//   smallest leaving t with strict <. The reduction takes the largest t over the lanes, then
//   the smallest index among the lanes holding it, then that lane's own t (+0 and -0 compare
//   equal but are different bits). That is the scalar loop's "first plane attaining the
//   maximum", whatever the lane count. A NaN t never wins (every comparison with it is false).
// - The scalar early exit (t_enter > t_exit) is dropped: t_enter only grows and t_exit only
//   shrinks, so testing once at the end gives the same answer.
// - Planes parallel to the ray (denom = +0 or -0) need no test of their own. Entering means
//   "denom has its sign bit set" (AVX-512) or "denom + 0 < 0" (the others: +0 turns -0 into
//   +0 and changes nothing else). A parallel plane with the origin outside (dist < 0) then
//   gives t_enter = +inf (dist / -0) or t_exit = -inf (dist / +0): either t_enter > t_exit
//   or the caller's strict window (t_min < t < t_max) rejects both ends, so no hit, as the
//   scalar loop's immediate miss. With the origin inside (dist >= 0, or NaN) it gives -inf
//   as an entering t, +inf as a leaving t or NaN: it never wins, as the scalar loop skips it.
//   Non-parallel planes are classified as in the scalar loop (denom < 0 entering, otherwise
//   leaving; a NaN denom gives a NaN t either way).
// - Blocks of W planes are 0, W, 2W, ..., then, when W does not divide n, the last W planes,
//   overlapping ones already seen: a plane seen twice (same t, same index) changes nothing.
//   Fewer than W planes: one block padded with neutral planes (normal 0, offset 1: denom is
//   +0, -0 or NaN, dist is 1 or NaN, so t is -inf entering, +inf leaving or NaN: never chosen).
// The planes are read as they lie in memory, Plane = {normal x, y, z, offset}, and
// transposed in registers; nothing is cached, so nothing can go stale.
#include "geometry/plane_set.h"
#include "geometry/simd.h"

#include <cstring>
#include <limits>

#if defined(__x86_64__)
#include <immintrin.h>
#define REFRACT_SLAB_X86 1
#else
#define REFRACT_SLAB_X86 0
#endif

namespace refract {

static_assert(sizeof(Plane) == 4 * sizeof(double), "plane_set.cpp reads a Plane as {n_x, n_y, n_z, offset}");

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The neutral-padded copy of fewer than `w` planes (4 doubles each) into `out`.
void pad_planes(const Plane* planes, std::size_t n, std::size_t w, double* out) {
    if (n > 0) std::memcpy(out, planes, n * sizeof(Plane));
    for (std::size_t j = n; j < w; ++j) {
        out[4 * j] = out[4 * j + 1] = out[4 * j + 2] = 0.0;
        out[4 * j + 3] = 1.0;
    }
}

// The first block of w planes: the planes themselves, or fewer than w padded into `padded`.
const double* first_block(const Plane* planes, std::size_t n, std::size_t w, double* padded) {
    if (n >= w) return reinterpret_cast<const double*>(planes);
    pad_planes(planes, n, w, padded);
    return padded;
}

// ---- Baseline (SSE2, W = 2) and AVX2 (W = 4): GNU vector extensions, written once. -----

using simd::Doubles;

// Inlined into the per-target functions below, so each copy is compiled for its own
// instruction set (no helper functions with vector arguments: clang refuses those across
// target boundaries).
template <int W>
[[gnu::always_inline]] inline SlabSpan slab_generic(const Plane* planes, std::size_t n, const Ray& r) {
    using vd = typename Doubles<W>::type;
    // x - (+0) is exactly x for every x, -0 and NaN included (0 + x would turn -0 into +0).
    const vd dx = r.dir.x() - vd{}, dy = r.dir.y() - vd{}, dz = r.dir.z() - vd{};
    const vd ox = r.origin.x() - vd{}, oy = r.origin.y() - vd{}, oz = r.origin.z() - vd{};
    const vd zero = vd{}, neg_inf = -kInf - vd{}, pos_inf = kInf - vd{};
    vd lane;
    for (int j = 0; j < W; ++j) lane[j] = j;

    vd t_enter = neg_inf, t_exit = pos_inf;          // per lane: running max / min
    vd f_enter = -1.0 - vd{}, f_exit = -1.0 - vd{};  // their plane indices (exact in double)
    double padded[4 * W];
    const double* all = reinterpret_cast<const double*>(planes);
    const double* q = first_block(planes, n, W, padded);
    vd index = lane;
    for (std::size_t first = 0;;) {
        vd nx, ny, nz, d;  // W planes {x, y, z, d} transposed
        if constexpr (W == 4) {
            typedef double half __attribute__((vector_size(2 * sizeof(double))));
            half p0a, p0b, p1a, p1b, p2a, p2b, p3a, p3b;
            std::memcpy(&p0a, q, sizeof(half));
            std::memcpy(&p0b, q + 2, sizeof(half));
            std::memcpy(&p1a, q + 4, sizeof(half));
            std::memcpy(&p1b, q + 6, sizeof(half));
            std::memcpy(&p2a, q + 8, sizeof(half));
            std::memcpy(&p2b, q + 10, sizeof(half));
            std::memcpy(&p3a, q + 12, sizeof(half));
            std::memcpy(&p3b, q + 14, sizeof(half));
            const vd a = __builtin_shufflevector(p0a, p2a, 0, 1, 2, 3);  // x0 y0 x2 y2
            const vd b = __builtin_shufflevector(p1a, p3a, 0, 1, 2, 3);  // x1 y1 x3 y3
            const vd c = __builtin_shufflevector(p0b, p2b, 0, 1, 2, 3);  // z0 d0 z2 d2
            const vd e = __builtin_shufflevector(p1b, p3b, 0, 1, 2, 3);  // z1 d1 z3 d3
            nx = __builtin_shufflevector(a, b, 0, 4, 2, 6);
            ny = __builtin_shufflevector(a, b, 1, 5, 3, 7);
            nz = __builtin_shufflevector(c, e, 0, 4, 2, 6);
            d = __builtin_shufflevector(c, e, 1, 5, 3, 7);
        } else {
            static_assert(W == 2, "W is 2 or 4");
            vd v0, v1, v2, v3;  // x0 y0, z0 d0, x1 y1, z1 d1
            std::memcpy(&v0, q, sizeof(vd));
            std::memcpy(&v1, q + 2, sizeof(vd));
            std::memcpy(&v2, q + 4, sizeof(vd));
            std::memcpy(&v3, q + 6, sizeof(vd));
            nx = __builtin_shufflevector(v0, v2, 0, 2);
            ny = __builtin_shufflevector(v0, v2, 1, 3);
            nz = __builtin_shufflevector(v1, v3, 0, 2);
            d = __builtin_shufflevector(v1, v3, 1, 3);
        }
        vd denom = nx * dx + ny * dy;
        denom = denom + nz * dz;
        denom = denom + zero;  // -0 -> +0 (parallel planes), nothing else changes
        vd dot_o = nx * ox + ny * oy;
        dot_o = dot_o + nz * oz;
        const vd dist = d - dot_o;
        const vd t = dist / denom;
        const auto entering = denom < zero;
        const vd t_in = entering ? t : neg_inf;
        const vd t_out = entering ? pos_inf : t;
        const auto in_wins = t_in > t_enter;
        t_enter = in_wins ? t_in : t_enter;
        f_enter = in_wins ? index : f_enter;
        const auto out_wins = t_out < t_exit;
        t_exit = out_wins ? t_out : t_exit;
        f_exit = out_wins ? index : f_exit;

        first += W;
        if (first + W <= n) {
            q = all + 4 * first;
            index = index + static_cast<double>(W);
        } else if (first < n) {
            first = n - W;
            q = all + 4 * first;
            index = lane + static_cast<double>(first);
        } else {
            break;
        }
    }

    // Reduction by halves (max / min trees, no ANDed masks): the extreme t, the smallest
    // index among the lanes holding it, that lane's t.
#define REFRACT_TREE(v, op)                                                   \
    do {                                                                      \
        if constexpr (W == 4) {                                               \
            const vd h_ = __builtin_shufflevector(v, v, 2, 3, 0, 1);          \
            v = h_ op v ? h_ : v;                                             \
            const vd s_ = __builtin_shufflevector(v, v, 1, 0, 3, 2);          \
            v = s_ op v ? s_ : v;                                             \
        } else {                                                              \
            const vd s_ = __builtin_shufflevector(v, v, 1, 0);                \
            v = s_ op v ? s_ : v;                                             \
        }                                                                     \
    } while (0)
    vd m_in = t_enter, m_out = t_exit;
    REFRACT_TREE(m_in, >);
    REFRACT_TREE(m_out, <);
    vd i_in = t_enter == m_in ? f_enter : pos_inf, i_out = t_exit == m_out ? f_exit : pos_inf;
    REFRACT_TREE(i_in, <);
    REFRACT_TREE(i_out, <);
    vd v_in = f_enter == i_in ? t_enter : neg_inf, v_out = f_exit == i_out ? t_exit : pos_inf;
    REFRACT_TREE(v_in, >);
    REFRACT_TREE(v_out, <);
#undef REFRACT_TREE
    return SlabSpan{v_in[0], v_out[0], static_cast<int>(i_in[0]), static_cast<int>(i_out[0])};
}

SlabSpan slab_baseline(const Plane* planes, std::size_t n, const Ray& r) { return slab_generic<2>(planes, n, r); }

#if REFRACT_SLAB_X86

__attribute__((target("avx2"))) SlabSpan slab_avx2(const Plane* planes, std::size_t n, const Ray& r) {
    return slab_generic<4>(planes, n, r);
}

// ---- AVX-512F (W = 8): intrinsics, for the k-mask forms (masked max/min and compares). ----
REFRACT_AVX512_BEGIN
__attribute__((target("avx512f"))) SlabSpan slab_avx512f(const Plane* planes, std::size_t n, const Ray& r) {
    constexpr std::size_t W = 8;
    const __m512d dx = _mm512_set1_pd(r.dir.x()), dy = _mm512_set1_pd(r.dir.y()), dz = _mm512_set1_pd(r.dir.z());
    const __m512d ox = _mm512_set1_pd(r.origin.x()), oy = _mm512_set1_pd(r.origin.y()),
                  oz = _mm512_set1_pd(r.origin.z());
    const __m512i sign = _mm512_set1_epi64(static_cast<long long>(0x8000000000000000ULL));
    // Lane j holds plane first + lane[j]: the order the unpack transposition leaves.
    const __m512d lane = _mm512_set_pd(7, 5, 6, 4, 3, 1, 2, 0);
    const __m512d step = _mm512_set1_pd(static_cast<double>(W));

    __m512d t_enter = _mm512_set1_pd(-kInf), t_exit = _mm512_set1_pd(kInf);
    __m512d f_enter = _mm512_set1_pd(-1.0), f_exit = _mm512_set1_pd(-1.0);
    double padded[4 * W];
    const double* all = reinterpret_cast<const double*>(planes);
    const double* q = first_block(planes, n, W, padded);
    __m512d index = lane;
    for (std::size_t first = 0;;) {
        // v0 = planes 0, 1; v1 = 2, 3; v2 = 4, 5; v3 = 6, 7 (x y z d each)
        const __m512d v0 = _mm512_loadu_pd(q), v1 = _mm512_loadu_pd(q + 8), v2 = _mm512_loadu_pd(q + 16),
                      v3 = _mm512_loadu_pd(q + 24);
        const __m512d a = _mm512_unpacklo_pd(v0, v1);  // x0 x2 z0 z2 x1 x3 z1 z3
        const __m512d b = _mm512_unpackhi_pd(v0, v1);  // y0 y2 d0 d2 y1 y3 d1 d3
        const __m512d c = _mm512_unpacklo_pd(v2, v3);  // x4 x6 z4 z6 x5 x7 z5 z7
        const __m512d e = _mm512_unpackhi_pd(v2, v3);  // y4 y6 d4 d6 y5 y7 d5 d7
        const __m512d nx = _mm512_shuffle_f64x2(a, c, 0x88);  // planes 0 2 1 3 4 6 5 7
        const __m512d nz = _mm512_shuffle_f64x2(a, c, 0xdd);
        const __m512d ny = _mm512_shuffle_f64x2(b, e, 0x88);
        const __m512d d = _mm512_shuffle_f64x2(b, e, 0xdd);

        const __m512d denom =
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(nx, dx), _mm512_mul_pd(ny, dy)), _mm512_mul_pd(nz, dz));
        const __m512d dot_o =
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(nx, ox), _mm512_mul_pd(ny, oy)), _mm512_mul_pd(nz, oz));
        const __m512d dist = _mm512_sub_pd(d, dot_o);
        const __m512d t = _mm512_div_pd(dist, denom);
        const __mmask8 entering = _mm512_test_epi64_mask(_mm512_castpd_si512(denom), sign);   // sign bit set
        const __mmask8 leaving = _mm512_testn_epi64_mask(_mm512_castpd_si512(denom), sign);   // sign bit clear
        const __mmask8 in_wins = _mm512_mask_cmp_pd_mask(entering, t, t_enter, _CMP_GT_OQ);
        const __mmask8 out_wins = _mm512_mask_cmp_pd_mask(leaving, t, t_exit, _CMP_LT_OQ);
        t_enter = _mm512_mask_max_pd(t_enter, entering, t, t_enter);  // t > t_enter ? t : t_enter
        t_exit = _mm512_mask_min_pd(t_exit, leaving, t, t_exit);      // t < t_exit ? t : t_exit
        f_enter = _mm512_mask_mov_pd(f_enter, in_wins, index);
        f_exit = _mm512_mask_mov_pd(f_exit, out_wins, index);

        first += W;
        if (first + W <= n) {
            q = all + 4 * first;
            index = _mm512_add_pd(index, step);
        } else if (first < n) {
            first = n - W;
            q = all + 4 * first;
            index = _mm512_add_pd(lane, _mm512_set1_pd(static_cast<double>(first)));
        } else {
            break;
        }
    }

    // The extreme t, the smallest index among the lanes holding it, that lane's t (a plane
    // in two lanes, from the overlapping last block, has the same bits in both).
    const double m_in = _mm512_reduce_max_pd(t_enter);
    const __mmask8 at_in = _mm512_cmp_pd_mask(t_enter, _mm512_set1_pd(m_in), _CMP_EQ_OQ);
    const double i_in = _mm512_mask_reduce_min_pd(at_in, f_enter);
    const __mmask8 lane_in = _mm512_mask_cmp_pd_mask(at_in, f_enter, _mm512_set1_pd(i_in), _CMP_EQ_OQ);
    const double m_out = _mm512_reduce_min_pd(t_exit);
    const __mmask8 at_out = _mm512_cmp_pd_mask(t_exit, _mm512_set1_pd(m_out), _CMP_EQ_OQ);
    const double i_out = _mm512_mask_reduce_min_pd(at_out, f_exit);
    const __mmask8 lane_out = _mm512_mask_cmp_pd_mask(at_out, f_exit, _mm512_set1_pd(i_out), _CMP_EQ_OQ);
    return SlabSpan{_mm512_cvtsd_f64(_mm512_maskz_compress_pd(lane_in, t_enter)),
                    _mm512_cvtsd_f64(_mm512_maskz_compress_pd(lane_out, t_exit)), static_cast<int>(i_in),
                    static_cast<int>(i_out)};
}

REFRACT_AVX512_END

#endif  // REFRACT_SLAB_X86

using SlabFn = SlabSpan (*)(const Plane*, std::size_t, const Ray&);

#if REFRACT_SLAB_X86
SlabFn slab_function(SlabIsa isa) { return simd::variant<SlabFn>(isa, slab_baseline, slab_avx2, slab_avx512f); }
#else
SlabFn slab_function(SlabIsa) { return slab_baseline; }
#endif

}  // namespace

const char* slab_isa_name(SlabIsa isa) {
    switch (isa) {
        case SlabIsa::avx512f: return "AVX-512F";
        case SlabIsa::avx2: return "AVX2";
        case SlabIsa::baseline: break;
    }
    return REFRACT_SLAB_X86 ? "baseline (SSE2)" : "baseline";
}

bool slab_isa_supported(SlabIsa isa) {
    if (isa == SlabIsa::baseline) return true;
#if REFRACT_SLAB_X86
    __builtin_cpu_init();  // harmless when already done; needed if called before main
    // libgcc's and compiler-rt's checks include the OS's support for the register state.
    if (isa == SlabIsa::avx2) return __builtin_cpu_supports("avx2");
    if (isa == SlabIsa::avx512f) return __builtin_cpu_supports("avx512f");
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
    return fn(planes, n, r);
}

SlabSpan slab_span(SlabIsa isa, const Plane* planes, std::size_t n, const Ray& r) {
    return slab_function(isa)(planes, n, r);
}

}  // namespace refract
