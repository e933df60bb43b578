// POV-Ray 3.7's mesh2 in the compatibility mode (core/compat/povray_mesh.h, HitSearch's
// interior lists): its single-precision triangles against the double ones, its edges, its
// BVH against the plain scan, and two pixels of the random search's minimal cases against
// the values POV-Ray 3.7 renders for them (measured once; no POV-Ray needed here).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include <refract/core/compat/povray_mesh.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/icosphere.h>

using namespace refract;

namespace {

// A value as single precision stores it (through memory, as the implementation does).
double single(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

Scene validation_case(const std::string& name, const std::string& compat) {
    std::ifstream in(std::string(REFRACT_SOURCE_DIR) + "/scenes/validation/" + name + ".json");
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json j = nlohmann::json::parse(text.str());
    j["render"]["compat"] = compat;
    return parse_scene(j, name + ".json");
}

}  // namespace

TEST_CASE("POV-Ray's mesh2: single-precision vertices, normal and plane distance, the hit keeps the stored normal",
          "[povray-mesh]") {
    // Six-digit vertices (the random scenes' kind), none exact in single precision.
    TriangleMesh m;
    m.vertices = {Vec3(2.30334, 1.97759, 1.38842), Vec3(1.95254, 1.7687, 1.23469), Vec3(2.13243, 1.79494, 1.54121)};
    m.triangles = {Eigen::Vector3i(0, 1, 2)};
    const povray::Mesh pm(m);
    const Vec3 c = (m.vertices[0] + m.vertices[1] + m.vertices[2]) / 3;
    const Vec3 d = Vec3(0.3, -0.4, -0.1).normalized();
    const Ray r{c - 3 * d, d};
    const auto h = pm.intersect(r, 1e-4, 1e7);
    REQUIRE(h);
    // The stored normal: (P3 − P1) × (P2 − P1) of the single-precision vertices, normalised
    // in double and stored in single precision; negated, the outward normal.
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = Vec3(single(m.vertices[k].x()), single(m.vertices[k].y()), single(m.vertices[k].z()));
    const Vec3 unit = (p[2] - p[0]).cross(p[1] - p[0]).normalized();
    const Vec3 stored(single(unit.x()), single(unit.y()), single(unit.z()));
    CHECK(h->normal == -stored);
    CHECK(h->normal.norm() != 1.0);  // not renormalised
    CHECK(std::abs(h->normal.norm() - 1.0) < 1e-7);
    // The double triangle's normal differs by the rounding of its vertices (~1e-7 here).
    const double off = (h->normal - triangle_normal(m, 0)).norm();
    CHECK(off > 1e-8);
    CHECK(off < 1e-6);
    // t from the stored plane: −(d + n·o)/(n·dir), d = −n·P1 in single precision.
    const double dist = single(-(unit.x() * p[0].x() + unit.y() * p[0].y() + unit.z() * p[0].z()));
    const double nd = stored.x() * d.x() + stored.y() * d.y() + stored.z() * d.z();
    const double no = stored.x() * r.origin.x() + stored.y() * r.origin.y() + stored.z() * r.origin.z();
    CHECK(h->t == -(dist + no) / nd);
    CHECK(h->point == r.at(h->t));
    CHECK(h->facet == 0);
    // Nothing before t_min, nothing past t_max, nothing behind.
    CHECK_FALSE(pm.intersect(r, 1e-4, 2.5));
    CHECK_FALSE(pm.intersect(Ray{c + 3 * d, d}, 1e-4, 1e7));
}

TEST_CASE("POV-Ray's mesh2: its edges and vertices belong to both triangles (tests with <)", "[povray-mesh]") {
    // Two triangles in the plane z = 0 sharing the edge x = y (exact in single precision).
    TriangleMesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    m.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 2, 3)};
    const povray::Mesh pm(m);
    for (const Vec3& at : {Vec3(0.5, 0.5, 0), Vec3(1, 1, 0), Vec3(0, 0, 0), Vec3(0.25, 0, 0)}) {
        const auto h = pm.intersect(Ray{at + Vec3(0, 0, 2), Vec3(0, 0, -1)}, 1e-4, 1e7);
        REQUIRE(h);
        CHECK(h->t == 2.0);
    }
    CHECK_FALSE(pm.intersect(Ray{Vec3(0.5, -1e-9, 2), Vec3(0, 0, -1)}, 1e-4, 1e7));
    // A crossing through the shared edge is one crossing.
    CHECK(pm.crossings(Ray{Vec3(0.5, 0.5, 2), Vec3(0, 0, -1)}, 10, -1) == 1);
}

