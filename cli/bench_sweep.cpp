// refract bench --sweep: the cost of the proportion sweep (docs/gem-metrics.md, "Sweep";
// docs/performance.md). Construction of a cut (CGAL) and its evaluation
// (gem_metrics::measure) timed apart on a coarse sub-grid of the full >= 26 000-cut grid,
// the sub-grid swept on the requested threads and extrapolated to the full grid, and the
// same sub-grid under `mpirun -np 1` and `-np 2` (one thread per rank), CSVs compared.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <unistd.h>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include "cli/sweep_mpi.h"
#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_sweep_file.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace refract::cli::bench {

namespace bench_sweep_command {

namespace sw = experiments::gem_sweep;
using experiments::fmt;

std::string self_exe() {
    std::error_code ec;
    const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("refract") : p.string();
}

std::string slurp(const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace bench_sweep_command
using namespace bench_sweep_command;

void sweep(int threads, int rays) {
    sw::Sweep full = experiments::gem_cuts::full_sweep();
    if (rays > 0) full.metric.rays = rays;
    // The sample: every 7th table, 12th crown angle and 25th pavilion angle of the full grid.
    sw::Sweep sample = full;
    sw::set_axis(sample.grid, sw::parse_axis("table", "52:66:7"));
    sw::set_axis(sample.grid, sw::parse_axis("crown_angle", "23:41:6"));
    sw::set_axis(sample.grid, sw::parse_axis("pavilion_angle", "38:43:2.5"));
    const std::int64_t n = sample.grid.size();
    std::cout << "sweep: the full grid " << experiments::gem_cuts::command_of(full, "sweep.csv") << "\n"
              << "  " << full.grid.size() << " cuts; " << full.metric.rays << " rays per metric, " << full.metric.wavelengths
              << " wavelengths, " << (full.metric.exact_polarisation ? "exact" : "natural") << " polarisation\n"
              << "  sample: " << n << " cuts, " << experiments::gem_cuts::command_of(sample, "sample.csv") << "\n";

    // Construction and evaluation apart, one thread.
    std::vector<double> build_s, eval_s;
    int impossible = 0;
    for (std::int64_t i = 0; i < n; ++i) {
        const BrilliantCut cut = sample.grid.cut(i);
        const double t0 = wall_seconds();
        Gem gem;
        try {
            gem = build_brilliant(cut);
        } catch (const InputError&) {
            ++impossible;
            continue;
        }
        const double t1 = wall_seconds();
        gem_metrics::MetricOptions m = sample.metric;
        m.seed = sw::cut_seed(sample.metric.seed, cut);
        const auto g = gem_metrics::measure(gem, m);
        (void)g;
        build_s.push_back(t1 - t0);
        eval_s.push_back(wall_seconds() - t1);
    }
    const auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0 : s / static_cast<double>(v.size());
    };
    std::cout << "  construction of one cut (validate + CGAL build, one thread): median " << fmt(1e3 * median(build_s), 3)
              << " ms, mean " << fmt(1e3 * mean(build_s), 3) << " ms (" << build_s.size() << " cuts, " << impossible
              << " impossible)\n"
              << "  evaluation of one cut (gem_metrics::measure, one thread): median " << fmt(1e3 * median(eval_s), 3)
              << " ms, mean " << fmt(1e3 * mean(eval_s), 3) << " ms\n";

    // The sample swept on `threads`, extrapolated.
    const double t0 = wall_seconds(), c0 = process_cpu_seconds();
    sw::run(sample, sw::all_indices(sample), threads);
    const double wall = wall_seconds() - t0, cpu = process_cpu_seconds() - c0;
    const double scale = static_cast<double>(full.grid.size()) / static_cast<double>(n);
    std::cout << "  sample on " << threads << " thread(s): " << fmt(wall, 3) << " s wall, " << fmt(cpu, 3)
              << " s CPU -> full grid extrapolated: " << fmt(wall * scale / 60, 3) << " min wall ("
              << fmt(wall * scale / 3600, 3) << " h)\n";

    // One and two MPI ranks on this machine, one thread each.
    if (!mpi::available() || std::system("command -v mpirun >/dev/null 2>&1") != 0) {
        std::cout << "  MPI: not measured (refract built without MPI, or mpirun missing)\n";
        return;
    }
    if (::geteuid() == 0) {  // Open MPI refuses root without these
        ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
        ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    }
    const std::string dir = (std::filesystem::temp_directory_path() / ("refract-bench-sweep-" + random_token())).string();
    std::filesystem::create_directories(dir);
    std::string cmd = experiments::gem_cuts::command_of(sample, "");
    cmd = cmd.substr(std::string("refract").size(), cmd.size() - std::string("refract").size() - 4);  // drop "refract" and " -o "
    double seconds[3] = {0, 0, 0};
    for (int np : {1, 2}) {
        const std::string out = dir + "/np" + std::to_string(np) + ".csv";
        const std::string run = "mpirun --oversubscribe -np " + std::to_string(np) + " '" + self_exe() + "'" + cmd +
                                " --threads 1 --quiet -o '" + out + "' >/dev/null";
        const double s0 = wall_seconds();
        const int rc = std::system(run.c_str());
        seconds[np] = wall_seconds() - s0;
        if (rc != 0) {
            std::cout << "  MPI: mpirun -np " << np << " failed (exit status " << rc << ")\n";
            std::filesystem::remove_all(dir);
            return;
        }
    }
    const bool same = slurp(dir + "/np1.csv") == slurp(dir + "/np2.csv");
    std::filesystem::remove_all(dir);
    std::cout << "  MPI on one machine, one thread per rank (launch included): 1 rank " << fmt(seconds[1], 3)
              << " s, 2 ranks " << fmt(seconds[2], 3) << " s, speed-up " << fmt(seconds[1] / seconds[2], 3)
              << "; CSVs byte-identical: " << (same ? "yes" : "NO") << "\n";
}

}  // namespace refract::cli::bench
