#include <refract/geometry/transform.h>

#include <cmath>
#include <utility>
#include <variant>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace refract {

std::optional<double> uniform_scale(const Eigen::Matrix3d& A) {
    const Eigen::Matrix3d G = A.transpose() * A;
    const double s2 = G.trace() / 3;
    if (!(s2 > 0) || !std::isfinite(s2)) return std::nullopt;
    if ((G - s2 * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-12 * s2) return std::nullopt;
    return std::sqrt(s2);
}

namespace {

Plane moved(const Plane& p, const Transform& T, const Eigen::Matrix3d& inverse_transpose) {
    // n·x = d for x = A⁻¹(x' − t): (A⁻ᵀ n)·x' = d + (A⁻ᵀ n)·t; the outward side stays outward.
    const Vec3 n = inverse_transpose * p.normal;
    const double len = n.norm();
    return Plane{n / len, (p.offset + n.dot(T.translation)) / len};
}

// One overload per shape kind, visited exhaustively: a new kind without one does not compile.
struct Transformed {
    const Transform& T;
    Eigen::Matrix3d inverse_transpose;

    std::optional<Shape> operator()(const Sphere& sp) const {
        const auto k = uniform_scale(T.linear);
        if (!k) return std::nullopt;
        return Shape(Sphere{T.point(sp.center), sp.radius * *k});
    }
    std::optional<Shape> operator()(const Plane& p) const { return Shape(moved(p, T, inverse_transpose)); }
    std::optional<Shape> operator()(const TriangleMesh& m) const {
        TriangleMesh out;
        out.vertices.reserve(m.vertices.size());
        for (const Vec3& v : m.vertices) out.vertices.push_back(T.point(v));
        out.triangles = m.triangles;
        if (T.linear.determinant() < 0)
            for (auto& t : out.triangles) std::swap(t[1], t[2]);
        return Shape(std::move(out));
    }
    std::optional<Shape> operator()(const ConvexPolyhedron& c) const {
        ConvexPolyhedron out = c;
        for (Plane& p : out.planes) p = moved(p, T, inverse_transpose);
        if (c.bound_radius > 0) {
            out.bound_center = T.point(c.bound_center);
            // The largest stretch of A (its spectral norm) bounds the moved sphere; a hair more
            // for rounding.
            const double stretch = Eigen::JacobiSVD<Eigen::Matrix3d>(T.linear).singularValues()(0);
            out.bound_radius = c.bound_radius * stretch * (1 + 1e-12);
        }
        return Shape(std::move(out));
    }
};

}  // namespace

std::optional<Shape> transformed(const Shape& s, const Transform& T) {
    return std::visit(Transformed{T, T.linear.inverse().transpose()}, s);
}

}  // namespace refract
