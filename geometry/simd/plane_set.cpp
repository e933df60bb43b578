// Vectorised slab pass over a convex plane set (see geometry/plane_set.h): written once over
// xsimd's batch of W doubles (geometry/simd/batch.h), compiled once per instruction set
// (geometry/simd.h; W = 2 for SSE2, 4 for AVX2, 8 for AVX-512F).
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
//   "denom + 0 < 0" (+0 turns -0 into +0 and changes nothing else), so a parallel plane is a
//   leaving one with denom = +0. With the origin outside (dist < 0) it gives t_exit = -inf
//   (dist / +0): either t_enter > t_exit or the caller's strict window (t_min < t < t_max)
//   rejects both ends, so no hit, as the scalar loop's immediate miss. With the origin inside
//   (dist >= 0, or NaN) it gives +inf as a leaving t or NaN: it never wins, as the scalar loop
//   skips it. Non-parallel planes are classified as in the scalar loop (denom < 0 entering,
//   otherwise leaving; a NaN denom gives a NaN t either way).
// - Blocks of W planes are 0, W, 2W, ..., then, when W does not divide n, the last W planes,
//   overlapping ones already seen: a plane seen twice (same t, same index) changes nothing.
//   Fewer than W planes: one block padded with neutral planes (normal 0, offset 1: denom + 0
//   is +0 or NaN, dist is 1 or NaN, so t is +inf leaving or NaN: never chosen).
// The planes are read as they lie in memory, Plane = {normal x, y, z, offset}, and
// transposed in registers (load_planes); nothing is cached, so nothing can go stale.
#include <cstring>
#include <limits>

#include <refract/geometry/simd.h>
#include <refract/geometry/simd/batch.h>

namespace refract::simd {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The first block of w planes (4 doubles each): the planes themselves, or fewer than w
// padded with neutral planes into `padded`.
const double* first_block(const double* planes, std::size_t n, std::size_t w, double* padded) {
    if (n >= w) return planes;
    if (n > 0) std::memcpy(padded, planes, 4 * n * sizeof(double));
    for (std::size_t j = n; j < w; ++j) {
        padded[4 * j] = padded[4 * j + 1] = padded[4 * j + 2] = 0.0;
        padded[4 * j + 3] = 1.0;
    }
    return padded;
}

}  // namespace

template <class A>
SlabSpan slab_kernel(const double* planes, std::size_t n, const double* o, const double* v) {
    using B = Batch<A>;
    constexpr std::size_t W = B::size;
    const B dx(v[0]), dy(v[1]), dz(v[2]), ox(o[0]), oy(o[1]), oz(o[2]);
    const B zero(0.0), neg_inf(-kInf), pos_inf(kInf);
    const B lane = B::load_aligned(kPlaneOrder<W>.plane);  // the plane of each lane in a block

    B t_enter = neg_inf, t_exit = pos_inf;  // per lane: running max / min
    B f_enter(-1.0), f_exit(-1.0);          // their plane indices (exact in double)
    alignas(64) double padded[4 * W];
    const double* q = first_block(planes, n, W, padded);
    B index = lane;
    for (std::size_t first = 0;;) {
        B nx, ny, nz, d;  // W planes {x, y, z, d} transposed
        load_planes<A>(q, nx, ny, nz, d);
        B denom = nx * dx + ny * dy;
        denom = denom + nz * dz;
        denom = denom + zero;  // -0 -> +0 (parallel planes), nothing else changes
        B dot_o = nx * ox + ny * oy;
        dot_o = dot_o + nz * oz;
        const B dist = d - dot_o;
        const B t = dist / denom;
        // Entering: denom < 0; leaving: the others (denom >= 0 leaves out a NaN denom, whose
        // NaN t would not win anyway).
        const auto in_wins = (denom < zero) & (t > t_enter);
        const auto out_wins = (denom >= zero) & (t < t_exit);
        t_enter = xsimd::select(in_wins, t, t_enter);
        f_enter = xsimd::select(in_wins, index, f_enter);
        t_exit = xsimd::select(out_wins, t, t_exit);
        f_exit = xsimd::select(out_wins, index, f_exit);

        first += W;
        if (first + W <= n) {
            q = planes + 4 * first;
            index = index + B(static_cast<double>(W));
        } else if (first < n) {
            first = n - W;
            q = planes + 4 * first;
            index = lane + B(static_cast<double>(first));
        } else {
            break;
        }
    }

    // The extreme t, the smallest index among the lanes holding it, that lane's t (a plane in
    // two lanes, from the overlapping last block, has the same bits in both): every lane
    // compares its (t, index) with another's, log2(W) times, and takes the other's where that
    // is better: a larger (smaller) t, or an equal t with a smaller index.
    const auto enter_first = [](const B& t, const B& f, const B& ot, const B& of) {
        return (ot > t) | ((ot == t) & (of < f));
    };
    const auto exit_first = [](const B& t, const B& f, const B& ot, const B& of) {
        return (ot < t) | ((ot == t) & (of < f));
    };
    best_of_lanes<A>(t_enter, f_enter, enter_first);
    best_of_lanes<A>(t_exit, f_exit, exit_first);
    return SlabSpan{t_enter.get(0), t_exit.get(0), static_cast<int>(f_enter.get(0)), static_cast<int>(f_exit.get(0))};
}

template SlabSpan slab_kernel<REFRACT_SIMD_ARCH>(const double*, std::size_t, const double*, const double*);

}  // namespace refract::simd
