#pragma once
// A scalar that counts the arithmetic done with it, and a tiny 3-vector over any scalar.
// Instantiating core/optics.h's generic laws with them counts the multiplications and
// divisions of a branching node exactly as the code writes them (no common
// subexpression is shared unless the code shares it).
#include <cmath>
#include <cstdint>

namespace refract::experiments {

struct OpCounts {
    std::uint64_t add = 0;   // additions and subtractions (and negations)
    std::uint64_t mul = 0;
    std::uint64_t div = 0;
    std::uint64_t sqrt = 0;  // square roots (and other library calls: pow)
    std::uint64_t cmp = 0;
    std::uint64_t muldiv() const { return mul + div; }
    OpCounts operator-(const OpCounts& o) const {
        return {add - o.add, mul - o.mul, div - o.div, sqrt - o.sqrt, cmp - o.cmp};
    }
};

// The counters of the calling thread.
inline OpCounts& op_counts() {
    thread_local OpCounts c;
    return c;
}

struct Counted {
    double v = 0;
    Counted() = default;
    Counted(double x) : v(x) {}  // implicit: literals mix freely with counted values

    friend Counted operator+(Counted a, Counted b) { ++op_counts().add; return a.v + b.v; }
    friend Counted operator-(Counted a, Counted b) { ++op_counts().add; return a.v - b.v; }
    friend Counted operator*(Counted a, Counted b) { ++op_counts().mul; return a.v * b.v; }
    friend Counted operator/(Counted a, Counted b) { ++op_counts().div; return a.v / b.v; }
    Counted operator-() const { ++op_counts().add; return -v; }
    Counted& operator+=(Counted b) { return *this = *this + b; }
    Counted& operator-=(Counted b) { return *this = *this - b; }
    Counted& operator*=(Counted b) { return *this = *this * b; }
    Counted& operator/=(Counted b) { return *this = *this / b; }
    friend bool operator<(Counted a, Counted b) { ++op_counts().cmp; return a.v < b.v; }
    friend bool operator>(Counted a, Counted b) { ++op_counts().cmp; return a.v > b.v; }
    friend bool operator<=(Counted a, Counted b) { ++op_counts().cmp; return a.v <= b.v; }
    friend bool operator>=(Counted a, Counted b) { ++op_counts().cmp; return a.v >= b.v; }
    friend bool operator==(Counted a, Counted b) { ++op_counts().cmp; return a.v == b.v; }
    friend bool operator!=(Counted a, Counted b) { ++op_counts().cmp; return a.v != b.v; }

    // Found by argument-dependent lookup from the generic laws (`using std::sqrt; sqrt(x)`).
    friend Counted sqrt(Counted a) { ++op_counts().sqrt; return std::sqrt(a.v); }
    friend Counted abs(Counted a) { return std::abs(a.v); }  // a sign flip: not counted
    friend Counted fmin(Counted a, Counted b) { ++op_counts().cmp; return std::fmin(a.v, b.v); }
    friend Counted pow(Counted a, int e) { ++op_counts().sqrt; return std::pow(a.v, e); }
};

// Just what the generic laws and refract's dielectric node use: Scalar, +, −, scalar·v,
// v/scalar, dot, squaredNorm, normalized, cwiseProduct, maxCoeff.
template <class S>
struct V3 {
    using Scalar = S;
    S x{}, y{}, z{};
    V3() = default;
    V3(S a, S b, S c) : x(a), y(b), z(c) {}
    friend V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    friend V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    V3 operator-() const { return {-x, -y, -z}; }
    friend V3 operator*(S s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
    friend V3 operator/(const V3& a, S s) { return {a.x / s, a.y / s, a.z / s}; }
    S dot(const V3& b) const { return x * b.x + y * b.y + z * b.z; }
    S squaredNorm() const { return dot(*this); }
    S norm() const {
        using std::sqrt;
        return sqrt(squaredNorm());
    }
    V3 normalized() const { return *this / norm(); }  // as Eigen: one norm, three divisions
    V3 cwiseProduct(const V3& b) const { return {x * b.x, y * b.y, z * b.z}; }
    S maxCoeff() const {  // two comparisons, as Eigen's
        S m = x;
        if (y > m) m = y;
        if (z > m) m = z;
        return m;
    }
};

}  // namespace refract::experiments
