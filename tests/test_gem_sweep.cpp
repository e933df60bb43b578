// The proportion sweep's mechanics (experiments/gem_sweep.h, gem_sweep_file.h; docs/gem-metrics.md
// "Sweep"): exact decimal ranges, the grid's order, impossible cuts recorded, results
// independent of order and threads, and the journal that lets an interrupted sweep resume
// into the byte-identical CSV. The metric values themselves are not asserted here.
#include <catch2/catch.hpp>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_sweep_file.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/error.h>
#include "tests/temp_dir.h"

namespace fs = std::filesystem;
namespace sw = refract::experiments::gem_sweep;

extern char** environ;

namespace {

fs::path fresh_dir(const std::string& name) { return refract::test::fresh_dir("sweep", name); }

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// crown 30:36:3 x pavilion 40:44:1: 15 cuts, the pavilion at 44 deg outside the domain.
sw::Sweep small_sweep() {
    sw::Sweep s;
    s.grid = sw::single_cut_grid(refract::brilliant_preset("gia-default"));
    sw::set_axis(s.grid, sw::parse_axis("crown_angle", "30:36:3"));
    sw::set_axis(s.grid, sw::parse_axis("pavilion_angle", "40:44:1"));
    s.metric.rays = 16;
    s.metric.wavelengths = 3;
    return s;
}

std::string csv_of(const std::vector<sw::Row>& rows) {
    sw::Lines lines;
    for (const auto& r : rows) lines[r.index] = sw::csv_line(r);
    return sw::csv_text(lines);
}

int fields(const std::string& line) {
    int n = 1;
    bool quoted = false;
    for (char c : line) {
        if (c == '"') quoted = !quoted;
        n += c == ',' && !quoted;
    }
    return n;
}

}  // namespace

TEST_CASE("Sweep ranges START STOP STEP give the exact decimal values", "[sweep]") {
    const sw::Axis p = sw::parse_axis("pavilion_angle", "38:43:0.1");
    CHECK(p.count == 51);
    CHECK(p.value(3) == 38.3);  // the double nearest 38.3, not 38 + 3 * 0.1
    CHECK(p.value(50) == 43.0);
    CHECK(p.text() == "38:43:0.1");
    CHECK(sw::parse_axis("table", "52.50:60:0.25").text() == "52.5:60:0.25");
    const sw::Axis c = sw::parse_axis("crown_angle", "23:41:0.5");
    CHECK(c.count == 37);
    CHECK(c.value(36) == 41.0);
    const sw::Axis off = sw::parse_axis("star", "40:50:3");  // STOP off the grid: the last value below it
    CHECK(off.count == 4);
    CHECK(off.value(3) == 49.0);
    const sw::Axis one = sw::parse_axis("lower_half", "77.5");
    CHECK(one.count == 1);
    CHECK(one.value(0) == 77.5);
}

TEST_CASE("Sweep range errors name the parameter", "[sweep]") {
    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(sw::parse_axis("crown_angle", "41:23:0.5"), Contains("--crown-angle") && Contains("STOP is below START"));
    CHECK_THROWS_WITH(sw::parse_axis("pavilion_angle", "38:43:0"), Contains("--pavilion-angle") && Contains("STEP must be positive"));
    CHECK_THROWS_WITH(sw::parse_axis("pavilion_angle", "38:43:-0.1"), Contains("--pavilion-angle"));
    CHECK_THROWS_WITH(sw::parse_axis("table", "50:60"), Contains("--table") && Contains("wrong number of fields"));
    CHECK_THROWS_WITH(sw::parse_axis("star", "4e1"), Contains("--star"));
    CHECK_THROWS_WITH(sw::parse_axis("lower_half", "1.1234567"), Contains("--lower-half"));
    CHECK_THROWS_WITH(sw::parse_axis("girdle", "0:1000:0.0001"), Contains("--girdle") && Contains("values"));
}

TEST_CASE("Sweep grid order has the last parameter varying fastest", "[sweep]") {
    const sw::Sweep s = small_sweep();
    REQUIRE(s.grid.size() == 15);
    CHECK(s.grid.cut(0).crown_angle == 30.0);
    CHECK(s.grid.cut(0).pavilion_angle == 40.0);
    CHECK(s.grid.cut(1).pavilion_angle == 41.0);
    CHECK(s.grid.cut(5).crown_angle == 33.0);
    CHECK(s.grid.cut(5).pavilion_angle == 40.0);
    CHECK(s.grid.cut(14).crown_angle == 36.0);
    CHECK(s.grid.cut(14).pavilion_angle == 44.0);
    CHECK(s.grid.cut(14).table == 57.0);  // the preset's value where nothing is swept
}

