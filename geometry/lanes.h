#pragma once
// Lanes: the rays of a packet side by side (the wavelengths of one photon), kLanes doubles
// per quantity. Each operation is the double operation applied to every lane, so that the
// laws written over a scalar type (core/optics.h, namespace generic) and the sphere test
// (geometry/shapes.h) run on kLanes rays at once with every lane's result bit for bit the
// scalar code's: the same IEEE operations in the same order (LaneVec3's dot and squared norm
// add x, y and z left to right, as Eigen's 3-vectors do). Lanes that are not in use carry
// whatever their arithmetic gives (NaN included) and are masked by the caller. The loops
// over lanes are plain, for the compiler to vectorise; comparisons, blends and square roots
// take two lanes at a time in xsimd's SSE2 batch (the x86-64 baseline, whatever the flags of
// the file including this one; geometry/simd.h says why xsimd); every operation is forced
// inline.
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <xsimd/xsimd.hpp>
#endif

#include <refract/geometry/ray.h>

#define REFRACT_LANE_OP inline __attribute__((always_inline))

namespace refract {

constexpr int kLanes = 8;

#if defined(__SSE2__)
namespace lanes_sse2 {
// Two lanes: lanes i and i + 1 of a packet.
using Pair = xsimd::batch<double, xsimd::sse2>;
using PairMask = xsimd::batch_bool<double, xsimd::sse2>;
using PairInts = xsimd::batch<std::int64_t, xsimd::sse2>;
// The bits of W lanes from the masks of their pairs, cmp(i) for lanes i, i + 1: each pair's
// lanes weighted 2^i and 2^(i+1) where set, summed as integers.
template <int W, class Compare>
REFRACT_LANE_OP std::uint32_t bits(Compare cmp) {
    static_assert(W % 2 == 0 && W <= 32, "lanes in pairs, one bit each");
    const auto weighted = [&](int i) {
        return xsimd::select(xsimd::bool_cast(cmp(i)), PairInts{std::int64_t{1} << i, std::int64_t{2} << i},
                             PairInts(0));
    };
    PairInts sum = weighted(0);
    for (int i = 2; i < W; i += 2) sum = sum + weighted(i);
    return static_cast<std::uint32_t>(xsimd::hadd(sum));
}
// The mask of a pair of lanes from its two bits (an SSE2 mask is all ones in a lane that is
// set, all zeros in one that is not).
alignas(16) inline constexpr std::int64_t kPair[4][2] = {{0, 0}, {-1, 0}, {0, -1}, {-1, -1}};
REFRACT_LANE_OP PairMask pair_mask(std::uint32_t two_bits) {
    return PairMask(Pair::load_aligned(reinterpret_cast<const double*>(kPair[two_bits])));
}
}  // namespace lanes_sse2
#endif

// Which lanes of a packet a statement applies to: one bit per lane (lane i: bit i), so that
// the tests, the combinations and the counts of a packet step are single instructions.
template <int W>
struct LaneMaskT {
    static_assert(W <= 32, "one bit per lane");
    static constexpr int kLanes = W;
    static constexpr std::uint32_t kAll = W == 32 ? ~0u : (1u << W) - 1u;
    std::uint32_t bits = 0;

    // Lane i of a mask, to read or set.
    class Lane {
    public:
        REFRACT_LANE_OP Lane(std::uint32_t& bits, std::uint32_t bit) : bits_(bits), bit_(bit) {}
        REFRACT_LANE_OP operator bool() const { return (bits_ & bit_) != 0; }
        REFRACT_LANE_OP Lane& operator=(bool b) {
            bits_ = b ? (bits_ | bit_) : (bits_ & ~bit_);
            return *this;
        }
        REFRACT_LANE_OP Lane& operator=(const Lane& o) { return *this = static_cast<bool>(o); }

    private:
        std::uint32_t& bits_;
        std::uint32_t bit_;
    };

