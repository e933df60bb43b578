// Reports of the validation suite: the plain-text table, report.md, report.html.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <refract/geometry/format.h>
#include <refract/validation/files.h>
#include <refract/validation/suite.h>

namespace refract::validation {
namespace {

std::string fmt(double v, bool percent) {
    if (std::isinf(v)) return "inf";
    char buf[64];
    if (percent) std::snprintf(buf, sizeof buf, "%.3f %%", 100.0 * v);
    else return format_significant(v, 3);
    return buf;
}

std::string tolerance_text(const Metric& m) { return m.tolerance ? "<= " + fmt(*m.tolerance, m.percent) : "-"; }

std::string md_escape(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '|') o += "\\|";
        else if (c == '\n') o += ' ';
        else o += c;
    }
    return o;
}

std::string summary_line(const SuiteResult& r) {
    std::ostringstream s;
    s << r.passed << " passed, " << r.failed << " failed, " << r.skipped << " skipped (of " << r.cases.size() << ")";
    return s.str();
}

}  // namespace

std::string format_table(const SuiteResult& r) {
    size_t wc = 4, wm = 6, wv = 5, wt = 9;
    for (const CaseResult& c : r.cases) {
        wc = std::max(wc, c.name.size());
        for (const Metric& m : c.metrics) {
            wm = std::max(wm, m.name.size());
            wv = std::max(wv, fmt(m.value, m.percent).size());
            wt = std::max(wt, tolerance_text(m).size());
        }
    }
    std::ostringstream o;
    auto row = [&](const std::string& a, const std::string& b, const std::string& c, const std::string& d,
                   const std::string& e) {
        char buf[1024];
        std::snprintf(buf, sizeof buf, "%-*s  %-*s  %*s  %-*s  %s\n", static_cast<int>(wc), a.c_str(), static_cast<int>(wm),
                      b.c_str(), static_cast<int>(wv), c.c_str(), static_cast<int>(wt), d.c_str(), e.c_str());
        o << buf;
    };
    row("case", "metric", "value", "tolerance", "status");
    o << std::string(wc + wm + wv + wt + 16, '-') << "\n";
    for (const CaseResult& c : r.cases) {
        for (const Metric& m : c.metrics) row(c.name, m.name, fmt(m.value, m.percent), tolerance_text(m), status_name(m.status));
        if (!c.skip_reason.empty()) row(c.name, "(skipped part)", "-", "-", std::string("SKIP: ") + c.skip_reason);
        row(c.name, "=> case", "", "", status_name(c.status));
    }
    o << summary_line(r) << "\n";
    return o.str();
}

