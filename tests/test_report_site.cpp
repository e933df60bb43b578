// The HTML report (experiments/report_site.h, markdown_html.h) and the figures' contour
// levels (experiments/plot.h): the summaries rendered as HTML with their links rebased into
// the section's directory, one page per section with the navigation, PDFs linked, and every
// relative link and image of the pages naming a file that exists.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <refract/experiments/markdown_html.h>
#include <refract/experiments/plot.h>
#include <refract/experiments/report_site.h>
#include <refract/validation/files.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract::experiments;
namespace fs = std::filesystem;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void put(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
}

}  // namespace

TEST_CASE("markdown summaries become HTML: headings, tables with alignment, lists, code, bold and rebased images") {
    const std::string md =
        "# Title <b>\n\nA paragraph with `gem_cuts_METRIC.png`, **bold** and *emphasis*;\nsecond line.\n\n"
        "| metric | value |\n|---|---:|\n| light_return | 0.8257 |\n\n- one\n- two [link](other.csv)\n\n"
        "1. first\n2. second\n\n![Fig. 4](fig4.png)\n\n```\nx < y\n```\n";
    const std::string h = markdown_to_html(md, "yasuda1984/");
    CHECK(has(h, "<h1 id=\"title-b\">Title &lt;b&gt;</h1>"));
    CHECK(has(h, "<p>A paragraph with <code>gem_cuts_METRIC.png</code>, <strong>bold</strong> and <em>emphasis</em>;\nsecond line.</p>"));
    CHECK(has(h, "<th>metric</th><th style=\"text-align:right\">value</th>"));
    CHECK(has(h, "<td>light_return</td><td style=\"text-align:right\">0.8257</td>"));
    CHECK(has(h, "<ul>\n<li>one</li>\n<li>two <a href=\"yasuda1984/other.csv\">link</a></li>\n</ul>"));
    CHECK(has(h, "<ol>\n<li>first</li>\n<li>second</li>\n</ol>"));
    CHECK(has(h, "<img src=\"yasuda1984/fig4.png\" alt=\"Fig. 4\">"));
    CHECK(has(h, "<pre><code>x &lt; y\n</code></pre>"));
    CHECK_FALSE(has(h, "![") );
    // Absolute and fragment targets are left alone; odd characters are percent-encoded.
    CHECK(has(markdown_to_html("[a](https://example.org/x) [b](#top) [c](a b.csv)", "d/"),
              "<a href=\"https://example.org/x\">a</a> <a href=\"#top\">b</a> <a href=\"d/a%20b.csv\">c</a>"));
}

TEST_CASE("contour levels are round numbers inside the data's range, at most the number asked for") {
    const ContourLevels lr = round_contour_levels(0.576, 0.8257, 5);  // the light-return map
    CHECK(lr.start == Approx(0.6));
    CHECK(lr.step == Approx(0.05));
    CHECK(lr.end == Approx(0.8));
    CHECK(lr.count == 5);
    CHECK(lr.format == "%.2f");
    const ContourLevels fire = round_contour_levels(0.02665, 0.11502, 5);
    CHECK(fire.start == Approx(0.04));
    CHECK(fire.step == Approx(0.02));
    CHECK(fire.count == 4);
    const ContourLevels q = round_contour_levels(0.30, 0.43, 5);  // 0.02 would give 6 levels
    CHECK(q.step == Approx(0.025));
    CHECK(q.start == Approx(0.325));
    CHECK(q.format == "%.3f");
    CHECK(round_contour_levels(120, 980, 6).step == Approx(200));
    CHECK(round_contour_levels(120, 980, 6).format == "%.0f");
    CHECK_THROWS(round_contour_levels(1, 1));
}

TEST_CASE("the report has a page per section with navigation, the summary as HTML, PDFs linked and no broken link") {
    const fs::path out = refract::test::fresh_dir("report", "site");
    put(out / "exp-a/summary.md", "# Exp A\n\nShown: ![Fig](shown.png)\n\n| a | b |\n|---|---|\n| 1 | 2 |\n");
    for (const char* f : {"shown.png", "shown.gp", "shown.pdf", "other.png", "other.gp", "other.pdf", "render.png",
                          "scenes/render.json"})
        put(out / "exp-a" / f, "x");
    put(out / "exp-a/table.csv", "x,y\n1,2\n");
    put(out / "validation/report.md", "# Validation\n\n![](case/povray.png)\n");
    put(out / "validation/report.html", "<html></html>");
    put(out / "validation/case/povray.png", "x");
    write_report_site(out.string(), {{"exp-a", "first experiment", "", "", false},
                                     {"validation", "the suite", "validation", "1 failed", true}});
    const std::string index = refract::validation::read_text_file((out / "index.html").string());
    const std::string a = refract::validation::read_text_file((out / "exp-a.html").string());
    const std::string v = refract::validation::read_text_file((out / "validation.html").string());
    CHECK(has(index, "<a href=\"exp-a.html\">exp-a</a>"));
    CHECK(has(index, "class=\"note\">1 failed"));
    CHECK(has(a, "<nav><a href=\"index.html\">overview</a><a href=\"exp-a.html\" aria-current=\"page\">exp-a</a>"
                 "<a href=\"validation.html\">validation</a></nav>"));
    CHECK(has(a, "<h1 id=\"exp-a\">Exp A</h1>"));
    CHECK(has(a, "<img src=\"exp-a/shown.png\""));
    CHECK(has(a, "<code>shown.png</code> (shown above): <a href=\"exp-a/shown.png\">PNG</a> · <a href=\"exp-a/shown.pdf\">PDF</a>"));
    CHECK(has(a, "<img src=\"exp-a/other.png\" alt=\"other\"></a><figcaption><code>other.png</code> · <a "
                 "href=\"exp-a/other.pdf\">PDF</a>"));
    CHECK(has(a, "<img src=\"exp-a/render.png\""));
    CHECK(has(a, "<a href=\"exp-a/scenes/render.json\">scenes/render.json</a>"));
    CHECK_FALSE(has(a, "!["));
    CHECK(has(v, "<a href=\"validation/report.html\">"));
    CHECK(has(v, "<img src=\"validation/case/povray.png\""));
    // Every relative href and src names a file of the report.
    const std::regex target("(?:href|src)=\"([^\"#:]+)\"");
    int checked = 0;
    for (const std::string* page : {&index, &a, &v})
        for (std::sregex_iterator it(page->begin(), page->end(), target), end; it != end; ++it, ++checked)
            CHECK(fs::exists(out / (*it)[1].str()));
    CHECK(checked > 20);
    fs::remove_all(out);
}

TEST_CASE("refract report: a results directory gets its pages, and a missing or empty one is refused with one line, "
          "nothing written") {
    const fs::path dir = refract::test::fresh_dir("report", "cli");
    refract::test::check_refused(refract::test::run("report " + (dir / "none").string(), dir), "none: not a directory");
    fs::create_directories(dir / "empty");
    refract::test::check_refused(refract::test::run("report " + (dir / "empty").string(), dir),
                                 "no experiment or validation results");
    CHECK_FALSE(fs::exists(dir / "empty/index.html"));
    put(dir / "out/gem-cuts/summary.md", "# gem-cuts\n");
    const auto ok = refract::test::run("report " + (dir / "out").string(), dir);
    CHECK(ok.code == 0);
    CHECK(fs::exists(dir / "out/index.html"));
    CHECK(fs::exists(dir / "out/gem-cuts.html"));
    fs::remove_all(dir);
}
