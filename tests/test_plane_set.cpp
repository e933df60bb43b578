// The vectorised convex plane-set intersection (geometry/plane_set.h) against the scalar
// loop it replaces (intersect_scalar): the same hit to the last bit (t, point, normal,
// facet) for every ray, through the dispatched kernel and through every variant this CPU
// can run. And, hidden ("[.bench]"), the speed of both.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/plane_set.h>
#include <refract/geometry/shapes.h>
#include "tests/hit_bits.h"

using namespace refract;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using test::bits;
using test::identical;
using test::random_direction;

std::string show(double x) {
    std::ostringstream o;
    o << std::setprecision(17) << x << " (0x" << std::hex << bits(x) << ")";
    return o.str();
}
std::string show(const Vec3& v) { return show(v.x()) + ", " + show(v.y()) + ", " + show(v.z()); }
std::string show(const std::optional<Hit>& h) {
    if (!h) return "no hit";
    return "t " + show(h->t) + ", facet " + std::to_string(h->facet) + ", point " + show(h->point);
}

std::vector<SlabIsa> supported_variants() {
    std::vector<SlabIsa> v;
    for (SlabIsa isa : {SlabIsa::baseline, SlabIsa::avx2, SlabIsa::avx512f})
        if (slab_isa_supported(isa)) v.push_back(isa);
    return v;
}

// Compares intersect (dispatched) and every supported variant with intersect_scalar for
// one ray over t windows that expose both ends of the slab: (-inf, inf) gives the entering
// hit when there is one, (that t, inf) the leaving one; (0, inf) and (1e-6, inf) are what
// the tracer asks; `more` adds windows hugging the hits and cutting them off.
struct Checker {
    std::vector<SlabIsa> variants = supported_variants();
    long rays = 0;
    long comparisons = 0;
    long hits = 0;
    long mismatches = 0;
    std::string first_mismatch;

    void compare(const ConvexPolyhedron& c, const Ray& r, double t_min, double t_max) {
        const auto want = intersect_scalar(c, r, t_min, t_max);
        hits += want.has_value();
        const auto check = [&](const std::optional<Hit>& got, const char* who) {
            ++comparisons;
            if (identical(got, want)) return;
            if (mismatches++ == 0)
                first_mismatch = std::string(who) + ": origin " + show(r.origin) + ", dir " + show(r.dir) +
                                 ", window (" + show(t_min) + ", " + show(t_max) + "), " +
                                 std::to_string(c.planes.size()) + " planes: scalar " + show(want) + ", vector " +
                                 show(got);
        };
        check(intersect(c, r, t_min, t_max), "dispatched");
        for (SlabIsa isa : variants) check(intersect(isa, c, r, t_min, t_max), slab_isa_name(isa));
    }

    void ray(const ConvexPolyhedron& c, const Ray& r, bool more = false) {
        ++rays;
        compare(c, r, -kInf, kInf);
        compare(c, r, 0.0, kInf);
        compare(c, r, 1e-6, kInf);
        const auto first = intersect_scalar(c, r, -kInf, kInf);
        if (!first) return;
        compare(c, r, first->t, kInf);
        if (!more) return;
        const auto second = intersect_scalar(c, r, first->t, kInf);
        for (const auto& h : {first, second}) {
            if (!h) continue;
            const double below = std::nextafter(h->t, -kInf), above = std::nextafter(h->t, kInf);
            compare(c, r, below, above);  // the hit alone
            compare(c, r, h->t, above);   // excluded at the bottom
            compare(c, r, below, h->t);   // excluded at the top
            compare(c, r, -kInf, h->t);
        }
    }
};

bool inside(const ConvexPolyhedron& c, const Vec3& p) {
    for (const Plane& q : c.planes)
        if (!(q.normal.dot(p) <= q.offset)) return false;
    return true;
}

