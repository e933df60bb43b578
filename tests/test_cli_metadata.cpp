// Outputs that describe themselves and the command line's shared rules (docs/limits.md,
// "Outputs"): the EXR header of a render, the JSON sidecar of every CSV, the sweep's ASET
// shares and energy balance, the far field's absorbed share, -o required, one meaning per
// flag, --threads 0, and the progress line.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/core/progress.h>
#include <refract/core/provenance.h>
#include <refract/core/spectrum/chromaticities.h>
#include <refract/experiments/plot.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;
using refract::test::check_refused;
using refract::test::run;

namespace {

fs::path fresh_dir(const std::string& name) { return refract::test::fresh_dir("climeta", name); }

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
}

const char* kSphere = R"({"camera": {"location": [0,0,-4], "width": 12, "height": 8},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "dielectric", "ior": 1.5}}]})";

// A unit sphere lit by a beam that just covers it; `alpha`: Beer–Lambert coefficient.
std::string beam_scene(double alpha) {
    nlohmann::json glass = {{"type", "dielectric"}, {"ior", 1.5}};
    if (alpha > 0) glass["absorption"] = {{"coefficients", {alpha, alpha, alpha}}};
    return nlohmann::json{
        {"camera", {{"location", {0, 0, -5}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 8}, {"height", 8}}},
        {"materials", {{"glass", glass}}},
        {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
        {"lights", {{{"type", "beam"}, {"position", {0, 0, -3}}, {"direction", {0, 0, 1}}, {"radius", 1}}}}}
        .dump();
}

}  // namespace

TEST_CASE("Chromaticities of the default pipeline: the CIE 1931 RGB primaries and, for equal energy, white at 1/3",
          "[outputs]") {
    std::vector<double> wl;
    for (int l = 400; l <= 700; l += 10) wl.push_back(l);
    const auto c = refract::spectrum::chromaticities(refract::spectrum::ColourPipeline::CieRgb, wl, {});
    // CIE 1931 RGB (Wright–Guild 700 / 546.1 / 435.8 nm): the columns of cie_rgb_to_xyz.
    CHECK(c[0] == Approx(0.49 / 0.66697).epsilon(1e-12));
    CHECK(c[1] == Approx(0.17697 / 0.66697).epsilon(1e-12));
    CHECK(c[2] == Approx(0.31 / 1.1324).epsilon(1e-12));
    CHECK(c[3] == Approx(0.8124 / 1.1324).epsilon(1e-12));
    CHECK(c[4] == Approx(0.20 / 1.20063).epsilon(1e-12));
    CHECK(c[5] == Approx(0.01063 / 1.20063).epsilon(1e-12));
    CHECK(c[6] == Approx(1.0 / 3).margin(0.01));  // E sampled on 400–700 nm, not the whole range
    CHECK(c[7] == Approx(1.0 / 3).margin(0.01));
    const auto s = refract::spectrum::chromaticities(refract::spectrum::ColourPipeline::XyzSrgb, wl,
                                                     {refract::spectrum::Illuminant::D65, 6504.0});
    CHECK(s[0] == Approx(0.64).margin(1e-4));  // IEC 61966-2-1
    CHECK(s[1] == Approx(0.33).margin(1e-4));
    CHECK(s[6] == Approx(0.3127).margin(3e-3));
    CHECK(s[7] == Approx(0.3290).margin(3e-3));
}

