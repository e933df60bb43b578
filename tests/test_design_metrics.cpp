// The gem metrics of any faceting design (experiments/design_metrics.h): the stone at width 2,
// the eye rays' frame covering an elongated outline, the regions of a design's facets by
// their normals, the tier sweep and its refusals, and `refract metrics` / `refract sweep
// design` on the command line. Few rays and bands: each test runs in well under 2 s.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <refract/experiments/design_metrics.h>
#include <refract/experiments/gem_observation.h>
#include <refract/geometry/error.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
namespace dm = refract::experiments::design_metrics;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string design_path(const std::string& name) {
    return std::string(REFRACT_SOURCE_DIR) + "/scenes/gems/designs/" + name + ".asc";
}

gem_metrics::MetricOptions few_rays() {
    gem_metrics::MetricOptions o;
    o.rays = 256;
    o.wavelengths = 3;
    o.spot_rotations = 4;
    return o;
}

std::string refusal(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(accepted)";
}

}  // namespace

TEST_CASE("A design is measured at width 2: the marquise (L/W 2) has the frame of its tips and every eye ray "
          "meets the stone",
          "[gem][design-metrics]") {
    const DesignGem m = dm::build_at_width_2(read_gemcad(design_path("marquise")));
    CHECK(m.width == Approx(2).epsilon(1e-12));
    CHECK(m.length / m.width > 1.8);
    const auto o = dm::options_for(m.gem, few_rays());
    CHECK(o.frame >= m.length / 2);
    const gem_metrics::GemMetrics g = dm::measure(m, few_rays());
    const auto& b = g.balance;
    CHECK(b.missed == 0);
    CHECK(b.crown + b.girdle + b.pavilion + b.lost == Approx(1).epsilon(1e-9));
    CHECK(g.light_return.value > 0.1);
    CHECK(g.light_return.value < 1);
    CHECK(g.fire.value > 0);
    CHECK(g.scintillation.value > 0);
}

TEST_CASE("A design's facets leak by the side their normals face: leakage is the light leaving downwards through "
          "the pavilion, whatever the tiers are named",
          "[gem][design-metrics]") {
    // The princess names its pavilion tiers "P1" and "P2", its crown "C1", "C2", "C3", "T".
    const DesignGem p = dm::build_at_width_2(read_gemcad(design_path("princess")));
    const gem_metrics::GemMetrics g = dm::measure(p, few_rays());
    CHECK(g.leakage.value > 0.01);
    CHECK(g.leakage.value == Approx(g.balance.pavilion).epsilon(1e-12));
    CHECK(gem_metrics::region_of_facet("1", Vec3(0.6, 0, -0.8)) == gem_metrics::Region::Pavilion);
    CHECK(gem_metrics::region_of_facet("1", Vec3(0.6, 0, 0.8)) == gem_metrics::Region::Crown);
    CHECK(gem_metrics::region_of_facet("G", Vec3(1, 0, 0)) == gem_metrics::Region::Girdle);
    CHECK(gem_metrics::region_of_facet("culet", Vec3(0, 0, -1)) == gem_metrics::Region::Pavilion);
}

TEST_CASE("The round brilliant written as a design measures as the brilliant, within the statistical errors",
          "[gem][design-metrics]") {
    const Gem b = build_brilliant(brilliant_preset("tolkowsky"));
    GemcadDesign d = brilliant_design(b);
    d.source = "tolkowsky.asc";
    const DesignGem asc = dm::build_at_width_2(d);
    CHECK(asc.width == Approx(2).epsilon(1e-9));
    const auto o = few_rays();
    const gem_metrics::GemMetrics x = gem_metrics::measure(b, o), y = dm::measure(asc, o);
    for (const auto& [a, c] : {std::make_pair(x.light_return, y.light_return), std::make_pair(x.leakage, y.leakage)})
        CHECK(std::abs(a.value - c.value) < 4 * std::hypot(a.error, c.error));
}

