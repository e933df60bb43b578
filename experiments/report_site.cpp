#include <refract/experiments/report_site.h>

#include <algorithm>
#include <set>
#include <filesystem>
#include <sstream>

#include <refract/experiments/experiment.h>
#include <refract/experiments/markdown_html.h>
#include <refract/experiments/plot.h>
#include <refract/validation/files.h>

namespace refract::experiments {

namespace {
namespace fs = std::filesystem;
using validation::html_escape;

const char* const kStyle =
    "body{font-family:sans-serif;margin:0;color:#222;line-height:1.4}\n"
    "nav{position:sticky;top:0;background:#f4f4f4;border-bottom:1px solid #ccc;padding:6px 1em;z-index:1}\n"
    "nav a{margin-right:1em;text-decoration:none;color:#0645ad;white-space:nowrap}\n"
    "nav a[aria-current]{font-weight:bold;color:#222}\n"
    "main{max-width:1400px;margin:1em auto;padding:0 1em}\n"
    "img{max-width:100%;border:1px solid #ccc}\n"
    "figure{display:inline-block;margin:6px;vertical-align:top}figure img{max-height:620px}\n"
    "figcaption{font-size:13px;color:#444}\n.renders img{height:160px;margin:3px}\n"
    "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px}\n"
    ".scroll{max-height:420px;overflow:auto;display:inline-block;max-width:100%}\n"
    ".note{color:#a00}code{background:#f4f4f4;padding:0 2px}\n.files{columns:3;font-size:13px}\n";

std::string dir_of(const ReportSection& s) { return s.dir.empty() ? s.name : s.dir; }

std::string page_of(const ReportSection& s) { return s.name + ".html"; }

std::string href(const std::string& path) { return html_escape(url_path(path)); }

// Regular files in DIR (and, with their relative paths, in its subdirectories), sorted.
std::vector<std::string> files_in(const fs::path& dir, bool recursive) {
    std::vector<std::string> v;
    std::error_code ec;
    if (recursive) {
        for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
             it.increment(ec))
            if (it->is_regular_file()) v.push_back(fs::relative(it->path(), dir).generic_string());
    } else {
        for (const auto& e : fs::directory_iterator(dir, ec))
            if (e.is_regular_file()) v.push_back(e.path().filename().string());
    }
    std::sort(v.begin(), v.end());
    return v;
}

bool has_ext(const std::string& f, const char* ext) { return fs::path(f).extension() == ext; }

std::string csv_table(const fs::path& file) {
    const Csv t = read_csv(file.string());
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

std::string head(const std::string& title, const std::vector<ReportSection>& sections, const std::string& current) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" << html_escape(title)
      << "</title>\n<style>\n" << kStyle << "</style></head><body>\n<nav><a href=\"index.html\""
      << (current.empty() ? " aria-current=\"page\"" : "") << ">overview</a>";
    for (const auto& s : sections)
        h << "<a href=\"" << href(page_of(s)) << "\"" << (s.name == current ? " aria-current=\"page\"" : "") << ">"
          << html_escape(s.name) << "</a>";
    h << "</nav>\n<main>\n";
    return h.str();
}

const char* const kTail = "</main></body></html>\n";

std::string figure(const std::string& dir, const std::string& png, const std::set<std::string>& files) {
    const std::string stem = fs::path(png).stem().string(), path = dir + "/" + png;
    std::ostringstream h;
    h << "<figure><a href=\"" << href(path) << "\"><img src=\"" << href(path) << "\" alt=\"" << html_escape(stem)
      << "\"></a><figcaption><code>" << html_escape(png) << "</code>";
    if (files.count(stem + ".pdf")) h << " · <a href=\"" << href(dir + "/" + stem + ".pdf") << "\">PDF</a>";
    if (files.count(stem + ".gp")) h << " · <a href=\"" << href(dir + "/" + stem + ".gp") << "\">gnuplot script</a>";
    h << "</figcaption></figure>\n";
    return h.str();
}

std::string section_page(const fs::path& out, const ReportSection& s, const std::vector<ReportSection>& sections) {
    const std::string dir = dir_of(s);
    const fs::path path = out / dir;
    const auto top = files_in(path, false);
    const std::set<std::string> files(top.begin(), top.end());
    std::ostringstream h;
    h << head("refract: " + s.name, sections, s.name) << "<h1>" << html_escape(s.name) << "</h1>\n<p>"
      << html_escape(s.description) << "</p>\n";
    if (!s.note.empty()) h << "<p" << (s.problem ? " class=\"note\"" : "") << ">" << html_escape(s.note) << "</p>\n";
    if (files.count("report.html"))
        h << "<p><a href=\"" << href(dir + "/report.html") << "\">the full report (report.html)</a></p>\n";
    // The markdown: summary.md or report.md first, then the others.
    std::vector<std::string> md;
    for (const char* first : {"summary.md", "report.md"})
        if (files.count(first)) md.push_back(first);
    for (const auto& f : top)
        if (has_ext(f, ".md") && std::find(md.begin(), md.end(), f) == md.end()) md.push_back(f);
    std::string shown;  // the markdown's text: figures it shows are not repeated
    for (const auto& f : md) {
        std::string text;
        try {
            text = validation::read_text_file((path / f).string());
        } catch (const std::exception& e) {
            h << "<p class=\"note\">" << html_escape(e.what()) << "</p>\n";
            continue;
        }
        shown += text;
        h << "<section class=\"markdown\">\n" << markdown_to_html(text, dir + "/")
          << "<p><small>from <a href=\"" << href(dir + "/" + f) << "\"><code>" << html_escape(f)
          << "</code></a></small></p>\n</section>\n";
    }
    // Figures (drawn by gnuplot: a .gp script beside them), then the renders.
    std::vector<std::string> figures, renders;
    for (const auto& f : top)
        if (has_ext(f, ".png"))
            (files.count(fs::path(f).stem().string() + ".gp") ? figures : renders).push_back(f);
    if (!figures.empty()) {
        h << "<h2 id=\"figures\">Figures</h2>\n";
        for (const auto& f : figures) {
            if (shown.find("(" + f + ")") == std::string::npos) {
                h << figure(dir, f, files);
                continue;
            }
            // Shown above: its files only.
            const std::string stem = fs::path(f).stem().string();
            h << "<p><code>" << html_escape(f) << "</code> (shown above): <a href=\"" << href(dir + "/" + f)
              << "\">PNG</a>";
            if (files.count(stem + ".pdf")) h << " · <a href=\"" << href(dir + "/" + stem + ".pdf") << "\">PDF</a>";
            h << "</p>\n";
        }
    }
    std::vector<std::string> unshown;
    for (const auto& f : renders)
        if (shown.find("(" + f + ")") == std::string::npos) unshown.push_back(f);
    if (!unshown.empty()) {
        h << "<h2 id=\"renders\">Rendered images</h2>\n<div class=\"renders\">\n";
        for (const auto& f : unshown)
            h << "<a href=\"" << href(dir + "/" + f) << "\"><img src=\"" << href(dir + "/" + f) << "\" alt=\""
              << html_escape(f) << "\" title=\"" << html_escape(f) << "\"></a>\n";
        h << "</div>\n";
    }
    std::vector<std::string> csvs;
    for (const auto& f : top)
        if (has_ext(f, ".csv")) csvs.push_back(f);
    if (!csvs.empty()) {
        h << "<h2 id=\"tables\">Tables</h2>\n";
        for (const auto& f : csvs) {
            try {
                h << csv_table(path / f);
            } catch (const std::exception& e) {
                h << "<p class=\"note\">" << html_escape(f) << ": " << html_escape(e.what()) << "</p>\n";
            }
        }
    }
    const auto all = files_in(path, true);
    if (!all.empty()) {
        h << "<h2 id=\"files\">Files</h2>\n<ul class=\"files\">\n";
        for (const auto& f : all)
            h << "<li><a href=\"" << href(dir + "/" + f) << "\">" << html_escape(f) << "</a></li>\n";
        h << "</ul>\n";
    }
    h << kTail;
    return h.str();
}

std::string index_page(const fs::path& out, const std::vector<ReportSection>& sections) {
    std::ostringstream h;
    h << head("refract: reproduced figures and tables", sections, "")
      << "<h1>refract: reproduced figures and tables</h1>\n<table>\n<tr><th>section</th><th>what</th><th>status</th>"
         "<th>figures</th></tr>\n";
    for (const auto& s : sections) {
        int figures = 0;
        for (const auto& f : files_in(out / dir_of(s), false))
            if (has_ext(f, ".png") && fs::exists(out / dir_of(s) / (fs::path(f).stem().string() + ".gp"))) ++figures;
        h << "<tr><td style=\"text-align:left\"><a href=\"" << href(page_of(s)) << "\">" << html_escape(s.name)
          << "</a></td><td style=\"text-align:left\">" << html_escape(s.description) << "</td><td"
          << (s.problem ? " class=\"note\"" : "") << ">" << html_escape(s.note.empty() ? "done" : s.note)
          << "</td><td>" << figures << "</td></tr>\n";
    }
    h << "</table>\n" << kTail;
    return h.str();
}

}  // namespace

void write_report_site(const std::string& out, const std::vector<ReportSection>& sections) {
    const fs::path o(out);
    for (const auto& s : sections) write_text_atomic((o / page_of(s)).string(), section_page(o, s, sections));
    write_text_atomic((o / "index.html").string(), index_page(o, sections));
}

ReportSection validation_section() {
    return {"validation",
            "Cross-renderer validation: refract (POV-Ray compatible mode) against POV-Ray 3.7, physical mode against "
            "analytic references",
            "validation", "", false};
}

std::vector<ReportSection> report_sections_found(const std::string& out) {
    std::vector<ReportSection> v;
    std::error_code ec;
    for (const auto& e : all())
        if (fs::is_directory(fs::path(out) / e.name, ec)) v.push_back({e.name, e.description, e.name, "", false});
    if (fs::is_directory(fs::path(out) / "validation", ec)) v.push_back(validation_section());
    return v;
}

}  // namespace refract::experiments
