// refract bench: the Ohtsuka & Kawai 1998 diamond timed with refract and with POV-Ray 3.7
// on the matching exported scene (docs/performance.md).
#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <vector>

#include <sys/resource.h>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include <unistd.h>

#include "cli/commands.h"
#include <refract/core/progress.h>
#include <refract/core/threads.h>
#include <refract/core/render.h>
#include <refract/core/tracer.h>
#include <refract/experiments/common.h>
#include <refract/experiments/ohtsuka1998.h>
#include <refract/geometry/error.h>
#include <refract/validation/compare.h>
#include <refract/validation/pov_export.h>
#include <refract/validation/povray_runner.h>

namespace bench_command {

struct Args {
    int width = 640, height = 480, threads = 0, samples = 31;
    std::uint64_t photons = 30000;
    std::string povray = "povray";
    double timeout = 900;
    bool no_povray = false;
    int polarisation_pairs = 0;
    int birefringence_pairs = 0;
    bool kernels = false, meshes = false, objects = false, sweep = false, mesh_file = false;
    bool trace = false, trace_quick = false, grin = false;
    int sweep_rays = 0;
    std::string rtiow;
    int rounds = 0;  // 0: 5 for --kernels / --meshes, 3 for the diamond
};

using refract::cli::bench::median;
double cpu_seconds() { return refract::cli::bench::process_cpu_seconds(); }

// Two scenes timed in pairs (a, b, a, b, ...): wall and CPU time of each render, median
// and min, the ratio b / a per pair, and the load average before and after.
struct PairTimes {
    std::vector<double> wall[2], cpu[2], ratio_wall, ratio_cpu;
    std::uint64_t segments[2] = {0, 0}, photon_segments[2] = {0, 0};
};
PairTimes time_pairs(const refract::Scene& a, const refract::Scene& b, const refract::RenderOptions& opt, int pairs) {
    using namespace refract;
    PairTimes t;
    for (int k = 0; k < pairs; ++k)
        for (int m = 0; m < 2; ++m) {
            const double c0 = cpu_seconds();
            const RenderResult r = render(m == 0 ? a : b, opt);
            t.wall[m].push_back(r.stats.seconds);
            t.segments[m] = r.stats.segments;
            t.photon_segments[m] = r.stats.photon_segments;
            t.cpu[m].push_back(cpu_seconds() - c0);
            if (m == 1) {
                t.ratio_wall.push_back(t.wall[1].back() / t.wall[0].back());
                t.ratio_cpu.push_back(t.cpu[1].back() / t.cpu[0].back());
            }
        }
    return t;
}

void print_row(const std::string& what, const std::vector<double>& v) {
    std::cout << "  " << std::left << std::setw(44) << what << std::right << std::fixed << std::setprecision(3)
              << " median " << std::setw(8) << median(v) << "  min " << std::setw(8)
              << *std::min_element(v.begin(), v.end()) << "\n";
}

void print_load(const char* when) {
    double load[3] = {0, 0, 0};
    if (getloadavg(load, 3) > 0)
        std::cout << "  load average " << when << ": " << std::setprecision(2) << load[0] << " " << load[1] << " "
                  << load[2] << "\n";
}

// The same brilliant in diamond and in moissanite as a uniaxial crystal (optic axis along
// the table normal of the scene's gem, tilted 25° about x), both with exact polarisation,
// light pass and spectral eye pass: target moissanite <= 3x diamond.
void compare_birefringence(const nlohmann::json& scene, const refract::RenderOptions& opt, int pairs) {
    using namespace refract;
    print_load("before");
    nlohmann::json dj = scene;
    dj["render"]["polarisation"] = "exact";
    nlohmann::json mj = dj;
    const double a = 25.0 * M_PI / 180.0;
    mj["materials"]["diamond"] = {{"type", "uniaxial"}, {"crystal", "moissanite"},
                                  {"optic_axis", {0.0, std::cos(a), std::sin(a)}}};
    const Scene diamond = experiments::scene_from_json(dj, "bench diamond exact");
    const Scene moissanite = experiments::scene_from_json(mj, "bench moissanite exact");
    const PairTimes t = time_pairs(diamond, moissanite, opt, pairs);
    std::cout << "  segments traced, diamond / moissanite: eye " << t.segments[0] << " / " << t.segments[1]
              << ", light " << t.photon_segments[0] << " / " << t.photon_segments[1] << "\n";
    print_row("diamond (exact), light + eye pass, wall (s)", t.wall[0]);
    print_row("moissanite (uniaxial, exact), wall (s)", t.wall[1]);
    print_row("diamond (exact), light + eye pass, CPU (s)", t.cpu[0]);
    print_row("moissanite (uniaxial, exact), CPU (s)", t.cpu[1]);
    print_row("moissanite / diamond per pair, wall", t.ratio_wall);
    print_row("moissanite / diamond per pair, CPU", t.ratio_cpu);
    std::cout << "  target: moissanite <= 3x diamond (CPU median " << std::setprecision(2) << median(t.ratio_cpu)
              << "x: " << (median(t.ratio_cpu) <= 3.0 ? "met" : "missed") << ")\n";
    print_load("after");
}

// Natural against exact polarisation on the same scene, in pairs (natural, exact, natural,
// exact, ...): wall and CPU time of each render, median and min, the ratio per pair, and
// the load average before and after.
void compare_polarisation(const nlohmann::json& scene, const refract::RenderOptions& opt, int pairs) {
    using namespace refract;
    double load[3] = {0, 0, 0};
    if (getloadavg(load, 3) > 0)
        std::cout << "  load average before: " << std::setprecision(2) << load[0] << " " << load[1] << " " << load[2] << "\n";
    nlohmann::json ej = scene;
    ej["render"]["polarisation"] = "exact";
    const Scene natural = experiments::scene_from_json(scene, "bench natural");
    const Scene exact = experiments::scene_from_json(ej, "bench exact");
    std::vector<double> wall[2], cpu[2], ratio_wall, ratio_cpu;
    std::uint64_t segments[2] = {0, 0}, photon_segments[2] = {0, 0};
    for (int k = 0; k < pairs; ++k)
        for (int m = 0; m < 2; ++m) {
            const double c0 = cpu_seconds();
            const RenderResult r = render(m == 0 ? natural : exact, opt);
            wall[m].push_back(r.stats.seconds);
            segments[m] = r.stats.segments;
            photon_segments[m] = r.stats.photon_segments;
            cpu[m].push_back(cpu_seconds() - c0);
            if (m == 1) {
                ratio_wall.push_back(wall[1].back() / wall[0].back());
                ratio_cpu.push_back(cpu[1].back() / cpu[0].back());
            }
        }
    auto row = [](const std::string& what, const std::vector<double>& v) {
        std::cout << "  " << std::left << std::setw(40) << what << std::right << std::fixed << std::setprecision(3)
                  << " median " << std::setw(8) << median(v) << "  min " << std::setw(8)
                  << *std::min_element(v.begin(), v.end()) << "\n";
    };
    // The same work: both models walk the same trees (the threshold uses natural-light
    // weights), so they trace the same segments.
    std::cout << "  segments traced, natural / exact: eye " << segments[0] << " / " << segments[1] << ", light "
              << photon_segments[0] << " / " << photon_segments[1]
              << (segments[0] == segments[1] && photon_segments[0] == photon_segments[1] ? " (the same)" : " (differ)")
              << "\n";
    row("natural light + eye pass, wall (s)", wall[0]);
    row("exact light + eye pass, wall (s)", wall[1]);
    row("natural light + eye pass, CPU (s)", cpu[0]);
    row("exact light + eye pass, CPU (s)", cpu[1]);
    row("exact / natural per pair, wall", ratio_wall);
    row("exact / natural per pair, CPU", ratio_cpu);
    std::cout << "  target: exact <= 1.5x natural (CPU median " << std::setprecision(2) << median(ratio_cpu)
              << "x: " << (median(ratio_cpu) <= 1.5 ? "met" : "missed") << ")\n";
    if (getloadavg(load, 3) > 0)
        std::cout << "  load average after: " << std::setprecision(2) << load[0] << " " << load[1] << " " << load[2] << "\n";
}

// The gem as a triangle mesh instead of a plane set: the same solid (mesh_of), searched by
// Embree in refract and written as mesh2 for POV-Ray.
refract::Scene with_gem_as_mesh(refract::Scene s) {
    for (refract::Object& o : s.objects)
        if (const auto* c = std::get_if<refract::ConvexPolyhedron>(&o.shape)) o.shape = refract::mesh_of(*c);
    return s;
}

// The 1998 diamond, paired rounds. Eye pass of the scene POV-Ray renders (compat mode,
// POV-Ray's dispersion law): refract with the gem as planes and as a mesh, POV-Ray with
// it as CSG and as mesh2; and refract's physical light + eye pass. Wall and CPU time of
// each run (POV-Ray: its whole process), medians and minima, ratios per pair, and the
// image differences that show each pair did the same work.
void diamond(const refract::experiments::ohtsuka1998::SceneParams& p, const Args& a, const refract::RenderOptions& opt) {
    using namespace refract;
    namespace oh = experiments::ohtsuka1998;
    namespace b = cli::bench;
    const Scene phys = experiments::scene_from_json(oh::scene_json(p), "bench scene");
    const Scene pov = experiments::scene_from_json(oh::povray_scene_json(p, a.samples), "bench povray scene");
    const Scene pov_mesh = with_gem_as_mesh(pov);
    size_t triangles = 0;
    for (const Object& o : pov_mesh.objects)
        if (const auto* m = std::get_if<TriangleMesh>(&o.shape)) triangles += m->triangles.size();
    validation::PovrayOptions po;
    po.executable = a.povray;
    po.threads = a.threads;
    po.timeout_seconds = a.timeout;
    const std::string sdl_csg = a.no_povray ? "" : validation::export_pov(pov);
    const std::string sdl_mesh = a.no_povray ? "" : validation::export_pov(pov_mesh);
    std::vector<std::string> names = {"refract compat, gem as 121 planes", "refract compat, gem as " +
                                      std::to_string(triangles) + " triangles (POV-Ray's mesh2 test)",
                                      "refract physical, light + eye pass, 31 λ",
                                      "the same, every gem segment by the full plane loop"};
    if (!a.no_povray) {
        names.push_back("POV-Ray, gem as CSG intersection");
        names.push_back("POV-Ray, gem as mesh2");
    }
    std::cout << "  eye pass of the scene POV-Ray renders: POV-Ray's law, " << a.samples
              << " bands; POV-Ray timed as a whole process; " << a.rounds << " paired rounds\n";
    b::print_load("before");
    std::vector<Image> images(names.size());
    std::vector<double> eye_wall, light_wall, per_core, gem_per_core;
    const b::Paired t = b::paired_runs(names.size(), a.rounds, [&](size_t k) {
        if (k >= 4) {
            images[k] = validation::render_povray(k == 4 ? sdl_csg : sdl_mesh, p.width, p.height, po).image;
            return;
        }
        RenderOptions o = opt;
        o.trace.facet_local = k != 3;
        const RenderResult r = render(k == 0 ? pov : k == 1 ? pov_mesh : phys, o);
        images[k] = r.image;
        if (k == 2) {
            light_wall.push_back(r.stats.light_seconds);
            eye_wall.push_back(r.stats.seconds - r.stats.light_seconds);
            per_core.push_back(static_cast<double>(r.stats.segments) / eye_wall.back() / a.threads);
            gem_per_core.push_back(static_cast<double>(r.stats.facet_local + r.stats.facet_full) / r.stats.seconds /
                                   a.threads);
        }
    });
    b::print_load("after");
    std::cout << "  " << std::left << std::setw(46) << "" << std::right << std::setw(12) << "wall median" << std::setw(10)
              << "min" << std::setw(12) << "CPU median" << std::setw(10) << "min" << "\n";
    for (size_t k = 0; k < names.size(); ++k)
        std::cout << "  " << std::left << std::setw(46) << names[k] << std::right << std::fixed << std::setprecision(3)
                  << std::setw(12) << b::median(t.wall[k]) << std::setw(10) << b::minimum(t.wall[k]) << std::setw(12)
                  << b::median(t.cpu[k]) << std::setw(10) << b::minimum(t.cpu[k]) << "\n";
    std::cout << "  physical render: light pass " << b::median(light_wall) << " s, eye pass " << b::median(eye_wall)
              << " s (wall medians), " << std::scientific << std::setprecision(3) << b::median(per_core)
              << " eye-pass segments/s per core; " << b::median(gem_per_core)
              << " segments leaving gem facets per second per core over the whole render (light and eye pass)"
              << std::fixed << "\n";
    std::cout << "  target: physical light + eye pass <= 2 s wall on 2 cores: "
              << (b::median(t.wall[2]) <= 2.0 ? "met" : "missed") << "\n";
    // Ratios per pair (the same round), then their median.
    const auto ratio = [&](size_t num, size_t den) {
        std::vector<double> r;
        for (size_t i = 0; i < t.cpu[num].size(); ++i) r.push_back(t.cpu[num][i] / t.cpu[den][i]);
        return b::median(r);
    };
    const auto diff = [&](size_t x, size_t y) { return validation::compare_images(images[x], images[y], 1.0 / 255); };
    const auto show_diff = [&](const std::string& what, size_t x, size_t y) {
        const auto d = diff(x, y);
        std::cout << "  same work? " << std::left << std::setw(44) << what << std::right << " RMSE " << std::scientific
                  << std::setprecision(2) << d.rmse << ", max " << d.max_error << std::fixed << ", "
                  << std::setprecision(3) << 100 * d.fraction_over << " % of pixels over 1/255\n";
    };
    show_diff("refract planes vs refract mesh:", 0, 1);
    show_diff("facet-local vs full plane loop:", 2, 3);
    std::cout << std::setprecision(2) << "  CPU ratio refract mesh / refract planes (paired median): " << ratio(1, 0) << "x\n"
              << "  CPU ratio full plane loop / facet-local, physical render: " << ratio(3, 2) << "x\n";
    if (a.no_povray) return;
    // Against POV-Ray: the suite's rule (validation/compare.h), refract clipped to POV-Ray's [0, 1].
    const validation::Targets targets;
    const auto show_povray = [&](const std::string& what, size_t x, size_t y) {
        const auto d = validation::compare_with_povray_image(images[x], images[y], targets);
        std::cout << "  same work? " << std::left << std::setw(44) << what << std::right << " RMSE " << std::scientific
                  << std::setprecision(2) << d.rmse << ", max " << d.max_error << std::fixed << ", "
                  << std::setprecision(3) << 100 * d.fraction_over << " % of pixels over " << targets.pixel_tolerance
                  << ": the suite's targets " << (targets.met_by(d) ? "met" : "missed") << "\n";
    };
    show_povray("POV-Ray CSG vs POV-Ray mesh2:", 4, 5);
    show_povray("refract planes vs POV-Ray CSG:", 0, 4);
    show_povray("refract mesh vs POV-Ray mesh2:", 1, 5);
    std::cout << std::setprecision(2) << "  CPU ratio POV-Ray mesh2 / refract planes (like for like, the fastest of each): "
              << ratio(5, 0) << "x (target >= 10x)\n"
              << "  CPU ratio POV-Ray mesh2 / refract mesh:   " << ratio(5, 1) << "x\n"
              << "  CPU ratio POV-Ray CSG / refract planes:   " << ratio(4, 0) << "x\n"
              << "  CPU ratio POV-Ray CSG / POV-Ray mesh2:    " << ratio(4, 5) << "x\n";
}
refract::cli::Registrar reg{75, [](CLI::App& app) {
    auto a = std::make_shared<Args>();
    auto* sub = app.add_subcommand(
        "bench", "Time the 1998 diamond against POV-Ray 3.7 (gem as CSG and as mesh2), paired; or the intersection "
                 "kernels and meshes against Embree");
    sub->add_option("--width", a->width, "Image width (640)");
    sub->add_option("--height", a->height, "Image height (480)");
    sub->add_option("--threads", a->threads, "Threads for refract and POV-Ray (+WT) (0: all cores)")->check(refract::cli::thread_range());
    sub->add_option("--samples", a->samples, "POV-Ray dispersion_samples (31 = 400-700 nm every 10 nm)");
    sub->add_option("--photons", a->photons, "Light-pass photons (30000)")->check(CLI::NonNegativeNumber);
    sub->add_option("--povray", a->povray, "POV-Ray executable");
    sub->add_option("--timeout", a->timeout, "POV-Ray time limit in seconds (900; 0.001 to 86400)");
    sub->add_flag("--no-povray", a->no_povray, "Time refract only");
    sub->add_option("--polarisation-pairs", a->polarisation_pairs,
                    "Only time natural against exact polarisation, in N pairs (natural, exact, ...)")
        ->check(CLI::Range(1, 100));
    sub->add_option("--birefringence-pairs", a->birefringence_pairs,
                    "Only time the brilliant in diamond against moissanite (uniaxial), exact polarisation, in N pairs")
        ->check(CLI::Range(1, 100));
    sub->add_flag("--kernels", a->kernels,
                  "Only the round brilliant's intersection: plane-set kernel against Embree on its triangles, same rays");
    sub->add_flag("--meshes", a->meshes, "Only the mesh search, 80 to 327 680 triangles, against Embree alone");
    sub->add_flag("--mesh-file", a->mesh_file,
                  "Only the mesh-file load: a 1.3 M-triangle binary PLY, STL and OBJ, load and BVH times, bytes per triangle");
    sub->add_flag("--objects", a->objects, "Only the nearest-hit search over 10 to 10 000 spheres, the tracer's (sphere set or object BVH) against one by one");
    sub->add_option("--rtiow", a->rtiow,
                    "Only the RTIOW chapter scene against a build of the book's code at PATH (docs/performance.md)");
    sub->add_flag("--sweep", a->sweep,
                  "Only the proportion sweep: one cut's construction and evaluation apart, the full grid extrapolated, "
                  "1 and 2 MPI ranks (--threads: the sample's threads)");
    sub->add_option("--sweep-rays", a->sweep_rays, "With --sweep: rays per metric (default: the documented count)")
        ->check(CLI::Range(1, 1 << 24));
    sub->add_flag("--trace", a->trace,
                  "Only ray queries on the 1998 diamond: one ray's record (trace) and trace_rays, one thread and all");
    sub->add_flag("--trace-quick", a->trace_quick, "With --trace: fewer calls and rays (seconds)");
    sub->add_flag("--grin", a->grin,
                  "Only gradient-index media: index-and-gradient evaluations per second per profile, adaptive against "
                  "fixed steps");
    sub->add_option("--rounds", a->rounds, "Paired rounds (5; the diamond: 3)")->check(CLI::Range(0, 100));
    sub->callback([a] {
        using namespace refract;
        // The elapsed time on stderr, when it is a terminal and the results (stdout) go elsewhere:
        // on one terminal the result lines themselves show the progress.
        Progress progress("bench", "", 0, cli::stderr_is_terminal() && isatty(STDOUT_FILENO) == 0);
        a->threads = worker_threads(a->threads);
        if (a->kernels || a->meshes || a->objects || a->sweep || a->mesh_file || a->trace || a->grin || !a->rtiow.empty()) {
            if (a->grin) cli::bench::grin(a->rounds > 0 ? a->rounds : 5);
            if (a->trace) cli::bench::trace(a->rounds > 0 ? a->rounds : 5, a->trace_quick);
            if (a->mesh_file) cli::bench::mesh_file();
            if (a->sweep) cli::bench::sweep(a->threads, a->sweep_rays);
            if (a->objects) cli::bench::objects(a->rounds > 0 ? a->rounds : 5);
            if (!a->rtiow.empty()) cli::bench::rtiow(a->rtiow, a->rounds > 0 ? a->rounds : 3);
            if (a->kernels) cli::bench::kernels(a->rounds > 0 ? a->rounds : 5);
            if (a->meshes) cli::bench::meshes(a->rounds > 0 ? a->rounds : 5);
            return;
        }
        namespace oh = experiments::ohtsuka1998;
        if (a->width < 1 || a->height < 1 || a->width > 8192 || a->height > 8192)
            throw InputError("bench: --width/--height must be in [1, 8192] (got " + std::to_string(a->width) + "×" +
                             std::to_string(a->height) + ")");
        if (a->threads < 1 || a->threads > 256)
            throw InputError("bench: --threads must be in [1, 256] (got " + std::to_string(a->threads) + ")");
        if (a->samples < 2 || a->samples > 1000)
            throw InputError("bench: --samples must be in [2, 1000] (got " + std::to_string(a->samples) + ")");
        if (!(a->timeout >= 0.001 && a->timeout <= 86400))  // NaN too
            throw InputError("bench: --timeout must be a number of seconds in [0.001, 86400]");
        if (!a->no_povray && a->polarisation_pairs == 0 && a->birefringence_pairs == 0 &&
            validation::find_povray(a->povray).empty())
            throw InputError("bench: POV-Ray executable '" + a->povray +
                             "' not found (install POV-Ray 3.7, or time refract alone with --no-povray)");
        oh::SceneParams p;
        p.width = a->width;
        p.height = a->height;
        p.photons = a->photons;
        RenderOptions opt;
        opt.threads = a->threads;
        std::cout << "Ohtsuka & Kawai 1998 diamond, " << p.width << "x" << p.height << ", " << a->threads
                  << " threads\n";
        if (a->polarisation_pairs > 0) {
            compare_polarisation(oh::scene_json(p), opt, a->polarisation_pairs);
            return;
        }
        if (a->birefringence_pairs > 0) {
            compare_birefringence(oh::scene_json(p), opt, a->birefringence_pairs);
            return;
        }
        if (a->rounds == 0) a->rounds = 3;
        diamond(p, *a, opt);
    });
}};

}  // namespace bench_command
using namespace bench_command;
