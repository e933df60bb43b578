// Gem metrics (experiments/gem_metrics.h, docs/gem-metrics.md): convergence of the
// statistical errors, the energy bookkeeping of the eye-ray trees, determinism, and the
// physics a cut's proportions and its material's dispersion must show.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <refract/core/image.h>
#include <refract/experiments/common.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/gem_metrics_experiment.h>
#include <refract/experiments/gem_metrics.h>
#include <refract/experiments/gem_observation.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/error.h>

using namespace refract;
using namespace refract::gem_metrics;

namespace {

const Gem& tolkowsky() {
    static const Gem g = build_brilliant(brilliant_preset("tolkowsky"));
    return g;
}

MetricOptions quick(int rays) {
    MetricOptions o;
    o.rays = rays;
    return o;
}

}  // namespace

TEST_CASE("Gem metrics: the statistical error of each metric falls as one over the square root of the ray count",
          "[gem-metrics]") {
    const GemMetrics a = measure(tolkowsky(), quick(496));
    const GemMetrics b = measure(tolkowsky(), quick(1984));  // 4x the rays: half the error
    for (const auto& [name, ea, eb] : {std::tuple{"light return", a.light_return.error, b.light_return.error},
                                       std::tuple{"leakage", a.leakage.error, b.leakage.error},
                                       std::tuple{"fire", a.fire.error, b.fire.error},
                                       std::tuple{"scintillation", a.scintillation.error, b.scintillation.error}}) {
        INFO(name << ": error " << ea << " at N, " << eb << " at 4N");
        REQUIRE(ea > 0);
        CHECK(ea / eb == Approx(2.0).epsilon(0.35));
    }
    // And the values agree within their errors (3 sigma).
    CHECK(std::abs(a.light_return.value - b.light_return.value) <
          3 * std::hypot(a.light_return.error, b.light_return.error));
    CHECK(std::abs(a.leakage.value - b.leakage.value) < 3 * std::hypot(a.leakage.error, b.leakage.error));
}

TEST_CASE("Gem metrics: light leaving through crown, girdle and pavilion plus the pruned light sums to one",
          "[gem-metrics]") {
    for (const bool exact : {true, false}) {
        MetricOptions o = quick(310);
        o.exact_polarisation = exact;
        const GemMetrics m = measure(tolkowsky(), o);
        const auto& s = m.balance;
        INFO("exact " << exact << ": crown " << s.crown << " girdle " << s.girdle << " pavilion " << s.pavilion
                      << " lost " << s.lost << " missed " << s.missed);
        CHECK(s.crown + s.girdle + s.pavilion + s.lost + s.missed == Approx(1.0).margin(1e-12));
        CHECK(s.missed == 0.0);                // every eye ray inside the girdle meets the stone
        CHECK(s.lost < 0.01);                  // the threshold drops less than 1 %
        CHECK(s.pavilion == Approx(m.leakage.value).margin(1e-12));
        double by_kind = 0;
        for (const auto& [kind, v] : m.leakage_by_kind) by_kind += v;
        CHECK(by_kind == Approx(s.pavilion + s.girdle).margin(1e-12));
        const auto& a = m.aset;
        CHECK(a.red + a.green + a.blue + a.white + s.lost == Approx(1.0).margin(1e-12));
        CHECK(a.white >= s.pavilion);  // light leaving through the pavilion goes below the horizon
        CHECK(a.red > a.green);        // a well-cut stone returns mostly ASET red
        // Light return counts only crown light outside the head cone, luminance weighted.
        CHECK(m.light_return.value > 0.2);
        CHECK(m.light_return.value < s.crown * 1.2);
    }
}

TEST_CASE("Gem metrics: the same seed gives identical metrics whichever thread measures", "[gem-metrics]") {
    MetricOptions o = quick(124);
    o.seed = 77;
    const GemMetrics a = measure(tolkowsky(), o);
    GemMetrics b;
    std::thread th([&] { b = measure(tolkowsky(), o); });
    th.join();
    const GemMetrics c = measure(tolkowsky(), o);
    for (const GemMetrics* x : std::vector<const GemMetrics*>{&b, &c}) {
        CHECK(x->light_return.value == a.light_return.value);
        CHECK(x->light_return.error == a.light_return.error);
        CHECK(x->fire.value == a.fire.value);
        CHECK(x->leakage.value == a.leakage.value);
        CHECK(x->scintillation.value == a.scintillation.value);
        CHECK(x->leakage_by_kind == a.leakage_by_kind);
    }
    o.seed = 78;
    const GemMetrics d = measure(tolkowsky(), o);
    CHECK(d.light_return.value != a.light_return.value);
    // Two cuts measured at once on two threads, as a sweep does: the same as one by one.
    const Gem gia = build_brilliant(brilliant_preset("gia-default"));
    const GemMetrics gia_alone = measure(gia, o);
    GemMetrics x, y;
    std::thread t1([&] { x = measure(tolkowsky(), o); });
    std::thread t2([&] { y = measure(gia, o); });
    t1.join();
    t2.join();
    CHECK(x.light_return.value == d.light_return.value);
    CHECK(x.fire.value == d.fire.value);
    CHECK(y.light_return.value == gia_alone.light_return.value);
    CHECK(y.scintillation.value == gia_alone.scintillation.value);
    CHECK(y.fire_spectrum == gia_alone.fire_spectrum);
}

