// Facet-local intersection (geometry/facet_graph.h): a ray leaving a facet of a convex
// plane set, decided from the planes around that facet and a guessed leaving facet, gives
// the full plane loop's hit to the last bit, for right and wrong guesses; and whole
// renders of the 1998 diamond are the same image with it and without it. A ray leaving a
// sphere likewise meets what the full search over the spheres finds.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/light_pass.h>
#include <refract/core/optics.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/tracer.h>
#include <refract/geometry/facet_graph.h>
#include <refract/geometry/lanes_wide.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/shapes.h>
#include "tests/hit_bits.h"

using namespace refract;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using test::bits;
using test::identical;
using test::lane_hit;
using test::random_direction;

// Compares the graph's decided answers with the full loop for rays leaving hits.
struct Comparison {
    long rays = 0, decided = 0, decided_right_guess = 0, right_guesses = 0, mismatches = 0, outward = 0,
         outward_decided = 0;

    void leave(const ConvexPolyhedron& c, const FacetGraph& g, const Hit& from, const Vec3& dir, std::mt19937_64& rng) {
        const Ray r{from.point, dir};
        for (const double t_max : {kInf, 0.05}) {
            const auto want = intersect(c, r, 1e-6, t_max);
            const bool out = dir.dot(c.planes[static_cast<size_t>(from.facet)].normal) > 0;
            const int right = want ? want->facet : -1;
            std::uniform_int_distribution<int> any(0, static_cast<int>(c.planes.size()) - 1);
            for (const int guess : {right, any(rng), -1}) {
                ++rays;
                const FacetGraph::Local l = g.intersect(c, r, 1e-6, t_max, from.facet, guess);
                if (out) {
                    ++outward;
                    outward_decided += l.decided;
                }
                if (!l.decided) continue;
                ++decided;
                if (guess == right && right >= 0) ++decided_right_guess;
                if (!identical(l.hit, want)) ++mismatches;
            }
            if (!out && right >= 0) ++right_guesses;
        }
    }
};

// Rays from outside onto c, then from each hit inward and outward in random directions.
// `aim`: c with its bounding sphere, to aim the rays.
Comparison compare_from_hits(const ConvexPolyhedron& c, const ConvexPolyhedron& aim, int rays, std::uint64_t seed) {
    const FacetGraph g(c);
    std::mt19937_64 rng(seed);
    Comparison cmp;
    for (int i = 0; i < rays; ++i) {
        const Vec3 from = aim.bound_center + 3 * aim.bound_radius * random_direction(rng);
        const Vec3 to = aim.bound_center + 0.9 * aim.bound_radius * random_direction(rng);
        const auto hit = intersect(c, Ray{from, (to - from).normalized()}, 0, kInf);
        if (!hit) continue;
        const Vec3 n = c.planes[static_cast<size_t>(hit->facet)].normal;
        Vec3 d = random_direction(rng);
        if (d.dot(n) > 0) d = -d;
        cmp.leave(c, g, *hit, d, rng);  // inward
        cmp.leave(c, g, *hit, -d, rng);  // outward
        // Grazing the facet, inward.
        Vec3 along = d - d.dot(n) * n;
        if (along.norm() > 1e-9) cmp.leave(c, g, *hit, (along.normalized() - 1e-9 * n).normalized(), rng);
    }
    return cmp;
}

// The variants of the vectorised kernels this CPU runs (FacetGraph::use_isa, use_wide_isa).
std::vector<SlabIsa> supported_variants() {
    std::vector<SlabIsa> v;
    for (const SlabIsa isa : {SlabIsa::baseline, SlabIsa::avx2, SlabIsa::avx512f})
        if (slab_isa_supported(isa)) v.push_back(isa);
    return v;
}

ConvexPolyhedron brilliant() {
    const Gem gem = build_brilliant(BrilliantCut{});
    ConvexPolyhedron c = gem.solid;
    set_bound(c, gem.mesh.vertices);
    return c;
}