    static REFRACT_LANE_OP LaneMaskT Constant(bool b) {
        LaneMaskT r;
        r.bits = b ? kAll : 0u;
        return r;
    }
    REFRACT_LANE_OP bool operator[](int i) const { return ((bits >> i) & 1u) != 0; }
    REFRACT_LANE_OP Lane operator[](int i) { return Lane(bits, 1u << i); }
    REFRACT_LANE_OP bool any() const { return bits != 0; }
    REFRACT_LANE_OP int count() const {  // the set bits, summed in place (no library call)
        std::uint32_t x = bits;
        x = x - ((x >> 1) & 0x55555555u);
        x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
        x = (x + (x >> 4)) & 0x0F0F0F0Fu;
        return static_cast<int>((x * 0x01010101u) >> 24);
    }
    // The first lane set (-1: none).
    REFRACT_LANE_OP int first() const { return bits ? __builtin_ctz(bits) : -1; }
    friend REFRACT_LANE_OP LaneMaskT operator&&(const LaneMaskT& a, const LaneMaskT& b) {
        LaneMaskT r;
        r.bits = a.bits & b.bits;
        return r;
    }
    friend REFRACT_LANE_OP LaneMaskT operator||(const LaneMaskT& a, const LaneMaskT& b) {
        LaneMaskT r;
        r.bits = a.bits | b.bits;
        return r;
    }
    friend REFRACT_LANE_OP LaneMaskT operator!(const LaneMaskT& a) {
        LaneMaskT r;
        r.bits = ~a.bits & kAll;
        return r;
    }
};

template <int W>
struct LanesT {
    static constexpr int kLanes = W;
    alignas(16) double v[W];

    LanesT() = default;
    REFRACT_LANE_OP LanesT(double x) {  // NOLINT: a constant in every lane, as S(2.0)
        for (int i = 0; i < kLanes; ++i) v[i] = x;
    }
    REFRACT_LANE_OP double operator[](int i) const { return v[i]; }
    REFRACT_LANE_OP double& operator[](int i) { return v[i]; }

#define REFRACT_LANE_BINARY(op)                                                         \
    friend REFRACT_LANE_OP LanesT operator op(const LanesT& a, const LanesT& b) {       \
        LanesT r;                                                                       \
        for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] op b.v[i];                     \
        return r;                                                                       \
    }
    REFRACT_LANE_BINARY(+)
    REFRACT_LANE_BINARY(-)
    REFRACT_LANE_BINARY(*)
    REFRACT_LANE_BINARY(/)
#undef REFRACT_LANE_BINARY
#if defined(__SSE2__)
    // Two lanes a step: the packed comparison (false where either is NaN, as the scalar
    // operator), its lanes into the mask's bits.
#define REFRACT_LANE_COMPARE(op)                                                    \
    friend REFRACT_LANE_OP LaneMaskT<W> operator op(const LanesT& a, const LanesT& b) {     \
        using lanes_sse2::Pair;                                                              \
        LaneMaskT<W> r;                                                                      \
        r.bits = lanes_sse2::bits<W>(                                                        \
            [&](int i) { return Pair::load_aligned(a.v + i) op Pair::load_aligned(b.v + i); }); \
        return r;                                                                            \
    }
    REFRACT_LANE_COMPARE(<)
    REFRACT_LANE_COMPARE(>)
    REFRACT_LANE_COMPARE(>=)
#else
#define REFRACT_LANE_COMPARE(op)                                                \
    friend REFRACT_LANE_OP LaneMaskT<W> operator op(const LanesT& a, const LanesT& b) { \
        LaneMaskT<W> r;                                                                    \
        for (int i = 0; i < kLanes; ++i) r.bits |= static_cast<std::uint32_t>(a.v[i] op b.v[i]) << i; \
        return r;                                                                       \
    }
    REFRACT_LANE_COMPARE(<)
    REFRACT_LANE_COMPARE(>)
    REFRACT_LANE_COMPARE(>=)
#endif
#undef REFRACT_LANE_COMPARE
    friend REFRACT_LANE_OP LanesT operator-(const LanesT& a) {
        LanesT r;
        for (int i = 0; i < kLanes; ++i) r.v[i] = -a.v[i];
        return r;
    }
    // The correctly rounded square root in every lane (NaN for a negative lane, without
    // touching errno: the instruction, not the library call).
    friend REFRACT_LANE_OP LanesT sqrt(const LanesT& a) {
        LanesT r;
#if defined(__SSE2__)
        static_assert(W % 2 == 0, "lanes in pairs");
        for (int i = 0; i < kLanes; i += 2)
            xsimd::sqrt(lanes_sse2::Pair::load_aligned(a.v + i)).store_aligned(r.v + i);
#else
        for (int i = 0; i < kLanes; ++i) r.v[i] = std::sqrt(a.v[i]);
#endif
        return r;
    }
    // a < b ? b : a in every lane (the scalar laws' max_of, std::max).
    friend REFRACT_LANE_OP LanesT max_of(const LanesT& a, const LanesT& b) {
        LanesT r;
        for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] < b.v[i] ? b.v[i] : a.v[i];
        return r;
    }
    // |a| in every lane (the sign bit cleared, as std::abs).
    friend REFRACT_LANE_OP LanesT abs(const LanesT& a) {
        LanesT r;
        for (int i = 0; i < kLanes; ++i) r.v[i] = std::abs(a.v[i]);
        return r;
    }
    // a < b ? a : b in every lane (the scalar laws' min_of).
    friend REFRACT_LANE_OP LanesT min_of(const LanesT& a, const LanesT& b) {
        LanesT r;
        for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] < b.v[i] ? a.v[i] : b.v[i];
        return r;
    }
};

