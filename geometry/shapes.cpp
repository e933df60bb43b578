#include <refract/geometry/shapes.h>

#include <refract/geometry/plane_set.h>

#include <cmath>
#include <algorithm>
#include <limits>

#include <Eigen/Dense>

namespace refract {

std::optional<Hit> intersect(const Sphere& s, const Ray& r, double t_min, double t_max) {
    const auto [b, disc] = sphere_quadratic<Vec3>(r.origin - s.center, r.dir, s.radius);
    if (disc < 0) return std::nullopt;
    const double sq = std::sqrt(disc);
    double t = -b - sq;
    // Written so that a NaN t (a sphere at 1e200: inf − inf) is never a hit.
    if (!(t > t_min && t < t_max)) {
        t = -b + sq;
        if (!(t > t_min && t < t_max)) return std::nullopt;
    }
    return sphere_hit(s, r, t);
}

Hit sphere_hit(const Sphere& s, const Ray& r, double t) {
    Hit h;
    h.t = t;
    h.point = r.at(t);
    h.normal = ((h.point - s.center) / s.radius).normalized();  // negative radius: flipped (RTIOW)
    return h;
}

__attribute__((flatten)) LaneShapeHits intersect_lanes(const Sphere& s, const LaneVec3& origin, const LaneVec3& dir,
                                                       const LaneMask& active, double t_min, const Lanes& t_max,
                                                       const LaneMask& leaving) {
    const LaneVec3 centre = LaneVec3::broadcast(s.center);
    const auto [b, disc] = sphere_quadratic<LaneVec3>(origin - centre, dir, Lanes(s.radius));
    LaneShapeHits h;
    const LaneMask ask = leaving.any() ? active && !(leaving && (b > Lanes(0.0))) : active;
    if (!ask.any()) {
        h.hit = ask;
        return h;
    }
    const Lanes sq = sqrt(disc);  // NaN where disc < 0: no hit there
    const Lanes near = -b - sq, far = -b + sq;
    const Lanes lo(t_min);
    // As the scalar test: the nearer root if it lies in (t_min, t_max), else the farther.
    const LaneMask near_ok = (near > lo) && (near < t_max), far_ok = (far > lo) && (far < t_max);
    h.hit = ask && !(disc < Lanes(0.0)) && (near_ok || far_ok);
    h.t = select(near_ok, near, far);
    h.point = origin + h.t * dir;
    h.normal = ((h.point - centre) / Lanes(s.radius)).normalized();
    return h;
}

std::optional<Hit> intersect(const Plane& p, const Ray& r, double t_min, double t_max) {
    const double denom = p.normal.dot(r.dir);
    if (denom == 0) return std::nullopt;
    const double t = (p.offset - p.normal.dot(r.origin)) / denom;
    if (!(t > t_min && t < t_max)) return std::nullopt;  // NaN is no hit
    return Hit{t, r.at(t), p.normal, -1};
}

__attribute__((flatten)) LaneShapeHits intersect_lanes(const Plane& p, const LaneVec3& origin, const LaneVec3& dir,
                                                       const LaneMask& active, double t_min, const Lanes& t_max) {
    // As the scalar test: no hit where the ray is parallel, nor where t is NaN.
    const LaneVec3 n = LaneVec3::broadcast(p.normal);
    const Lanes denom = n.dot(dir);
    const Lanes t = (Lanes(p.offset) - n.dot(origin)) / denom;
    LaneShapeHits h;
    h.hit = active && ((denom > Lanes(0.0)) || (denom < Lanes(0.0))) && (t > Lanes(t_min)) && (t < t_max);
    h.t = t;
    h.point = origin + t * dir;
    h.normal = n;
    return h;
}

std::optional<TriangleT> triangle_t(const Vec3& a, const Vec3& e1, const Vec3& e2, const Ray& r) {
    // Möller–Trumbore.
    const Vec3 pv = r.dir.cross(e2);
    const double det = e1.dot(pv);
    if (det == 0) return std::nullopt;
    const double inv = 1.0 / det;
    const Vec3 tv = r.origin - a;
    const Vec3 qv = tv.cross(e1);
    return TriangleT{e2.dot(qv) * inv, tv.dot(pv) * inv, r.dir.dot(qv) * inv};
}

std::optional<TriangleT> triangle_t(const TriangleMesh& m, size_t k, const Ray& r) {
    const auto& tri = m.triangles[k];
    const Vec3& a = m.vertices[tri[0]];
    return triangle_t(a, m.vertices[tri[1]] - a, m.vertices[tri[2]] - a, r);
}

Vec3 triangle_normal(const TriangleMesh& m, size_t k) {
    const auto& tri = m.triangles[k];
    const Vec3& a = m.vertices[tri[0]];
    return (m.vertices[tri[1]] - a).cross(m.vertices[tri[2]] - a).normalized();
}

std::optional<Hit> intersect(const TriangleMesh& m, const Ray& r, double t_min, double t_max) {
    // Nearest over all triangles, in order (the reference geometry/mesh_accel.h is tested
    // against; the tracer uses that one for meshes of more than a few triangles).
    std::optional<Hit> best;
    double t_best = t_max;
    for (size_t k = 0; k < m.triangles.size(); ++k) {
        const auto h = triangle_t(m, k, r);
        if (!h || h->u < 0 || h->u > 1 || h->v < 0 || h->u + h->v > 1) continue;
        if (!(h->t > t_min && h->t < t_best)) continue;  // NaN is no hit
        t_best = h->t;
        best = Hit{h->t, r.at(h->t), triangle_normal(m, k), static_cast<int>(k)};
    }
    return best;
}

// The bounding-sphere reject: the origin outside the sphere and the ray missing it.
bool misses_bound(const ConvexPolyhedron& c, const Ray& r) {
    if (!(c.bound_radius > 0)) return false;
    const Vec3 oc = r.origin - c.bound_center;
    const double b = oc.dot(r.dir);
    const double q = oc.squaredNorm() - c.bound_radius * c.bound_radius;
    return q > 0 && (b > 0 || b * b < q);
}

// The scalar reference: the slab loop as it always was. intersect() below gives the same
// result to the last bit through the vectorised kernel (geometry/plane_set.h); the tests
// compare the two.
std::optional<Hit> intersect_scalar(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max) {
    if (misses_bound(c, r)) return std::nullopt;
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

namespace {

// The end of intersect_scalar, from the vectorised slab pass (its early exit once, at the
// end). The same conditions, combined without branches (t_enter and t_exit are never NaN,
// so !(t_enter > t_exit) is t_enter <= t_exit): one unpredictable branch instead of four.
[[gnu::always_inline]] inline std::optional<Hit> hit_from(const SlabSpan& s, const ConvexPolyhedron& c, const Ray& r,
                                                          double t_min, double t_max) {
    const bool span = s.t_enter <= s.t_exit;
    const bool enter = span & (s.t_enter > t_min) & (s.t_enter < t_max) & (s.f_enter >= 0);
    const bool leave = span & (s.t_exit > t_min) & (s.t_exit < t_max) & (s.f_exit >= 0);
    if (!(enter | leave)) return std::nullopt;
    const double t = enter ? s.t_enter : s.t_exit;
    const int f = enter ? s.f_enter : s.f_exit;
    return Hit{t, r.at(t), c.planes[static_cast<size_t>(f)].normal, f};
}

}  // namespace

std::optional<Hit> intersect(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max) {
    if (misses_bound(c, r)) return std::nullopt;
    return hit_from(slab_span(c.planes.data(), c.planes.size(), r), c, r, t_min, t_max);
}

std::optional<Hit> intersect(SlabIsa isa, const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max) {
    if (misses_bound(c, r)) return std::nullopt;
    return hit_from(slab_span(isa, c.planes.data(), c.planes.size(), r), c, r, t_min, t_max);
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

namespace {

std::optional<Bounds> box_of(const std::vector<Vec3>& pts) {
    if (pts.empty()) return std::nullopt;
    Bounds b{pts[0], pts[0]};
    for (const auto& v : pts) {
        b.lo = b.lo.cwiseMin(v);
        b.hi = b.hi.cwiseMax(v);
    }
    return b;
}

std::optional<BoundingSphere> sphere_of_points(const std::vector<Vec3>& pts) {
    if (pts.empty()) return std::nullopt;
    Vec3 lo = pts[0], hi = pts[0];
    for (const Vec3& p : pts) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const Vec3 c = 0.5 * (lo + hi);
    double r = 0;
    for (const Vec3& p : pts) r = std::fmax(r, (p - c).norm());
    return BoundingSphere{c, r * (1 + 1e-9) + 1e-12};
}

// Unbounded iff the recession cone {v : n_i·v <= 0} holds a non-zero v; such a cone has
// an extreme ray along n_i × n_j, or all normals lie in one plane.
bool unbounded(const ConvexPolyhedron& c) {
    const size_t n = c.planes.size();
    Eigen::MatrixXd N(static_cast<Eigen::Index>(n), 3);
    for (size_t i = 0; i < n; ++i) N.row(static_cast<Eigen::Index>(i)) = c.planes[i].normal.transpose();
    if (n < 3 || Eigen::FullPivLU<Eigen::MatrixXd>(N).rank() < 3) return true;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            const Vec3 v = c.planes[i].normal.cross(c.planes[j].normal);
            if (v.norm() < 1e-12) continue;
            for (const Vec3& d : {Vec3(v.normalized()), Vec3(-v.normalized())}) {
                bool in_cone = true;
                for (const Plane& p : c.planes) in_cone = in_cone && p.normal.dot(d) <= 1e-12;
                if (in_cone) return true;
            }
        }
    return false;
}

}  // namespace

std::optional<Hit> intersect(const Shape& s, const Ray& r, double t_min, double t_max) {
    return std::visit([&](const auto& x) { return intersect(x, r, t_min, t_max); }, s);
}

std::optional<Bounds> bounds(const Sphere& s) {
    const double r = std::abs(s.radius);
    return Bounds{s.center - Vec3::Constant(r), s.center + Vec3::Constant(r)};
}
std::optional<Bounds> bounds(const Plane&) { return std::nullopt; }  // a half-space
std::optional<Bounds> bounds(const TriangleMesh& m) { return box_of(m.vertices); }
std::optional<Bounds> bounds(const ConvexPolyhedron& c) { return box_of(vertices(c)); }
std::optional<Bounds> bounds(const Shape& s) {
    return std::visit([](const auto& x) { return bounds(x); }, s);
}

std::optional<BoundingSphere> bounding_sphere(const Sphere& s) { return BoundingSphere{s.center, std::abs(s.radius)}; }
std::optional<BoundingSphere> bounding_sphere(const Plane&) { return std::nullopt; }
std::optional<BoundingSphere> bounding_sphere(const TriangleMesh& m) { return sphere_of_points(m.vertices); }
std::optional<BoundingSphere> bounding_sphere(const ConvexPolyhedron& c) { return sphere_of_points(vertices(c)); }
std::optional<BoundingSphere> bounding_sphere(const Shape& s) {
    return std::visit([](const auto& x) { return bounding_sphere(x); }, s);
}

std::vector<Vec3> vertices(const Sphere&) { return {}; }
std::vector<Vec3> vertices(const Plane&) { return {}; }
std::vector<Vec3> vertices(const TriangleMesh& m) { return m.vertices; }
std::vector<Vec3> vertices(const ConvexPolyhedron& c) {
    // Every triple of planes meeting in a point inside all half-spaces; none when the
    // polyhedron is unbounded.
    std::vector<Vec3> v;
    if (unbounded(c)) return v;
    const size_t n = c.planes.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k) {
                Eigen::Matrix3d A;
                A.row(0) = c.planes[i].normal.transpose();
                A.row(1) = c.planes[j].normal.transpose();
                A.row(2) = c.planes[k].normal.transpose();
                if (std::abs(A.determinant()) < 1e-12) continue;
                const Vec3 p = A.partialPivLu().solve(Vec3(c.planes[i].offset, c.planes[j].offset, c.planes[k].offset));
                // Most triples meet outside the solid: stop at the first plane that cuts
                // the point away.
                const bool inside = std::all_of(c.planes.begin(), c.planes.end(), [&](const Plane& q) {
                    return q.normal.dot(p) <= q.offset + 1e-9;
                });
                if (inside) v.push_back(p);
            }
    return v;
}
TriangleMesh mesh_of(const ConvexPolyhedron& c) {
    // The corners without repeats (a corner where more than three planes meet is found
    // once per triple), then per plane its corners in angular order, fanned.
    TriangleMesh m;
    const std::vector<Vec3> corners = vertices(c);
    double scale = 0;
    for (const Vec3& p : corners) scale = std::fmax(scale, p.cwiseAbs().maxCoeff());
    const double tol = 1e-9 * (1 + scale);
    for (const Vec3& p : corners) {
        bool seen = false;
        for (const Vec3& q : m.vertices) seen = seen || (p - q).cwiseAbs().maxCoeff() <= tol;
        if (!seen) m.vertices.push_back(p);
    }
    for (const Plane& pl : c.planes) {
        std::vector<int> on;
        Vec3 centre(0, 0, 0);
        for (size_t i = 0; i < m.vertices.size(); ++i)
            if (std::abs(pl.normal.dot(m.vertices[i]) - pl.offset) <= tol) {
                on.push_back(static_cast<int>(i));
                centre += m.vertices[i];
            }
        if (on.size() < 3) continue;  // a plane touching the solid in an edge or a point
        centre /= static_cast<double>(on.size());
        const Vec3 u = pl.normal.unitOrthogonal(), w = pl.normal.cross(u);  // u × w = normal
        const auto angle = [&](int i) {
            const Vec3 d = m.vertices[static_cast<size_t>(i)] - centre;
            return std::atan2(d.dot(w), d.dot(u));
        };
        std::sort(on.begin(), on.end(), [&](int a, int b) { return angle(a) < angle(b); });
        for (size_t k = 1; k + 1 < on.size(); ++k) m.triangles.push_back({on[0], on[k], on[k + 1]});
    }
    return m;
}

std::vector<Vec3> vertices(const Shape& s) {
    return std::visit([](const auto& x) { return vertices(x); }, s);
}

MapSurface map_surface(const Sphere&) { return {}; }
MapSurface map_surface(const Plane& p) { return &p; }
MapSurface map_surface(const TriangleMesh& m) { return &m; }
MapSurface map_surface(const ConvexPolyhedron&) { return {}; }
MapSurface map_surface(const Shape& s) {
    return std::visit([](const auto& x) { return map_surface(x); }, s);
}

}  // namespace refract
