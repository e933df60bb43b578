// The search structures against the linear searches they replace: Embree's BVH for a
// triangle mesh (geometry/mesh_accel.h, refined in double) against the Möller–Trumbore
// loop, and the BVH over objects (geometry/object_bvh.h, used by SceneTracer from
// kBvhMinObjects objects) against the in-order nearest-hit loop, ties included, and the
// spheres tested together (geometry/sphere_set.h) against the same loop, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include <refract/core/tracer.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/icosphere.h>
#include <refract/geometry/mesh_accel.h>
#include <refract/geometry/object_bvh.h>
#include <refract/geometry/sphere_set.h>

#include "hit_bits.h"

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

// Random rays of the Embree test: fewer in the sanitizer build (ten times slower).
#ifdef REFRACT_SANITIZED
constexpr int kMeshRays = 1000;
#else
constexpr int kMeshRays = 20000;
#endif

TEST_CASE("Embree mesh search: the linear Möller–Trumbore search's hits, t to the last bit on the same triangle",
          "[geometry][mesh]") {
    const TriangleMesh m = icosphere(3, Vec3(0.3, -0.2, 0.1), 1.0);  // 1 280 triangles
    const MeshAccel accel(m);
    std::mt19937_64 g(12);
    std::uniform_real_distribution<double> u(0, 1);
    int rays = 0, hits = 0, same_facet = 0, other_facet = 0, inside_hits = 0;
    for (int n = 0; n < kMeshRays; ++n) {
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
    CHECK(hits > 25000 / (20000 / kMeshRays));
    CHECK(inside_hits > 12000 / (20000 / kMeshRays));  // rays starting on the surface: no self-hit, the far side found
    CHECK(other_facet <= std::max(1, hits / 10000));
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

TEST_CASE("Sphere set: the in-order nearest-hit search's object, t, point and normal to the last bit, exact ties to "
          "the object first in order",
          "[geometry][spheres]") {
    // 40 spheres (hollow ones among them), coincident copies, a plane and a mesh between
    // them in the list, and a plane set: below the BVH's threshold, so the tracer tests the
    // spheres together and the rest one by one. Rays from random points, and rays leaving
    // a sphere's surface (reflected and refracted directions alike: random).
    Scene s;
    s.materials.push_back({"white", material::Diffuse{}});
    std::mt19937_64 g(11);
    std::uniform_real_distribution<double> u(-4, 4), rad(0.2, 1.5), sign(0, 1);
    for (int k = 0; k < 40; ++k) {
        const double r = rad(g) * (sign(g) < 0.2 ? -1 : 1);
        s.objects.push_back({"s" + std::to_string(k), Sphere{Vec3(u(g), u(g), u(g)), r}, 0});
        if (k == 10) s.objects.push_back({"floor", Plane{Vec3(0, 1, 0), -3.9}, 0});
        if (k == 20) s.objects.push_back({"ball", icosphere(2, Vec3(0.5, 0.5, 0.5), 1.2), 0});
    }
    for (int k = 0; k < 40; k += 9) s.objects.push_back({"copy", s.objects[static_cast<size_t>(k)].shape, 0});
    s.objects.push_back({"mirror", Plane{Vec3(0, 0, 1), 3.5}, 0});
    REQUIRE(s.objects.size() < HitSearch::kBvhMinObjects);
    const SceneTracer tracer(s);
    RenderStats st;
    long hits = 0, ties = 0, leaving = 0, mismatches = 0;
    for (int n = 0; n < 40000; ++n) {
        Ray r{Vec3(u(g), u(g), u(g)), test::random_direction(g)};
        RayOrigin from;
        if (n % 2 == 1) {  // from the surface of a sphere this ray meets
            const auto h = tracer.intersect(r, st);
            if (!h || !std::holds_alternative<Sphere>(h->object->shape)) continue;
            from = tracer.origin_of(*h);
            r = Ray{h->hit.point, test::random_direction(g)};
            ++leaving;
        }
        // The search it replaces: in scene order, strictly nearer replaces; a ray leaving a
        // sphere away from its centre skips it.
        std::optional<Hit> best;
        int best_k = -1, at_best = 0;
        double t_max = kInf;
        for (size_t k = 0; k < s.objects.size(); ++k) {
            const auto* sp = std::get_if<Sphere>(&s.objects[k].shape);
            if (static_cast<int>(k) == from.object && sp && (r.origin - sp->center).dot(r.dir) > 0) continue;
            if (const auto h = intersect(s.objects[k].shape, r, SceneTracer::kEpsilon, t_max)) {
                t_max = h->t;
                best = h;
                best_k = static_cast<int>(k);
            }
        }
        const auto b = tracer.intersect(r, st, from);
        if (best)
            for (const Object& obj : s.objects) {
                const auto h = intersect(obj.shape, r, SceneTracer::kEpsilon, kInf);
                at_best += h && h->t == best->t;
            }
        hits += best.has_value();
        ties += at_best > 1;
        const std::optional<Hit> got = b ? std::optional<Hit>(b->hit) : std::nullopt;
        mismatches += !test::identical(got, best) || (b && b->object != &s.objects[static_cast<size_t>(best_k)]);
    }
    INFO(hits << " hits, " << ties << " exact ties, " << leaving << " rays leaving a sphere");
    CHECK(hits > 20000);
    CHECK(ties > 100);
    CHECK(leaving > 5000);
    CHECK(mismatches == 0);
    // The set alone against each sphere's own test, on rays through many of them, one ray
    // and packets of eight (each lane its own window and starting sphere), under every
    // variant this CPU runs.
    SphereSet set;
    std::vector<Sphere> list;
    for (int k = 0; k < 70; ++k) {  // more than one block of 8, more than the stack's 64
        list.push_back(Sphere{Vec3(u(g), u(g), u(g)), rad(g) * (k % 5 == 0 ? -1 : 1)});
        set.add(list.back());
    }
    // The in-order search with the sphere `from` skipped when the ray leaves its centre.
    const auto reference = [&](const Ray& r, double t_min, double t_max, int from) {
        std::optional<Hit> best;
        int best_k = -1;
        for (size_t k = 0; k < list.size(); ++k) {
            if (static_cast<int>(k) == from && (r.origin - list[k].center).dot(r.dir) > 0) continue;
            if (const auto h = intersect(list[k], r, t_min, t_max)) {
                t_max = h->t;
                best = h;
                best_k = static_cast<int>(k);
            }
        }
        return std::make_pair(best, best_k);
    };
    for (const SlabIsa isa : {SlabIsa::baseline, SlabIsa::avx2, SlabIsa::avx512f}) {
        if (!slab_isa_supported(isa)) continue;
        INFO(slab_isa_name(isa));
        SphereSet::use_isa(isa);
        long set_mismatches = 0, lane_mismatches = 0, lane_hits = 0;
        for (int n = 0; n < 4000; ++n) {
            const Ray r{Vec3(u(g), u(g), u(g)), test::random_direction(g)};
            const double t_min = n % 3 == 0 ? 0.0 : 1e-6, t_max = n % 5 == 0 ? 2.0 : kInf;
            const auto [best, best_k] = reference(r, t_min, t_max, -1);
            const auto got = set.nearest(r, t_min, t_max);
            set_mismatches += got.has_value() != best.has_value() ||
                              (got && (static_cast<int>(got->index) != best_k ||
                                       !test::identical(sphere_hit(list[got->index], r, got->t), best)));
            // A packet: lanes from random points and from sphere surfaces, some inactive.
            LaneVec3 o, d;
            LaneMask active;
            SphereSet::LaneHits io;
            std::array<std::int32_t, kLanes> from;
            std::array<Ray, kLanes> rays;
            for (int l = 0; l < kLanes; ++l) {
                const size_t i = static_cast<size_t>(l);
                rays[i] = Ray{Vec3(u(g), u(g), u(g)), test::random_direction(g)};
                from[i] = -1;
                if (l % 2 == 1 && best) {  // from the first ray's hit, in a random direction
                    rays[i] = Ray{best->point, test::random_direction(g)};
                    from[i] = best_k;
                }
                o.set(l, rays[i].origin);
                d.set(l, rays[i].dir);
                active[l] = (n + l) % 7 != 0;
                io.best[l] = l % 3 == 0 ? 3.0 : kInf;
                io.index[i] = -1;
            }
            set.nearest_lanes(o, d, active, t_min, from, io);
            for (int l = 0; l < kLanes; ++l) {
                const size_t i = static_cast<size_t>(l);
                if (!active[l]) {
                    lane_mismatches += io.hit[l];
                    continue;
                }
                const auto [want, want_k] = reference(rays[i], t_min, l % 3 == 0 ? 3.0 : kInf, from[i]);
                if (io.hit[l] != want.has_value()) {
                    ++lane_mismatches;
                    continue;
                }
                if (!want) continue;
                ++lane_hits;
                const Hit h{io.best[l], io.point.lane(l), io.normal.lane(l), -1};
                lane_mismatches += io.index[i] != want_k || !test::identical(h, want);
            }
        }
        CHECK(set_mismatches == 0);
        CHECK(lane_hits > 5000);
        CHECK(lane_mismatches == 0);
    }
    SphereSet::use_isa(slab_isa());
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