// The default round brilliant (121 planes: 33 crown, 64 bruted girdle, 24 pavilion),
// with its bounding sphere as the scene reader sets it.
struct Brilliant {
    Gem gem = build_brilliant(BrilliantCut{});
    ConvexPolyhedron solid = gem.solid;
    Vec3 lo, hi;
    Brilliant() {
        set_bound(solid, gem.mesh.vertices);
        lo = hi = gem.mesh.vertices.front();
        for (const Vec3& v : gem.mesh.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
    }
    // From a sphere of radius 3 around it, aimed at a random point of its bounding sphere.
    Ray outside_ray(std::mt19937_64& rng) const {
        std::uniform_real_distribution<double> u(0, 1);
        const Vec3 from = solid.bound_center + 3 * random_direction(rng);
        const Vec3 to = solid.bound_center + solid.bound_radius * std::cbrt(u(rng)) * random_direction(rng);
        return {from, (to - from).normalized()};
    }
    // From a random point inside, in a random direction (the internal reflections).
    Ray inside_ray(std::mt19937_64& rng) const {
        std::uniform_real_distribution<double> u(0, 1);
        for (;;) {
            const Vec3 p = lo + (hi - lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
            if (inside(solid, p)) return {p, random_direction(rng)};
        }
    }
};

}  // namespace

TEST_CASE("Vectorised plane-set intersection equals the scalar loop bit for bit on the round brilliant", "[geometry]") {
    const Brilliant b;
    CHECK(b.solid.planes.size() >= 57);  // 121 with the default bruted girdle of 64 planes
    std::mt19937_64 rng(20240611);
    Checker check;
    for (int i = 0; i < 60000; ++i) check.ray(b.solid, b.outside_ray(rng));
    for (int i = 0; i < 60000; ++i) check.ray(b.solid, b.inside_ray(rng));
    // And without the bounding sphere (every ray reaches the plane loop).
    ConvexPolyhedron unbounded_check = b.solid;
    unbounded_check.bound_radius = 0;
    for (int i = 0; i < 5000; ++i) check.ray(unbounded_check, b.outside_ray(rng));

    INFO("variants checked besides the dispatched one (" << slab_isa_name(slab_isa()) << "): "
                                                            << check.variants.size());
    INFO(check.rays << " rays, " << check.comparisons << " comparisons, " << check.hits << " scalar hits");
    INFO("first mismatch: " << check.first_mismatch);
    CHECK(check.rays == 125000);
    CHECK(check.hits > 200000);  // most windows of most rays hit: the rays do reach the planes
    CHECK(check.mismatches == 0);
}

TEST_CASE("Vectorised plane-set intersection equals the scalar loop bit for bit on random convex polyhedra", "[geometry]") {
    // 1..130 planes (every remainder modulo 8, 4 and 2, and fewer planes than lanes), random
    // unit normals at random distances, some repeated exactly (equal t: the first plane must
    // win) and some opposite (parallel pairs); half of them closed by a box with a bounding
    // sphere, the others without a sphere and possibly unbounded.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    Checker check;
    for (int poly = 0; poly < 260; ++poly) {
        const int n = 1 + poly % 130;
        ConvexPolyhedron c;
        for (int k = 0; k < n; ++k) {
            const double roll = u(rng);
            if (k > 0 && roll < 0.1) {
                c.planes.push_back(c.planes[static_cast<size_t>(rng() % static_cast<unsigned>(k))]);  // a repeat
            } else if (k > 0 && roll < 0.15) {
                const Plane& p = c.planes[static_cast<size_t>(rng() % static_cast<unsigned>(k))];
                c.planes.push_back(Plane{-p.normal, 0.5 + u(rng)});  // the opposite side
            } else {
                c.planes.push_back(Plane{random_direction(rng), 0.5 + u(rng)});
            }
        }
        if (poly % 2 == 0) {
            for (int axis = 0; axis < 3; ++axis)
                for (double s : {-1.0, 1.0}) {
                    Vec3 normal = Vec3::Zero();
                    normal[axis] = s;
                    const auto at = static_cast<std::ptrdiff_t>(rng() % (c.planes.size() + 1));
                    c.planes.insert(c.planes.begin() + at, Plane{normal, 1.5});
                }
            c.bound_center = Vec3::Zero();
            c.bound_radius = 1.5 * std::sqrt(3.0) * (1 + 1e-9);
        }
        for (int i = 0; i < 400; ++i) {
            Ray r;
            if (i % 2 == 0) {
                r.origin = 4 * random_direction(rng);
                r.dir = (1.2 * std::cbrt(u(rng)) * random_direction(rng) - r.origin).normalized();
            } else {
                r.origin = 0.6 * std::cbrt(u(rng)) * random_direction(rng);
                r.dir = random_direction(rng);
            }
            check.ray(c, r);
        }
    }
    INFO(check.rays << " rays, " << check.comparisons << " comparisons, " << check.hits << " scalar hits");
    INFO("first mismatch: " << check.first_mismatch);
    CHECK(check.rays == 104000);
    CHECK(check.hits > 100000);
    CHECK(check.mismatches == 0);
}

TEST_CASE("Vectorised plane-set intersection matches the scalar loop on vertex and edge rays, parallel planes, signed zeros, t bounds and non-finite rays", "[geometry]") {
    Checker check;
    std::mt19937_64 rng(11);
    const Brilliant b;
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : b.gem.mesh.vertices) centre += v;
    centre /= static_cast<double>(b.gem.mesh.vertices.size());