// A packet test of the lanes of `active` against each lane's one-ray facet-local answer
// (decided or not, and the hit to the last bit) and the full plane loop's: counts the
// lanes, those decided locally and the mismatches.
void compare_packet(const FacetGraph& g, const ConvexPolyhedron& c, const LaneVec3& o, const LaneVec3& d,
                    const LaneMask& active, double t_min, const Lanes& t_max, int from,
                    const std::array<std::int32_t, kLanes>& guess, long& lanes, long& decided, long& mismatches) {
    const FacetGraph::LocalLanes loc = g.intersect_lanes(c, o, d, active, t_min, t_max, from, guess);
    for (int l = 0; l < kLanes; ++l) {
        if (!active[l]) continue;
        ++lanes;
        const Ray r{o.lane(l), d.lane(l)};
        const FacetGraph::Local one = g.intersect(c, r, t_min, t_max[l], from, guess[static_cast<size_t>(l)]);
        if (loc.decided[l] != one.decided) {
            ++mismatches;
            continue;
        }
        if (!one.decided) continue;
        ++decided;
        std::optional<Hit> got;
        if (loc.hit[l])
            got = Hit{loc.t[l], loc.point.lane(l), c.planes[static_cast<size_t>(loc.facet[static_cast<size_t>(l)])].normal,
                      loc.facet[static_cast<size_t>(l)]};
        mismatches += !identical(got, one.hit) || !identical(got, intersect(c, r, t_min, t_max[l]));
    }
}

}  // namespace

TEST_CASE("Facet-local intersection equals the full plane loop bit for bit on the round brilliant", "[geometry]") {
    const ConvexPolyhedron c = brilliant();
    const FacetGraph g(c);
    int usable = 0;
    for (int f = 0; f < g.facets(); ++f) usable += g.usable(f);
    CHECK(usable >= 57);  // every facet of the cut (bruted girdle facets included)
    for (int f = 0; f < g.facets(); ++f)
        if (g.usable(f)) {
            CHECK(g.gap(f) > 100 * g.tolerance());
            CHECK(g.neighbours(f).size() >= 3);
        }
    // Under every variant of the vectorised plane test the CPU runs.
    for (const SlabIsa isa : supported_variants()) {
        INFO(slab_isa_name(isa));
        FacetGraph::use_isa(isa);
        const Comparison cmp = compare_from_hits(c, c, 20000, 3);
        INFO(cmp.rays << " rays, " << cmp.decided << " decided locally");
        CHECK(cmp.rays > 100000);
        CHECK(cmp.mismatches == 0);
        // Outward rays are always decided; inward ones with the right guess nearly always.
        CHECK(cmp.outward_decided == cmp.outward);
        CHECK(cmp.decided_right_guess > 0.99 * cmp.right_guesses);
    }
    FacetGraph::use_isa(slab_isa());
}

TEST_CASE("Facet-local intersection equals the full plane loop on rays from the brilliant's vertices and edges", "[geometry]") {
    const Gem gem = build_brilliant(BrilliantCut{});
    ConvexPolyhedron c = gem.solid;
    set_bound(c, gem.mesh.vertices);
    const FacetGraph g(c);
    std::mt19937_64 rng(5);
    Comparison cmp;
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : gem.mesh.vertices) centre += v / static_cast<double>(gem.mesh.vertices.size());
    for (const GemFacet& f : gem.facets)
        for (size_t i = 0; i < f.polygon.size(); ++i) {
            const Vec3& p = f.polygon[i];
            const Vec3& q = f.polygon[(i + 1) % f.polygon.size()];
            for (const Vec3& at : {p, Vec3(0.5 * (p + q))}) {
                // The hit the full loop reports for a ray aimed at the corner or the edge.
                const auto hit = intersect(c, Ray{2 * at - centre, (centre - at).normalized()}, 0, kInf);
                if (!hit) continue;
                for (int k = 0; k < 4; ++k) {
                    const Vec3 d = random_direction(rng);
                    cmp.leave(c, g, *hit, d, rng);
                }
                cmp.leave(c, g, *hit, (centre - hit->point).normalized(), rng);
            }
        }
    INFO(cmp.rays << " rays, " << cmp.decided << " decided locally");
    CHECK(cmp.rays > 5000);
    CHECK(cmp.mismatches == 0);
}