TEST_CASE("Sweep impossible cuts are recorded with their one-line reason", "[sweep]") {
    const sw::Sweep s = small_sweep();
    const sw::Row ok = sw::evaluate(s, 3), bad = sw::evaluate(s, 4);  // pavilion 43 and 44 deg
    CHECK(ok.possible);
    CHECK(ok.measured.pavilion_angle == Approx(43.0).margin(1e-9));
    CHECK_FALSE(bad.possible);
    CHECK(bad.reason.find("pavilion angle") != std::string::npos);
    CHECK(bad.reason.find('\n') == std::string::npos);
    const std::string header = sw::csv_header();
    CHECK(fields(sw::csv_line(ok)) == fields(header));
    CHECK(fields(sw::csv_line(bad)) == fields(header));
    CHECK(sw::csv_line(bad).find(",impossible,") != std::string::npos);
}

TEST_CASE("Sweep seed and row depend on the cut only, not on its index", "[sweep]") {
    const sw::Sweep s = small_sweep();
    sw::Sweep other = s;  // the same cut (crown 33, pavilion 41) at another index
    sw::set_axis(other.grid, sw::parse_axis("crown_angle", "33"));
    const sw::Row a = sw::evaluate(s, 6), b = sw::evaluate(other, 1);
    REQUIRE(a.cut.crown_angle == b.cut.crown_angle);
    REQUIRE(a.cut.pavilion_angle == b.cut.pavilion_angle);
    CHECK(sw::cut_seed(1, a.cut) == sw::cut_seed(1, b.cut));
    CHECK(sw::cut_seed(1, a.cut) != sw::cut_seed(2, a.cut));
    CHECK(sw::cut_seed(1, a.cut) != sw::cut_seed(1, s.grid.cut(7)));
    const std::string la = sw::csv_line(a), lb = sw::csv_line(b);
    CHECK(la.substr(la.find(',')) == lb.substr(lb.find(',')));
}

TEST_CASE("Sweep CSV is byte-identical for any thread count and cut order", "[sweep]") {
    const sw::Sweep s = small_sweep();
    std::vector<std::int64_t> idx = sw::all_indices(s);
    const std::string one = csv_of(sw::run(s, idx, 1));
    std::reverse(idx.begin(), idx.end());
    const std::string two = csv_of(sw::run(s, idx, 2));
    CHECK(one == two);
    CHECK(std::count(one.begin(), one.end(), '\n') == 16);
}

TEST_CASE("Sweep resumes a torn journal into the byte-identical CSV", "[sweep]") {
    const fs::path dir = fresh_dir("resume");
    const sw::Sweep s = small_sweep();
    const std::string full = (dir / "full.csv").string(), part = (dir / "part.csv").string();
    const auto st = sw::run_to_file(s, full, 2);
    CHECK(st.computed == 15);
    CHECK(st.impossible == 3);
    CHECK_FALSE(fs::exists(sw::journal_path(full)));
    const std::string reference = slurp(full);

    // An interrupted sweep: rows 0, 2 and 7 finished, row 9 torn in the middle, one more row
    // left by rank 2 of an MPI run.
    std::istringstream in(reference);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    {
        std::ofstream j(sw::journal_path(part), std::ios::binary);
        j << "# " << sw::fingerprint(s) << "\n" << lines[1] << "\n" << lines[3] << "\n" << lines[8] << "\n"
          << lines[10].substr(0, 20);
        std::ofstream p(sw::part_journal_path(part, 2), std::ios::binary);
        p << "# " << sw::fingerprint(s) << "\n" << lines[12] << "\n";
    }
    const auto resumed = sw::run_to_file(s, part, 1);
    CHECK(resumed.resumed == 4);
    CHECK(resumed.computed == 11);
    CHECK(slurp(part) == reference);
    CHECK_FALSE(fs::exists(sw::journal_path(part)));
    CHECK_FALSE(fs::exists(sw::part_journal_path(part, 2)));
    fs::remove_all(dir);
}

