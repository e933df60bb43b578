#include <refract/core/object_transform.h>

#include <cmath>

#include <Eigen/LU>

namespace refract {

namespace {

// Beyond this a transformed coordinate of an ordinary scene leaves the range the tracer's
// tolerances are set for (docs/limits.md).
constexpr double kMaxEntry = 1e12;

Eigen::Matrix4d read_matrix(const JsonReader& r) {
    const auto& v = r.raw("matrix");
    Eigen::Matrix4d M;
    const auto fail = [&] { r.fail_at("matrix", "must be 4 rows of 4 finite numbers (row-major), or 16 numbers"); };
    if (!v.is_array()) fail();
    const bool flat = v.size() == 16;
    if (!flat && v.size() != 4) fail();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const auto& e = flat ? v[static_cast<size_t>(4 * i + j)]
                                 : (v[static_cast<size_t>(i)].is_array() && v[static_cast<size_t>(i)].size() == 4
                                        ? v[static_cast<size_t>(i)][static_cast<size_t>(j)]
                                        : v);
            if (!e.is_number() || !std::isfinite(e.get<double>())) fail();
            M(i, j) = e.get<double>();
        }
    if (!(M.row(3) == Eigen::RowVector4d(0, 0, 0, 1))) r.fail_at("matrix", "the last row must be [0, 0, 0, 1] (affine)");
    return M;
}

}  // namespace

Transform parse_transform(const JsonReader& r) {
    r.only({"translate", "rotate", "scale", "matrix"});
    Transform T;
    if (r.has("matrix")) {
        const Eigen::Matrix4d M = read_matrix(r);
        T.linear = M.topLeftCorner<3, 3>();
        T.translation = M.topRightCorner<3, 1>();
    }
    if (r.has("scale")) {
        Vec3 s;
        if (r.raw("scale").is_number()) s = Vec3::Constant(r.number("scale"));
        else s = r.vec3("scale");
        if (!(s.cwiseAbs().minCoeff() > 0) || !(s.cwiseAbs().maxCoeff() <= kMaxEntry))
            r.fail_at("scale", "must be non-zero and at most 1e12 in size (a number or [sx, sy, sz])");
        T = Transform{s.asDiagonal().toDenseMatrix(), Vec3::Zero()}.after(T);
    }
    if (r.has("rotate")) {
        const Vec3 a = r.vec3("rotate") * (M_PI / 180.0);
        const Eigen::Matrix3d R = (Eigen::AngleAxisd(a.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(a.y(), Vec3::UnitY()) *
                                   Eigen::AngleAxisd(a.x(), Vec3::UnitX()))
                                      .toRotationMatrix();
        T = Transform{R, Vec3::Zero()}.after(T);
    }
    if (r.has("translate")) T.translation += r.vec3("translate");
    const double det = T.linear.determinant();
    if (!(std::abs(det) > 0) || !T.linear.inverse().allFinite())
        r.fail("the transform is singular (it flattens the object)");
    if (!(T.linear.cwiseAbs().maxCoeff() <= kMaxEntry) || !(T.translation.cwiseAbs().maxCoeff() <= kMaxEntry) ||
        !(T.linear.inverse().cwiseAbs().maxCoeff() <= kMaxEntry))
        r.fail("the transform's entries (or its inverse's) exceed 1e12");
    return T;
}

}  // namespace refract
