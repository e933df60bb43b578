#include "geometry/shapes.h"

#include <cmath>
#include <algorithm>
#include <limits>

namespace refract {

std::optional<Hit> intersect(const Sphere& s, const Ray& r, double t_min, double t_max) {
    // |o + t d − c|² = ρ², with |d| = 1: t² + 2 b t + c = 0 (half-b form).
    const Vec3 oc = r.origin - s.center;
    const double b = oc.dot(r.dir);
    const double c = oc.squaredNorm() - s.radius * s.radius;
    const double disc = b * b - c;
    if (disc < 0) return std::nullopt;
    const double sq = std::sqrt(disc);
    double t = -b - sq;
    if (t <= t_min || t >= t_max) {
        t = -b + sq;
        if (t <= t_min || t >= t_max) return std::nullopt;
    }
    Hit h;
    h.t = t;
    h.point = r.at(t);
    h.normal = ((h.point - s.center) / s.radius).normalized();  // negative radius: flipped (RTIOW)
    return h;
}

std::optional<Hit> intersect(const Plane& p, const Ray& r, double t_min, double t_max) {
    const double denom = p.normal.dot(r.dir);
    if (denom == 0) return std::nullopt;
    const double t = (p.offset - p.normal.dot(r.origin)) / denom;
    if (t <= t_min || t >= t_max) return std::nullopt;
    return Hit{t, r.at(t), p.normal, -1};
}

std::optional<Hit> intersect(const TriangleMesh& m, const Ray& r, double t_min, double t_max) {
    // Möller–Trumbore, nearest over all triangles.
    std::optional<Hit> best;
    double t_best = t_max;
    for (size_t k = 0; k < m.triangles.size(); ++k) {
        const auto& tri = m.triangles[k];
        const Vec3& a = m.vertices[tri[0]];
        const Vec3 e1 = m.vertices[tri[1]] - a;
        const Vec3 e2 = m.vertices[tri[2]] - a;
        const Vec3 pv = r.dir.cross(e2);
        const double det = e1.dot(pv);
        if (det == 0) continue;
        const double inv = 1.0 / det;
        const Vec3 tv = r.origin - a;
        const double u = tv.dot(pv) * inv;
        if (u < 0 || u > 1) continue;
        const Vec3 qv = tv.cross(e1);
        const double v = r.dir.dot(qv) * inv;
        if (v < 0 || u + v > 1) continue;
        const double t = e2.dot(qv) * inv;
        if (t <= t_min || t >= t_best) continue;
        t_best = t;
        best = Hit{t, r.at(t), e1.cross(e2).normalized(), static_cast<int>(k)};
    }
    return best;
}

std::optional<Hit> intersect(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max) {
    if (c.bound_radius > 0) {
        const Vec3 oc = r.origin - c.bound_center;
        const double b = oc.dot(r.dir);
        const double q = oc.squaredNorm() - c.bound_radius * c.bound_radius;
        if (q > 0 && (b > 0 || b * b < q)) return std::nullopt;  // outside and missing the sphere
    }
    // Slab method over half-spaces n·x <= d: the ray is inside on [t_enter, t_exit],
    // t_enter = largest entering t, t_exit = smallest leaving t.
    double t_enter = -std::numeric_limits<double>::infinity();
    double t_exit = std::numeric_limits<double>::infinity();
    int f_enter = -1, f_exit = -1;
    for (size_t k = 0; k < c.planes.size(); ++k) {
        const Plane& p = c.planes[k];
        const double denom = p.normal.dot(r.dir);
        const double dist = p.offset - p.normal.dot(r.origin);  // >= 0 inside
        if (denom == 0) {
            if (dist < 0) return std::nullopt;  // parallel and outside
            continue;
        }
        const double t = dist / denom;
        if (denom < 0) {
            if (t > t_enter) { t_enter = t; f_enter = static_cast<int>(k); }
        } else {
            if (t < t_exit) { t_exit = t; f_exit = static_cast<int>(k); }
        }
        if (t_enter > t_exit) return std::nullopt;
    }
    if (t_enter > t_min && t_enter < t_max && f_enter >= 0)
        return Hit{t_enter, r.at(t_enter), c.planes[f_enter].normal, f_enter};
    if (t_exit > t_min && t_exit < t_max && f_exit >= 0)
        return Hit{t_exit, r.at(t_exit), c.planes[f_exit].normal, f_exit};
    return std::nullopt;
}

void set_bound(ConvexPolyhedron& c, const std::vector<Vec3>& vertices) {
    if (vertices.empty()) return;
    Vec3 lo = vertices[0], hi = vertices[0];
    for (const auto& v : vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    c.bound_center = 0.5 * (lo + hi);
    double r = 0;
    for (const auto& v : vertices) r = std::max(r, (v - c.bound_center).norm());
    c.bound_radius = r * (1 + 1e-9) + 1e-12;
}

std::optional<Bounds> bounds(const Sphere& s) {
    const double r = std::abs(s.radius);
    return Bounds{s.center - Vec3::Constant(r), s.center + Vec3::Constant(r)};
}

std::optional<Bounds> bounds(const TriangleMesh& m) {
    if (m.vertices.empty()) return std::nullopt;
    Bounds b{m.vertices[0], m.vertices[0]};
    for (const auto& v : m.vertices) {
        b.lo = b.lo.cwiseMin(v);
        b.hi = b.hi.cwiseMax(v);
    }
    return b;
}

}  // namespace refract