TEST_CASE("Gem metrics: a pavilion far too shallow leaks more light through the pavilion than Tolkowsky's",
          "[gem-metrics]") {
    BrilliantCut shallow = brilliant_preset("tolkowsky");
    shallow.pavilion_angle = 37.5;  // below the critical-angle design: light escapes the pavilion
    const GemMetrics s = measure(build_brilliant(shallow), quick(1984));
    const GemMetrics t = measure(tolkowsky(), quick(1984));
    INFO("leakage shallow " << s.leakage.value << " +- " << s.leakage.error << ", Tolkowsky " << t.leakage.value
                            << " +- " << t.leakage.error);
    CHECK(s.leakage.value > t.leakage.value + 5 * std::hypot(s.leakage.error, t.leakage.error));
}

TEST_CASE("Gem metrics: a material without dispersion shows no fire", "[gem-metrics]") {
    MetricOptions o = quick(496);
    o.material = "2.417";  // diamond's index at every wavelength
    const GemMetrics flat = measure(tolkowsky(), o);
    CHECK(flat.fire.value == 0.0);
    CHECK(flat.fire.error == 0.0);
    o.material = "diamond";
    const GemMetrics dia = measure(tolkowsky(), o);
    CHECK(dia.fire.value > 3 * dia.fire.error);
    // Without dispersion light return is nearly the same (the index at 560 nm is 2.42).
    CHECK(flat.light_return.value == Approx(dia.light_return.value).margin(4 * dia.light_return.error));
}

TEST_CASE("Gem metrics: exact polarisation and natural light give close light return for a diamond",
          "[gem-metrics]") {
    MetricOptions o = quick(992);
    const GemMetrics ex = measure(tolkowsky(), o);
    o.exact_polarisation = false;
    const GemMetrics nat = measure(tolkowsky(), o);
    // Same rays: the difference is the model's, a few per cent at most.
    CHECK(ex.light_return.value != nat.light_return.value);
    CHECK(ex.light_return.value == Approx(nat.light_return.value).epsilon(0.05));
}

TEST_CASE("Gem metrics: the set-ups code exit directions by elevation as ASET and the viewers do", "[gem-metrics]") {
    const Vec3 up(0, 0, 1);
    auto dir = [](double el_deg) {
        const double e = el_deg * M_PI / 180;
        return Vec3(std::cos(e), 0, std::sin(e));
    };
    CHECK(aset_colour(dir(30), up) == Vec3(0, 1, 0));
    CHECK(aset_colour(dir(60), up) == Vec3(1, 0, 0));
    CHECK(aset_colour(dir(80), up) == Vec3(0, 0, 1));
    CHECK(aset_colour(dir(-10), up) == Vec3(1, 1, 1));
    CHECK(diffuse_with_head(dir(74), up) == 1.0);
    CHECK(diffuse_with_head(dir(76), up) == 0.0);
    CHECK(diffuse_with_head(dir(-1), up) == 0.0);
    CHECK(elevation_deg(dir(33), up) == Approx(33).margin(1e-12));
    // A spot's centre (ring 2 at 30°, azimuth offset 10°) is lit, a direction midway between spots is not.
    const double e = 30 * M_PI / 180, az = 10 * M_PI / 180;
    CHECK(spot_lighting(Vec3(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e)), up) == 1.0);
    CHECK(spot_lighting(dir(25), up) == 0.0);
}

TEST_CASE("Gem metrics: options outside their range are refused with the option named", "[gem-metrics]") {
    CHECK_THROWS_WITH(measure(tolkowsky(), quick(8)), Catch::Contains("rays = 8"));
    MetricOptions o = quick(64);
    o.wavelengths = 0;
    CHECK_THROWS_WITH(measure(tolkowsky(), o), Catch::Contains("wavelengths = 0"));
    o = quick(64);
    o.tilt_deg = -1;
    CHECK_THROWS_WITH(measure(tolkowsky(), o), Catch::Contains("tilt_deg"));
    o = quick(64);
    o.material = "unobtainium";
    CHECK_THROWS_AS(measure(tolkowsky(), o), InputError);
    o = quick(64);
    o.threshold = 1;
    CHECK_THROWS_WITH(measure(tolkowsky(), o), Catch::Contains("threshold"));
}