// m ? a : b in every lane (bit for bit: a blend).
template <int W>
REFRACT_LANE_OP LanesT<W> select(const LaneMaskT<W>& m, const LanesT<W>& a, const LanesT<W>& b) {
    LanesT<W> r;
#if defined(__SSE2__)
    using lanes_sse2::Pair;
    static_assert(W % 2 == 0, "lanes in pairs");
    for (int i = 0; i < W; i += 2)
        xsimd::select(lanes_sse2::pair_mask((m.bits >> i) & 3u), Pair::load_aligned(a.v + i), Pair::load_aligned(b.v + i))
            .store_aligned(r.v + i);
#else
    for (int i = 0; i < W; ++i) r.v[i] = m[i] ? a.v[i] : b.v[i];
#endif
    return r;
}

template <int W>
struct LaneVec3T {
    using Scalar = LanesT<W>;
    using Lanes = LanesT<W>;
    using LaneVec3 = LaneVec3T;
    Lanes x, y, z;

    static REFRACT_LANE_OP LaneVec3 broadcast(const Vec3& v) { return {Lanes(v.x()), Lanes(v.y()), Lanes(v.z())}; }
    Vec3 lane(int i) const { return {x[i], y[i], z[i]}; }
    void set(int i, const Vec3& v) {
        x[i] = v.x();
        y[i] = v.y();
        z[i] = v.z();
    }
    REFRACT_LANE_OP Lanes dot(const LaneVec3& o) const { return x * o.x + y * o.y + z * o.z; }
    REFRACT_LANE_OP Lanes squaredNorm() const { return x * x + y * y + z * z; }
    // v / |v| (Eigen's normalized(), for vectors of non-zero length).
    REFRACT_LANE_OP LaneVec3 normalized() const {
        const Lanes n = sqrt(squaredNorm());
        return {x / n, y / n, z / n};
    }
    friend REFRACT_LANE_OP LaneVec3 operator+(const LaneVec3& a, const LaneVec3& b) {
        return {a.x + b.x, a.y + b.y, a.z + b.z};
    }
    friend REFRACT_LANE_OP LaneVec3 operator-(const LaneVec3& a, const LaneVec3& b) {
        return {a.x - b.x, a.y - b.y, a.z - b.z};
    }
    friend REFRACT_LANE_OP LaneVec3 operator-(const LaneVec3& a) { return {-a.x, -a.y, -a.z}; }
    friend REFRACT_LANE_OP LaneVec3 operator*(const Lanes& s, const LaneVec3& a) { return {s * a.x, s * a.y, s * a.z}; }
    friend REFRACT_LANE_OP LaneVec3 operator/(const LaneVec3& a, const Lanes& s) { return {a.x / s, a.y / s, a.z / s}; }
};

template <int W>
REFRACT_LANE_OP LaneVec3T<W> select(const LaneMaskT<W>& m, const LaneVec3T<W>& a, const LaneVec3T<W>& b) {
    return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

using LaneMask = LaneMaskT<kLanes>;
using Lanes = LanesT<kLanes>;
using LaneVec3 = LaneVec3T<kLanes>;

}  // namespace refract
