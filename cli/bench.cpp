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

#include "cli/commands.h"
#include "core/render.h"
#include "experiments/common.h"
#include "experiments/ohtsuka1998.h"
#include "geometry/error.h"
#include "validation/pov_export.h"
#include "validation/povray_runner.h"

namespace {

struct Args {
    int width = 640, height = 480, threads = 2, samples = 31;
    std::uint64_t photons = 30000;
    std::string povray = "povray";
    double timeout = 900;
    bool no_povray = false;
    bool no_photons = false;
    int polarisation_pairs = 0;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
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

void line(const std::string& what, double seconds, const std::string& extra = "") {
    std::cout << "  " << std::left << std::setw(52) << what << std::right << std::setw(10) << std::fixed
              << std::setprecision(3) << seconds << " s" << extra << "\n";
}

refract::cli::Registrar reg{75, [](CLI::App& app) {
    auto a = std::make_shared<Args>();
    auto* sub = app.add_subcommand(
        "bench", "Time the 1998 diamond (light + eye pass) and POV-Ray 3.7 on the matching scene, as ratios");
    sub->add_option("--width", a->width, "Image width (640)");
    sub->add_option("--height", a->height, "Image height (480)");
    sub->add_option("--threads", a->threads, "Threads for refract and POV-Ray (+WT), 2")->check(refract::cli::thread_range(1));
    sub->add_option("--samples", a->samples, "POV-Ray dispersion_samples (31 = 400-700 nm every 10 nm)");
    sub->add_option("--photons", a->photons, "Light-pass photons (30000)");
    sub->add_option("--povray", a->povray, "POV-Ray executable");
    sub->add_option("--timeout", a->timeout, "POV-Ray time limit in seconds (900; 0.001 to 86400)");
    sub->add_flag("--no-povray", a->no_povray, "Time refract only");
    sub->add_flag("--no-photons", a->no_photons, "Skip the light pass against POV-Ray photons");
    sub->add_option("--polarisation-pairs", a->polarisation_pairs,
                    "Only time natural against exact polarisation, in N pairs (natural, exact, ...)")
        ->check(CLI::Range(1, 100));
    sub->callback([a] {
        using namespace refract;
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
        if (!a->no_povray && a->polarisation_pairs == 0 && validation::find_povray(a->povray).empty())
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
        // refract, physical: light pass + eye pass, full spectral split (31 wavelengths).
        const Scene phys = experiments::scene_from_json(oh::scene_json(p), "bench scene");
        const RenderResult full = render(phys, opt);
        const double eye = full.stats.seconds - full.stats.light_seconds;
        line("refract light pass (" + std::to_string(p.photons) + " photons)", full.stats.light_seconds);
        line("refract eye pass (31 wavelengths, no shortcut)", eye);
        line("refract light + eye pass", full.stats.seconds, full.stats.seconds < 10 ? "  (target < 10 s: met)"
                                                                                      : "  (target < 10 s: missed)");
        const double per_core = static_cast<double>(full.stats.segments) / eye / a->threads;
        std::cout << "  eye-pass segments " << full.stats.segments << " (" << full.stats.wavelength_segments
                  << " single-wavelength, inside/after the gem): " << std::scientific << std::setprecision(3)
                  << per_core << " segments/s per core\n"
                  << std::fixed;
        // refract, POV-Ray compat mode with POV-Ray's law: the scene POV-Ray renders.
        const nlohmann::json pj = oh::povray_scene_json(p, a->samples);
        const Scene pov = experiments::scene_from_json(pj, "bench povray scene");
        const RenderResult compat = render(pov, opt);
        line("refract compat (POV-Ray law, " + std::to_string(a->samples) + " bands)", compat.stats.seconds);
        // The same with a light pass: what POV-Ray renders with photons (statistically).
        nlohmann::json pjl = pj;
        pjl["render"]["light_pass"] = {{"photons", p.photons}, {"element_size", p.element_size}, {"region", 3}, {"seed", 7}};
        const Scene pov_light = experiments::scene_from_json(pjl, "bench povray scene with light pass");
        std::optional<RenderResult> compat_light;
        if (!a->no_photons) {
            compat_light = render(pov_light, opt);
            line("refract compat light + eye pass (" + std::to_string(p.photons) + " photons)",
                 compat_light->stats.seconds);
        }
        if (a->no_povray) return;
        validation::PovrayOptions po;
        po.executable = a->povray;
        po.threads = a->threads;
        po.timeout_seconds = a->timeout;
        try {
            const auto pr = validation::render_povray(validation::export_pov(pov), p.width, p.height, po);
            line(pr.version + " (dispersion_samples " + std::to_string(a->samples) + ", no photons)", pr.seconds);
            std::cout << "  ratio POV-Ray / refract compat eye pass:   " << std::setprecision(2)
                      << pr.seconds / compat.stats.seconds << "x (target >= 10x)\n"
                      << "  ratio POV-Ray / refract physical eye pass: " << pr.seconds / eye << "x\n";
        } catch (const validation::PovrayError& e) {
            std::cout << "  POV-Ray not timed: " << e.what() << "\n";
        }
        if (a->no_photons) return;
        try {
            validation::ExportOptions eo;
            eo.photons = true;  // photons { count N } and the gem as photon target
            eo.photon_count = p.photons;
            const auto pr = validation::render_povray(validation::export_pov(pov_light, eo), p.width, p.height, po);
            line(pr.version + " (same, photons count " + std::to_string(p.photons) + ")", pr.seconds);
            std::cout << "  ratio POV-Ray photons / refract compat light + eye pass:   " << std::setprecision(2)
                      << pr.seconds / compat_light->stats.seconds << "x (target >= 10x)\n"
                      << "  ratio POV-Ray photons / refract physical light + eye pass: "
                      << pr.seconds / full.stats.seconds << "x\n";
        } catch (const validation::PovrayError& e) {
            std::cout << "  POV-Ray with photons not timed: " << e.what() << "\n";
        }
    });
}};

}  // namespace
