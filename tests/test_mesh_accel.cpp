// The search structures against the linear searches they replace: Embree's BVH for a
// triangle mesh (geometry/mesh_accel.h, refined in double) against the Möller–Trumbore
// loop, and the BVH over objects (geometry/object_bvh.h, used by SceneTracer from
// kBvhMinObjects objects) against the in-order nearest-hit loop, ties included.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "core/tracer.h"
#include "geometry/gem/brilliant.h"
#include "geometry/icosphere.h"
#include "geometry/mesh_accel.h"
#include "geometry/object_bvh.h"

using namespace refract;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec3 random_unit(std::mt19937_64& g) {
    std::normal_distribution<double> n;
    return Vec3(n(g), n(g), n(g)).normalized();
}

}  // namespace

TEST_CASE("Icosphere: 20·4^s triangles, closed, wound counter-clockwise seen from outside", "[geometry][mesh]") {
    for (int s : {0, 1, 3}) {
        const TriangleMesh m = icosphere(s, Vec3(1, 2, 3), 2.0);
        REQUIRE(m.triangles.size() == static_cast<size_t>(20 * std::pow(4, s)));
        // Euler: V − E + F = 2 with E = 3F/2 for a closed triangle mesh.
        REQUIRE(static_cast<long>(m.vertices.size()) - static_cast<long>(m.triangles.size()) / 2 == 2);
        for (size_t k = 0; k < m.triangles.size(); ++k) {
            const Vec3 c = (m.vertices[m.triangles[k][0]] + m.vertices[m.triangles[k][1]] + m.vertices[m.triangles[k][2]]) / 3;
            REQUIRE(triangle_normal(m, k).dot((c - Vec3(1, 2, 3)).normalized()) > 0.95);
        }
        for (const Vec3& v : m.vertices) REQUIRE((v - Vec3(1, 2, 3)).norm() == Approx(2.0).epsilon(1e-14));
    }
}

TEST_CASE("Embree mesh search: the linear Möller–Trumbore search's hits, t to the last bit on the same triangle",
          "[geometry][mesh]") {
    const TriangleMesh m = icosphere(3, Vec3(0.3, -0.2, 0.1), 1.0);  // 1 280 triangles
    const MeshAccel accel(m);
    std::mt19937_64 g(12);
    std::uniform_real_distribution<double> u(0, 1);
    int rays = 0, hits = 0, same_facet = 0, other_facet = 0, inside_hits = 0;
    for (int n = 0; n < 20000; ++n) {
        // From outside towards a point near the sphere (about 3/4 of them hit).
        const Vec3 o = Vec3(0.3, -0.2, 0.1) + 3.0 * random_unit(g);
        const Vec3 aim = Vec3(0.3, -0.2, 0.1) + 1.3 * std::cbrt(u(g)) * random_unit(g);
        Ray r{o, (aim - o).normalized()};
        for (int bounce = 0; bounce < 3; ++bounce) {
            ++rays;
            const double t_min = bounce == 0 ? 0.0 : 1e-6;
            const auto a = intersect(m, r, t_min, kInf);
            const auto b = accel.intersect(r, t_min, kInf);
            REQUIRE(a.has_value() == b.has_value());
            if (!a) break;
            ++hits;
            if (a->facet == b->facet) {
                ++same_facet;
                REQUIRE(a->t == b->t);
                REQUIRE(a->normal == b->normal);
            } else {
                ++other_facet;  // an edge or vertex: the same point to rounding
                REQUIRE(std::abs(a->t - b->t) < 1e-12);
            }
            if (bounce > 0) ++inside_hits;
            // Straight on from the surface point: the chord to the far side, then out.
            r = Ray{a->point, r.dir};
        }
    }
    INFO("rays " << rays << ", hits " << hits << ", other facet " << other_facet);
    CHECK(hits > 25000);
    CHECK(inside_hits > 12000);  // rays starting on the surface: no self-hit, the far side found
    CHECK(other_facet <= hits / 10000);
    // A window that excludes the hit: none (a ray clear of vertices and edges).
    const Ray r{Vec3(0.31, -0.187, -5), Vec3(0, 0, 1)};
    const auto near = accel.intersect(r, 0, kInf);
    REQUIRE(near);
    REQUIRE_FALSE(accel.intersect(r, 0, near->t));
    REQUIRE(accel.intersect(r, near->t, kInf)->t > near->t + 1.5);  // the far side
}

