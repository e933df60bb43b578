// The observer models of the light return (experiments/gem_observer.h, docs/gem-metrics.md
// "Observer models"): the default is the model the metrics always had, to the bit; a
// larger head cone returns less light, the whole hemisphere more; the names on the
// command line and in the CSVs.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <refract/experiments/gem_metrics.h>
#include <refract/experiments/gem_observer.h>
#include <refract/experiments/gem_sweep.h>
#include <refract/geometry/error.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
using namespace refract::gem_metrics;
namespace fs = std::filesystem;
namespace sw = refract::experiments::gem_sweep;

namespace {

// Tolkowsky's cut as `refract sweep brilliant --preset tolkowsky --wavelengths 5 --rays N
// --observer NAME` measures it (the cut's own seed from base seed 1).
GemMetrics under(const std::string& observer, int rays) {
    MetricOptions o;
    o.rays = rays;
    o.wavelengths = 5;
    o.observer = observer;
    const sw::Row r = sw::evaluate_cut(brilliant_preset("tolkowsky"), o);
    REQUIRE(r.possible);
    return r.metrics;
}

}  // namespace

TEST_CASE("Gem observer: the default aset model gives the metrics measured before observer models, to the bit",
          "[gem-metrics][observer]") {
    // The sweep's row of Tolkowsky's cut (128 rays, 5 bands, seed 1) as refract wrote it
    // before the observer models existed.
    MetricOptions o;
    o.rays = 128;
    o.wavelengths = 5;
    const sw::Row r = sw::evaluate_cut(brilliant_preset("tolkowsky"), o);
    REQUIRE(r.possible);
    CHECK(r.metrics.observer == "aset");
    CHECK(r.metrics.light_return.value == 0.7378222423338175);
    CHECK(r.metrics.light_return.error == 0.02798389991916193);
    CHECK(r.metrics.fire.value == 0.028484167378972365);
    CHECK(r.metrics.leakage.value == 0.06866251120590983);
    CHECK(r.metrics.scintillation.value == 0.22962419201995818);
    CHECK(r.metrics.aset.red == 0.49569547035181655);
    CHECK(r.metrics.balance.crown == 0.9277798088822813);
    o.observer = "aset";  // named: the same
    CHECK(sw::evaluate_cut(brilliant_preset("tolkowsky"), o).metrics.light_return.value == r.metrics.light_return.value);
}

TEST_CASE("Gem observer: Sasian's 40 degree head obscuration lowers Tolkowsky's light return, the whole hemisphere "
          "raises it",
          "[gem-metrics][observer]") {
    const GemMetrics aset = under("aset", 1024), sasian = under("sasian", 1024), hemi = under("hemisphere", 1024);
    INFO("light return aset " << aset.light_return.value << " +- " << aset.light_return.error << ", sasian "
                              << sasian.light_return.value << " +- " << sasian.light_return.error << ", hemisphere "
                              << hemi.light_return.value << " +- " << hemi.light_return.error);
    // The same eye rays: per ray, the 40 deg head blocks all the 15 deg head does and more,
    // the hemisphere blocks nothing; so the order holds ray by ray, not only on average.
    CHECK(sasian.light_return.value < aset.light_return.value);
    CHECK(hemi.light_return.value >= aset.light_return.value);
    // Measured: aset 0.7270 +- 0.0096, sasian 0.3072 +- 0.0095, hemisphere 0.9206 +- 0.0043:
    // the 40 deg head hides the directions above 50 deg elevation, where most of the light
    // Tolkowsky's crown returns comes from.
    CHECK(aset.light_return.value - sasian.light_return.value == Approx(0.4199).margin(0.02));
    CHECK(hemi.light_return.value - aset.light_return.value == Approx(0.1936).margin(0.01));
    // Only the light return depends on the observer.
    CHECK(sasian.fire.value == aset.fire.value);
    CHECK(sasian.leakage.value == aset.leakage.value);
    CHECK(sasian.aset.blue == aset.aset.blue);
    CHECK(sasian.observer == "sasian");
}

TEST_CASE("Gem observer: Tolkowsky's light return averaged over tilts of 0, 10, 20 and 30 degrees stays near its "
          "face-up value",
          "[gem-metrics][observer]") {
    const GemMetrics aset = under("aset", 512), tilt = under("tilt", 512);
    INFO("light return aset " << aset.light_return.value << " +- " << aset.light_return.error << ", tilt "
                              << tilt.light_return.value << " +- " << tilt.light_return.error);
    // Measured: aset 0.7285 +- 0.0138, tilt 0.7262 +- 0.0067 (four traces per sample: a
    // smaller error).
    CHECK(tilt.light_return.value == Approx(0.7262).margin(0.02));
    CHECK(std::abs(tilt.light_return.value - aset.light_return.value) <
          3 * std::hypot(tilt.light_return.error, aset.light_return.error));
    CHECK(tilt.light_return.error < aset.light_return.error);
    CHECK(tilt.leakage.value == aset.leakage.value);  // measured face-up, as before
}

