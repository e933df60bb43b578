#pragma once
// The cross-renderer validation suite (docs/validation.md). A case is a scene file
// scenes/validation/NAME.json with its tolerances beside it in NAME.tol.json:
//
//   { "description": "...",
//     "povray":   { "pixel_tolerance": 1e-3, "max_fraction_over": 1e-3, "rmse": 2e-4 },
//     "analytic": { "kind": "fresnel-sphere", "tolerance": 1e-6,
//                   "profile": { "from": [0, 60], "to": [159, 60], "tolerance": 1e-5 } },
//     "timeout": 60 }
//
// Each case renders the scene with refract in POV-Ray-compatible mode and with POV-Ray
// itself and compares them; renders it in physical mode and reports the physical vs
// compat difference as a result; and, when an analytic reference is named, checks the
// physical render (and POV-Ray's profile) against it. A case that cannot run (POV-Ray
// missing or failing, a scene POV-Ray cannot express, an unreadable file) is skipped
// with its reason and never counts as passed.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <refract/validation/povray_runner.h>

namespace refract::validation {

enum class Status { Pass, Fail, Skip, Info };
const char* status_name(Status s);

struct Metric {
    std::string name;                 // e.g. "compat vs povray: rmse"
    double value = 0;
    std::optional<double> tolerance;  // checked metrics: pass iff value <= tolerance
    Status status = Status::Info;     // Pass / Fail for checked metrics, Info for results
    bool percent = false;             // show value and tolerance as percentages
};

struct CaseResult {
    std::string name;
    std::string description;
    Status status = Status::Skip;
    std::string skip_reason;              // why a part of the case could not run
    std::vector<Metric> metrics;
    std::vector<std::string> images;      // image files written, relative to the report directory
    std::vector<std::string> image_titles;
    std::string povray_log;               // relative path of POV-Ray's log when it failed
    double refract_seconds = 0, povray_seconds = 0;
};

struct SuiteOptions {
    std::string scenes_dir = "scenes/validation";
    std::string out_dir;                 // report directory (created)
    std::vector<std::string> cases;      // empty: all
    int threads = 0;                     // refract threads (0: all cores); POV-Ray gets the same (0: 2)
    PovrayOptions povray;
};

struct SuiteResult {
    std::vector<CaseResult> cases;
    std::string povray_version;
    int passed = 0, failed = 0, skipped = 0;
};

// Refuses (InputError naming `where`) a case name that is not one plain path component:
// letters, digits, '.', '_', '-', not starting with '.' (a case writes into OUT/NAME).
void check_case_name(const std::string& name, const std::string& where);

// Case names in `dir` (NAME.json files that are not NAME.tol.json), sorted.
// Throws InputError when the directory cannot be read or holds a case name
// check_case_name refuses.
std::vector<std::string> list_cases(const std::string& dir);

// Runs one case, writing its images under out_dir/NAME/. Never throws for a problem
// of the case itself (that is a Skip with its reason).
CaseResult run_case(const std::string& name, const SuiteOptions& opt, std::string* povray_version = nullptr);

// Runs the selected cases (InputError for an unknown name, listing the known ones),
// printing one line per case to `progress` when given, and writes the reports.
SuiteResult run_suite(const SuiteOptions& opt, std::ostream* progress = nullptr);

// The plain-text table: case, metric, value, tolerance, status; then the summary.
std::string format_table(const SuiteResult& r);

// DIR/report.md and DIR/report.html (images side by side, diff heat maps).
void write_reports(const SuiteResult& r, const std::string& dir);

}  // namespace refract::validation
