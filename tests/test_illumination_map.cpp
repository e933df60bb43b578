// Reconstruction of illumination maps (core/illumination_map.h): box and bilinear on
// plane maps, box and barycentric corner means on mesh maps; the scene field that picks
// them; and the error of the reconstructed caustic against a reference as photons grow.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

using namespace refract;

namespace {

// A linear RGB field on the floor (y = 0).
Vec3 linear_field(const Vec3& p) { return Vec3(1.0 + 0.3 * p.x() - 0.2 * p.z(), 2.0 + 0.5 * p.x(), 0.7 - 0.1 * p.z()); }

Hit at(const Vec3& p, int facet = -1) {
    Hit h;
    h.point = p;
    h.facet = facet;
    return h;
}

// 20 × 20 elements of edge 0.1 on the floor, centred on the origin.
IlluminationMap floor_map() { return IlluminationMap::for_plane(Plane{Vec3(0, 1, 0), 0}, Vec3(0, 0.5, 0), 1.0, 0.1); }

}  // namespace

TEST_CASE("Bilinear reconstruction of a linear irradiance field on a plane map is exact", "[light-pass][map]") {
    IlluminationMap m = floor_map();
    REQUIRE(m.cells() == 20);
    // An element's mean of a linear field is its value at the element's centre.
    for (int e = 0; e < m.elements(); ++e) m.irradiance[static_cast<size_t>(e)] = linear_field(m.centre(e));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-0.95, 0.95);  // between the outermost centres
    double worst_bilinear = 0, worst_box = 0;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 p(u(rng), 0, u(rng));
        worst_bilinear = std::fmax(worst_bilinear, (m.value(at(p), MapFilter::Bilinear) - linear_field(p)).cwiseAbs().maxCoeff());
        worst_box = std::fmax(worst_box, (m.value(at(p), MapFilter::Box) - linear_field(p)).cwiseAbs().maxCoeff());
    }
    CHECK(worst_bilinear < 1e-12);
    // The box is off by up to the gradient times half an element: 0.5 · 0.05 = 0.025.
    CHECK(worst_box > 0.02);
    CHECK(worst_box <= 0.025 + 1e-12);
}

TEST_CASE("Bilinear plane map: continuous across element edges, edge values held, zero outside", "[light-pass][map]") {
    IlluminationMap m = floor_map();
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 10.0);
    for (Vec3& v : m.irradiance) v = Vec3(u(rng), u(rng), u(rng));  // noise: a rough field
    // Across an element edge (x = 0.3) the bilinear value changes by O(ε), the box by a step.
    double jump_bilinear = 0, jump_box = 0;
    for (double z = -0.9; z < 0.9; z += 0.07) {
        const Vec3 a(0.3 - 1e-9, 0, z), b(0.3 + 1e-9, 0, z);
        jump_bilinear = std::fmax(jump_bilinear, (m.value(at(a), MapFilter::Bilinear) - m.value(at(b), MapFilter::Bilinear)).norm());
        jump_box = std::fmax(jump_box, (m.value(at(a), MapFilter::Box) - m.value(at(b), MapFilter::Box)).norm());
    }
    CHECK(jump_bilinear < 1e-6);
    CHECK(jump_box > 1.0);
    // At an element's centre both filters give the element's mean.
    const int e = 7 * 20 + 11;
    CHECK((m.value(at(m.centre(e)), MapFilter::Bilinear) - m.irradiance[e]).norm() < 1e-12);
    // Beyond the outermost centres (the half element along the map's edge) the edge value
    // is held: the corner element's value at the map's corner.
    CHECK((m.value(at(Vec3(0.999, 0, 0.999)), MapFilter::Bilinear) - m.irradiance[0]).norm() < 1e-12);
    // Outside the map: no caustic.
    CHECK(m.value(at(Vec3(1.01, 0, 0)), MapFilter::Bilinear) == Vec3(0, 0, 0));
    CHECK(m.value(at(Vec3(0, 0, -1.01)), MapFilter::Box) == Vec3(0, 0, 0));
}

TEST_CASE("A constant irradiance field stays constant under every filter, on plane and mesh maps", "[light-pass][map]") {
    const Vec3 c(0.25, 1.5, 3.0);
    IlluminationMap plane = floor_map();
    for (Vec3& v : plane.irradiance) v = c;
    TriangleMesh mesh;
    mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 0, 1), Vec3(1.3, 0, 0.9)};
    mesh.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(1, 3, 2)};
    IlluminationMap tri = IlluminationMap::for_mesh(mesh, 0.15);
    for (Vec3& v : tri.irradiance) v = c;
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 p(2 * u(rng) - 1, 0, 2 * u(rng) - 1);  // anywhere on the plane map, edges too
        for (const MapFilter f : {MapFilter::Box, MapFilter::Bilinear}) worst = std::fmax(worst, (plane.value(at(p), f) - c).norm());
        double s = u(rng), t = u(rng);  // anywhere on either triangle, edges too
        if (s + t > 1) s = 1 - s, t = 1 - t;
        const int facet = k % 2;
        const auto& T = mesh.triangles[static_cast<size_t>(facet)];
        const Vec3 q = mesh.vertices[T[0]] + s * (mesh.vertices[T[1]] - mesh.vertices[T[0]]) +
                       t * (mesh.vertices[T[2]] - mesh.vertices[T[0]]);
        for (const MapFilter f : {MapFilter::Box, MapFilter::Bilinear}) worst = std::fmax(worst, (tri.value(at(q, facet), f) - c).norm());
    }
    CHECK(worst < 1e-12);
}

