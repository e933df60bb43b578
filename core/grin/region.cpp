// Regions as signed distances (core/grin/region.h).
#include <refract/core/grin/region.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <refract/core/grin/check.h>

namespace refract::grin {

using detail::finite;
using detail::finite_vec;
using detail::unit_in_place;

namespace {
constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// Parallel (+1), antiparallel (−1) or neither (0), to rounding.
int parallel(const Vec3& a, const Vec3& b) {
    const double c = a.dot(b);
    if (c >= 1.0 - 1e-12) return 1;
    if (c <= -1.0 + 1e-12) return -1;
    return 0;
}
}  // namespace

double signed_distance(const Sphere& s, const Vec3& x) { return (x - s.centre).norm() - s.radius; }
double signed_distance(const Box& b, const Vec3& x) {
    const Vec3 c = 0.5 * (b.lo + b.hi), h = 0.5 * (b.hi - b.lo);
    const Vec3 q = (x - c).cwiseAbs() - h;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}
double signed_distance(const Slab& s, const Vec3& x) {
    const double h = s.normal.dot(x);
    return std::max(s.lo - h, h - s.hi);
}
double signed_distance(const HalfSpace& h, const Vec3& x) { return h.normal.dot(x) - h.offset; }
double signed_distance(const Polyhedron& q, const Vec3& x) {
    double d = -kUnbounded;
    for (const HalfSpace& f : q.faces) d = std::max(d, signed_distance(f, x));
    return d;
}
double signed_distance(const Region& r, const Vec3& x) {
    return std::visit([&](const auto& k) { return signed_distance(k, x); }, r);
}

Vec3 outward_normal(const Sphere& s, const Vec3& x) {
    const Vec3 v = x - s.centre;
    const double n = v.norm();
    return n > 0 ? Vec3(v / n) : Vec3(Vec3::UnitZ());
}
Vec3 outward_normal(const Box& b, const Vec3& x) {
    const Vec3 c = 0.5 * (b.lo + b.hi), h = 0.5 * (b.hi - b.lo), p = x - c;
    const Vec3 q = p.cwiseAbs() - h;
    Vec3 g = Vec3::Zero();
    if (q.maxCoeff() > 0) {
        for (int i = 0; i < 3; ++i) g[i] = q[i] > 0 ? std::copysign(q[i], p[i]) : 0.0;
        return g.normalized();
    }
    int i = 0;
    q.maxCoeff(&i);
    g[i] = std::copysign(1.0, p[i]);
    return g;
}
Vec3 outward_normal(const Slab& s, const Vec3& x) {
    const double h = s.normal.dot(x);
    return s.lo - h > h - s.hi ? Vec3(-s.normal) : s.normal;
}
Vec3 outward_normal(const HalfSpace& h, const Vec3&) { return h.normal; }
namespace {
size_t nearest(const Polyhedron& q, const Vec3& x) {
    size_t best = 0;
    for (size_t i = 1; i < q.faces.size(); ++i)
        if (signed_distance(q.faces[i], x) > signed_distance(q.faces[best], x)) best = i;
    return best;
}
int face_of(const Sphere&, const Vec3&) { return -1; }
int face_of(const Box&, const Vec3&) { return -1; }
int face_of(const Slab&, const Vec3&) { return -1; }
int face_of(const HalfSpace&, const Vec3&) { return -1; }
int face_of(const Polyhedron& q, const Vec3& x) { return static_cast<int>(nearest(q, x)); }
}  // namespace
int nearest_face(const Region& r, const Vec3& x) {
    return std::visit([&](const auto& k) { return face_of(k, x); }, r);
}
Vec3 outward_normal(const Polyhedron& q, const Vec3& x) { return q.faces[nearest(q, x)].normal; }
Vec3 outward_normal(const Region& r, const Vec3& x) {
    return std::visit([&](const auto& k) { return outward_normal(k, x); }, r);
}

std::pair<double, double> extent(const Sphere& s, const Vec3& u) {
    const double c = u.dot(s.centre);
    return {c - s.radius, c + s.radius};
}
std::pair<double, double> extent(const Box& b, const Vec3& u) {
    const double c = u.dot(0.5 * (b.lo + b.hi)), w = u.cwiseAbs().dot(0.5 * (b.hi - b.lo));
    return {c - w, c + w};
}
std::pair<double, double> extent(const Slab& s, const Vec3& u) {
    const int p = parallel(u, s.normal);
    if (p > 0) return {s.lo, s.hi};
    if (p < 0) return {-s.hi, -s.lo};
    return {-kUnbounded, kUnbounded};
}
std::pair<double, double> extent(const HalfSpace& h, const Vec3& u) {
    const int p = parallel(u, h.normal);
    if (p > 0) return {-kUnbounded, h.offset};
    if (p < 0) return {-h.offset, kUnbounded};
    return {-kUnbounded, kUnbounded};
}
std::pair<double, double> extent(const Polyhedron& q, const Vec3& u) {
    double lo = kUnbounded, hi = -kUnbounded;
    for (const Vec3& v : q.vertices) {
        lo = std::min(lo, u.dot(v));
        hi = std::max(hi, u.dot(v));
    }
    return {lo, hi};
}
std::pair<double, double> extent(const Region& r, const Vec3& u) {
    return std::visit([&](const auto& k) { return extent(k, u); }, r);
}

namespace {
double line_distance(const Vec3& x, const Vec3& p, const Vec3& d) {
    const Vec3 v = x - p;
    return (v - v.dot(d) * d).norm();
}
}  // namespace
double max_distance_from_line(const Sphere& s, const Vec3& p, const Vec3& d) {
    return line_distance(s.centre, p, d) + s.radius;
}
double max_distance_from_line(const Box& b, const Vec3& p, const Vec3& d) {
    double m = 0;  // the distance is convex: its largest value is at a corner
    for (int k = 0; k < 8; ++k) {
        const Vec3 c((k & 1) ? b.hi.x() : b.lo.x(), (k & 2) ? b.hi.y() : b.lo.y(), (k & 4) ? b.hi.z() : b.lo.z());
        m = std::max(m, line_distance(c, p, d));
    }
    return m;
}
double max_distance_from_line(const Slab&, const Vec3&, const Vec3&) { return kUnbounded; }
double max_distance_from_line(const HalfSpace&, const Vec3&, const Vec3&) { return kUnbounded; }
double max_distance_from_line(const Polyhedron& q, const Vec3& p, const Vec3& d) {
    double m = 0;  // convex: the largest distance is at a vertex
    for (const Vec3& v : q.vertices) m = std::max(m, line_distance(v, p, d));
    return m;
}
double max_distance_from_line(const Region& r, const Vec3& p, const Vec3& d) {
    return std::visit([&](const auto& k) { return max_distance_from_line(k, p, d); }, r);
}

namespace {
double scale_of(const Sphere& s) { return s.radius; }
double scale_of(const Box& b) { return 0.5 * (b.hi - b.lo).norm(); }
double scale_of(const Slab& s) { return s.hi - s.lo; }
double scale_of(const HalfSpace&) { return 1.0; }
double scale_of(const Polyhedron& q) {  // half the diameter
    double s = 0;
    for (const Vec3& a : q.vertices)
        for (const Vec3& b : q.vertices) s = std::max(s, (a - b).squaredNorm());
    return 0.5 * std::sqrt(s);
}
}  // namespace
double length_scale(const Region& r) {
    return std::visit([](const auto& k) { return scale_of(k); }, r);
}

namespace {
void check(Sphere& s, const std::string& path) {
    finite_vec(s.centre, path + "/centre");
    finite(s.radius, path + "/radius");
    if (!(s.radius > 0)) throw InputError(path + "/radius: " + format_value(s.radius) + " must be > 0");
}
void check(Box& b, const std::string& path) {
    finite_vec(b.lo, path + "/lo");
    finite_vec(b.hi, path + "/hi");
    for (int i = 0; i < 3; ++i)
        if (!(b.lo[i] < b.hi[i]))
            throw InputError(path + "/hi/" + std::to_string(i) + ": " + format_value(b.hi[i]) + " must be > lo (" +
                             format_value(b.lo[i]) + ")");
}
void check(Slab& s, const std::string& path) {
    unit_in_place(s.normal, path + "/normal");
    finite(s.lo, path + "/lo");
    finite(s.hi, path + "/hi");
    if (!(s.lo < s.hi)) throw InputError(path + "/hi: " + format_value(s.hi) + " must be > lo (" + format_value(s.lo) + ")");
}
void check(HalfSpace& h, const std::string& path) {
    unit_in_place(h.normal, path + "/normal");
    finite(h.offset, path + "/offset");
}
void check(Polyhedron& q, const std::string& path) {
    if (q.faces.size() < 4 || q.vertices.size() < 4)
        throw InputError(path + ": a polyhedron needs at least 4 faces and 4 vertices (a bounded solid)");
    for (size_t i = 0; i < q.faces.size(); ++i) check(q.faces[i], path + "/faces/" + std::to_string(i));
    for (size_t i = 0; i < q.vertices.size(); ++i) finite_vec(q.vertices[i], path + "/vertices/" + std::to_string(i));
}
}  // namespace

void validate(Region& r, const std::string& path) {
    std::visit([&](auto& k) { check(k, path); }, r);
}

}  // namespace refract::grin
