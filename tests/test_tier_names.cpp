// The trade's tier names (geometry/gem/gemcad_names.h, docs/gems.md "Tier names"): the
// catalogue and the brilliant written as a design name their tiers G, T, C1…, P1…, CU, and
// `--tier` takes those names also for a design whose file names its tiers otherwise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <refract/experiments/design_metrics.h>
#include <refract/geometry/error.h>
#include <refract/geometry/gem/gemcad_names.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
namespace dm = refract::experiments::design_metrics;
namespace fs = std::filesystem;

namespace {

std::string design_path(const std::string& name) {
    return std::string(REFRACT_SOURCE_DIR) + "/scenes/gems/designs/" + name + ".asc";
}

gem_metrics::MetricOptions few_rays() {
    gem_metrics::MetricOptions o;
    o.rays = 64;
    o.wavelengths = 3;
    o.spot_rotations = 4;
    return o;
}

// The first facet name of each tier, in file order.
std::vector<std::string> file_names(const GemcadDesign& d) {
    std::vector<std::string> n;
    for (std::size_t k = 0; k < d.tiers.size(); ++k) n.push_back(d.tiers[k].name(static_cast<int>(k) + 1));
    return n;
}

}  // namespace

TEST_CASE("Tier names: every catalogued design names its tiers as the trade does, G, C1 C2 from the girdle inwards, "
          "T, P1 P2, CU",
          "[gemcad][tier-names]") {
    for (const char* name : {"princess", "emerald", "asscher", "radiant", "cushion", "oval", "pear", "marquise",
                             "old-european", "single"}) {
        INFO(name);
        const GemcadDesign d = read_gemcad(design_path(name));
        CHECK(file_names(d) == trade_tier_names(d));
    }
    const GemcadDesign p = read_gemcad(design_path("princess"));
    // Crown 40, 30 (corners), 28 degrees; pavilion 42 (chevrons), 40.
    CHECK(trade_tier_names(p) == std::vector<std::string>{"G", "C1", "C2", "C3", "T", "P1", "P2"});
    CHECK(p.tiers[1].angle == 40);
    CHECK(p.tiers[3].angle == 28);
    CHECK(p.tiers[5].angle == 42);
    const GemcadDesign e = read_gemcad(design_path("old-european"));
    CHECK(trade_tier_names(e).back() == "CU");
}

TEST_CASE("Tier names: the brilliant written as a design names its upper halves C1, bezels C2, stars C3, lower "
          "halves P1, pavilion mains P2",
          "[gemcad][tier-names]") {
    const Gem b = build_brilliant(brilliant_preset("gia-default"));
    const GemcadDesign d = brilliant_design(b);
    std::vector<std::pair<std::string, std::string>> kinds;  // (brilliant's kind, the tier's name), each once
    for (std::size_t k = 0, f = 0; k < d.tiers.size(); f += d.tiers[k].indices.size(), ++k) {
        const std::pair<std::string, std::string> p{facet_kind(b.facets[f].label), d.tiers[k].name(0)};
        if (std::find(kinds.begin(), kinds.end(), p) == kinds.end()) kinds.push_back(p);
    }
    using P = std::pair<std::string, std::string>;
    CHECK(kinds == std::vector<P>{P{"table", "T"}, P{"star", "C3"}, P{"bezel", "C2"}, P{"upper half", "C1"},
                                  P{"girdle", "G"}, P{"lower half", "P1"}, P{"pavilion main", "P2"}});  // no culet
    // Read back, the sweep takes them: the pavilion mains at the preset's 40.75 degrees.
    const GemcadDesign back = parse_gemcad(gemcad_text(d), "b.asc");
    const dm::TierSweep s = dm::parse_tier_sweep(back, "P2:40:41:1", few_rays());
    REQUIRE(!s.tiers.empty());
    for (std::size_t k : s.tiers) {
        CHECK(back.tiers[k].pavilion);
        CHECK(back.tiers[k].angle == Approx(40.75).margin(1e-9));
    }
}

TEST_CASE("Tier names: --tier P1 picks a design's pavilion tiers of the steepest angle by side and angle when the file "
          "names its tiers otherwise, and the file's own names still win",
          "[gemcad][tier-names][design-metrics]") {
    GemcadDesign d = read_gemcad(design_path("princess"));
    const auto named = dm::parse_tier_sweep(d, "P1:41:42:1", few_rays()).tiers;
    const auto crown = dm::parse_tier_sweep(d, "C2:29:30:1", few_rays()).tiers;
    // GemCad's own files name tiers as their designers like: here 1, 2 and A, B, K.
    const char* other[] = {"G", "A", "K", "B", "T", "1", "2"};
    for (std::size_t k = 0; k < d.tiers.size(); ++k)
        for (std::string& n : d.tiers[k].names)
            if (!n.empty()) n = other[k];
    CHECK(dm::parse_tier_sweep(d, "P1:41:42:1", few_rays()).tiers == named);
    CHECK(dm::parse_tier_sweep(d, "C2:29:30:1", few_rays()).tiers == crown);
    CHECK(dm::parse_tier_sweep(d, "1:41:42:1", few_rays()).tiers == named);
    CHECK(dm::parse_tier_sweep(d, "K:29:30:1", few_rays()).tiers == crown);
    try {
        dm::parse_tier_sweep(d, "P7:41:42:1", few_rays());
        FAIL("P7 accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("(its tiers: G, A, K, B, T, 1, 2; by side and angle: G, C1, C2, C3, T, P1, P2)") !=
              std::string::npos);
    }
    // A file's name wins over the trade's: a crown tier named P1 is the file's P1.
    d.tiers[1].names[0] = "P1";
    CHECK(dm::parse_tier_sweep(d, "P1:39:40:1", few_rays()).tiers == std::vector<std::size_t>{1});
}

TEST_CASE("Tier names on the command line: sweep design --tier P1 on a catalogued design, and the brilliant written "
          "by cut brilliant -o x.asc named so",
          "[gemcad][tier-names][cli]") {
    const fs::path dir = test::fresh_dir("tier-names", "cli");
    const std::string fast = " --rays 16 --wavelengths 3";
    const auto r = test::run("sweep design " + design_path("princess") + " --tier P1:38:43:5 -o " +
                                 (dir / "p.csv").string() + fast,
                             dir);
    CHECK(r.code == 0);
    std::ifstream in(dir / "p.csv");
    std::stringstream text;
    text << in.rdbuf();
    CHECK(text.str().find("\n0,P1,38,ok,") != std::string::npos);
    CHECK(text.str().find("\n1,P1,43,ok,") != std::string::npos);
    // The brilliant as cut brilliant writes it names its pavilion mains P2 (swept in the test above).
    REQUIRE(test::run("cut brilliant -o " + (dir / "b.asc").string(), dir).code == 0);
    const GemcadDesign b = read_gemcad((dir / "b.asc").string());
    const std::vector<std::string> names = file_names(b);
    CHECK(names == trade_tier_names(b));
    CHECK(std::count(names.begin(), names.end(), "P2") == 1);
    fs::remove_all(dir);
}