TEST_CASE("Sweep refuses the journal of a sweep with other parameters", "[sweep]") {
    const fs::path dir = fresh_dir("other");
    const std::string out = (dir / "s.csv").string();
    sw::Sweep s = small_sweep();
    { std::ofstream(sw::journal_path(out)) << "# " << sw::fingerprint(s) << "\n"; }
    s.metric.rays = 32;
    CHECK_THROWS_WITH(sw::run_to_file(s, out, 1),
                      Catch::Matchers::Contains("s.csv.journal") && Catch::Matchers::Contains("other parameters"));
    CHECK_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST_CASE("Sweep killed mid-run resumes into the byte-identical CSV", "[sweep]") {
    const fs::path dir = fresh_dir("kill");
    const std::string out = (dir / "s.csv").string(), ref = (dir / "ref.csv").string();
    const std::vector<std::string> args{REFRACT_EXE, "sweep", "brilliant", "--crown-angle", "30:36:1", "--pavilion-angle",
                                        "40:43:1", "--rays", "16", "--wavelengths", "3", "--threads", "1", "--quiet",
                                        "-o", out};
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    REQUIRE(posix_spawn(&pid, REFRACT_EXE, nullptr, nullptr, argv.data(), environ) == 0);
    // Kill it (SIGKILL: no clean-up at all) once two rows are in its journal.
    const auto rows_in_journal = [&] {
        const std::string j = slurp(sw::journal_path(out));
        return std::count(j.begin(), j.end(), '\n') - 1;
    };
    int status = 0;
    bool exited = false;
    for (int i = 0; i < 20000 && rows_in_journal() < 2; ++i) {
        if (::waitpid(pid, &status, WNOHANG) == pid) {
            exited = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    REQUIRE_FALSE(exited);  // it finished (or failed) before it could be interrupted
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    const long finished = rows_in_journal();
    INFO("rows in the journal when killed: " << finished);
    CHECK(finished >= 2);
    CHECK(finished < 28);
    CHECK_FALSE(fs::exists(out));

    const std::string cmd = std::string(REFRACT_EXE) + " sweep brilliant --crown-angle 30:36:1 --pavilion-angle 40:43:1 "
                            "--rays 16 --wavelengths 3 --threads 2 --quiet -o ";
    REQUIRE(std::system((cmd + out + " >/dev/null").c_str()) == 0);
    REQUIRE(std::system((cmd + ref + " >/dev/null").c_str()) == 0);
    CHECK(slurp(out) == slurp(ref));
    CHECK_FALSE(fs::exists(sw::journal_path(out)));
    fs::remove_all(dir);
}

TEST_CASE("Sweep command refuses a bad range naming the parameter", "[sweep]") {
    const fs::path dir = fresh_dir("cli");
    const std::string out = (dir / "s.csv").string(), err = (dir / "err.txt").string();
    for (const auto& [args, name] : std::vector<std::pair<std::string, std::string>>{
             {"--crown-angle 41:23:0.5", "--crown-angle"},
             {"--pavilion-angle 38:x:0.1", "--pavilion-angle"},
             {"--table 50:60:0", "--table"},
             {"--lower-half 70:80", "--lower-half"},
             {"--material unobtainium", "--material"}}) {
        const int status = std::system((std::string(REFRACT_EXE) + " sweep brilliant " + args + " -o " + out + " 2>" + err).c_str());
        const std::string e = slurp(err);
        INFO(e);
        CHECK(WEXITSTATUS(status) == 2);
        CHECK(std::count(e.begin(), e.end(), '\n') == 1);
        CHECK(e.find(name) != std::string::npos);
        CHECK_FALSE(fs::exists(out));
        CHECK_FALSE(fs::exists(sw::journal_path(out)));
    }
    fs::remove_all(dir);
}

TEST_CASE("gem-cuts quick writes the crown x pavilion maps, best cuts and summary", "[sweep]") {
    namespace gc = refract::experiments::gem_cuts;
    const fs::path dir = fresh_dir("gem-cuts");
    const gc::Result r = gc::compute({dir.string(), 2, true});
    REQUIRE(r.main_rows.size() == 9);
    REQUIRE(r.detail_rows.size() == 4);
    REQUIRE(r.optima.size() == gc::metrics().size());
    REQUIRE(r.presets.size() == 2);
    CHECK(r.presets[0].second.cut.table == 53.0);  // Tolkowsky's own cut, not a grid cell
    for (size_t k = 0; k < gc::metrics().size(); ++k) {
        const auto& m = gc::metrics()[k];
        const auto& o = r.optima[k];
        REQUIRE(o.top.size() == 5);
        const double best = gc::metric_of(o.best.metrics, m.key).value;
        for (const auto& row : r.main_rows)  // no cut of the grid beats the one named best
            if (row.possible) CHECK_FALSE((m.maximise ? gc::metric_of(row.metrics, m.key).value > best
                                                      : gc::metric_of(row.metrics, m.key).value < best));
        CHECK(o.d_crown == o.best.cut.crown_angle - 34.5);
    }
    if (!refract::experiments::gnuplot_available()) return;
    gc::write(r, dir.string());
    for (const auto& m : gc::metrics()) {
        CHECK(fs::file_size(dir / ("gem_cuts_" + m.key + ".png")) > 1000);
        CHECK(fs::exists(dir / ("gem_cuts_" + m.key + ".pdf")));
    }
    const std::string csv = slurp(dir / "gem_cuts_sweep.csv");
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 10);
    const std::string summary = slurp(dir / "summary.md");
    CHECK(summary.find("refract sweep brilliant --crown-angle 30:38:4 --pavilion-angle 39:42:1.5") != std::string::npos);
    CHECK(summary.find("28305 cuts") != std::string::npos);
    fs::remove_all(dir);
}