TEST_CASE("Mesh map: barycentric corner means are exact for a linear field inside a triangle", "[light-pass][map]") {
    TriangleMesh mesh;
    const Vec3 a(0, 0, 0), b(1, 0, 0.1), c(0.1, 0, 1);
    mesh.vertices = {a, b, c};
    mesh.triangles = {Eigen::Vector3i(0, 1, 2)};
    IlluminationMap m = IlluminationMap::for_mesh(mesh, 0.1);
    const int k = static_cast<int>(std::lround(std::sqrt(static_cast<double>(m.elements()))));
    REQUIRE(k * k == m.elements());
    REQUIRE(k == 13);  // ceil(|b − c| / 0.1) = ceil(12.73)
    auto point = [&](double s, double r) { return a + (s / k) * (b - a) + (r / k) * (c - a); };
    // Each element's mean of a linear field: the value at its centroid.
    int filled = 0;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i + j < k; ++i)
            for (int up = 0; up < (i + j < k - 1 ? 2 : 1); ++up) {
                const Vec3 g = up ? point(i + 2.0 / 3, j + 2.0 / 3) : point(i + 1.0 / 3, j + 1.0 / 3);
                const int e = m.element(at(g, 0));
                REQUIRE(e >= 0);
                m.irradiance[static_cast<size_t>(e)] = linear_field(g);
                ++filled;
            }
    REQUIRE(filled == m.elements());
    // Points in elements whose corners lie inside the triangle (lattice a, b ≥ 1, a + b ≤ k − 1).
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(1.0, k - 2.0);
    double worst_bilinear = 0, worst_box = 0, worst_edge = 0;
    int tested = 0;
    for (int n = 0; n < 4000; ++n) {
        const double s = u(rng), r = u(rng);
        if (std::floor(s) + std::floor(r) + 2 > k - 1) continue;
        const Vec3 p = point(s, r);
        worst_bilinear = std::fmax(worst_bilinear, (m.value(at(p, 0), MapFilter::Bilinear) - linear_field(p)).cwiseAbs().maxCoeff());
        worst_box = std::fmax(worst_box, (m.value(at(p, 0), MapFilter::Box) - linear_field(p)).cwiseAbs().maxCoeff());
        ++tested;
    }
    REQUIRE(tested > 1000);
    CHECK(worst_bilinear < 1e-12);
    CHECK(worst_box > 0.01);
    // Along the triangle's edges the corner means are one-sided: biased, but no worse than
    // the box (the field changes by at most 0.04 across an element there).
    for (double s = 0.05; s < k; s += 0.37) {
        const Vec3 p = point(s, 0.0);
        worst_edge = std::fmax(worst_edge, (m.value(at(p, 0), MapFilter::Bilinear) - linear_field(p)).cwiseAbs().maxCoeff());
    }
    CHECK(worst_edge > 0);
    CHECK(worst_edge < 0.04);
}

TEST_CASE("Scene file: render.light_pass.filter picks the reconstruction, bilinear by default", "[light-pass][map][scene]") {
    nlohmann::json j = {
        {"camera", {{"location", {0, 2, -4}}, {"look_at", {0, 0, 0}}, {"width", 8}, {"height", 6}}},
        {"materials", {{"floor", {{"type", "diffuse"}, {"color", {0.8, 0.8, 0.8}}}}, {"glass", {{"type", "dielectric"}, {"ior", 1.5}}}}},
        {"objects",
         {{{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}},
          {{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 0.5}, {"material", "glass"}}}},
        {"lights", {{{"position", {0, 5, 0}}, {"color", {1, 1, 1}}}}},
        {"render", {{"light_pass", {{"photons", 1000}}}}}};
    CHECK(parse_scene(j, "f.json").settings.light_pass.filter == MapFilter::Bilinear);
    j["render"]["light_pass"]["filter"] = "box";
    CHECK(parse_scene(j, "f.json").settings.light_pass.filter == MapFilter::Box);
    j["render"]["light_pass"]["filter"] = "gaussian";
    CHECK_THROWS_WITH(parse_scene(j, "f.json"), Catch::Contains("f.json") &&
                                                    Catch::Contains("/render/light_pass/filter") &&
                                                    Catch::Contains("gaussian") && Catch::Contains("box, bilinear"));
    j["render"]["light_pass"]["filter"] = 1;
    CHECK_THROWS_WITH(parse_scene(j, "f.json"), Catch::Contains("/render/light_pass/filter"));
}

