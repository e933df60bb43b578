#include <refract/core/scene_gem.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <variant>

#include <refract/geometry/error.h>
#include <refract/geometry/gem/gemcad.h>

namespace refract {

namespace {

// The stone's tracing shape (tracing_shape) moved by x -> scale·M·x + pos, by its kind.
Shape placed(const ConvexPolyhedron& solid, const Gem& gem, double scale, const Eigen::Matrix3d& M, const Vec3& pos) {
    ConvexPolyhedron c = solid;
    for (Plane& p : c.planes) {
        p.normal = (M * p.normal).normalized();
        p.offset = scale * p.offset + p.normal.dot(pos);
    }
    std::vector<Vec3> moved;
    for (const Vec3& v : gem.mesh.vertices) moved.push_back(scale * (M * v) + pos);
    set_bound(c, moved);
    return c;
}
Shape placed(const TriangleMesh& mesh, const Gem&, double scale, const Eigen::Matrix3d& M, const Vec3& pos) {
    TriangleMesh m = mesh;
    for (Vec3& v : m.vertices) v = scale * (M * v) + pos;
    return m;
}
Shape placed(const Sphere&, const Gem&, double, const Eigen::Matrix3d&, const Vec3&) {
    throw std::logic_error("a gem is traced as a plane set or a mesh, not a sphere");
}
Shape placed(const Plane&, const Gem&, double, const Eigen::Matrix3d&, const Vec3&) {
    throw std::logic_error("a gem is traced as a plane set or a mesh, not a plane");
}

}  // namespace

Shape place_gem(const Gem& gem, double scale, const JsonReader& o) {
    const Vec3 pos = o.vec3("position", Vec3(0, 0, 0));
    const Vec3 rot = o.vec3("rotation", Vec3(0, 0, 0)) * (M_PI / 180.0);
    const Eigen::Matrix3d M = (Eigen::AngleAxisd(rot.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(rot.y(), Vec3::UnitY()) *
                               Eigen::AngleAxisd(rot.x(), Vec3::UnitX()) *
                               Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX())).toRotationMatrix();
    return std::visit([&](const auto& s) { return placed(s, gem, scale, M, pos); }, tracing_shape(gem));
}

Shape parse_gem_design(const JsonReader& o) {
    o.only({"type", "name", "material", "design", "position", "diameter", "rotation", "transform"});
    const std::string name = o.string("design");
    if (name.empty()) o.fail_at("design", "must name a GemCad .asc design file");
    const std::filesystem::path path = std::filesystem::path(o.file()).parent_path() / name;
    DesignGem d;
    try {
        d = build_design(read_gemcad(path.lexically_normal().string()));
    } catch (const InputError& e) {
        o.fail_at("design", e.what());
    }
    const double scale = o.has("diameter") ? o.positive("diameter", 1.0) / d.width : 1.0;
    if (!std::isfinite(scale) || !(scale > 0)) o.fail_at("diameter", "gives a scale beyond a double's range");
    return place_gem(d.gem, scale, o);
}

}  // namespace refract
