// refract sweep brilliant --crown-angle 23:41:0.5 --pavilion-angle 38:43:0.1 -o sweep.csv
// The proportion sweep (experiments/gem_sweep.h, docs/gem-metrics.md "Sweep"): one CSV row
// per cut, resumable through a journal beside the output, parallel over cuts with oneTBB
// and, under `mpirun -np N`, over N ranks; the CSV is byte-identical for any N and threads.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/gem_options.h"
#include "cli/sweep_mpi.h"
#include <refract/core/progress.h>
#include <refract/experiments/gem_metrics.h>
#include <refract/experiments/gem_sweep_file.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/geometry/error.h>

namespace sweep_command {

namespace sw = refract::experiments::gem_sweep;

struct Args {
    std::string preset = "gia-default";
    std::vector<std::string> ranges = std::vector<std::string>(sw::parameter_names().size());
    std::string output, material = "diamond", polarisation = "exact", observer = "aset";
    int rays = 4096, wavelengths = 31, threads = 0;
    std::uint64_t seed = 1;
    bool quiet = false;
    bool old_spelling = false;  // --polarisation given (deprecated here)
};

sw::Sweep make_sweep(const Args& a) {
    sw::Sweep s;
    s.grid = sw::single_cut_grid(refract::brilliant_preset(a.preset));
    for (size_t k = 0; k < a.ranges.size(); ++k)
        if (!a.ranges[k].empty()) sw::set_axis(s.grid, sw::parse_axis(sw::parameter_names()[k], a.ranges[k]));
    if (a.polarisation != "exact" && a.polarisation != "natural")
        throw refract::InputError("--polarisation-model '" + a.polarisation + "': expected exact or natural");
    try {
        refract::spectrum::catalogue(a.material);  // before any cut: an unknown name is bad input
    } catch (const refract::InputError& e) {
        throw refract::InputError("--material: " + std::string(e.what()));
    }
    refract::cli::check_observer(a.observer);
    s.metric.observer = a.observer;
    s.metric.material = a.material;
    s.metric.rays = a.rays;
    s.metric.wavelengths = a.wavelengths;
    s.metric.exact_polarisation = a.polarisation == "exact";
    s.metric.seed = a.seed;
    refract::gem_metrics::validate(s.metric);  // what the library would refuse, before any cut
    return s;
}

void check_output(const std::string& out) {
    if (out.empty()) throw refract::InputError("-o: the output CSV is required");
    try {
        sw::check_output(out);
    } catch (const refract::InputError& e) {
        throw refract::InputError(std::string("-o ") + e.what());
    }
}

void report(const sw::Sweep& s, const std::string& out, std::int64_t resumed, std::int64_t computed,
            std::int64_t impossible, int ranks) {
    std::cout << "sweep: " << s.grid.size() << " cuts (" << resumed << " resumed from the journal, " << computed
              << " computed on " << ranks << (ranks == 1 ? " rank" : " ranks") << ", " << impossible
              << " of them impossible) -> " << out << "\n";
}

// Under mpirun with N > 1 ranks: rank 0 recovers the journal and broadcasts the missing
// cuts; rank r evaluates every N-th of them (journalled in OUT.journal.r); rank 0 gathers
// the lines and writes the CSV.
void run_mpi(const sw::Sweep& s, const Args& a, const refract::cli::mpi::Session& mpi) {
    std::string status;
    sw::Lines lines;
    if (mpi.rank() == 0) {
        try {
            bool found = false;
            lines = sw::recover(s, a.output, &found);
            status = found ? "ok resumed\n" : "ok\n";
            for (std::int64_t i = 0; i < s.grid.size(); ++i)
                if (!lines.count(i)) status += std::to_string(i) + "\n";
        } catch (const refract::InputError& e) {
            status = std::string("error\n") + e.what();
        }
    }
    status = mpi.broadcast(status);
    if (status.rfind("error\n", 0) == 0) throw refract::InputError(status.substr(6));
    const bool resuming = status.rfind("ok resumed\n", 0) == 0;
    std::vector<std::int64_t> share;
    {
        std::int64_t k = 0;
        for (size_t b = status.find('\n') + 1; b < status.size();) {
            const size_t e = status.find('\n', b);
            if (k++ % mpi.size() == mpi.rank()) share.push_back(std::stoll(status.substr(b, e - b)));
            b = e + 1;
        }
    }
    const std::string journal = mpi.rank() == 0 ? sw::journal_path(a.output) : sw::part_journal_path(a.output, mpi.rank());
    std::string mine;
    std::int64_t impossible = 0;
    try {
        sw::JournalWriter writer(journal, sw::fingerprint(s));
        const auto rows = sw::run(s, share, a.threads, [&](const sw::Row& r) { writer.append(sw::csv_line(r)); });
        for (const auto& r : rows) {
            mine += sw::csv_line(r) + "\n";
            impossible += !r.possible;
        }
    } catch (const refract::InputError&) {
        // Refused after it started: the journal this run began goes (rank 0's only when
        // there was none to resume).
        if (mpi.rank() > 0 || !resuming) sw::remove_new_journal(journal);
        throw;
    }
    const std::string all = mpi.gather(mine);
    if (mpi.rank() == 0) {
        const std::int64_t resumed = static_cast<std::int64_t>(lines.size());
        std::int64_t computed = 0;
        for (size_t b = 0; b < all.size();) {
            const size_t e = all.find('\n', b);
            const std::string line = all.substr(b, e - b);
            lines[sw::line_index(line)] = line;
            ++computed;
            b = e + 1;
        }
        try {
            sw::finish(s, a.output, lines);
        } catch (const refract::InputError&) {
            if (!resuming)  // every journal of this run, the other ranks' too (they wait at the barrier)
                for (int r = 0; r < mpi.size(); ++r)
                    sw::remove_new_journal(r == 0 ? journal : sw::part_journal_path(a.output, r));
            throw;
        }
        report(s, a.output, resumed, computed, impossible, mpi.size());
    }
    mpi.barrier();
    if (mpi.rank() != 0) std::filesystem::remove(journal);
}

void run(const Args& a) {
    refract::cli::mpi::Session mpi;  // MPI only under mpirun
    const sw::Sweep s = make_sweep(a);  // the same on every rank: bad input fails everywhere
    check_output(a.output);
    if (mpi.size() > 1) {
        try {
            run_mpi(s, a, mpi);
        } catch (const std::exception& e) {
            std::cerr << "refract: " << e.what() << " (rank " << mpi.rank() << ")\n";
            mpi.abort(2);
        }
        return;
    }
    refract::Progress progress("sweep", "cuts", s.grid.size(), !a.quiet && refract::cli::stderr_is_terminal());
    const auto st = sw::run_to_file(s, a.output, a.threads, [&](std::int64_t done, std::int64_t total) {
        progress.set_total(total);
        progress.set(done);
    });
    progress.finish();
    report(s, a.output, st.resumed, st.computed, st.impossible, 1);
}

refract::cli::Registrar reg{35, [](CLI::App& app) {
    auto a = std::make_shared<Args>();
    auto* sweep = app.add_subcommand("sweep", "Proportion sweeps: every cut of a grid measured, one CSV row per cut");
    sweep->require_subcommand(1);
    auto* sub = sweep->add_subcommand(
        "brilliant", "Round brilliant over ranges START:STOP:STEP of its parameters (docs/gem-metrics.md, Sweep)");
    sub->add_option("--preset", a->preset, "Cut giving the parameters that are not swept (tolkowsky, gia-default)");
    const char* units[] = {"%", "deg", "deg", "%", "%", "%"};
    for (size_t k = 0; k < a->ranges.size(); ++k) {
        const std::string& p = sw::parameter_names()[k];
        sub->add_option(sw::option_name(p), a->ranges[k],
                        "START:STOP:STEP (inclusive) or one value, " + std::string(units[k]));
    }
    sub->add_option("-o,--output", a->output, "Output CSV (its journal OUT.journal lets an interrupted sweep resume)")
        ->required();
    sub->add_option("--material", a->material, "Material (catalogue name, core/spectrum/dispersion.h)");
    sub->add_option("--rays", a->rays, "Eye rays per metric")->check(CLI::Range(16, 1 << 26));  // gem_metrics::validate: from 16
    sub->add_option("--wavelengths", a->wavelengths, "Spectral bands, 400..700 nm")->check(CLI::Range(1, 301));
    auto* model = sub->add_option("--polarisation-model", a->polarisation, "exact (Stokes-Mueller) or natural (exact)");
    // The old spelling (before --polarisation meant a light state, as in trace): still
    // accepted, with one line saying so; not listed in --help.
    sub->add_option_function<std::string>(
           "--polarisation",
           [a](const std::string& v) {
               a->polarisation = v;
               a->old_spelling = true;
               std::cerr << "refract sweep: --polarisation is deprecated here (in trace it is a light state); "
                            "use --polarisation-model\n";
           })
        ->group("");
    sub->add_option("--seed", a->seed, "Base seed (each cut's seed derives from it and the cut's parameters)")
        ->check(CLI::NonNegativeNumber);
    refract::cli::add_observer_option(sub, a->observer);
    sub->add_option("--threads", a->threads, "Worker threads per process (0: all cores)")->check(refract::cli::thread_range());
    sub->add_flag("--quiet", a->quiet, "No progress line");
    sub->callback([a, model] {
        if (a->old_spelling && model->count() > 0)
            throw refract::InputError("--polarisation: give --polarisation-model alone");
        run(*a);
    });
}};

}  // namespace sweep_command
using namespace sweep_command;
