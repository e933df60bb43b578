#pragma once
// Lanes: the rays of a packet side by side (the wavelengths of one photon), kLanes doubles
// per quantity. Each operation is the double operation applied to every lane, so that the
// laws written over a scalar type (core/optics.h, namespace generic) and the sphere test
// (geometry/shapes.h) run on kLanes rays at once with every lane's result bit for bit the
// scalar code's: the same IEEE operations in the same order (LaneVec3's dot and squared norm
// add x, y and z left to right, as Eigen's 3-vectors do). Lanes that are not in use carry
// whatever their arithmetic gives (NaN included) and are masked by the caller. The loops
// over lanes are plain, for the compiler to vectorise; every operation is forced inline.
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "geometry/ray.h"

#define REFRACT_LANE_OP inline __attribute__((always_inline))

namespace refract {

constexpr int kLanes = 8;

template <int W>
struct LaneMaskT {
    static constexpr int kLanes = W;
    bool m[W];

    static REFRACT_LANE_OP LaneMaskT Constant(bool b) {
        LaneMaskT r;
        for (int i = 0; i < kLanes; ++i) r.m[i] = b;
        return r;
    }
    REFRACT_LANE_OP bool operator[](int i) const { return m[i]; }
    REFRACT_LANE_OP bool& operator[](int i) { return m[i]; }
    REFRACT_LANE_OP bool any() const {
        bool a = false;
        for (int i = 0; i < kLanes; ++i) a = a || m[i];
        return a;
    }
    REFRACT_LANE_OP int count() const {
        int n = 0;
        for (int i = 0; i < kLanes; ++i) n += m[i] ? 1 : 0;
        return n;
    }
    friend REFRACT_LANE_OP LaneMaskT operator&&(const LaneMaskT& a, const LaneMaskT& b) {
        LaneMaskT r;
        for (int i = 0; i < kLanes; ++i) r.m[i] = a.m[i] && b.m[i];
        return r;
    }
    friend REFRACT_LANE_OP LaneMaskT operator||(const LaneMaskT& a, const LaneMaskT& b) {
        LaneMaskT r;
        for (int i = 0; i < kLanes; ++i) r.m[i] = a.m[i] || b.m[i];
        return r;
    }
    friend REFRACT_LANE_OP LaneMaskT operator!(const LaneMaskT& a) {
        LaneMaskT r;
        for (int i = 0; i < kLanes; ++i) r.m[i] = !a.m[i];
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
#define REFRACT_LANE_COMPARE(op)                                                        \
    friend REFRACT_LANE_OP LaneMaskT<W> operator op(const LanesT& a, const LanesT& b) { \
        LaneMaskT<W> r;                                                                    \
        for (int i = 0; i < kLanes; ++i) r.m[i] = a.v[i] op b.v[i];                     \
        return r;                                                                       \
    }
    REFRACT_LANE_COMPARE(<)
    REFRACT_LANE_COMPARE(>)
    REFRACT_LANE_COMPARE(>=)
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
        for (int i = 0; i < kLanes; i += 2) _mm_store_pd(r.v + i, _mm_sqrt_pd(_mm_load_pd(a.v + i)));
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

template <int W>
REFRACT_LANE_OP LanesT<W> select(const LaneMaskT<W>& m, const LanesT<W>& a, const LanesT<W>& b) {
    LanesT<W> r;
    for (int i = 0; i < kLanes; ++i) r.v[i] = m.m[i] ? a.v[i] : b.v[i];
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