    SECTION("rays aimed exactly at the brilliant's vertices and along its edges") {
        for (const Vec3& v : b.gem.mesh.vertices) {
            for (int i = 0; i < 8; ++i) {
                const Vec3 from = b.solid.bound_center + 3 * random_direction(rng);
                check.ray(b.solid, Ray{from, (v - from).normalized()}, true);   // at the vertex
                check.ray(b.solid, Ray{v, (v - from).normalized()}, true);      // leaving from it
                check.ray(b.solid, Ray{v, (from - v).normalized()}, true);      // from it, outward
            }
            check.ray(b.solid, Ray{centre, (v - centre).normalized()}, true);   // from inside
            check.ray(b.solid, Ray{v + (v - centre), (centre - v).normalized()}, true);
        }
        for (const GemFacet& f : b.gem.facets)
            for (size_t i = 0; i < f.polygon.size(); ++i) {
                const Vec3& p = f.polygon[i];
                const Vec3& q = f.polygon[(i + 1) % f.polygon.size()];
                const Vec3 along = (q - p).normalized();  // parallel to both planes of the edge
                check.ray(b.solid, Ray{p, along}, true);
                check.ray(b.solid, Ray{p - along, along}, true);
                check.ray(b.solid, Ray{0.5 * (p + q), along}, true);
                check.ray(b.solid, Ray{0.5 * (p + q), -along}, true);
                const Vec3 mid = 0.5 * (p + q);
                check.ray(b.solid, Ray{centre, (mid - centre).normalized()}, true);  // at the edge
                check.ray(b.solid, Ray{mid + (mid - centre), (centre - mid).normalized()}, true);
            }
        INFO(check.rays << " rays; first mismatch: " << check.first_mismatch);
        CHECK(check.rays > 5000);
        CHECK(check.mismatches == 0);
    }