void write_reports(const SuiteResult& r, const std::string& dir) {
    const std::string pov = r.povray_version.empty() ? "POV-Ray (not run)" : r.povray_version;
    // Markdown.
    std::ostringstream md;
    md << "# refract validation report\n\n"
       << "refract in POV-Ray-compatible mode against " << pov
       << " on the same scene; refract's physical mode against closed-form physics; "
       << "and the physical-vs-compat difference of each case as a result.\n\n"
       << "**" << summary_line(r) << "**\n\n"
       << "| case | metric | value | tolerance | status |\n|---|---|---:|---|---|\n";
    for (const CaseResult& c : r.cases) {
        for (const Metric& m : c.metrics)
            md << "| " << c.name << " | " << m.name << " | " << fmt(m.value, m.percent) << " | " << tolerance_text(m)
               << " | " << status_name(m.status) << " |\n";
        if (!c.skip_reason.empty()) md << "| " << c.name << " | skipped part | | | SKIP: " << md_escape(c.skip_reason) << " |\n";
        md << "| **" << c.name << "** | case | | | **" << status_name(c.status) << "** |\n";
    }
    md << "\n";
    for (const CaseResult& c : r.cases) {
        md << "## " << c.name << " — " << status_name(c.status) << "\n\n";
        if (!c.description.empty()) md << md_escape(c.description) << "\n\n";
        if (!c.skip_reason.empty()) md << "Skipped: " << md_escape(c.skip_reason) << "\n\n";
        if (!c.povray_log.empty()) md << "POV-Ray log: [" << c.povray_log << "](" << c.povray_log << ")\n\n";
        if (!c.images.empty()) {
            md << "|";
            for (const auto& t : c.image_titles) md << " " << t << " |";
            md << "\n|";
            for (size_t k = 0; k < c.images.size(); ++k) md << "---|";
            md << "\n|";
            for (const auto& im : c.images) md << " ![](" << im << ") |";
            md << "\n\n";
        }
        char t[128];
        std::snprintf(t, sizeof t, "refract %.2f s (both modes), POV-Ray %.2f s.\n\n", c.refract_seconds, c.povray_seconds);
        md << t;
    }
    md << "Heat maps: max over channels of |difference|, log scale from 1e-6 (black) to 1e-1 (top of the "
          "'inferno' map); 1e-3 sits at 60 %.\n";
    write_text_file((std::filesystem::path(dir) / "report.md").string(), md.str());

    // HTML.
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>refract validation</title>\n<style>\n"
      << "body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse}"
      << "td,th{border:1px solid #ccc;padding:2px 8px;font-size:90%}td.v{text-align:right;font-family:monospace}"
      << ".PASS{background:#cfc}.FAIL{background:#fcc}.SKIP{background:#ffc}.result{color:#555}"
      << "figure{display:inline-block;margin:4px}figcaption{font-size:80%;text-align:center}"
      << "img{image-rendering:pixelated;width:240px}\n</style></head><body>\n"
      << "<h1>refract validation report</h1>\n<p>refract in POV-Ray-compatible mode against " << html_escape(pov)
      << " on the same scene; refract's physical mode against closed-form physics; and the physical-vs-compat "
      << "difference of each case as a result.</p>\n<p><b>" << summary_line(r) << "</b></p>\n"
      << "<table><tr><th>case</th><th>metric</th><th>value</th><th>tolerance</th><th>status</th></tr>\n";
    for (const CaseResult& c : r.cases) {
        for (const Metric& m : c.metrics)
            h << "<tr><td>" << html_escape(c.name) << "</td><td>" << html_escape(m.name) << "</td><td class=\"v\">"
              << fmt(m.value, m.percent) << "</td><td>" << html_escape(tolerance_text(m)) << "</td><td class=\""
              << status_name(m.status) << "\">" << status_name(m.status) << "</td></tr>\n";
        if (!c.skip_reason.empty())
            h << "<tr><td>" << html_escape(c.name) << "</td><td>skipped part</td><td></td><td></td><td class=\"SKIP\">SKIP: "
              << html_escape(c.skip_reason) << "</td></tr>\n";
        h << "<tr><th>" << html_escape(c.name) << "</th><th>case</th><td></td><td></td><th class=\""
          << status_name(c.status) << "\">" << status_name(c.status) << "</th></tr>\n";
    }
    h << "</table>\n";
    for (const CaseResult& c : r.cases) {
        h << "<h2 id=\"" << html_escape(c.name) << "\">" << html_escape(c.name) << " &mdash; <span class=\""
          << status_name(c.status) << "\">" << status_name(c.status) << "</span></h2>\n";
        if (!c.description.empty()) h << "<p>" << html_escape(c.description) << "</p>\n";
        if (!c.skip_reason.empty()) h << "<p class=\"SKIP\">Skipped: " << html_escape(c.skip_reason) << "</p>\n";
        if (!c.povray_log.empty())
            h << "<p><a href=\"" << html_escape(c.povray_log) << "\">POV-Ray log</a></p>\n";
        for (size_t k = 0; k < c.images.size(); ++k)
            h << "<figure><img src=\"" << html_escape(c.images[k]) << "\" alt=\"" << html_escape(c.image_titles[k])
              << "\"><figcaption>" << html_escape(c.image_titles[k]) << "</figcaption></figure>\n";
        char t[128];
        std::snprintf(t, sizeof t, "<p>refract %.2f s (both modes), POV-Ray %.2f s.</p>\n", c.refract_seconds, c.povray_seconds);
        h << t;
    }
    h << "<p>Heat maps: max over channels of |difference|, log scale from 1e-6 (black) to 1e-1 (top of the "
         "'inferno' map); 1e-3 sits at 60 %.</p>\n</body></html>\n";
    write_text_file((std::filesystem::path(dir) / "report.html").string(), h.str());
}

}  // namespace refract::validation