TEST_CASE("POV-Ray's mesh2: the BVH over triangles gives the plain scan's hits, and crossings are counted once",
          "[povray-mesh]") {
    const TriangleMesh m = icosphere(2, Vec3(0.31, -0.17, 0.09), 1.23);  // 320 triangles
    REQUIRE(m.triangles.size() >= povray::Mesh::kMinBvhTriangles);
    const povray::Mesh pm(m);
    std::vector<povray::Mesh> one;  // each triangle alone: the plain scan, triangle by triangle
    for (const auto& t : m.triangles) one.emplace_back(TriangleMesh{m.vertices, {t}});
    std::mt19937_64 g(7);
    std::normal_distribution<double> n;
    int hits = 0;
    for (int k = 0; k < 3000; ++k) {
        const Vec3 o = Vec3(0.31, -0.17, 0.09) + 3.0 * Vec3(n(g), n(g), n(g)).normalized();
        const Vec3 aim = Vec3(0.31, -0.17, 0.09) + 1.4 * Vec3(n(g), n(g), n(g)).normalized() * std::abs(n(g)) * 0.6;
        const Ray r{o, (aim - o).normalized()};
        std::optional<Hit> best;
        for (size_t f = 0; f < one.size(); ++f)
            if (const auto h = one[f].intersect(r, 1e-4, best ? best->t : 1e7); h && (!best || h->t < best->t)) {
                best = *h;
                best->facet = static_cast<int>(f);
            }
        const auto h = pm.intersect(r, 1e-4, 1e7);
        REQUIRE(bool(h) == bool(best));
        if (!h) continue;
        ++hits;
        CHECK(h->t == best->t);
        CHECK(h->facet == best->facet);
        // In through the sphere and out: two crossings; leaving the entry triangle, one.
        CHECK(pm.crossings(r, 1e7, -1) == 2);
        CHECK(pm.crossings(Ray{h->point, r.dir}, 1e7, h->facet) == 1);
    }
    CHECK(hits > 1000);
}

TEST_CASE("Compat mode follows POV-Ray's interior list: a ray that re-entered a mesh within 1e-4 still enters at its "
          "next hit (random seed 20261139, R6)",
          "[povray-mesh][compat]") {
    // The pixel where the two disagreed by 0.12: POV-Ray 3.7 renders (0.459190, 0.566033,
    // 0.248341) there (16-bit output); by the outward normal refract gave 0.3616 in red.
    const Scene s = validation_case("random-mesh-reentry", "povray");
    const Vec3 v = render_pixel(s, 29, 27);
    CHECK(v.x() == Approx(0.459190).margin(2e-5));
    CHECK(v.y() == Approx(0.566033).margin(2e-5));
    CHECK(v.z() == Approx(0.248341).margin(2e-5));
    // The physical mode keeps the normal's decision, as before.
    CHECK(render_pixel(validation_case("random-mesh-reentry", "physical"), 29, 27).x() < 0.45);
}

TEST_CASE("Compat mode meets meshes in POV-Ray's single precision (random seed 20261149, R7)", "[povray-mesh][compat]") {
    // POV-Ray 3.7 renders (0.016190, 0.009720, 0.072282) at this pixel; with double
    // triangles refract gave (0.0247, 0.0417, 0.0566).
    const Vec3 v = render_pixel(validation_case("random-mesh-single-precision", "povray"), 46, 31);
    CHECK(v.x() == Approx(0.016190).margin(2e-5));
    CHECK(v.y() == Approx(0.009720).margin(2e-5));
    CHECK(v.z() == Approx(0.072282).margin(2e-5));
}
