// refract reproduce -o OUT [--quick] [--threads N] [--skip-validation]
// The main job: every registered experiment into OUT/<name>/, the validation suite into
// OUT/validation/, and the report: OUT/index.html and a page per section
// (experiments/report_site.h).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include <refract/core/progress.h>
#include "cli/data_dir.h"
#include <refract/experiments/experiment.h>
#include <refract/experiments/plot.h>
#include <refract/experiments/report_site.h>
#include <refract/geometry/error.h>
#include <refract/validation/files.h>
#include <refract/validation/povray_runner.h>
#include <refract/validation/suite.h>

namespace reproduce_command {
namespace fs = std::filesystem;
namespace ex = refract::experiments;

struct Args {
    std::string out = "out";
    std::string scenes = "scenes/validation";
    int threads = 0;
    bool quick = false;
    bool skip_validation = false;
};

refract::cli::Registrar reg{90, [](CLI::App& app) {
    auto a = std::make_shared<Args>();
    auto* sub = app.add_subcommand(
        "reproduce", "Run every experiment and the validation suite into OUT, with OUT/index.html showing them");
    sub->add_option("-o,--output", a->out, "Output directory (default: out)");
    sub->add_option("--threads", a->threads, "Worker threads (0: all cores)")->check(refract::cli::thread_range());
    sub->add_flag("--quick", a->quick, "Small images and few samples (smoke run)");
    auto* scenes = sub->add_option("--scenes", a->scenes,
                                   "Validation scenes directory (default: scenes/validation, else the installed "
                                   "share/refract/scenes/validation)");
    sub->add_flag("--skip-validation", a->skip_validation, "Do not run the validation suite");
    sub->callback([a, scenes] {
        if (a->threads < 0) throw refract::InputError("reproduce: --threads must be >= 0 (got " +
                                                      std::to_string(a->threads) + ")");
        if (a->out.empty()) throw refract::InputError("reproduce: -o OUT must not be empty");
        // Validation that cannot run is bad input, refused before any work: its scenes and POV-Ray.
        if (!a->skip_validation) {
            a->scenes = refract::cli::validation_scenes(a->scenes, scenes->count() > 0);
            const std::string hint = " (pass --scenes DIR or --skip-validation)";
            try {
                refract::validation::list_cases(a->scenes);
            } catch (const refract::InputError& e) {
                throw refract::InputError("reproduce: the validation cannot run: " + std::string(e.what()) + hint);
            }
            if (refract::validation::find_povray().empty())
                throw refract::InputError("reproduce: the validation cannot run: POV-Ray executable 'povray' not found "
                                          "(install POV-Ray 3.7 or pass --skip-validation)");
        }
        const fs::path out(a->out);
        std::error_code ec;
        fs::create_directories(out, ec);
        if (ec || !fs::is_directory(out))
            throw refract::InputError(a->out + ": cannot create the output directory");
        std::vector<ex::ReportSection> sections;
        refract::Progress progress("reproduce", "experiments", static_cast<std::int64_t>(ex::all().size()),
                                   refract::cli::stderr_is_terminal());
        for (const auto& e : ex::all()) {
            const auto t0 = std::chrono::steady_clock::now();
            progress.message("experiment " + e.name + " ...");
            const std::string dir = (out / e.name).string();
            fs::create_directories(dir, ec);
            e.run({dir, a->threads, a->quick});
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            progress.message("experiment " + e.name + ": done in " + ex::fmt(s, 3) + " s");
            progress.add(1);
            sections.push_back({e.name, e.description, e.name, "", false});
        }
        progress.finish();
        int failed = 0;
        ex::ReportSection val = ex::validation_section();
        if (a->skip_validation) {
            val.note = "skipped (--skip-validation)";
            val.problem = true;
        } else {
            std::cerr << "validation ..." << std::endl;
            namespace v = refract::validation;
            v::SuiteOptions opt;
            opt.scenes_dir = a->scenes;
            opt.out_dir = (out / "validation").string();
            opt.threads = a->threads;
            try {
                const v::SuiteResult r = v::run_suite(opt, &std::cerr);
                failed = r.failed;
                val.problem = r.failed > 0 || r.skipped > 0;
                val.note = std::to_string(r.passed) + " passed, " + std::to_string(r.failed) + " failed, " +
                           std::to_string(r.skipped) + " skipped (see report.html)";
            } catch (const refract::InputError& e) {  // checked above: should not happen, but exits 2 if it does
                val.note = std::string("not run: ") + e.what();
                val.problem = true;
                sections.push_back(val);
                ex::write_report_site(out.string(), sections);
                throw refract::InputError(std::string("reproduce: the validation did not run: ") + e.what());
            }
        }
        sections.push_back(val);
        ex::write_report_site(out.string(), sections);
        std::cout << "reproduce: results in " << a->out << ", open " << (out / "index.html").string() << std::endl;
        if (failed > 0) {
            std::cerr << "reproduce: " << failed << " validation case(s) failed" << std::endl;
            std::exit(1);
        }
    });
}};

}  // namespace reproduce_command
using namespace reproduce_command;