TEST_CASE("render writes into its EXR header the chromaticities, version, scene name and hash, integrator, samples, "
          "seed and command line, and the pixels do not change",
          "[cli][outputs]") {
    const fs::path dir = fresh_dir("exr");
    std::ofstream(dir / "s.json") << kSphere;
    const std::string s = (dir / "s.json").string();
    const auto r = run("render " + s + " --seed 5 --threads 0 -o " + (dir / "a.exr").string(), dir);
    REQUIRE(r.code == 0);
    CHECK(r.err.empty());  // no progress line when stderr is not a terminal
    const refract::Channels c = refract::read_channels((dir / "a.exr").string());
    const auto attr = [&](const std::string& name) {
        const std::string* v = c.attribute(name);
        INFO(name);
        REQUIRE(v);
        return *v;
    };
    double xy[8] = {};
    const std::string chroma = attr("chromaticities");
    {
        std::string t = chroma;
        for (char& ch : t) ch = ch == ',' ? ' ' : ch;
        std::istringstream in(t);
        for (double& v : xy) in >> v;
        REQUIRE(in);
    }
    CHECK(xy[0] == Approx(0.73467).margin(1e-5));  // CIE 1931 RGB red
    CHECK(xy[1] == Approx(0.26533).margin(1e-5));
    CHECK(xy[4] == Approx(0.16658).margin(1e-5));  // blue
    CHECK(xy[6] == Approx(1.0 / 3).margin(0.01));  // equal-energy white
    CHECK(attr("refract:version") == refract::version());
    CHECK(attr("refract:scene") == s);
    CHECK(attr("refract:scene_fnv1a64") == refract::fnv1a64_hex(slurp(dir / "s.json")));
    CHECK(attr("refract:integrator") == "fresnel-tree");
    CHECK(attr("refract:samples") == "1");
    CHECK(attr("refract:seed") == "5");
    CHECK(attr("refract:colour_pipeline") == "cie-rgb");
    CHECK(attr("refract:command_line").find("render " + s + " --seed 5") != std::string::npos);
    // --threads 0 (all cores) and 1: the same pixels.
    REQUIRE(run("render " + s + " --seed 5 --threads 1 -o " + (dir / "b.exr").string(), dir).code == 0);
    CHECK(refract::read_channels((dir / "b.exr").string()).data == c.data);
    fs::remove_all(dir);
}

TEST_CASE("sweep: the CSV gains the ASET shares and the energy balance, and its sidecar holds the settings",
          "[cli][outputs][gem]") {
    const fs::path dir = fresh_dir("sweep");
    const std::string out = (dir / "s.csv").string();
    const auto r = run("sweep brilliant --crown-angle 34 --rays 16 --wavelengths 3 --threads 0 --seed 9 "
                       "--polarisation-model natural --quiet -o " + out, dir);
    INFO(r.err);
    REQUIRE(r.code == 0);
    std::istringstream csv(slurp(out));
    std::string header, line;
    std::getline(csv, header);
    std::getline(csv, line);
    const auto h = split(header), v = split(line);
    REQUIRE(h.size() == v.size());
    std::map<std::string, double> cell;
    for (size_t k = 0; k < h.size(); ++k)
        if (h[k] != "status" && h[k] != "reason" && h[k] != "leakage_by_kind" && h[k] != "observer")
            cell[h[k]] = std::stod(v[k]);
    CHECK(h.back() == "observer");
    CHECK(v.back() == "aset");
    for (const char* f : {"aset_red", "aset_green", "aset_blue", "aset_white", "balance_crown", "balance_girdle",
                          "balance_pavilion", "balance_lost", "balance_missed"})
        REQUIRE(cell.count(f));
    // GemMetrics: the ASET shares with the lost part sum to 1, and so does the balance.
    CHECK(cell["aset_red"] + cell["aset_green"] + cell["aset_blue"] + cell["aset_white"] + cell["balance_lost"] ==
          Approx(1).margin(1e-9));
    CHECK(cell["balance_crown"] + cell["balance_girdle"] + cell["balance_pavilion"] + cell["balance_lost"] +
              cell["balance_missed"] == Approx(1).margin(1e-9));
    CHECK(cell["aset_red"] > 0);
    const auto j = nlohmann::json::parse(slurp(out + ".json"));
    CHECK(j["csv"] == "s.csv");
    CHECK(j["refract_version"] == refract::version());
    CHECK(j["command_line"].get<std::string>().find("--seed 9") != std::string::npos);
    CHECK(j["settings"]["rays"] == 16);
    CHECK(j["settings"]["wavelengths"] == 3);
    CHECK(j["settings"]["seed"] == 9);
    CHECK(j["settings"]["polarisation_model"] == "natural");
    CHECK(j["settings"]["material"] == "diamond");
    CHECK(j["settings"]["axes"]["crown_angle"] == "34");
    fs::remove_all(dir);
}

TEST_CASE("sweep: --polarisation-model names the model, and the old --polarisation is accepted with one deprecation line",
          "[cli][outputs][gem]") {
    const fs::path dir = fresh_dir("polmodel");
    const std::string sweep = "sweep brilliant --crown-angle 34 --rays 16 --wavelengths 3 --threads 1 --quiet -o ";
    const auto old = run(sweep + (dir / "old.csv").string() + " --polarisation natural", dir);
    CHECK(old.code == 0);
    CHECK(old.err == "refract sweep: --polarisation is deprecated here (in trace it is a light state); use "
                     "--polarisation-model\n");
    REQUIRE(run(sweep + (dir / "new.csv").string() + " --polarisation-model natural", dir).code == 0);
    CHECK(slurp(dir / "old.csv") == slurp(dir / "new.csv"));
    check_refused(run(sweep + (dir / "bad.csv").string() + " --polarisation-model sideways", dir),
                  "--polarisation-model 'sideways': expected exact or natural");
    CHECK(!fs::exists(dir / "bad.csv"));
    fs::remove_all(dir);
}

