#pragma once
// The HTML report of a results directory OUT (what `refract reproduce` writes): OUT/index.html
// listing the sections, and one page OUT/NAME.html per section, each with the same navigation
// bar, the section's markdown (summary.md, report.md, other .md files) rendered as HTML, its
// figures (drawn by gnuplot: NAME.gp beside NAME.png) each with its PDF linked, the rendered
// images, the CSV tables and a list of every file in OUT/NAME/. Relative links only: the
// report opens from the file system and can be moved with its directory.
#include <string>
#include <vector>

namespace refract::experiments {

struct ReportSection {
    std::string name;         // page OUT/NAME.html; also the directory OUT/NAME unless `dir` is set
    std::string description;  // one line
    std::string dir;          // relative to OUT; empty: `name`
    std::string note;         // status line, may be empty
    bool problem = false;     // the note reports a failure or a skip
};

// Writes OUT/index.html and OUT/NAME.html for each section (atomically, file by file).
// Throws InputError naming the file when one cannot be written.
void write_report_site(const std::string& out, const std::vector<ReportSection>& sections);

// The validation suite's section (OUT/validation/, its report.md and report.html).
ReportSection validation_section();

// The sections of the registered experiments whose directories exist in OUT, and the
// validation suite's when OUT/validation/ exists (`refract report OUT`).
std::vector<ReportSection> report_sections_found(const std::string& out);

}  // namespace refract::experiments
