// refract experiment NAME -o DIR (required: no default directory)
#include <chrono>
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include <refract/core/progress.h>
#include <refract/experiments/common.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/error.h>

namespace experiment_command {

struct Args {
    std::string name, out;
    int threads = 0;
    bool quick = false;
    bool list = false;
};

refract::cli::Registrar reg{20, [](CLI::App& app) {
    auto a = std::make_shared<Args>();
    std::string help = "Run one experiment driver: CSV, figures and summary.md into DIR";
    auto* sub = app.add_subcommand("experiment", help);
    sub->add_option("name", a->name, "Experiment name (--list shows them)");
    sub->add_option("-o,--output", a->out, "REQUIRED to run one: output directory (none is assumed)");
    sub->add_option("--threads", a->threads, "Worker threads (0: all cores)")->check(refract::cli::thread_range());
    sub->add_flag("--quick", a->quick, "Smaller images and fewer samples (smoke runs)");
    sub->add_flag("--list", a->list, "List the experiments");
    sub->callback([a] {
        namespace ex = refract::experiments;
        if (a->list || a->name.empty()) {
            for (const auto& e : ex::all()) std::cout << e.name << "\t" << e.description << "\n";
            return;
        }
        const auto& e = ex::find(a->name);
        // No default directory: a run never writes where it was not told to.
        if (a->out.empty()) throw refract::InputError("experiment " + e.name + ": -o DIR (output directory) is required");
        const bool created = ex::ensure_dir(a->out);  // before the work: a bad -o is bad input
        const auto t0 = std::chrono::steady_clock::now();
        try {
            refract::Progress progress("experiment " + e.name, "", 0, refract::cli::stderr_is_terminal());
            e.run({a->out, a->threads, a->quick});
        } catch (const refract::InputError&) {
            std::error_code ec;
            if (created) std::filesystem::remove_all(a->out, ec);  // refused: nothing left
            throw;
        }
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::cout << e.name << ": results in " << a->out << " (" << ex::fmt(s, 3) << " s)\n";
    });
}};

}  // namespace experiment_command
using namespace experiment_command;
