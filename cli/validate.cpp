// refract validate [CASE...] -o DIR [--scenes DIR] [--threads N] [--list]
// refract validate --random N [--seed S] -o DIR   (generated scenes, shrunk failures)
// Exit status: 0 every case passed, 1 some case failed, 3 none failed but some were
// skipped (not validated), 2 bad input.
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "cli/data_dir.h"
#include <refract/geometry/error.h>
#include <refract/validation/caustics.h>
#include <refract/validation/random_suite.h>
#include <refract/validation/suite.h>

namespace validate_command {

struct ValidateArgs {
    std::vector<std::string> cases;
    std::string out_dir;
    std::string scenes = "scenes/validation";
    std::string povray = "povray";
    int threads = 0;
    bool list = false;
    bool caustics = false;
    int random = -1;
    std::uint64_t seed = 1;
    std::vector<int> size{80, 60};  // W H
    bool no_dispersion = false, no_shrink = false, transforms = false, area_lights = false, mesh_files = false;
    double timeout = 60;
};

refract::cli::Registrar reg{60, [](CLI::App& app) {
    auto args = std::make_shared<ValidateArgs>();
    auto* sub = app.add_subcommand(
        "validate", "Cross-renderer validation: refract (compat povray) vs POV-Ray 3.7, physical mode vs analytic physics");
    sub->add_option("cases", args->cases, "Cases to run (default: all in the scenes directory)");
    sub->add_option("-o,--output", args->out_dir, "Report directory (report.md, report.html, images)");
    auto* scenes = sub->add_option("--scenes", args->scenes,
                                   "Directory of NAME.json scenes and NAME.tol.json tolerances (default: "
                                   "scenes/validation, else the installed share/refract/scenes/validation)");
    sub->add_option("--threads", args->threads, "Threads for refract and POV-Ray (0: all cores)")
        ->check(refract::cli::thread_range());
    sub->add_option("--povray", args->povray, "POV-Ray executable (name on PATH or path)");
    sub->add_flag("--list", args->list, "List the cases and exit");
    sub->add_option("--random", args->random,
                    "Generate N random compat scenes, compare each with POV-Ray, shrink failures to minimal cases")
        ->check(CLI::Range(0, 1000000));
    sub->add_option("--seed", args->seed, "--random: generator seed of the first scene (scene k has seed S + k)")
        ->check(CLI::NonNegativeNumber);
    sub->add_option("--size", args->size, "--random: image size W H, each 1 to 4096 (80 60)")
        ->expected(2)
        ->check(CLI::Range(1, 4096));
    sub->add_flag("--no-dispersion", args->no_dispersion, "--random: no dispersive materials");
    sub->add_flag("--transforms", args->transforms,
                  "--random: objects written untransformed with a random transform (the same scenes otherwise)");
    sub->add_flag("--area-lights", args->area_lights,
                  "--random: about half of the point lights made 2x2 rectangle or disk area lights (the same scenes otherwise)");
    sub->add_flag("--mesh-files", args->mesh_files,
                  "--random: about half of the meshes written as OBJ files in the case's directory (OUT/seed-N)");
    sub->add_flag("--no-shrink", args->no_shrink, "--random: do not shrink failures");
    sub->add_option("--timeout", args->timeout, "--random: POV-Ray time limit per scene, seconds (60)")
        ->check(CLI::Range(0.001, 86400.0));
    sub->add_flag("--caustics", args->caustics,
                  "Only the caustic comparison: refract light pass vs POV-Ray photons, region means and a profile");
    sub->callback([args, scenes] {
        namespace v = refract::validation;
        args->scenes = refract::cli::validation_scenes(args->scenes, scenes->count() > 0);
        // POV-Ray is needed by every comparison: missing, it is bad input (exit 2), not a
        // suite of skipped cases.
        const auto need_povray = [&] {
            if (v::find_povray(args->povray).empty())
                throw refract::InputError("validate: POV-Ray executable '" + args->povray +
                                          "' not found (install POV-Ray 3.7 or pass --povray PATH)");
        };
        if (args->list) {
            for (const auto& n : v::list_cases(args->scenes)) std::cout << n << "\n";
            return;
        }
        if (args->caustics) {
            if (args->threads < 0) throw refract::InputError("validate: --threads must be >= 0");
            need_povray();
            v::CausticOptions co;
            co.threads = args->threads;
            co.povray.executable = args->povray;
            co.povray.threads = refract::worker_threads(args->threads);  // 0: all cores, as everywhere
            v::SuiteResult r;
            try {
                r.cases.push_back(v::run_caustics(co));
            } catch (const v::PovrayError& e) {
                v::CaseResult c;
                c.name = "caustic-statistics";
                c.skip_reason = e.what();
                r.cases.push_back(c);
            }
            const v::Status st = r.cases[0].status;
            r.passed = st == v::Status::Pass;
            r.failed = st == v::Status::Fail;
            r.skipped = st == v::Status::Skip;
            std::cout << v::format_table(r);
            if (!args->out_dir.empty()) {
                std::error_code ec;
                std::filesystem::create_directories(args->out_dir, ec);
                if (ec) throw refract::InputError("validate: -o " + args->out_dir + ": cannot create directory (" + ec.message() + ")");
                v::write_reports(r, args->out_dir);
                std::cout << "reports: " << args->out_dir << "/report.md, " << args->out_dir << "/report.html" << std::endl;
            }
            if (r.failed > 0) std::exit(1);
            if (r.skipped > 0) std::exit(3);
            return;
        }
        if (args->out_dir.empty()) throw refract::InputError("validate: -o DIR (report directory) is required");
        if (args->random >= 0) {
            if (args->threads < 0 || args->threads > 256)
                throw refract::InputError("validate: --threads must be in [0, 256] (scenes in flight)");
            if (!(args->timeout >= 0.001 && args->timeout <= 86400))  // also NaN
                throw refract::InputError("validate: --timeout must be a number of seconds in [0.001, 86400]");
            if (!args->cases.empty()) throw refract::InputError("validate: --random takes no case names");
            v::RandomOptions ro;
            ro.count = args->random;
            ro.seed = args->seed;
            ro.out_dir = args->out_dir;
            ro.scene.width = args->size[0];
            ro.scene.height = args->size[1];
            ro.scene.dispersion = !args->no_dispersion;
            ro.scene.transforms = args->transforms;
            ro.scene.area_lights = args->area_lights;
            ro.scene.mesh_files = args->mesh_files;
            ro.shrink = !args->no_shrink;
            ro.jobs = args->threads;
            ro.povray.executable = args->povray;
            ro.povray.timeout_seconds = args->timeout;
            need_povray();
            const v::RandomResult r = v::run_random(ro, &std::cerr);
            std::cout << v::format_random(r);
            std::cout << "report: " << args->out_dir << "/report.md" << std::endl;
            if (r.failed > 0) std::exit(1);
            if (r.skipped > 0) std::exit(3);
            return;
        }
        if (args->threads < 0) throw refract::InputError("validate: --threads must be >= 0");
        for (const auto& name : args->cases) v::check_case_name(name, "validate");
        need_povray();
        v::SuiteOptions opt;
        opt.scenes_dir = args->scenes;
        opt.out_dir = args->out_dir;
        opt.cases = args->cases;
        opt.threads = args->threads;
        opt.povray.executable = args->povray;
        opt.povray.threads = refract::worker_threads(args->threads);  // 0: all cores, as everywhere
        const v::SuiteResult r = v::run_suite(opt, &std::cerr);
        std::cout << v::format_table(r);
        std::cout << "reports: " << args->out_dir << "/report.md, " << args->out_dir << "/report.html" << std::endl;
        // main() maps every CLI error to status 2; the suite's own statuses are set here.
        if (r.failed > 0) std::exit(1);
        if (r.skipped > 0) std::exit(3);
    });
}};

}  // namespace validate_command
using namespace validate_command;