TEST_CASE("Facet-local intersection equals the full plane loop on random polyhedra", "[geometry]") {
    std::mt19937_64 rng(17);
    long rays = 0, mismatches = 0, decided = 0;
    for (int shape = 0; shape < 40; ++shape) {
        // The hull of random tangent planes of the unit sphere: 8 to 80 facets.
        std::uniform_int_distribution<int> count(8, 80);
        ConvexPolyhedron c;
        const int n = count(rng);
        for (int k = 0; k < n; ++k) {
            const Vec3 nrm = random_direction(rng);
            c.planes.push_back(Plane{nrm, 1.0 + 0.2 * std::uniform_real_distribution<double>(0, 1)(rng)});
        }
        const std::vector<Vec3> corners = vertices(c);
        if (corners.empty()) continue;
        // Half of them without a bounding sphere (as the scene reader's polyhedra): the
        // graph finds one of its own; the rays are aimed with the corners' sphere.
        ConvexPolyhedron aim = c;
        set_bound(aim, corners);
        if (shape % 2 == 0) c = aim;
        const Comparison cmp = compare_from_hits(c, aim, 500, 100 + static_cast<std::uint64_t>(shape));
        rays += cmp.rays;
        mismatches += cmp.mismatches;
        decided += cmp.decided;
        const FacetGraph g(c);
        int usable = 0;
        for (int f = 0; f < g.facets(); ++f) usable += g.usable(f);
        CHECK(usable >= 4);
    }
    INFO(rays << " rays, " << decided << " decided locally");
    CHECK(rays > 50000);
    CHECK(decided > rays / 4);
    CHECK(mismatches == 0);
}

TEST_CASE("Ohtsuka & Kawai 1998 diamond: the same image with facet-local intersection as with the full plane loop", "[render]") {
    Scene s = load_scene(std::string(REFRACT_SOURCE_DIR) + "/scenes/examples/ohtsuka1998-diamond.json");
#ifdef REFRACT_SANITIZED  // ten times slower: a quarter of the pixels
    s.camera.width = 48;
    s.camera.height = 36;
#else
    s.camera.width = 96;
    s.camera.height = 72;
#endif
    s.settings.light_pass.photons = 3000;
    RenderOptions o;
    o.threads = 2;
    o.trace.facet_local = false;
    const RenderResult full = render(s, o);
    o.trace.facet_local = true;
    const RenderResult local = render(s, o);
    CHECK(full.stats.facet_local == 0);
    CHECK(local.stats.facet_local > local.stats.facet_full);
    CHECK(local.stats.segments == full.stats.segments);
    long differing = 0;
    for (int j = 0; j < s.camera.height; ++j)
        for (int i = 0; i < s.camera.width; ++i)
            for (int c = 0; c < 3; ++c)
                differing += bits(full.image.at(i, j)[c]) != bits(local.image.at(i, j)[c]);
    CHECK(differing == 0);
}

