// refract sweep design DESIGN.asc --tier NAME:FROM:TO:STEP -o sweep.csv
// One tier's angle of a faceting design swept (experiments/design_metrics.h, docs/gems.md
// "Metrics of a design"): one CSV row per angle, the stone built exactly at width 2 and
// measured; the CSV is written atomically when every row is in.
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/gem_options.h"
#include <refract/experiments/design_metrics.h>
#include <refract/experiments/gem_sweep_file.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace sweep_design_command {

namespace dm = refract::experiments::design_metrics;

struct Args {
    refract::cli::GemOptionArgs gem;
    std::string design, tier, output;
    int threads = 0;
};

void run(const Args& a) {
    const auto m = refract::cli::metric_options(a.gem);
    try {
        refract::experiments::gem_sweep::check_output(a.output);
    } catch (const refract::InputError& e) {
        throw refract::InputError(std::string("-o ") + e.what());
    }
    const refract::GemcadDesign design = refract::read_gemcad(a.design);
    refract::build_design(design);  // a design refused as it stands is bad input, not a row
    const dm::TierSweep s = dm::parse_tier_sweep(design, a.tier, m);
    const auto rows = dm::run(s, a.threads);
    refract::write_file_atomic(a.output, dm::csv_text(s, rows));
    int impossible = 0;
    for (const auto& r : rows) impossible += !r.possible;
    std::cout << "sweep: " << rows.size() << " cuts of " << a.design << " (" << impossible << " of them impossible) -> "
              << a.output << "\n";
}

refract::cli::Registrar reg{37, [](CLI::App& app) {
    CLI::App* sweep = app.get_subcommand("sweep");  // cli/sweep.cpp (order 35)
    auto a = std::make_shared<Args>();
    auto* sub = sweep->add_subcommand(
        "design", "A faceting design (.asc) over one tier's angle: --tier NAME:FROM:TO:STEP (docs/gems.md)");
    sub->add_option("design", a->design, "GemCad .asc design file")->required();
    sub->add_option("--tier", a->tier, "The tier (its name; 'tier N' for the N-th) and its angles FROM:TO:STEP, degrees")
        ->required();
    sub->add_option("-o,--output", a->output, "Output CSV")->required();
    refract::cli::add_gem_options(sub, a->gem, "Seed of the eye rays (the same for every angle)");
    sub->add_option("--threads", a->threads, "Worker threads (0: all cores)")->check(refract::cli::thread_range());
    sub->callback([a] { run(*a); });
}};

}  // namespace sweep_design_command
using namespace sweep_design_command;
