// refract bench --trace: ray queries on the 1998 diamond (docs/performance.md, "Ray
// queries"): one ray's whole record through a TraceSession (and without one, building the
// tracer per call), and trace_rays over the camera's rays that meet the diamond, on one
// thread and on all. CPU time of the calling thread for the one-thread figures.
#include <ctime>
#include <iomanip>
#include <iostream>
#include <memory>
#include <vector>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include <refract/core/trace_rays.h>
#include <refract/core/tracer.h>
#include <refract/core/trace_record.h>
#include <refract/experiments/common.h>
#include <refract/experiments/ohtsuka1998.h>

namespace refract::cli::bench {

namespace bench_trace_command {

// Wall and thread-CPU seconds of f(), `rounds` times.
template <class F>
Paired rounds_of(int rounds, F&& f) {
    Paired p;
    p.wall.resize(1);
    p.cpu.resize(1);
    for (int r = 0; r < rounds; ++r) {
        const double w0 = wall_seconds(), c0 = thread_cpu_seconds();
        f();
        p.cpu[0].push_back(thread_cpu_seconds() - c0);
        p.wall[0].push_back(wall_seconds() - w0);
    }
    return p;
}

void print_per(const char* what, const Paired& p, double per, double scale, const char* unit) {
    std::cout << "  " << what << ": " << std::fixed << std::setprecision(2) << median(p.cpu[0]) / per * scale
              << " " << unit << " CPU (median; best " << minimum(p.cpu[0]) / per * scale << "), wall "
              << median(p.wall[0]) / per * scale << " " << unit << "\n";
}

struct TraceRays {
    std::vector<Vec3> origins, directions;
    std::vector<double> wavelengths;
};

// The camera's rays through every `step`-th pixel's centre whose first hit is the diamond
// (the last object), at 400, 410, ..., 700 nm in turn.
TraceRays diamond_rays(const TraceSession& session, int step) {
    TraceRays r;
    const Scene& scene = session.scene();
    const SceneTracer& tracer = session.tracer();
    const Object* diamond = &scene.objects.back();
    RenderStats stats;
    for (int j = 0; j < scene.camera.height; j += step)
        for (int i = 0; i < scene.camera.width; i += step) {
            const Ray ray = scene.camera.ray(i + 0.5, j + 0.5);
            const auto h = tracer.intersect(ray, stats);
            if (!h || h->object != diamond) continue;
            r.origins.push_back(ray.origin);
            r.directions.push_back(ray.dir);
            r.wavelengths.push_back(400.0 + 10.0 * static_cast<double>(r.wavelengths.size() % 31));
        }
    return r;
}

}  // namespace bench_trace_command
using namespace bench_trace_command;

void trace(int rounds, bool quick) {
    namespace oh = experiments::ohtsuka1998;
    const auto scene = std::make_shared<const Scene>(experiments::scene_from_json(oh::scene_json({}), "bench scene"));
    std::cout << "Ray queries, the 1998 diamond (" << scene->objects.size() << " objects)\n";
    print_load("before");
    // One ray: the camera's centre ray through pixel (320, 200), on the diamond's table.
    const Ray ray = scene->camera.ray(320.5, 200.5);
    const TraceSession session(scene);
    const TraceRecord first = session.ray(ray);
    std::cout << "  one ray, pixel (320, 200): " << first.segments.size() << " segments\n";
    const int calls = quick ? 200 : 2000;
    std::size_t sink = 0;
    const Paired one = rounds_of(rounds, [&] {
        for (int k = 0; k < calls; ++k) sink += session.ray(ray).segments.size();
    });
    print_per("trace, one ray through a session", one, calls, 1e6, "us");
    const int builds = quick ? 2 : 10;
    const Paired built = rounds_of(quick ? 1 : rounds, [&] {
        for (int k = 0; k < builds; ++k) sink += trace_ray(*scene, ray).segments.size();
    });
    print_per("trace_ray, one ray, tracer built per call", built, builds, 1e6, "us");

    // Many rays: the camera's rays that meet the diamond (every second pixel), 400-700 nm.
    const TraceRays rays = diamond_rays(session, quick ? 8 : 2);
    const std::size_t n = rays.origins.size();
    const RayBatch b0 = trace_rays(session, rays.origins.data(), rays.directions.data(), rays.wavelengths.data(), n, 1);
    double segments = 0;
    for (std::int32_t s : b0.segments) segments += s;
    std::cout << "  trace_rays: " << n << " camera rays on the diamond at 400-700 nm, " << std::setprecision(1)
              << segments / static_cast<double>(n) << " segments per ray\n";
    const Paired batch = rounds_of(rounds, [&] {
        sink += trace_rays(session, rays.origins.data(), rays.directions.data(), rays.wavelengths.data(), n, 1).n;
    });
    std::cout << "  trace_rays, one thread: " << std::setprecision(3) << static_cast<double>(n) / median(batch.cpu[0]) / 1e6
              << " M rays/s CPU (median; best " << static_cast<double>(n) / minimum(batch.cpu[0]) / 1e6 << "), wall "
              << static_cast<double>(n) / median(batch.wall[0]) / 1e6 << " M rays/s; "
              << std::setprecision(1) << median(batch.cpu[0]) / segments * 1e9 << " ns per segment\n";
    const Paired all = rounds_of(rounds, [&] {
        sink += trace_rays(session, rays.origins.data(), rays.directions.data(), rays.wavelengths.data(), n, 0).n;
    });
    std::cout << "  trace_rays, all threads: " << std::setprecision(3)
              << static_cast<double>(n) / median(all.wall[0]) / 1e6 << " M rays/s wall (median)\n";
    print_load("after");
    if (sink == 0) std::cout << "  (nothing traced)\n";
}

}  // namespace refract::cli::bench
