#pragma once
// What the vectorised kernels of geometry/simd/ share: xsimd's batch of doubles for the
// instruction set A a kernel file is compiled for, and the few operations every kernel needs
// that xsimd 8.1 (Debian 12) lacks or gives differently from one instruction set to another,
// written once with its API.
//
// The rules of bit identity with the scalar code, for every A:
// - + − × ÷ and sqrt are the IEEE operations lane by lane; the files are compiled with
//   -ffp-contract=off (geometry/CMakeLists.txt) and call no fma, so nothing is fused.
// - Negation is neg() below, never the unary minus: xsimd 8.1 computes −x on AVX-512 as
//   0 − x, which gives +0 for +0 where the scalar −x gives −0.
// - Comparisons are <, >, <=, >= and == only (ordered: false where a lane is NaN, as the
//   scalar operators). xsimd 8.1's != is unordered on SSE2 and ordered on AVX, so it is not
//   used; nor are xsimd::max/min (their NaN and ±0 results are the instruction's), nor
//   bitwise_andnot (its operand order differs between SSE2/AVX and AVX-512), nor zip_lo /
//   zip_hi across 128-bit blocks (AVX and AVX-512 interleave within each block, SSE2 has one).
// - Choices are xsimd::select (a blend: the chosen lane's bits).
#include <cstddef>
#include <cstdint>

#include <xsimd/xsimd.hpp>

