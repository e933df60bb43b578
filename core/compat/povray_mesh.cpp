#include <refract/core/compat/povray_mesh.h>

#include <refract/core/compat/povray.h>

#include <algorithm>
#include <cmath>

namespace refract::povray {

namespace {

constexpr double kEpsilon = 1e-10;         // frame.h EPSILON: a ray parallel to the plane
constexpr double kDepthTolerance = 1e-6;   // mesh.cpp DEPTH_TOLERANCE

// A value as single precision stores it. Through a volatile float: GCC 12's vectoriser
// (-O2 and above) was seen to drop the float round trip of an Eigen vector's components.
double single(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}
Vec3 single(const Vec3& v) { return Vec3(single(v.x()), single(v.y()), single(v.z())); }

// The index of the largest of |n|'s components, ties as POV-Ray's max3_coordinate.
int dominant_axis(const Vec3& n) {
    const double x = std::abs(n.x()), y = std::abs(n.y()), z = std::abs(n.z());
    return x > y ? (x > z ? 0 : 2) : (y > z ? 1 : 2);
}

// a·b in POV-Ray's order of operations (x, then y, then z).
double dot(const Vec3& a, const Vec3& b) { return a.x() * b.x() + a.y() * b.y() + a.z() * b.z(); }

// The two axes of the plane the edges are tested in, for a dominant axis.
constexpr int kU[3] = {1, 0, 0}, kV[3] = {2, 2, 1};

}  // namespace

Mesh::Mesh(const TriangleMesh& m) {
    tri_.reserve(m.triangles.size());
    std::vector<std::optional<Bounds>> boxes;
    for (const auto& t : m.triangles) {
        Vec3 p1 = single(m.vertices[static_cast<size_t>(t[0])]), p2 = single(m.vertices[static_cast<size_t>(t[1])]),
             p3 = single(m.vertices[static_cast<size_t>(t[2])]);
        Triangle tr;
        const Vec3 n = (p3 - p1).cross(p2 - p1);
        const double len = n.norm();
        if (len == 0) {  // POV-Ray drops degenerate triangles: none is ever hit
            tr = Triangle{p1, p2, p3, Vec3::Zero(), 0.0, -1};
        } else {
            const Vec3 unit = n / len;
            const double distance = single(-dot(unit, p1));  // of the first vertex before any swap
            const int axis = dominant_axis(unit);
            const int u = kU[axis], v = kV[axis];
            if ((p2[u] - p3[u]) * (p2[v] - p1[v]) < (p2[v] - p3[v]) * (p2[u] - p1[u])) std::swap(p1, p2);
            tr = Triangle{p1, p2, p3, single(unit), distance, axis};
        }
        // Boxes padded beyond the hits' rounding: the point o + t·dir lies on the stored
        // plane, which single precision may put ~1e-7 relative off the vertices' box.
        const Vec3 lo = p1.cwiseMin(p2).cwiseMin(p3), hi = p1.cwiseMax(p2).cwiseMax(p3);
        const double pad = 1e-5 * std::max(1.0, std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
        boxes.push_back(Bounds{Vec3(lo.array() - pad), Vec3(hi.array() + pad)});
        tri_.push_back(tr);
    }
    if (tri_.size() >= kMinBvhTriangles) bvh_.emplace(boxes);
}

std::optional<double> Mesh::hit_t(const Triangle& tr, const Ray& r, double lo) const {
    if (tr.axis < 0) return std::nullopt;
    const double nd = dot(tr.normal, r.dir);
    if (std::abs(nd) < kEpsilon) return std::nullopt;
    const double t = -(tr.distance + dot(tr.normal, r.origin)) / nd;
    if (!(t >= lo && t <= kMaxDistance)) return std::nullopt;
    const int u = kU[tr.axis], v = kV[tr.axis];
    const double s = r.origin[u] + t * r.dir[u], w = r.origin[v] + t * r.dir[v];
    const Vec3 &p1 = tr.p1, &p2 = tr.p2, &p3 = tr.p3;
    if ((p2[u] - s) * (p2[v] - p1[v]) < (p2[v] - w) * (p2[u] - p1[u])) return std::nullopt;
    if ((p3[u] - s) * (p3[v] - p2[v]) < (p3[v] - w) * (p3[u] - p2[u])) return std::nullopt;
    if ((p1[u] - s) * (p1[v] - p3[v]) < (p1[v] - w) * (p1[u] - p3[u])) return std::nullopt;
    return t;
}

template <class Visit>
void Mesh::candidates(const Ray& r, double t_min, const double& t_cull, Visit&& visit) const {
    if (bvh_) {
        bvh_->search(r, t_min, t_cull, [&](int k) { visit(static_cast<size_t>(k)); });
        return;
    }
    for (size_t k = 0; k < tri_.size(); ++k) visit(k);
}

std::optional<Hit> Mesh::intersect(const Ray& r, double t_min, double t_max) const {
    // The nearest, on an exact tie the first triangle (measure zero: POV-Ray's order is its
    // box tree's).
    double best_t = t_max;
    int best = -1;
    candidates(r, t_min, best_t, [&](size_t k) {
        const auto t = hit_t(tri_[k], r, kDepthTolerance);
        if (!t || !(*t > t_min && *t < t_max)) return;
        if (best >= 0 && (*t > best_t || (*t == best_t && static_cast<int>(k) > best))) return;
        best_t = *t;
        best = static_cast<int>(k);
    });
    if (best < 0) return std::nullopt;
    return Hit{best_t, r.at(best_t), -tri_[static_cast<size_t>(best)].normal, best};
}

int Mesh::crossings(const Ray& r, double t_max, int skip) const {
    std::vector<double> ts;
    const double cull = t_max;
    candidates(r, 0.0, cull, [&](size_t k) {
        if (static_cast<int>(k) == skip) return;
        if (const auto t = hit_t(tri_[k], r, 0.0); t && *t > 0 && *t < t_max) ts.push_back(*t);
    });
    std::sort(ts.begin(), ts.end());
    return static_cast<int>(std::unique(ts.begin(), ts.end()) - ts.begin());
}

}  // namespace refract::povray