    SECTION("axis-aligned box: rays parallel to four of its planes, inside, outside and on them") {
        ConvexPolyhedron box;
        for (int axis = 0; axis < 3; ++axis)
            for (double s : {1.0, -1.0}) {
                Vec3 normal = Vec3::Zero();
                normal[axis] = s;
                box.planes.push_back(Plane{normal, 1.0});
            }
        const std::vector<double> coords = {-3.0, -1.0, -0.5, -0.0, 0.0, 0.5, 1.0, 3.0,
                                            std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0)};
        for (int axis = 0; axis < 3; ++axis)
            for (double s : {1.0, -1.0, -0.0})
                for (double a : coords)
                    for (double bb : coords)
                        for (double start : {-3.0, -1.0, 0.0, 1.0, 3.0}) {
                            Vec3 o(a, bb, a), dir = Vec3::Zero();
                            o[axis] = start;
                            dir[axis] = s;
                            dir[(axis + 1) % 3] = -0.0;
                            check.ray(box, Ray{o, dir}, true);
                        }
        // Known answers, for the record.
        const auto h = intersect(box, Ray{Vec3(-3, 0, 0), Vec3(1, 0, 0)}, 0, kInf);
        REQUIRE(h);
        CHECK(h->t == 2);
        CHECK(h->facet == 1);  // the -x plane
        CHECK_FALSE(intersect(box, Ray{Vec3(-3, 2, 0), Vec3(1, 0, 0)}, 0, kInf));  // parallel and outside
        const auto on = intersect(box, Ray{Vec3(-3, 1, 0), Vec3(1, 0, 0)}, 0, kInf);  // on the +y plane
        REQUIRE(on);
        CHECK(on->facet == 1);
        INFO(check.rays << " rays; first mismatch: " << check.first_mismatch);
        CHECK(check.mismatches == 0);
    }

    SECTION("planes through the origin, rays from it: t = +0 or -0 must come out with its sign") {
        std::vector<double> signed_zeros = {0.0, -0.0};
        for (int trial = 0; trial < 200; ++trial) {
            ConvexPolyhedron c;
            for (int k = 0; k < 3 + trial % 20; ++k) {
                Plane p{random_direction(rng), signed_zeros[static_cast<size_t>(rng() % 2)]};
                if (k % 3 == 0) p.normal.x() = signed_zeros[static_cast<size_t>(rng() % 2)];
                c.planes.push_back(p);
            }
            for (int i = 0; i < 20; ++i) {
                Vec3 o(signed_zeros[static_cast<size_t>(rng() % 2)], signed_zeros[static_cast<size_t>(rng() % 2)],
                       signed_zeros[static_cast<size_t>(rng() % 2)]);
                Vec3 d = random_direction(rng);
                if (i % 2) d.y() = signed_zeros[static_cast<size_t>(rng() % 2)];
                check.ray(c, Ray{o, d}, true);
            }
        }
        INFO(check.rays << " rays; first mismatch: " << check.first_mismatch);
        CHECK(check.mismatches == 0);
    }

    SECTION("t bounds around every hit, and the plane counts on either side of a lane multiple") {
        for (int n : {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 57, 64, 121, 122}) {
            ConvexPolyhedron c;
            for (int k = 0; k < n; ++k) c.planes.push_back(Plane{random_direction(rng), 1.0});
            for (int i = 0; i < 200; ++i) {
                const Vec3 o = (i % 2 ? 0.3 : 3.0) * random_direction(rng);
                check.ray(c, Ray{o, random_direction(rng)}, true);
            }
        }
        for (int i = 0; i < 2000; ++i) check.ray(b.solid, i % 2 ? b.inside_ray(rng) : b.outside_ray(rng), true);
        INFO(check.rays << " rays; first mismatch: " << check.first_mismatch);
        CHECK(check.mismatches == 0);
    }

    SECTION("non-finite and degenerate rays") {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        ConvexPolyhedron unbounded_check = b.solid;
        unbounded_check.bound_radius = 0;
        for (const ConvexPolyhedron* c : std::vector<const ConvexPolyhedron*>{&b.solid, &unbounded_check})
            for (const Vec3& o : {Vec3(0, 0, 0), Vec3(0, 0, 3), Vec3(kInf, 0, 0), Vec3(nan, 0, 0), Vec3(1e300, 1e300, 0)})
                for (const Vec3& d : {Vec3(0, 0, -1), Vec3(nan, 0, 1), Vec3(kInf, 0, 0), Vec3(0, 0, 0), Vec3(1e-320, 0, -1e-320),
                                      Vec3(1e300, 0, -1)})
                    check.ray(*c, Ray{o, d}, true);
        INFO(check.rays << " rays; first mismatch: " << check.first_mismatch);
        CHECK(check.mismatches == 0);
    }
}