TEST_CASE("Object BVH: the in-order nearest-hit search's object and t, exact ties to the object first in order",
          "[geometry][bvh]") {
    Scene s;
    s.materials.push_back({"white", material::Diffuse{}});
    std::mt19937_64 g(7);
    std::uniform_real_distribution<double> u(-10, 10), rad(0.05, 0.6);
    for (int k = 0; k < 600; ++k)
        s.objects.push_back({"s" + std::to_string(k), Sphere{Vec3(u(g), u(g), u(g)), rad(g)}, 0});
    // Coincident copies (exact ties), a floor plane (unbounded) and a mesh.
    for (int k = 0; k < 100; k += 7) s.objects.push_back({"copy", s.objects[static_cast<size_t>(k)].shape, 0});
    s.objects.push_back({"floor", Plane{Vec3(0, 1, 0), -9.5}, 0});
    s.objects.push_back({"ball", icosphere(2, Vec3(1, 1, 1), 1.5), 0});
    const SceneTracer tracer(s);
    RenderStats st;
    int hits = 0, ties = 0;
    for (int n = 0; n < 20000; ++n) {
        const Vec3 o(u(g), u(g), u(g));
        const Ray r{o, random_unit(g)};
        // The linear search in scene order (physical mode tests the objects in scene order).
        std::optional<Hit> best;
        const Object* best_o = nullptr;
        double t_max = kInf;
        int at_best = 0;
        for (const Object& obj : s.objects) {
            const auto h = intersect(obj.shape, r, SceneTracer::kEpsilon, t_max);
            if (h) {
                t_max = h->t;
                best = h;
                best_o = &obj;
            }
        }
        for (const Object& obj : s.objects)
            if (best) {
                const auto h = intersect(obj.shape, r, SceneTracer::kEpsilon, kInf);
                at_best += h && h->t == best->t;
            }
        const auto b = tracer.intersect(r, st);
        REQUIRE(best.has_value() == b.has_value());
        if (!best) continue;
        ++hits;
        ties += at_best > 1;
        REQUIRE(b->object == best_o);
        REQUIRE(b->hit.t == best->t);
    }
    CHECK(hits > 10000);
    CHECK(ties > 50);  // the coincident copies were met, and the first one kept
}

TEST_CASE("A convex polyhedron as a mesh (mesh_of, for POV-Ray's mesh2) is the same solid: hits agree",
          "[geometry][mesh]") {
    // A box cut by its corner planes: 6 + 8 faces.
    ConvexPolyhedron c;
    for (int a = 0; a < 3; ++a)
        for (double sgn : {-1.0, 1.0}) {
            Vec3 n(0, 0, 0);
            n[a] = sgn;
            c.planes.push_back({n, 1.0});
        }
    for (double x : {-1.0, 1.0})
        for (double y : {-1.0, 1.0})
            for (double z : {-1.0, 1.0}) c.planes.push_back({Vec3(x, y, z).normalized(), 2.5 / std::sqrt(3.0)});
    const TriangleMesh m = mesh_of(c);
    // Euler for the closed mesh; 6 octagons and 8 triangles fanned: 6·6 + 8 triangles.
    REQUIRE(m.vertices.size() == 24);
    REQUIRE(m.triangles.size() == 44);
    for (size_t k = 0; k < m.triangles.size(); ++k) {
        const Vec3 centre = (m.vertices[m.triangles[k][0]] + m.vertices[m.triangles[k][1]] + m.vertices[m.triangles[k][2]]) / 3;
        REQUIRE(triangle_normal(m, k).dot(centre) > 0);  // outward
    }
    // And the round brilliant (121 planes), against its construction's own mesh size.
    const Gem gem = build_brilliant(BrilliantCut{});
    const TriangleMesh gm = mesh_of(gem.solid);
    REQUIRE(gm.vertices.size() == gem.mesh.vertices.size());
    REQUIRE(gm.triangles.size() == gem.mesh.triangles.size());
    std::mt19937_64 g(3);
    std::uniform_real_distribution<double> u(0, 1);
    using Pair = std::pair<const ConvexPolyhedron*, const TriangleMesh*>;
    for (const auto& [solid, mesh] : {Pair{&c, &m}, Pair{&gem.solid, &gm}}) {
        int hits = 0;
        for (int n = 0; n < 5000; ++n) {
            const Vec3 o = 4.0 * random_unit(g), aim = 1.2 * std::cbrt(u(g)) * random_unit(g);
            const Ray r{o, (aim - o).normalized()};
            const auto a = intersect(*solid, r, 0, kInf);
            const auto b = intersect(*mesh, r, 0, kInf);
            REQUIRE(a.has_value() == b.has_value());
            if (!a) continue;
            ++hits;
            REQUIRE(b->t == Approx(a->t).margin(1e-12));
            REQUIRE(b->normal.dot(a->normal) == Approx(1.0).margin(1e-12));
        }
        CHECK(hits > 2000);
    }
}