TEST_CASE("Gem observer: two eyes 64 mm apart at 250 mm, each with ASET's head cone, see less of Tolkowsky's light "
          "than one eye and more than Sasian's 40 degree head",
          "[gem-metrics][observer]") {
    CHECK(eye_half_angle_deg(64.0, 250.0) == Approx(7.2942).margin(1e-4));  // atan(32 / 250)
    CHECK(find_observer("binocular").eye_half_angle_deg == Approx(eye_half_angle_deg(64.0, 250.0)));
    CHECK(traces_own_rays(find_observer("binocular")));
    CHECK_FALSE(traces_own_rays(find_observer("sasian")));
    // The head blocks within 15 deg of either eye (each 7.29 deg off the axis along x): a
    // direction 10 deg from the left eye is blocked; one tilted 18.5 deg from the axis towards
    // y, 19.9 deg from each eye, is not.
    const double h = eye_half_angle_deg(64.0, 250.0) * M_PI / 180, c15 = std::cos(15 * M_PI / 180);
    const Vec3 left(-std::sin(h), 0, std::cos(h)), right(std::sin(h), 0, std::cos(h)), up(0, 0, 1);
    const double a = (-h + 10 * M_PI / 180);
    CHECK(observer_radiance(Vec3(std::sin(a), 0, std::cos(a)), up, left, right, c15) == 0.0);
    const double b = 18.5 * M_PI / 180;
    CHECK(observer_radiance(Vec3(0, std::sin(b), std::cos(b)), up, left, right, c15) == 1.0);
    // Measured (512 rays, 5 bands): aset 0.7285 +- 0.0138, binocular 0.6618 +- 0.0099, sasian
    // 0.2887 +- 0.0130: the union of two 15 deg cones 14.6 deg apart hides more of the
    // near-axis light than one cone, far less than a 40 deg cone.
    const GemMetrics aset = under("aset", 512), two = under("binocular", 512), sasian = under("sasian", 512);
    CHECK(two.light_return.value == Approx(0.6618).margin(1e-3));
    CHECK(two.light_return.value < aset.light_return.value - 3 * two.light_return.error);
    CHECK(two.light_return.value > sasian.light_return.value + 3 * std::hypot(two.light_return.error, sasian.light_return.error));
    // Only the light return: the cyclopean eye ray gives the rest.
    CHECK(two.leakage.value == aset.leakage.value);
    CHECK(two.nail_head.value == aset.nail_head.value);
    CHECK(two.observer == "binocular");
    MetricOptions o;
    o.also_observers = {"binocular"};
    CHECK_THROWS_AS(measure(build_brilliant(brilliant_preset("tolkowsky")), o), InputError);
}

TEST_CASE("Gem observer: an unknown observer is refused with the names listed", "[gem-metrics][observer]") {
    MetricOptions o;
    o.observer = "cyclops";
    try {
        validate(o);
        FAIL("accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == "gem metrics: observer 'cyclops': expected aset, sasian, hemisphere, tilt or binocular");
    }
    CHECK(observers().front().name == "aset");
    for (const Observer& m : observers()) CHECK_FALSE(m.source.empty());
}

TEST_CASE("refract metrics and refract sweep take --observer: an unknown name exits 2 with one line listing the "
          "names, the CSVs carry the observer",
          "[gem-metrics][observer][cli]") {
    const fs::path dir = test::fresh_dir("gem-observer", "cli");
    const std::string design = std::string(REFRACT_SOURCE_DIR) + "/scenes/gems/designs/emerald.asc";
    const std::string fast = " --rays 64 --wavelengths 3";
    const std::string names = "--observer 'cyclops': expected aset, sasian, hemisphere, tilt or binocular";
    test::check_refused(test::run("metrics " + design + fast + " --observer cyclops", dir), names);
    test::check_refused(
        test::run("sweep brilliant --preset tolkowsky" + fast + " --observer cyclops -o " + (dir / "b.csv").string(), dir),
        names);
    CHECK_FALSE(fs::exists(dir / "b.csv"));
    CHECK_FALSE(fs::exists(dir / "b.csv.journal"));
    test::check_refused(test::run("sweep design " + design + " --tier P1:40:41:1" + fast + " --observer cyclops -o " +
                                      (dir / "d.csv").string(),
                                  dir),
                        names);
    CHECK_FALSE(fs::exists(dir / "d.csv"));
    const auto last_cells = [](const fs::path& p) {
        std::ifstream in(p);
        std::string header, row;
        std::getline(in, header);
        std::getline(in, row);
        return header.substr(header.rfind(',') + 1) + "=" + row.substr(row.rfind(',') + 1);
    };
    REQUIRE(test::run("sweep brilliant --preset tolkowsky" + fast + " --observer sasian --quiet -o " +
                          (dir / "s.csv").string(),
                      dir)
                .code == 0);
    CHECK(last_cells(dir / "s.csv") == "observer=sasian");
    REQUIRE(test::run("sweep design " + design + " --tier P1:40:41:1" + fast + " -o " + (dir / "e.csv").string(), dir)
                .code == 0);
    CHECK(last_cells(dir / "e.csv") == "observer=aset");
    fs::remove_all(dir);
}