namespace {

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Rays per second of wall time and of this thread's CPU time (which leaves out the time the
// thread waits for a core on a shared machine) for one run of `f` over `rays`.
struct Rate {
    double wall, cpu;  // rays per second
    double sum_t;      // the hits' t summed in ray order: the same bits for every variant
};

template <class F>
Rate rays_per_second(const std::vector<Ray>& rays, F f) {
    double sink = 0;
    const double c0 = thread_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (const Ray& r : rays) {
        const auto h = f(r);
        if (h) sink += h->t;
    }
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - t0;
    const double cpu = thread_cpu_seconds() - c0;
    const double n = static_cast<double>(rays.size());
    return {n / wall.count(), n / cpu, sink};
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

TEST_CASE("Plane-set intersection speed on the round brilliant, scalar loop against the vectorised kernels", "[.bench]") {
    const Brilliant b;
    std::mt19937_64 rng(1);
    std::vector<Ray> outside, in;
    for (int i = 0; i < 1000000; ++i) outside.push_back(b.outside_ray(rng));
    for (int i = 0; i < 1000000; ++i) in.push_back(b.inside_ray(rng));
    std::printf("round brilliant, %zu planes; CPU: avx2 %s, avx512f %s; dispatch picks %s\n", b.solid.planes.size(),
                slab_isa_supported(SlabIsa::avx2) ? "yes" : "no", slab_isa_supported(SlabIsa::avx512f) ? "yes" : "no",
                slab_isa_name(slab_isa()));
    std::printf("intersect(c, r, 1e-6, inf), one thread, 1e6 rays per run, 5 runs (the variants taking turns);\n"
                "medians in Mrays/s per wall second [per thread-CPU second]:\n");
    std::printf("%-28s %24s %24s\n", "", "outside, through bound", "inside, any direction");
    const std::vector<SlabIsa> variants = supported_variants();
    std::vector<std::string> names = {"scalar loop", std::string("dispatched (") + slab_isa_name(slab_isa()) + ")"};
    for (SlabIsa isa : variants) names.push_back(slab_isa_name(isa));
    // One run of row `k` over `rays`; each row its own loop, with the call inlined or direct.
    const auto run = [&](size_t k, const std::vector<Ray>& rays) {
        if (k == 0) return rays_per_second(rays, [&](const Ray& r) { return intersect_scalar(b.solid, r, 1e-6, kInf); });
        if (k == 1) return rays_per_second(rays, [&](const Ray& r) { return intersect(b.solid, r, 1e-6, kInf); });
        const SlabIsa isa = variants[k - 2];
        return rays_per_second(rays, [&](const Ray& r) { return intersect(isa, b.solid, r, 1e-6, kInf); });
    };
    std::vector<std::vector<double>> wall(2 * names.size()), cpu(2 * names.size());
    std::optional<double> run_sum[2];  // the first run's sum of t: every other run must equal it
    for (int round = 0; round < 5; ++round)
        for (size_t k = 0; k < names.size(); ++k)
            for (size_t set = 0; set < 2; ++set) {
                const Rate rate = run(k, set == 0 ? outside : in);
                wall[2 * k + set].push_back(rate.wall);
                cpu[2 * k + set].push_back(rate.cpu);
                if (!run_sum[set]) run_sum[set] = rate.sum_t;
                CHECK(bits(rate.sum_t) == bits(*run_sum[set]));  // the same hits, whatever the variant
            }
    for (size_t k = 0; k < names.size(); ++k) {
        char cell[2][64];
        for (size_t set = 0; set < 2; ++set)
            std::snprintf(cell[set], sizeof cell[set], "%6.2f [%6.2f]", median(wall[2 * k + set]) / 1e6,
                          median(cpu[2 * k + set]) / 1e6);
        std::printf("%-28s %24s %24s\n", names[k].c_str(), cell[0], cell[1]);
    }
}