TEST_CASE("A tier sweep varies the angle of every tier of one name on its side, and unknown names, names on both "
          "sides and angles beyond 90 degrees are refused naming --tier",
          "[gem][design-metrics]") {
    const GemcadDesign d = read_gemcad(design_path("princess"));
    auto o = few_rays();
    o.rays = 64;
    const dm::TierSweep s = dm::parse_tier_sweep(d, "P2:38:40:2", o);
    REQUIRE(s.angles.count == 2);
    REQUIRE(s.tiers == std::vector<std::size_t>{6});
    CHECK(d.tiers[6].pavilion);
    const auto rows = dm::run(s, 1);
    REQUIRE(rows.size() == 2);
    CHECK(rows[0].angle == 38);
    CHECK(rows[1].angle == 40);
    for (const auto& r : rows) CHECK(r.possible);
    CHECK(rows[0].stone.volume != rows[1].stone.volume);
    const std::string csv = dm::csv_text(s, rows);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 3);
    CHECK_THAT(csv, Contains("\n0,P2,38,ok,,"));
    // The oval cuts its pavilion mains "P1" as five tiers (one distance per azimuth): swept together.
    CHECK(dm::parse_tier_sweep(read_gemcad(design_path("oval")), "P1:41:43:1", o).tiers.size() == 5);
    CHECK_THAT(refusal([&] { dm::parse_tier_sweep(d, "P9:38:40:1", o); }),
               Contains("--tier 'P9:38:40:1': ") && Contains("princess.asc has no tier named 'P9' (its tiers: G, C1, C2, C3, T, P1, P2)"));
    CHECK_THAT(refusal([&] { dm::parse_tier_sweep(d, "P2:80:95:5", o); }), Contains("the angles run from 0 to 90 degrees"));
    CHECK_THAT(refusal([&] { dm::parse_tier_sweep(d, "P2:40:38:1", o); }), Contains("STOP is below START"));
    CHECK_THAT(refusal([&] { dm::parse_tier_sweep(d, "P2", o); }), Contains("expected NAME:FROM:TO:STEP"));
    GemcadDesign both = d;
    both.tiers[1].names[0] = "P2";  // a crown tier named like a pavilion tier
    CHECK_THAT(refusal([&] { dm::parse_tier_sweep(both, "P2:38:40:1", o); }),
               Contains("tiers named 'P2' lie on the crown and on the pavilion"));
    CHECK(dm::parse_tier_sweep(both, "tier 7:38:40:1", o).tiers == std::vector<std::size_t>{6});
}

TEST_CASE("refract metrics and refract sweep design on the command line: the metrics as JSON, the ASET image, "
          "the sweep's CSV, and a bad tier exits 2 with one line",
          "[gem][design-metrics][cli]") {
    const fs::path dir = test::fresh_dir("design-metrics", "cli");
    const std::string oval = design_path("oval");
    const std::string fast = " --rays 64 --wavelengths 3";
    CHECK(test::run("metrics " + oval + fast + " --json --aset " + (dir / "aset.png").string() +
                        " --image-size 16 --image-samples 1",
                    dir)
              .code == 0);
    CHECK(fs::file_size(dir / "aset.png") > 0);
    CHECK(test::run("sweep design " + oval + " --tier P1:40:41:1 -o " + (dir / "s.csv").string() + fast, dir).code == 0);
    std::ifstream in(dir / "s.csv");
    std::stringstream text;
    text << in.rdbuf();
    const std::string csv = text.str();
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 3);
    test::check_refused(test::run("sweep design " + oval + " --tier X:1:2:1 -o " + (dir / "t.csv").string() + fast, dir),
                        "oval.asc has no tier named 'X'");
    CHECK_FALSE(fs::exists(dir / "t.csv"));
    test::check_refused(test::run("metrics " + oval + fast + " --aset " + (dir / "a.xyz").string(), dir), "a.xyz");
    fs::remove_all(dir);
}
