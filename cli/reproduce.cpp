// refract reproduce -o OUT [--quick] [--threads N] [--skip-validation]
// The main job: every registered experiment into OUT/<name>/, the validation suite into
// OUT/validation/, and OUT/index.html showing every figure and table.
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
#include <refract/geometry/error.h>
#include <refract/validation/files.h>
#include <refract/validation/povray_runner.h>
#include <refract/validation/suite.h>

namespace {
namespace fs = std::filesystem;
namespace ex = refract::experiments;
using refract::validation::html_escape;

struct Args {
    std::string out = "out";
    std::string scenes = "scenes/validation";
    int threads = 0;
    bool quick = false;
    bool skip_validation = false;
};

// Files of one kind in DIR, sorted by name.
std::vector<std::string> files_with(const fs::path& dir, const std::string& ext) {
    std::vector<std::string> v;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().extension() == ext) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
}

std::string csv_table(const fs::path& file) {
    const ex::Csv t = ex::read_csv(file.string());
    std::ostringstream h;
    h << "<details><summary><code>" << html_escape(file.filename().string()) << "</code> (" << t.rows.size()
      << " rows)</summary>\n<div class=\"scroll\"><table>\n<tr>";
    for (const auto& c : t.header) h << "<th>" << html_escape(c) << "</th>";
    h << "</tr>\n";
    for (const auto& r : t.rows) {
        h << "<tr>";
        for (const auto& c : r) h << "<td>" << html_escape(c) << "</td>";
        h << "</tr>\n";
    }
    h << "</table></div></details>\n";
    return h.str();
}

struct Section {
    std::string name, description, dir;  // dir relative to OUT
    std::string note;                     // status line
    bool problem = false;                 // the note reports a failure or a skip
};

std::string index_html(const fs::path& out, const std::vector<Section>& sections) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      << "<title>refract: reproduced figures and tables</title>\n<style>\n"
      << "body{font-family:sans-serif;max-width:1400px;margin:1em auto;padding:0 1em;color:#222}\n"
      << "img{max-width:100%;border:1px solid #ccc;margin:4px}\n"
      << ".figures img{max-height:620px}\n.renders img{height:160px}\n"
      << "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}\n"
      << ".scroll{max-height:400px;overflow:auto;display:inline-block}\n.note{color:#a00}\n"
      << "</style></head><body>\n<h1>refract: reproduced figures and tables</h1>\n<ul>\n";
    for (const auto& s : sections)
        h << "<li><a href=\"#" << html_escape(s.name) << "\">" << html_escape(s.name) << "</a>: "
          << html_escape(s.description) << "</li>\n";
    h << "</ul>\n";
    for (const auto& s : sections) {
        const fs::path dir = out / s.dir;
        h << "<h2 id=\"" << html_escape(s.name) << "\">" << html_escape(s.name) << "</h2>\n<p>"
          << html_escape(s.description) << "</p>\n";
        if (!s.note.empty())
            h << "<p" << (s.problem ? " class=\"note\"" : "") << ">" << html_escape(s.note) << "</p>\n";
        for (const char* doc : {"summary.md", "report.html", "report.md"})
            if (fs::exists(dir / doc))
                h << "<p><a href=\"" << html_escape(s.dir + "/" + doc) << "\">" << doc << "</a></p>\n";
        // Figures (drawn by gnuplot: a .gp script beside them) first, then the renders.
        std::vector<std::string> figures, renders;
        for (const auto& f : files_with(dir, ".png"))
            (fs::exists(dir / (fs::path(f).stem().string() + ".gp")) ? figures : renders).push_back(f);
        if (!figures.empty()) {
            h << "<div class=\"figures\">\n";
            for (const auto& f : figures)
                h << "<a href=\"" << html_escape(s.dir + "/" + f) << "\"><img src=\"" << html_escape(s.dir + "/" + f)
                  << "\" alt=\"" << html_escape(f) << "\" title=\"" << html_escape(f) << "\"></a>\n";
            h << "</div>\n";
        }
        if (!renders.empty()) {
            h << "<h3>Rendered images</h3>\n<div class=\"renders\">\n";
            for (const auto& f : renders)
                h << "<a href=\"" << html_escape(s.dir + "/" + f) << "\"><img src=\"" << html_escape(s.dir + "/" + f)
                  << "\" alt=\"" << html_escape(f) << "\" title=\"" << html_escape(f) << "\"></a>\n";
            h << "</div>\n";
        }
        const auto csvs = files_with(dir, ".csv");
        if (!csvs.empty()) {
            h << "<h3>Tables</h3>\n";
            for (const auto& f : csvs) {
                try {
                    h << csv_table(dir / f);
                } catch (const std::exception& e) {
                    h << "<p class=\"note\">" << html_escape(f) << ": " << html_escape(e.what()) << "</p>\n";
                }
            }
        }
    }
    h << "</body></html>\n";
    return h.str();
}

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
        std::vector<Section> sections;
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
        Section val{"validation", "Cross-renderer validation: refract (POV-Ray compatible mode) against POV-Ray 3.7, "
                                  "physical mode against analytic references",
                    "validation", "", false};
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
                ex::write_text_atomic((out / "index.html").string(), index_html(out, sections));
                throw refract::InputError(std::string("reproduce: the validation did not run: ") + e.what());
            }
        }
        sections.push_back(val);
        ex::write_text_atomic((out / "index.html").string(), index_html(out, sections));
        std::cout << "reproduce: results in " << a->out << ", open " << (out / "index.html").string() << std::endl;
        if (failed > 0) {
            std::cerr << "reproduce: " << failed << " validation case(s) failed" << std::endl;
            std::exit(1);
        }
    });
}};

}  // namespace
