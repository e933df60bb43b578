// Transforms drawn onto a random scene (RandomSceneOptions::transforms): each chosen
// object is written as its shape moved back by a random affine transform T (rotation,
// positive scales, for meshes and polyhedra a non-uniform one, translation) together with
// "transform": T, so that the scene's objects stay where the generator placed and checked
// them (to rounding, ~1e-15 relative), while refract and POV-Ray each apply T themselves.
// The draws come from their own stream of the seed: the scene without transforms is
// unchanged.
#include <cmath>
#include <string>

#include <Eigen/LU>

#include <refract/validation/random_scene.h>
#include <refract/validation/random_geometry.h>

namespace refract::validation::random_detail {

namespace {

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json matrix(const Mat3& A, const Vec3& t) {
    json m = json::array();
    for (int i = 0; i < 3; ++i) m.push_back(json::array({A(i, 0), A(i, 1), A(i, 2), t[i]}));
    m.push_back(json::array({0, 0, 0, 1}));
    return m;
}

}  // namespace

void draw_transforms(json& scene, std::uint64_t seed) {
    Rand rng(seed ^ 0x7472616e73666f72ULL);  // "transfor"
    int count = 0;
    for (json& o : scene["objects"]) {
        const std::string type = o["type"];
        if (type == "brilliant" || !rng.chance(0.6)) continue;
        const Mat3 R = rng.rotation();
        const bool uniform = type == "sphere";
        const double k = rng.uniform(0.5, 2);
        Vec3 s(k, k, k);
        if (!uniform) {
            s.y() = rng.uniform(0.5, 2);
            s.z() = rng.uniform(0.5, 2);
        }
        const Mat3 A = R * s.asDiagonal();
        const Vec3 t = rng.box(-3, 3);
        const Mat3 Ai = A.inverse();
        // x_world = A x_local + t: points move back by A⁻¹(x − t), planes n·x = d become
        // (Aᵀn)·x' = d − n·t.
        const auto back = [&](const json& p) { return vec(Ai * (Vec3(p[0], p[1], p[2]) - t)); };
        if (type == "sphere") {
            o["center"] = back(o["center"]);
            o["radius"] = o["radius"].get<double>() / k;
        } else if (type == "mesh") {
            for (json& v : o["vertices"]) v = back(v);
        } else if (type == "polyhedron") {
            for (json& p : o["planes"]) {
                const Vec3 n(p[0], p[1], p[2]);
                const Vec3 m = A.transpose() * n;
                p = json::array({m.x(), m.y(), m.z(), p[3].get<double>() - n.dot(t)});
            }
        } else if (type == "plane") {
            const Vec3 n = Vec3(o["normal"][0], o["normal"][1], o["normal"][2]).normalized();  // as the reader takes it
            const Vec3 m = A.transpose() * n;  // a plane's offset is along its unit normal
            o["normal"] = vec(m / m.norm());
            o["offset"] = (o.value("offset", 0.0) - n.dot(t)) / m.norm();
        } else {
            continue;
        }
        o["transform"] = {{"matrix", matrix(A, t)}};
        ++count;
    }
    scene["description"] = scene["description"].get<std::string>() + "; transforms on " + std::to_string(count) +
                           (count == 1 ? " object" : " objects");
}

}  // namespace refract::validation::random_detail