namespace refract::simd {

template <class A>
using Batch = xsimd::batch<double, A>;
template <class A>
using Mask = xsimd::batch_bool<double, A>;

// −x in every lane: the sign bit flipped, as the scalar operator (−0 for +0, NaN stays NaN).
template <class A>
[[gnu::always_inline]] inline Batch<A> neg(const Batch<A>& x) {
    return xsimd::bitwise_xor(x, Batch<A>(-0.0));
}

// A 3-vector of batches, for the templates written over a vector type (sphere_quadratic in
// geometry/shapes.h): dot and squared norm add x, y and z left to right, as Eigen's Vec3 and
// LaneVec3 do.
template <class A>
struct Vec3Batch {
    using Scalar = Batch<A>;
    Scalar x, y, z;
    [[gnu::always_inline]] Scalar dot(const Vec3Batch& o) const { return x * o.x + y * o.y + z * o.z; }
    [[gnu::always_inline]] Scalar squaredNorm() const { return x * x + y * y + z * z; }
    [[gnu::always_inline]] friend Vec3Batch operator-(const Vec3Batch& a, const Vec3Batch& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
};

namespace detail {
// Generators of compile-time batches (xsimd::make_batch_constant).
template <std::size_t K>
struct LaneXor {  // lane i takes lane i ^ K
    static constexpr std::uint64_t get(std::size_t i, std::size_t) { return i ^ K; }
};
struct OddBlock {  // the lanes of the odd 128-bit blocks (two doubles each)
    static constexpr bool get(std::size_t i, std::size_t) { return (i & 2) != 0; }
};
struct LaneBit {  // lane i: 2^i
    static constexpr std::int64_t get(std::size_t i, std::size_t) { return std::int64_t{1} << i; }
};
}  // namespace detail

// Lane i of the result is lane i ^ K of v (K < the batch size; a compile-time permutation).
template <std::size_t K, class A>
[[gnu::always_inline]] inline Batch<A> swap_lanes(const Batch<A>& v) {
    return xsimd::swizzle(v, xsimd::make_batch_constant<xsimd::batch<std::uint64_t, A>, detail::LaneXor<K>>());
}

// The lane bits (lane i: bit i) of a mask: lane i weighted 2^i where set, summed.
template <class A>
[[gnu::always_inline]] inline std::uint32_t bits_of(const Mask<A>& m) {
    using Ints = xsimd::batch<std::int64_t, A>;
    const Ints weights = xsimd::make_batch_constant<Ints, detail::LaneBit>();
    return static_cast<std::uint32_t>(xsimd::hadd(xsimd::select(xsimd::bool_cast(m), weights, Ints(0))));
}

// The mask of lane bits (lane i: bit i; higher bits ignored).
template <class A>
[[gnu::always_inline]] inline Mask<A> mask_of(std::uint32_t bits) {
    using Ints = xsimd::batch<std::int64_t, A>;
    const Ints weights = xsimd::make_batch_constant<Ints, detail::LaneBit>();
    return xsimd::bool_cast((Ints(static_cast<std::int64_t>(bits)) & weights) == weights);
}

// Every lane of (v, key) set to the lane pair (v[j], key[j]) that `better` prefers to all
// others (better(v, key, other_v, other_key): a mask of the lanes where the other pair is
// strictly better): a butterfly of log2(N) steps, each lane comparing with its partner
// i ^ K. The preference must single out one value's bits (a unique key among equal values:
// +0 and −0 are equal but different bits).
template <class A, class Better, std::size_t K = Batch<A>::size / 2>
[[gnu::always_inline]] inline void best_of_lanes(Batch<A>& v, Batch<A>& key, Better better) {
    if constexpr (K >= 1) {
        const Batch<A> ov = swap_lanes<K, A>(v), okey = swap_lanes<K, A>(key);
        const Mask<A> take = better(v, key, ov, okey);
        v = xsimd::select(take, ov, v);
        key = xsimd::select(take, okey, key);
        best_of_lanes<A, Better, K / 2>(v, key, better);
    }
}

// N planes {n_x, n_y, n_z, d} lying one after another from q (4 N doubles), as four batches
// of N lanes: lane i of each holds plane kPlaneOrder<N>.plane[i]. The doubles from q are a
// stream of pairs, (x, y) and (z, d) of each plane in turn; a batch loaded from q + 2s holds
// in its 128-bit block j the pair s + j. Loads at even and odd s, blended block by block,
// give u and v with an (x, y) pair in every block, g and h with a (z, d) pair, of the same
// planes; the interleave within each block (zip_lo / zip_hi, which act within blocks on
// every instruction set) then makes the coordinates.
template <class A>
[[gnu::always_inline]] inline void load_planes(const double* q, Batch<A>& nx, Batch<A>& ny, Batch<A>& nz,
                                               Batch<A>& d) {
    using B = Batch<A>;
    constexpr std::size_t N = B::size;
    // Even blocks: planes 0 .. N/4 − 1 (u, g) and N/2 .. 3N/4 − 1 (v, h).
    B u = B::load_unaligned(q), g = B::load_unaligned(q + 2);
    B v = B::load_unaligned(q + 2 * N), h = B::load_unaligned(q + 2 * N + 2);
    if constexpr (N > 2) {
        // Odd blocks: planes N/4 .. N/2 − 1 and 3N/4 .. N − 1.
        const auto odd = xsimd::make_batch_bool_constant<B, detail::OddBlock>();
        u = xsimd::select(odd, B::load_unaligned(q + N - 2), u);
        g = xsimd::select(odd, B::load_unaligned(q + N), g);
        v = xsimd::select(odd, B::load_unaligned(q + 3 * N - 2), v);
        h = xsimd::select(odd, B::load_unaligned(q + 3 * N), h);
    }
    nx = xsimd::zip_lo(u, v);
    ny = xsimd::zip_hi(u, v);
    nz = xsimd::zip_lo(g, h);
    d = xsimd::zip_hi(g, h);
}

// The plane each lane of load_planes holds: lane i, plane i with its log2(N) bits reversed
// (N = 4: 0 2 1 3; N = 8: 0 4 2 6 1 5 3 7). The interleave pairs the planes of u and v (g
// and h), N / 2 apart: the lowest bit of a lane number picks the highest bit of its plane's;
// the blocks, even from one load and odd from the other, take the next ones.
template <std::size_t N>
struct PlaneOrder {
    double plane[N];
    constexpr PlaneOrder() : plane() {
        for (std::size_t i = 0; i < N; ++i) {
            std::size_t r = 0;
            for (std::size_t bit = 1, top = N / 2; bit < N; bit <<= 1, top >>= 1)
                if (i & bit) r |= top;
            plane[i] = static_cast<double>(r);
        }
    }
};
template <std::size_t N>
alignas(64) inline constexpr PlaneOrder<N> kPlaneOrder{};

}  // namespace refract::simd