TEST_CASE("A ray leaving a sphere meets the same surface whether or not the tracer knows the sphere it leaves",
          "[geometry]") {
    // A solid sphere, a hollow one (negative radius) and a third sphere behind them: rays from
    // outside, then the reflected, refracted and random rays leaving each hit, asked with the
    // hit's origin (outward rays skip the sphere they leave) and without it (every sphere
    // tested in full).
    const Scene s = parse_scene(nlohmann::json::parse(R"({
        "camera": {"location": [0, 0, -6], "look_at": [0, 0, 0], "angle": 30, "width": 4, "height": 4},
        "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"},
                    {"type": "sphere", "center": [0.3, 0.1, 0], "radius": -0.4, "material": "glass"},
                    {"type": "sphere", "center": [2.5, 0, 1], "radius": 0.8, "material": "glass"}]})"),
                                "spheres.json");
    const SceneTracer tracer(s);
    RenderStats st;
    std::mt19937_64 rng(7);
    long compared = 0, outward = 0, mismatches = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 target = 1.2 * random_direction(rng);
        const Vec3 origin = target - 5.0 * random_direction(rng);
        Ray ray{origin, (target - origin).normalized()};
        std::optional<SurfaceHit> h = tracer.intersect(ray, st);
        for (int bounce = 0; h && bounce < 4; ++bounce) {
            const auto refr = optics::refract(ray.dir, h->normal, h->entering ? 1.5 : 1 / 1.5);
            std::vector<Vec3> dirs{optics::reflect(ray.dir, h->normal).normalized(), random_direction(rng)};
            if (refr) dirs.push_back(refr->normalized());
            for (const Vec3& d : dirs) {
                const Ray leaving{h->hit.point, d};
                const auto known = tracer.intersect(leaving, st, tracer.origin_of(*h));
                const auto unknown = tracer.intersect(leaving, st);
                ++compared;
                outward += (h->hit.point - std::get<Sphere>(h->object->shape).center).dot(d) > 0;
                const bool same = known.has_value() == unknown.has_value() &&
                                  (!known || (known->object == unknown->object && identical(known->hit, unknown->hit)));
                mismatches += !same;
            }
            ray = Ray{h->hit.point, dirs.back()};
            h = tracer.intersect(ray, st, tracer.origin_of(*h));
        }
    }
    CHECK(compared > 50000);
    CHECK(outward > compared / 4);
    CHECK(mismatches == 0);
}

TEST_CASE("The sphere test on a packet of rays equals the one-ray test in every lane, bit for bit", "[geometry]") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    long compared = 0, hits = 0, mismatches = 0;
    for (const double radius : {1.0, -0.7, 1e-3}) {
        const Sphere s{Vec3(0.1, -0.2, 0.3), radius};
        for (int i = 0; i < 4000; ++i) {
            LaneVec3 o, d;
            Lanes t_max;
            LaneMask active;
            for (int l = 0; l < kLanes; ++l) {
                // From outside, from inside and from the surface, in any direction.
                const Vec3 dir = random_direction(rng);
                const double r = std::abs(radius) * (l % 3 == 0 ? 3.0 : l % 3 == 1 ? 0.5 : 1.0);
                o.set(l, s.center + r * random_direction(rng));
                d.set(l, dir);
                t_max[l] = l % 4 == 3 ? std::abs(radius) * (1 + u(rng)) : kInf;
                active[l] = l != 5 || i % 2 == 0;
            }
            const LaneShapeHits h = intersect_lanes(s, o, d, active, 1e-6, t_max);
            for (int l = 0; l < kLanes; ++l) {
                if (!active[l]) continue;
                ++compared;
                const auto want = intersect(s, Ray{o.lane(l), d.lane(l)}, 1e-6, t_max[l]);
                hits += want.has_value();
                mismatches += !identical(want, lane_hit(h, l));
            }
        }
    }
    CHECK(compared > 80000);
    CHECK(hits > compared / 3);
    CHECK(mismatches == 0);
}