TEST_CASE("farfield reports the share absorbed inside an absorbing glass (0 for a clear one), and every CSV it "
          "writes has its settings beside it",
          "[cli][outputs][far-field]") {
    const fs::path dir = fresh_dir("farfield");
    double inside[2] = {};
    for (int k = 0; k < 2; ++k) {
        const fs::path scene = dir / ("s" + std::to_string(k) + ".json"), out = dir / ("ff" + std::to_string(k));
        std::ofstream(scene) << beam_scene(k ? 0.5 : 0.0);
        const std::string cmd = std::string(REFRACT_EXE) + " farfield " + scene.string() + " -o " + out.string() +
                                " --binning axis --photons 4000 --wavelengths 550 --threads 0 --no-plot >" + (dir / "stdout.txt").string() +
                                " 2>&1";
        REQUIRE(std::system(cmd.c_str()) == 0);
        const auto t = refract::experiments::read_csv((out / "far_field_summary.csv").string());
        REQUIRE(t.header.back() == "absorbed_inside");
        REQUIRE(t.rows.size() == 1);
        const auto col = [&](const std::string& name) {
            const size_t i = static_cast<size_t>(std::find(t.header.begin(), t.header.end(), name) - t.header.begin());
            REQUIRE(i < t.header.size());
            return std::stod(t.rows[0][i]);
        };
        inside[k] = col("absorbed_inside");
        CHECK(col("sum") + inside[k] == Approx(1).margin(1e-9));
        const std::string text = slurp(dir / "stdout.txt");
        CHECK(text.find(", absorbed " + (k ? std::string("0.") : std::string("0 (inside the objects 0,"))) !=
              std::string::npos);
        for (const char* f : {"far_field.csv.json", "far_field_summary.csv.json"}) {
            const auto j = nlohmann::json::parse(slurp(out / f));
            CHECK(j["settings"]["command"] == "farfield");
            CHECK(j["settings"]["options"]["--photons"] == "4000");
            CHECK(j["refract_version"] == refract::version());
        }
    }
    CHECK(inside[0] == 0);
    // Two chords through a unit sphere at 0.5 per unit length: a large share, not 0.
    CHECK(inside[1] > 0.3);
    CHECK(inside[1] < 0.8);
    fs::remove_all(dir);
}

TEST_CASE("experiment needs -o (no default ./out/NAME) and says so in its help, as sweep does", "[cli][outputs]") {
    const fs::path dir = fresh_dir("expo");
    check_refused(run("experiment optics-bench --quick", dir, "cd " + dir.string() + " &&"),
                  "experiment optics-bench: -o DIR (output directory) is required");
    CHECK(!fs::exists(dir / "out"));
    for (const std::string help : {"experiment --help", "sweep brilliant --help"}) {
        const std::string cmd =
            std::string(REFRACT_EXE) + " " + help + " >" + (dir / "help.txt").string() + " 2>&1";
        REQUIRE(std::system(cmd.c_str()) == 0);
        const std::string text = slurp(dir / "help.txt");
        const size_t o = text.find("-o,--output");
        REQUIRE(o != std::string::npos);
        const std::string line = text.substr(o, text.find('\n', o) - o);
        INFO(help << ": " << line);
        CHECK(line.find("REQUIRED") != std::string::npos);
    }
    fs::remove_all(dir);
}

TEST_CASE("The progress line: done / total, percent, elapsed and the time left, and elapsed only without a total",
          "[outputs]") {
    CHECK(refract::progress_line("render", "tiles", 30, 120, 3.0) ==
          "render: 30 / 120 tiles (25%), 3.0 s elapsed, about 9.0 s left");
    CHECK(refract::progress_line("sweep", "cuts", 0, 10, 1.5) == "sweep: 0 / 10 cuts (0%), 1.5 s elapsed");
    CHECK(refract::progress_line("far field", "photons", 4, 4, 100.0) ==
          "far field: 4 / 4 photons (100%), 1 min 40 s elapsed");
    CHECK(refract::progress_line("experiment gem-cuts", "", 0, 0, 7.25) == "experiment gem-cuts: 7.2 s elapsed");
}
