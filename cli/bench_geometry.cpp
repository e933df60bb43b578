// refract bench --kernels / --meshes: intersection throughput on fixed ray sets, one
// thread, every variant on the same rays, in paired rounds.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include <refract/core/tracer.h>
#include <refract/geometry/facet_graph.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/icosphere.h>
#include <refract/geometry/mesh_accel.h>
#include <refract/geometry/plane_set.h>

namespace refract::cli::bench {

namespace bench_geometry_command {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec3 random_direction(std::mt19937_64& g) {
    std::normal_distribution<double> n;
    for (;;) {
        const Vec3 v(n(g), n(g), n(g));
        if (v.norm() > 1e-6) return v.normalized();
    }
}

// A ray and the near end of its window (0 from outside, 1e-6 from a surface or inside).
struct Query {
    Ray ray;
    double t_min;
};

// Rays from a sphere of radius 3·r around `centre` aimed at random points of the ball of
// radius r, and as many from random points inside the ball in random directions.
std::vector<Query> ball_rays(const Vec3& centre, double r, int n, std::uint64_t seed) {
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Query> q;
    for (int i = 0; i < n; ++i) {
        const Vec3 from = centre + 3 * r * random_direction(g);
        const Vec3 to = centre + r * std::cbrt(u(g)) * random_direction(g);
        q.push_back({Ray{from, (to - from).normalized()}, 0.0});
    }
    for (int i = 0; i < n; ++i) q.push_back({Ray{centre + r * std::cbrt(u(g)) * random_direction(g), random_direction(g)}, 1e-6});
    return q;
}

// Runs `hit` over the rays; returns the number of hits (every variant must find as many,
// up to edge rays).
template <class F>
long run_rays(const std::vector<Query>& rays, F&& hit) {
    long n = 0;
    for (const Query& q : rays) n += hit(q);
    return n;
}

void table_header(const char* unit) {
    std::printf("  %-40s %14s %14s %14s\n", "", (std::string("median ") + unit).c_str(),
                (std::string("best ") + unit).c_str(), "CPU median");
}

void table_row(const std::string& name, const std::vector<double>& wall, const std::vector<double>& cpu, double rays,
               long hits) {
    std::printf("  %-40s %14.2f %14.2f %14.2f   (%ld hits)\n", name.c_str(), rays / median(wall) / 1e6,
                rays / minimum(wall) / 1e6, rays / median(cpu) / 1e6, hits);
}

}  // namespace bench_geometry_command
using namespace bench_geometry_command;

void kernels(int rounds) {
    Gem gem = build_brilliant(BrilliantCut{});
    ConvexPolyhedron solid = gem.solid;
    set_bound(solid, gem.mesh.vertices);
    const MeshAccel accel(gem.mesh), plain(gem.mesh, MeshAccel::Mode::plain);
    const std::vector<Query> rays = ball_rays(solid.bound_center, solid.bound_radius, 500000, 1);
    std::printf("Round brilliant: %zu planes (plane set), %zu triangles (mesh); %zu rays, half from outside aimed at its "
                "bounding sphere, half from inside it in random directions; one thread; %d paired rounds\n",
                solid.planes.size(), gem.mesh.triangles.size(), rays.size(), rounds);
    std::printf("  plane-set kernel variant dispatched: %s\n", slab_isa_name(slab_isa()));
    print_load("before");
    const std::vector<std::string> names = {"plane set, scalar loop", "plane set, vectorised (dispatched)",
                                            "mesh, Embree alone (float)", "mesh, Embree + double refinement"};
    std::vector<long> hits(names.size());
    const Paired p = paired_runs(names.size(), rounds, [&](size_t k) {
        switch (k) {
            case 0: hits[k] = run_rays(rays, [&](const Query& q) { return intersect_scalar(solid, q.ray, q.t_min, kInf).has_value(); }); break;
            case 1: hits[k] = run_rays(rays, [&](const Query& q) { return intersect(solid, q.ray, q.t_min, kInf).has_value(); }); break;
            case 2: hits[k] = run_rays(rays, [&](const Query& q) { return plain.intersect_float(q.ray, q.t_min, kInf).triangle >= 0; }); break;
            default: hits[k] = run_rays(rays, [&](const Query& q) { return accel.intersect(q.ray, q.t_min, kInf).has_value(); });
        }
    });
    table_header("Mrays/s");
    for (size_t k = 0; k < names.size(); ++k) table_row(names[k], p.wall[k], p.cpu[k], static_cast<double>(rays.size()), hits[k]);
    std::printf("  vectorised plane set / Embree alone, paired medians: %.2fx (target: plane set >= 20 Mrays/s per core)\n",
                median(p.wall[2]) / median(p.wall[1]));
    print_load("after");
    facet_local(solid, rounds);
}

namespace bench_geometry_command {

// A ray leaving hit `from` on a facet of the gem, with a guess of the facet it leaves through.
struct FacetQuery {
    Ray ray;
    int from, guess;
};

}  // namespace bench_geometry_command

// Rays as a render of the gem makes them: each leaving the hit of an outside ray on a
// facet, half inward (the guess: the leaving facet of a ray 0.3° away, as the neighbouring
// wavelength of a spectral split), half outward (no guess needed). The full plane loop
// against facet-local intersection with the full loop where it is undecided.
void facet_local(const ConvexPolyhedron& solid, int rounds) {
    const FacetGraph graph(solid);
    std::mt19937_64 g(3);
    std::vector<FacetQuery> rays;
    while (rays.size() < 1000000) {
        const Vec3 from = solid.bound_center + 3 * solid.bound_radius * random_direction(g);
        const Vec3 to = solid.bound_center + 0.9 * solid.bound_radius * random_direction(g);
        const auto h = intersect(solid, Ray{from, (to - from).normalized()}, 0, kInf);
        if (!h) continue;
        const Vec3 n = solid.planes[static_cast<size_t>(h->facet)].normal;
        Vec3 d = random_direction(g);
        if (d.dot(n) > 0) d = -d;
        const Vec3 near = (d + 0.005 * random_direction(g)).normalized();
        const auto companion = intersect(solid, Ray{h->point, near}, 1e-6, kInf);
        rays.push_back({Ray{h->point, d}, h->facet, companion ? companion->facet : -1});
        rays.push_back({Ray{h->point, -d}, h->facet, -1});
    }
    std::printf("Rays leaving the brilliant's facets: %zu, half inward (guess: the leaving facet of a ray 0.3 degrees "
                "away), half outward; one thread; %d paired rounds\n", rays.size(), rounds);
    print_load("before");
    long hits[2] = {0, 0}, local = 0;
    const Paired p = paired_runs(2, rounds, [&](size_t k) {
        long n = 0, decided = 0;
        for (const FacetQuery& q : rays) {
            if (k == 0) {
                n += intersect(solid, q.ray, 1e-6, kInf).has_value();
                continue;
            }
            const FacetGraph::Local l = graph.intersect(solid, q.ray, 1e-6, kInf, q.from, q.guess);
            decided += l.decided;
            n += l.decided ? l.hit.has_value() : intersect(solid, q.ray, 1e-6, kInf).has_value();
        }
        hits[k] = n;
        if (k == 1) local = decided;
    });
    table_header("Mrays/s");
    table_row("full plane loop (vectorised)", p.wall[0], p.cpu[0], static_cast<double>(rays.size()), hits[0]);
    table_row("facet-local, full loop when undecided", p.wall[1], p.cpu[1], static_cast<double>(rays.size()), hits[1]);
    std::printf("  decided locally: %.1f %% of the rays; facet-local / full loop, paired medians: %.2fx\n",
                100.0 * static_cast<double>(local) / static_cast<double>(rays.size()), median(p.wall[0]) / median(p.wall[1]));
    print_load("after");
}

void meshes(int rounds) {
    std::printf("Icospheres (radius 1), 80 to 327 680 triangles; per mesh 200 000 rays, half from outside aimed at the "
                "ball, half from inside; one thread; %d paired rounds; ns per ray (wall, median / best)\n", rounds);
    print_load("before");
    const std::vector<Query> rays = ball_rays(Vec3(0, 0, 0), 1.0, 100000, 2);
    const std::vector<Query> few(rays.begin(), rays.begin() + 2000);
    std::printf("  %10s %22s %22s %10s %22s\n", "triangles", "refract (Embree+refine)", "Embree alone", "ratio",
                "linear search");
    for (int s = 1; s <= 7; ++s) {
        const TriangleMesh m = icosphere(s);
        const MeshAccel accel(m), plain(m, MeshAccel::Mode::plain);
        const bool linear = m.triangles.size() <= 5120;
        const size_t variants = linear ? 3 : 2;
        long hits[3] = {0, 0, 0};
        const Paired p = paired_runs(variants, rounds, [&](size_t k) {
            if (k == 0) hits[0] = run_rays(rays, [&](const Query& q) { return accel.intersect(q.ray, q.t_min, kInf).has_value(); });
            if (k == 1) hits[1] = run_rays(rays, [&](const Query& q) { return plain.intersect_float(q.ray, q.t_min, kInf).triangle >= 0; });
            if (k == 2) hits[2] = run_rays(few, [&](const Query& q) { return intersect(m, q.ray, q.t_min, kInf).has_value(); });
        });
        const double n = static_cast<double>(rays.size());
        char lin[64] = "—";
        if (linear)
            std::snprintf(lin, sizeof lin, "%9.0f / %9.0f", 1e9 * median(p.wall[2]) / few.size(), 1e9 * minimum(p.wall[2]) / few.size());
        std::printf("  %10zu %10.1f / %9.1f %10.1f / %9.1f %9.2fx %22s   (hits %ld / %ld)\n", m.triangles.size(),
                    1e9 * median(p.wall[0]) / n, 1e9 * minimum(p.wall[0]) / n, 1e9 * median(p.wall[1]) / n,
                    1e9 * minimum(p.wall[1]) / n, median(p.wall[0]) / median(p.wall[1]), lin, hits[0], hits[1]);
    }
    std::printf("  (ratio: refract / Embree alone, paired medians; target <= 1.5x, cost logarithmic in triangles)\n");
    print_load("after");
}

void objects(int rounds) {
    std::printf("Scenes of N random spheres (radius 0.05-0.6) in a cube of edge 20, and a floor plane; 100 000 rays from "
                "random points in random directions; one thread; %d paired rounds; ns per nearest-hit search (wall, "
                "median / best)\n", rounds);
    print_load("before");
    std::printf("  %8s %24s %24s %10s\n", "objects", "tracer", "linear search", "ratio");
    for (int count : {10, 100, 300, 1000, 10000}) {
        Scene s;
        s.materials.push_back({"white", material::Diffuse{}});
        std::mt19937_64 g(static_cast<std::uint64_t>(count));
        std::uniform_real_distribution<double> u(-10, 10), rad(0.05, 0.6);
        for (int k = 0; k < count; ++k) s.objects.push_back({"s", Sphere{Vec3(u(g), u(g), u(g)), rad(g)}, 0});
        s.objects.push_back({"floor", Plane{Vec3(0, 1, 0), -10.5}, 0});
        const SceneTracer tracer(s);
        std::vector<Ray> rays;
        for (int i = 0; i < 100000; ++i) rays.push_back({Vec3(u(g), u(g), u(g)), random_direction(g)});
        const size_t linear_rays = count <= 1000 ? rays.size() : 10000;
        long hits[2] = {0, 0};
        RenderStats st;
        const Paired p = paired_runs(2, rounds, [&](size_t k) {
            long n = 0;
            if (k == 0) {
                for (const Ray& r : rays) n += tracer.intersect(r, st).has_value();
            } else {
                for (size_t i = 0; i < linear_rays; ++i) {
                    double t_max = kInf;
                    bool hit = false;
                    for (const Object& o : s.objects)
                        if (const auto h = intersect(o.shape, rays[i], SceneTracer::kEpsilon, t_max)) {
                            t_max = h->t;
                            hit = true;
                        }
                    n += hit;
                }
            }
            hits[k] = n;
        });
        const double a = 1e9 * median(p.wall[0]) / rays.size(), b = 1e9 * median(p.wall[1]) / linear_rays;
        std::printf("  %8d %11.1f / %10.1f %11.1f / %10.1f %9.1fx   (%s; hits %ld of %zu; linear on %zu rays)\n",
                    count + 1, a, 1e9 * minimum(p.wall[0]) / rays.size(), b, 1e9 * minimum(p.wall[1]) / linear_rays, b / a,
                    HitSearch::uses_object_bvh(s) ? "object BVH" : "sphere set", hits[0], rays.size(), linear_rays);
    }
    print_load("after");
}

}  // namespace refract::cli::bench