TEST_CASE("gem-metrics quick run writes the metric table, convergence, cost and the set-up images",
          "[gem-metrics][experiment]") {
    namespace fs = std::filesystem;
    using namespace refract::experiments;
    const fs::path dir = fs::temp_directory_path() / ("refract-gem-metrics-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    find("gem-metrics").run({dir.string(), 2, true});
    for (const char* f : {"summary.md", "gem_metrics.csv", "gem_convergence.csv", "gem_cost.csv",
                          "gem_leakage_by_kind.csv", "gem_view_tolkowsky_aset.png", "gem_view_gia-default_hearts.png"})
        CHECK(fs::file_size(dir / f) > 0);
    const Csv t = read_csv((dir / "gem_metrics.csv").string());
    REQUIRE(t.rows.size() == 2 * 2 * 4);  // presets × polarisation models × metrics
    for (const auto& row : t.rows) {
        INFO(row[0] << " " << row[1] << " " << row[2]);
        CHECK(std::stod(row[3]) >= 0);
        CHECK(std::stod(row[4]) > 0);  // every value carries its error
    }
    CHECK(read_csv((dir / "gem_leakage_by_kind.csv").string()).rows.size() == 2 * 2 * 4);
    std::error_code ec;
    fs::remove_all(dir, ec);
}

TEST_CASE("Gem viewer scene files in scenes/gems are exactly the ones gem-metrics writes, maps coloured by elevation",
          "[gem-metrics][scenes]") {
    namespace fs = std::filesystem;
    using namespace refract::experiments;
    const fs::path dir = fs::path(REFRACT_SOURCE_DIR) / "scenes" / "gems";
    for (const auto& [file, scene] : gem_metrics_experiment::viewer_scenes(320)) {
        std::ifstream in(dir / file, std::ios::binary);
        REQUIRE(in);
        std::ostringstream text;
        text << in.rdbuf();
        CHECK(text.str() == json_text(scene));
        CHECK_NOTHROW(scene_from_json(scene, (dir / file).string()));
    }
    for (const auto& [file, view] : gem_metrics_experiment::viewer_maps()) {
        const Image want = viewer_environment(view, gem_metrics_experiment::kViewerMapWidth);
        const Image got = read_image((dir / file).string());
        REQUIRE(got.width == want.width);
        REQUIRE(got.height == want.height);
        double worst = 0;
        for (size_t k = 0; k < want.rgb.size(); ++k) worst = std::max(worst, std::abs(got.rgb[k] - want.rgb[k]));
        CHECK(worst < 1e-3);  // stored in half precision
    }
    // ASET's map: the top rows (the viewer) blue, rows at 60° red, at 30° green, below white.
    const Image aset = viewer_environment("aset", 360);
    CHECK(aset.at(0, 5) == Vec3(0, 0, 1));
    CHECK(aset.at(0, 30) == Vec3(1, 0, 0));
    CHECK(aset.at(0, 60) == Vec3(0, 1, 0));
    CHECK(aset.at(0, 120) == Vec3(1, 1, 1));
}

TEST_CASE("Gem tracer: the table reflects the normal-incidence Fresnel share of an eye ray back along the axis",
          "[gem-metrics]") {
    // R = ((n − 1)/(n + 1))² at normal incidence (Born & Wolf §1.5.3); n = 2.417.
    const double n = 2.417, R = std::pow((n - 1) / (n + 1), 2);
    for (const bool exact : {true, false}) {
        MetricOptions o = quick(64);
        o.material = "2.417";
        o.exact_polarisation = exact;
        GemTracer t(tolkowsky(), o);
        std::vector<GemTracer::Exit> exits;
        const auto tr = t.trace({Vec3(0.01, 0.02, 4.0), Vec3(0, 0, -1)}, 0, exits);
        REQUIRE(exits.size() > 1);
        INFO("exact " << exact);
        CHECK(exits[0].weight == Approx(R).epsilon(1e-12));
        CHECK(t.kinds()[static_cast<size_t>(exits[0].kind)] == "table");
        CHECK(exits[0].dir.z() == Approx(1.0).epsilon(1e-15));
        CHECK(diffuse_with_head(exits[0].dir, Vec3(0, 0, 1)) == 0.0);  // the head blocks it
        double sum = tr.lost;
        for (const auto& e : exits) sum += e.weight;
        CHECK(sum == Approx(1.0).epsilon(1e-12));
    }
}