namespace {

// A glass sphere (n = 1.5) high above the floor under a point light: the floor lies
// below the focus, so the caustic is a broad disc.
Scene sphere_caustic(std::uint64_t photons, std::uint64_t seed, double element) {
    const nlohmann::json j = {
        {"camera", {{"location", {0, 4, -4}}, {"look_at", {0, 0, 0}}, {"width", 8}, {"height", 6}}},
        {"materials", {{"floor", {{"type", "diffuse"}, {"color", {0.8, 0.8, 0.8}}}}, {"glass", {{"type", "dielectric"}, {"ior", 1.5}}}}},
        {"objects",
         {{{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}},
          {{"type", "sphere"}, {"center", {0, 4, 0}}, {"radius", 1.0}, {"material", "glass"}}}},
        {"lights", {{{"position", {0.5, 9, 0.3}}, {"color", {1, 1, 1}}}}},
        {"render",
         {{"max_depth", 6},
          {"light_pass", {{"photons", photons}, {"element_size", element}, {"region", 2}, {"seed", seed}}}}}};
    return parse_scene(j, "sphere caustic");
}

std::shared_ptr<IlluminationMaps> maps_of(const Scene& s) { return light_pass(s, SpectralContext::build(s), 0); }

// Relative RMS of map `a` (read with `f`) against the reference (finer elements,
// bilinear) at a grid of points under the sphere.
double rel_error(const IlluminationMap& a, MapFilter f, const IlluminationMap& ref) {
    double e = 0, n = 0;
    for (double x = -1.9; x <= 1.9; x += 0.013)
        for (double z = -1.9; z <= 1.9; z += 0.013) {
            const Vec3 r = ref.value(at(Vec3(x, 0, z)), MapFilter::Bilinear);
            e += (a.value(at(Vec3(x, 0, z)), f) - r).squaredNorm();
            n += r.squaredNorm();
        }
    return std::sqrt(e / n);
}

}  // namespace

TEST_CASE("Caustic error falls with photon count, bilinear below box at every count",
          "[light-pass][map][statistical]") {
    const auto ref = maps_of(sphere_caustic(1600000, 99, 0.04));
    const IlluminationMap& r = *ref->by_object[0];
    std::vector<double> box, bil;
    for (const std::uint64_t n : {5000u, 20000u, 80000u}) {
        const auto m = maps_of(sphere_caustic(n, 7, 0.08));
        box.push_back(rel_error(*m->by_object[0], MapFilter::Box, r));
        bil.push_back(rel_error(*m->by_object[0], MapFilter::Bilinear, r));
    }
    INFO("box " << box[0] << " " << box[1] << " " << box[2] << "; bilinear " << bil[0] << " " << bil[1] << " " << bil[2]);
    // Measured: box 0.526, 0.263, 0.138; bilinear 0.346, 0.177, 0.091 (0.66 of the box:
    // bilinear weights average white noise down to 2/3).
    for (size_t k = 0; k < 3; ++k) CHECK(bil[k] < 0.75 * box[k]);
    for (size_t k = 0; k + 1 < 3; ++k) {  // noise-bound: about 1/2 per 4× photons
        CHECK(bil[k + 1] < 0.6 * bil[k]);
        CHECK(box[k + 1] < 0.6 * box[k]);
    }
    CHECK(bil[2] < 0.1);
}

TEST_CASE("Mesh map: a hit on a triangle's long edge stays in that triangle's elements", "[light-pass][map]") {
    // Two triangles cut into k = 2: the midpoint of the first one's long edge is a lattice
    // point (1, 1), whose cell does not exist; it belongs to a lower triangle of its own.
    TriangleMesh mesh;
    mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)};
    mesh.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(1, 3, 2)};
    IlluminationMap m = IlluminationMap::for_mesh(mesh, 0.75);
    REQUIRE(m.elements() == 8);
    for (int e = 0; e < 8; ++e) m.irradiance[static_cast<size_t>(e)] = Vec3::Constant(e < 4 ? 1.0 : 100.0);
    for (const Vec3& p : {Vec3(0.5, 0, 0.5), Vec3(0.5 + 1e-13, 0, 0.5 + 1e-13), Vec3(1, 0, 0), Vec3(0, 0, 1)}) {
        INFO("point " << p.transpose());
        const int e = m.element(at(p, 0));
        CHECK(e >= 0);
        CHECK(e < 4);
        CHECK(m.value(at(p, 0), MapFilter::Box) == Vec3::Constant(1.0));
        CHECK((m.value(at(p, 0), MapFilter::Bilinear) - Vec3::Constant(1.0)).norm() < 1e-12);
    }
}
