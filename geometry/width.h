#pragma once
// The width of a walk: code written once over the scalar type S runs on one ray (S =
// double) and on a packet of kLanes rays (S = Lanes, geometry/lanes.h) alike. Per S: its
// mask type (bool, LaneMask), its 3-vector (Vec3, LaneVec3), lane access, and the
// operations a generic step needs beyond arithmetic (any, for_each_lane, select,
// max_coeff, mean). Where a lane of a packet and the one ray differ in what they compute,
// the lane code does the same IEEE operations in the same order, so that every lane's
// result is the one-ray result to the last bit.
#include <array>
#include <cstdint>
#include <type_traits>

#include <refract/geometry/lanes.h>
#include <refract/geometry/ray.h>

namespace refract {

template <class S>
struct Width;
template <>
struct Width<double> {
    static constexpr int kLanes = 1;
    static constexpr bool kPacket = false;
    using Mask = bool;
    using Vec = Vec3;
    template <class T>
    using Each = T;  // one value per lane
};
template <int W>
struct Width<LanesT<W>> {
    static constexpr int kLanes = W;
    static constexpr bool kPacket = true;
    using Mask = LaneMaskT<W>;
    using Vec = LaneVec3T<W>;
    template <class T>
    using Each = std::array<T, static_cast<std::size_t>(W)>;
};
template <class S>
using MaskOf = typename Width<S>::Mask;
template <class S>
using VecOf = typename Width<S>::Vec;
template <class S, class T>
using EachOf = typename Width<S>::template Each<T>;
template <class S>
inline constexpr bool kPacketOf = Width<S>::kPacket;

// A ray of each width: origin and direction.
template <class S>
struct RayOfT {
    VecOf<S> origin, dir;
};
template <class S>
using RayOf = std::conditional_t<kPacketOf<S>, RayOfT<S>, Ray>;

// Lane l of a value: the value itself for one ray.
inline bool lane_of(bool m, int) { return m; }
inline double lane_of(double x, int) { return x; }
inline const Vec3& lane_of(const Vec3& v, int) { return v; }
template <class T>
const T& lane_of(const T& x, int) {
    return x;
}
template <class T, std::size_t N>
const T& lane_of(const std::array<T, N>& a, int l) {
    return a[static_cast<std::size_t>(l)];
}
template <int W>
bool lane_of(const LaneMaskT<W>& m, int l) {
    return m[l];
}
template <int W>
double lane_of(const LanesT<W>& x, int l) {
    return x[l];
}
template <int W>
Vec3 lane_of(const LaneVec3T<W>& v, int l) {
    return v.lane(l);
}
// Lane l of a value set to v.
inline void set_lane(double& x, int, double v) { x = v; }
inline void set_lane(Vec3& x, int, const Vec3& v) { x = v; }
template <class T>
void set_lane(T& x, int, const T& v) {
    x = v;
}
template <class T, std::size_t N>
void set_lane(std::array<T, N>& a, int l, const T& v) {
    a[static_cast<std::size_t>(l)] = v;
}
template <int W>
void set_lane(LanesT<W>& x, int l, double v) {
    x[l] = v;
}
template <int W>
void set_lane(LaneVec3T<W>& x, int l, const Vec3& v) {
    x.set(l, v);
}

inline bool any(bool m) { return m; }
template <int W>
bool any(const LaneMaskT<W>& m) {
    return m.any();
}
inline int count(bool m) { return m ? 1 : 0; }
template <int W>
int count(const LaneMaskT<W>& m) {
    return m.count();
}
// f(l) for every lane l set in m, in increasing order.
template <class F>
void for_each_lane(bool m, F&& f) {
    if (m) f(0);
}
template <int W, class F>
void for_each_lane(const LaneMaskT<W>& m, F&& f) {
    for (std::uint32_t b = m.bits; b != 0; b &= b - 1) f(__builtin_ctz(b));
}
// The mask with every lane of the width set, or none.
template <class S>
MaskOf<S> all_lanes(bool on) {
    if constexpr (kPacketOf<S>) {
        return MaskOf<S>::Constant(on);
    } else {
        return on;
    }
}

// m ? a : b for one ray (the packet types have their own, lane by lane).
inline double select(bool m, double a, double b) { return m ? a : b; }
inline Vec3 select(bool m, const Vec3& a, const Vec3& b) { return m ? a : b; }

// The largest component (Eigen's maxCoeff, max(max(x, y), z)) and the mean ((x + y + z) / 3).
inline double max_coeff(const Vec3& v) { return v.maxCoeff(); }
template <int W>
LanesT<W> max_coeff(const LaneVec3T<W>& v) {
    return max_of(max_of(v.x, v.y), v.z);
}
inline double mean_of(const Vec3& v) { return v.mean(); }
template <int W>
LanesT<W> mean_of(const LaneVec3T<W>& v) {
    return (v.x + v.y + v.z) / LanesT<W>(3.0);
}
// Component by component products (a colour weight times a factor).
inline Vec3 cwise(const Vec3& a, const Vec3& b) { return a.cwiseProduct(b); }
template <int W>
LaneVec3T<W> cwise(const LaneVec3T<W>& a, const LaneVec3T<W>& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <int W>
LaneVec3T<W> cwise(const LaneVec3T<W>& a, const Vec3& b) {
    return {a.x * LanesT<W>(b.x()), a.y * LanesT<W>(b.y()), a.z * LanesT<W>(b.z())};
}
// The same constant in every component.
template <class S>
VecOf<S> splat(const S& s) {
    if constexpr (kPacketOf<S>) {
        return {s, s, s};
    } else {
        return Vec3::Constant(s);
    }
}
// v in every lane.
template <class S>
VecOf<S> broadcast(const Vec3& v) {
    if constexpr (kPacketOf<S>) {
        return VecOf<S>::broadcast(v);
    } else {
        return v;
    }
}

}  // namespace refract