TEST_CASE("Facet-local intersection of a packet of rays leaving one facet equals the one-ray answer in every lane",
          "[geometry]") {
    // Packets leaving hits on the brilliant's facets, inward and outward, each lane with the
    // right guess, a random one or none: every lane decided as FacetGraph::intersect decides
    // it, with the same hit to the last bit, under every variant of the vectorised plane
    // test the CPU runs.
    const ConvexPolyhedron c = brilliant();
    const FacetGraph g(c);
    for (const SlabIsa isa : supported_variants()) {
        INFO(slab_isa_name(isa));
        FacetGraph::use_isa(isa);
        std::mt19937_64 rng(5);
        std::uniform_int_distribution<int> any(0, static_cast<int>(c.planes.size()) - 1);
        long lanes = 0, decided = 0, mismatches = 0;
        for (int i = 0; i < 6000; ++i) {
            const Vec3 from = c.bound_center + 3 * c.bound_radius * random_direction(rng);
            const Vec3 to = c.bound_center + 0.9 * c.bound_radius * random_direction(rng);
            const auto hit = intersect(c, Ray{from, (to - from).normalized()}, 0, kInf);
            if (!hit || !g.usable(hit->facet)) continue;
            const Vec3 n = c.planes[static_cast<size_t>(hit->facet)].normal;
            Vec3 d0 = random_direction(rng);
            if ((d0.dot(n) > 0) != (i % 4 == 0)) d0 = -d0;  // a quarter outward
            LaneVec3 o, d;
            Lanes t_max;
            LaneMask active;
            std::array<std::int32_t, kLanes> guess;
            for (int l = 0; l < kLanes; ++l) {
                // The wavelengths of a split: nearly the same direction from nearly the same point.
                const Vec3 dir = (d0 + 0.01 * random_direction(rng)).normalized();
                o.set(l, hit->point);
                d.set(l, dir);
                t_max[l] = l == 6 ? 0.05 : kInf;
                active[l] = l != 3 || i % 2 == 0;
                const auto want = intersect(c, Ray{hit->point, dir}, 1e-6, t_max[l]);
                guess[static_cast<size_t>(l)] = l % 3 == 0 ? -1 : l % 3 == 1 && want ? want->facet : any(rng);
            }
            compare_packet(g, c, o, d, active, 1e-6, t_max, hit->facet, guess, lanes, decided, mismatches);
        }
        CHECK(lanes > 20000);
        CHECK(decided > lanes / 3);
        CHECK(mismatches == 0);
    }
    FacetGraph::use_isa(slab_isa());
}

TEST_CASE("Facet-local intersection of packets aimed at the brilliant's corners and edges equals the one-ray answer",
          "[geometry]") {
    // Packets leaving facet hits towards the corners and edge midpoints of the facets, where
    // the leaving planes' t are equal or within rounding of each other (ties broken by the
    // smaller index), each lane with the right guess, a random one or none, a window
    // starting at 1e-6 or at 0.
    const Gem gem = build_brilliant(BrilliantCut{});
    ConvexPolyhedron c = gem.solid;
    set_bound(c, gem.mesh.vertices);
    const FacetGraph g(c);
    for (const SlabIsa isa : supported_variants()) {
        INFO(slab_isa_name(isa));
        FacetGraph::use_isa(isa);
        std::mt19937_64 rng(9);
        std::uniform_int_distribution<int> any(0, static_cast<int>(c.planes.size()) - 1);
        long lanes = 0, decided = 0, mismatches = 0;
        std::vector<Vec3> targets;
        for (const GemFacet& f : gem.facets)
            for (size_t i = 0; i < f.polygon.size(); ++i) {
                targets.push_back(f.polygon[i]);
                targets.push_back(0.5 * (f.polygon[i] + f.polygon[(i + 1) % f.polygon.size()]));
            }
        for (size_t i = 0; i < 4 * targets.size(); ++i) {
            const Vec3 from = c.bound_center + 3 * c.bound_radius * random_direction(rng);
            const Vec3 to = c.bound_center + 0.5 * c.bound_radius * random_direction(rng);
            const auto hit = intersect(c, Ray{from, (to - from).normalized()}, 0, kInf);
            if (!hit || !g.usable(hit->facet)) continue;
            const double t_min = i % 3 == 0 ? 0.0 : 1e-6;
            LaneVec3 o, d;
            Lanes t_max;
            LaneMask active = LaneMask::Constant(true);
            std::array<std::int32_t, kLanes> guess;
            for (int l = 0; l < kLanes; ++l) {
                const Vec3& at = targets[(i + static_cast<size_t>(l) * 7) % targets.size()];
                Vec3 dir = (at - hit->point).normalized();
                if (l >= 4) dir = (dir + 1e-13 * random_direction(rng)).normalized();  // beside it
                o.set(l, hit->point);
                d.set(l, dir);
                t_max[l] = kInf;
                const auto want = intersect(c, Ray{hit->point, dir}, t_min, kInf);
                guess[static_cast<size_t>(l)] = l % 3 == 2 ? -1 : l % 3 == 0 && want ? want->facet : any(rng);
            }
            compare_packet(g, c, o, d, active, t_min, t_max, hit->facet, guess, lanes, decided, mismatches);
        }
        INFO(lanes << " lanes, " << decided << " decided locally");
        CHECK(lanes > 5000);
        CHECK(decided > lanes / 4);
        CHECK(mismatches == 0);
    }
    FacetGraph::use_isa(slab_isa());
}

TEST_CASE("The plane test on a packet of rays equals the one-ray test in every lane, bit for bit", "[geometry]") {
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(-2, 2);
    const Plane p{Vec3(0.3, 0.9, -0.2).normalized(), 0.4};
    long compared = 0, hits = 0, mismatches = 0;
    for (int i = 0; i < 10000; ++i) {
        LaneVec3 o, d;
        Lanes t_max;
        LaneMask active;
        for (int l = 0; l < kLanes; ++l) {
            Vec3 dir = random_direction(rng);
            if (l == 7) dir = (dir - dir.dot(p.normal) * p.normal).normalized();  // parallel to the plane
            o.set(l, Vec3(u(rng), u(rng), u(rng)));
            d.set(l, dir);
            t_max[l] = l % 4 == 3 ? 1.0 : kInf;
            active[l] = l != 2 || i % 2 == 0;
        }
        const LaneShapeHits h = intersect_lanes(p, o, d, active, 1e-6, t_max);
        for (int l = 0; l < kLanes; ++l) {
            if (!active[l]) continue;
            ++compared;
            const auto want = intersect(p, Ray{o.lane(l), d.lane(l)}, 1e-6, t_max[l]);
            hits += want.has_value();
            mismatches += !identical(want, lane_hit(h, l));
        }
    }
    CHECK(compared > 70000);
    CHECK(hits > compared / 4);
    CHECK(mismatches == 0);
}

TEST_CASE("Normalising a packet on the widest instructions equals Eigen's normalized() in every lane, bit for bit",
          "[geometry]") {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-3, 3), scale(-30, 30);
    for (const SlabIsa isa : supported_variants()) {
        INFO(slab_isa_name(isa));
        use_wide_isa(isa);
        long lanes = 0, mismatches = 0;
        for (int n = 0; n < 20000; ++n) {
            LaneVec3 v;
            LaneMask m;
            for (int l = 0; l < kLanes; ++l) {
                Vec3 x = std::ldexp(1.0, static_cast<int>(scale(rng))) * Vec3(u(rng), u(rng), u(rng));
                if ((n + l) % 97 == 0) x = Vec3::Zero();  // stays as it is
                v.set(l, x);
                m[l] = (n + l) % 5 != 0;
            }
            const LaneVec3 before = v;
            normalize_lanes(v, m);
            for (int l = 0; l < kLanes; ++l) {
                ++lanes;
                const Vec3 want = m[l] ? Vec3(before.lane(l).normalized()) : before.lane(l);
                for (int c = 0; c < 3; ++c) mismatches += test::bits(v.lane(l)[c]) != test::bits(want[c]);
            }
        }
        CHECK(lanes == 160000);
        CHECK(mismatches == 0);
    }
    use_wide_isa(slab_isa());
}
