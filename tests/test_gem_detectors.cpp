// The nail-head and fish-eye detectors (experiments/gem_detectors.h, docs/gem-metrics.md
// "Nail-head and fish-eye"): the trade's limits, a pavilion steeper than about 42–43°
// gives a dark centre and one shallower than about 39° the girdle's reflection in the
// table; Tolkowsky's cut shows neither. Small ray counts, fixed seeds.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_detectors.h>
#include <refract/experiments/gem_observation.h>
#include <refract/experiments/gem_sweep.h>

using namespace refract;
using namespace refract::gem_metrics;
namespace sw = refract::experiments::gem_sweep;
namespace gc = refract::experiments::gem_cuts;

namespace {

// Tolkowsky's crown and table with the GIA default's girdle (his knife edge has none to
// reflect) and another pavilion angle; the light return's rays only matter (the detectors
// use them), 3 wavelengths.
GemMetrics tolkowsky_with_pavilion(double pavilion, int rays, const std::string& observer = "aset") {
    const BrilliantCut c = gc::tolkowsky_with_girdle(pavilion);
    MetricOptions o;
    o.rays = rays;
    o.wavelengths = 3;
    o.observer = observer;
    o.fire_divisor = o.scintillation_divisor = rays;
    o.spot_rotations = 1;
    const sw::Row r = sw::evaluate_cut(c, o);
    REQUIRE(r.possible);
    return r.metrics;
}

}  // namespace

TEST_CASE("Nail-head detector fires on a 43.75 degree pavilion and not on Tolkowsky's 40.75, from 42.5 under a 40 degree head",
          "[gem][detectors]") {
    // Sasian's 40 deg head obscuration: the table's centre leaves within it from about 41.2 deg.
    const GemMetrics steep = tolkowsky_with_pavilion(43.75, 1024, "sasian"),
                     tolk = tolkowsky_with_pavilion(40.75, 1024, "sasian");
    CHECK(shows_nail_head(steep.nail_head));
    CHECK_FALSE(shows_nail_head(tolk.nail_head));
    CHECK(steep.nail_head.value - tolk.nail_head.value > 3 * std::hypot(steep.nail_head.error, tolk.nail_head.error));
    CHECK(steep.nail_head.error > 0);
    CHECK(steep.nail_head.error < 0.1);
    CHECK(shows_nail_head(tolkowsky_with_pavilion(42.5, 1024, "sasian").nail_head));
    // ASET's 15 deg head: the centre's exit falls inside it only above about 43.4 deg
    // (at 16384 rays, 4096 of them central: 0.421 +- 0.006 at 43.75, 0.062 +- 0.002 at 43.25,
    // 0.248 +- 0.006 at 40.75, the threshold 0.35).
    CHECK(shows_nail_head(tolkowsky_with_pavilion(43.75, 1024, "aset").nail_head));
    CHECK_FALSE(shows_nail_head(tolkowsky_with_pavilion(43.25, 1024, "aset").nail_head));
    CHECK_FALSE(shows_nail_head(tolkowsky_with_pavilion(40.75, 1024, "aset").nail_head));
}

TEST_CASE("Fish-eye detector fires on a 37.25 degree pavilion and not on Tolkowsky's 40.75", "[gem][detectors]") {
    const GemMetrics shallow = tolkowsky_with_pavilion(37.25, 1024), tolk = tolkowsky_with_pavilion(40.75, 1024);
    CHECK(shows_fish_eye(shallow.fish_eye));
    CHECK_FALSE(shows_fish_eye(tolk.fish_eye));
    CHECK_FALSE(shows_nail_head(shallow.nail_head));
    CHECK_FALSE(shows_fish_eye(tolkowsky_with_pavilion(43.75, 512).fish_eye));
    CHECK(shallow.fish_eye.error > 0);
    // The knife-edge girdle of Tolkowsky's own preset has nothing to reflect.
    MetricOptions o;
    o.rays = 128;
    o.wavelengths = 3;
    BrilliantCut knife = brilliant_preset("tolkowsky");
    knife.pavilion_angle = 37.25;
    CHECK(sw::evaluate_cut(knife, o).metrics.fish_eye.value == 0.0);
}

TEST_CASE("Nail-head detector sees the head: a larger head darkens the centre, the whole hemisphere does not",
          "[gem][detectors]") {
    const GemMetrics sasian = tolkowsky_with_pavilion(42.5, 256, "sasian"),
                     aset = tolkowsky_with_pavilion(42.5, 256, "aset"),
                     hemi = tolkowsky_with_pavilion(43.75, 256, "hemisphere");
    CHECK(sasian.nail_head.value > aset.nail_head.value);
    CHECK_FALSE(shows_nail_head(hemi.nail_head));
    // The same eye rays under every observer: the fish-eye does not depend on the model.
    CHECK(sasian.fish_eye.value == aset.fish_eye.value);
}

TEST_CASE("Obstruction detector: ASET's head sends 0.18 of Tolkowsky's face light, 0.29 at a 38.75 degree pavilion, "
          "Sasian's head 0.59, the whole hemisphere none",
          "[gem][detectors]") {
    // Measured (1024 rays, 3 bands): aset 40.75 0.1846 +- 0.0091, 38.75 0.2937 +- 0.0111,
    // 43.75 0.0896 +- 0.0070; sasian 40.75 0.5876 +- 0.0110; at 16384 rays 0.186, 0.269, 0.089, 0.616.
    const GemMetrics tolk = tolkowsky_with_pavilion(40.75, 1024), shallow = tolkowsky_with_pavilion(38.75, 1024),
                     deep = tolkowsky_with_pavilion(43.75, 1024),
                     sasian = tolkowsky_with_pavilion(40.75, 1024, "sasian"),
                     hemi = tolkowsky_with_pavilion(40.75, 256, "hemisphere");
    CHECK(tolk.obstruction.value == Approx(0.1846).margin(1e-3));
    CHECK(tolk.obstruction.error == Approx(0.0091).margin(1e-3));
    CHECK(shallow.obstruction.value == Approx(0.2937).margin(1e-3));
    CHECK(deep.obstruction.value == Approx(0.0896).margin(1e-3));
    CHECK(sasian.obstruction.value == Approx(0.5876).margin(1e-3));
    CHECK_FALSE(shows_obstruction(tolk.obstruction));
    CHECK(shows_obstruction(shallow.obstruction));
    CHECK_FALSE(shows_obstruction(deep.obstruction));
    CHECK(shows_obstruction(sasian.obstruction));
    // The same eye rays: the 40 deg head blocks all the 15 deg head does, ray by ray.
    CHECK(sasian.obstruction.value >= tolk.obstruction.value);
    CHECK(hemi.obstruction.value == 0.0);
    CHECK_FALSE(shows_obstruction(hemi.obstruction));
}

TEST_CASE("Nail-head decision at two standard errors: a value within 2 sigma of the threshold is undecided",
          "[gem][detectors]") {
    CHECK(nail_head_decided({0.421, 0.006}));
    CHECK(shows_nail_head({0.421, 0.006}));
    CHECK_FALSE(nail_head_decided({0.339, 0.012}));  // measured: crown 37, pavilion 38.75, aset
    CHECK(nail_head_decided({0.248, 0.006}));
    CHECK_FALSE(shows_nail_head({0.248, 0.006}));
    CHECK(nail_head_decided({0.0, 0.0}));  // no head: decided, none
}

TEST_CASE("gem-cuts optimum on the grid's edge is said to be, one inside is not", "[gem][findings]") {
    sw::Grid g = sw::single_cut_grid(brilliant_preset("gia-default"));
    sw::set_axis(g, sw::parse_axis("crown_angle", "23:41:1"));
    sw::set_axis(g, sw::parse_axis("pavilion_angle", "38:43:0.25"));
    gc::Optimum o;
    o.metric = "light_return";
    o.best.cut = g.base;
    o.best.cut.crown_angle = 25;
    o.best.cut.pavilion_angle = 43;
    o.edge = gc::edge_of(g, o.best.cut);
    CHECK(o.edge.pavilion_high);
    CHECK_FALSE(o.edge.crown_low);
    CHECK(gc::optimum_sentence(o, g).find("lies on the grid's edge (pavilion 43°, the grid's steepest)") !=
          std::string::npos);
    o.best.cut.pavilion_angle = 41;
    o.edge = gc::edge_of(g, o.best.cut);
    CHECK_FALSE(o.edge.any());
    CHECK(gc::optimum_sentence(o, g).find("lies inside the grid") != std::string::npos);
    // Where the grid ends at the cut builder's limit (pavilion up to 43.8, crown from 20:
    // a step beyond is refused), the sentence says so instead of calling the distance a
    // lower bound.
    sw::set_axis(g, sw::parse_axis("crown_angle", "20:41:1"));
    sw::set_axis(g, sw::parse_axis("pavilion_angle", "38:43.75:0.25"));
    o.best.cut.crown_angle = 20;
    o.best.cut.pavilion_angle = 43.75;
    o.edge = gc::edge_of(g, o.best.cut);
    o.builder_limit = gc::builder_limits(g, o.best.cut, o.edge);
    CHECK(o.builder_limit.crown_low);
    CHECK(o.builder_limit.pavilion_high);
    CHECK(gc::optimum_sentence(o, g).find("(crown 20°, the grid's shallowest, the cut builder's limit and pavilion "
                                          "43.75°, the grid's steepest, the cut builder's limit): the grid ends there") !=
          std::string::npos);
    o.best.cut.crown_angle = 41;  // the steepest crown the builder takes is 41.5: 42 is refused
    o.edge = gc::edge_of(g, o.best.cut);
    o.builder_limit = gc::builder_limits(g, o.best.cut, o.edge);
    CHECK(o.builder_limit.crown_high);
    sw::set_axis(g, sw::parse_axis("crown_angle", "20:40:1"));  // 41 can be built: the old sentence
    o.best.cut.crown_angle = 40;
    o.edge = gc::edge_of(g, o.best.cut);
    o.builder_limit = gc::builder_limits(g, o.best.cut, o.edge);
    CHECK_FALSE(o.builder_limit.crown_high);
    CHECK(gc::optimum_sentence(o, g).find("a lower bound") != std::string::npos);
}

TEST_CASE("gem-cuts detector onsets: the nail-head from the steepest firing run, the fish-eye up to the shallowest",
          "[gem][findings]") {
    sw::Sweep s;
    s.grid = sw::single_cut_grid(brilliant_preset("gia-default"));
    sw::set_axis(s.grid, sw::parse_axis("crown_angle", "30:35:5"));
    sw::set_axis(s.grid, sw::parse_axis("pavilion_angle", "38:43:1"));
    std::vector<sw::Row> rows;
    for (std::int64_t i = 0; i < s.grid.size(); ++i) {
        sw::Row r;
        r.index = i;
        r.cut = s.grid.cut(i);
        r.possible = true;
        const double p = r.cut.pavilion_angle;
        r.metrics.nail_head.value = p >= 42 ? 0.8 : p == 39 ? 0.9 : 0.1;  // 39: an isolated firing cell
        r.metrics.fish_eye.value = r.cut.crown_angle == 30 && p <= 39 ? 0.2 : 0.0;
        rows.push_back(r);
    }
    const auto nail = gc::nail_head_onsets(s, rows), fish = gc::fish_eye_limits(s, rows);
    REQUIRE(nail.size() == 2);
    CHECK(nail[0].pavilion == 42);
    CHECK(nail[1].pavilion == 42);
    CHECK(fish[0].pavilion == 39);
    CHECK(std::isnan(fish[1].pavilion));
}

TEST_CASE("gem-cuts trend slopes recover a known plane and line, their errors zero on exact data", "[gem][findings]") {
    std::vector<sw::Row> rows;
    for (int c = 0; c < 4; ++c)
        for (int p = 0; p < 3; ++p) {
            sw::Row r;
            r.possible = true;
            r.cut = brilliant_preset("gia-default");
            r.cut.crown_angle = 30 + c;
            r.cut.pavilion_angle = 40 + 0.5 * p;
            r.cut.table = 52 + 2 * (c * 3 + p);
            r.metrics.light_return.value = 0.9 - 0.01 * r.cut.crown_angle + 0.02 * r.cut.pavilion_angle;
            r.metrics.fire.value = 0.5 - 0.003 * r.cut.table;
            rows.push_back(r);
        }
    const auto [crown, pavilion] = gc::crown_pavilion_slopes(rows, "light_return");
    CHECK(crown.value == Approx(-0.01).margin(1e-12));
    CHECK(pavilion.value == Approx(0.02).margin(1e-12));
    CHECK(crown.error == Approx(0).margin(1e-9));
    CHECK(crown.falls());
    CHECK_FALSE(crown.rises());
    const gc::Slope t = gc::table_slope(rows, "fire");
    CHECK(t.value == Approx(-0.003).margin(1e-12));
    CHECK(t.falls());
    // Noise as large as the trend: neither falls nor rises by 2 sigma.
    rows[0].metrics.fire.value += 0.2;
    rows[1].metrics.fire.value -= 0.2;
    rows.back().metrics.fire.value += 0.2;
    const gc::Slope noisy = gc::table_slope(rows, "fire");
    CHECK(noisy.error > 0);
    CHECK_FALSE(noisy.rises());
}

TEST_CASE("gem-cuts literature: Tolkowsky 'among the best' only when few cuts beat him by 2 sigma", "[gem][findings]") {
    gc::Result r;
    gc::ObserverMap m;
    m.observer = "aset";
    for (int i = 0; i < 20; ++i) {
        sw::Row row;
        row.possible = true;
        row.cut = brilliant_preset("gia-default");
        row.cut.crown_angle = 30 + i % 5;
        row.cut.pavilion_angle = 40 + 0.25 * (i / 5);
        row.metrics.light_return = {0.70 + 0.001 * i, 0.005};
        m.rows.push_back(row);
    }
    m.tolkowsky.possible = true;
    m.tolkowsky.cut = brilliant_preset("tolkowsky");
    m.tolkowsky.metrics.light_return = {0.715, 0.005};  // beaten by 2 sigma (0.0141) only by 0.730 and up: 0 cuts
    r.observers.push_back(m);
    r.nail_head_onset.push_back({});
    r.fish_eye_limit.push_back({});
    auto find = [](const std::vector<gc::LiteratureRow>& rows, const std::string& key) {
        for (const auto& x : rows)
            if (x.key == key) return x;
        FAIL("no row " << key);
        return gc::LiteratureRow{};
    };
    auto best = find(gc::literature(r), "tolkowsky_among_best");
    REQUIRE(best.agrees.size() == 1);
    CHECK(best.agrees[0]);
    r.observers[0].tolkowsky.metrics.light_return = {0.69, 0.005};  // 0.705 and up beat him: 15 of 20
    best = find(gc::literature(r), "tolkowsky_among_best");
    CHECK_FALSE(best.agrees[0]);
    CHECK(best.numbers[0] == "15 of 20 cuts (75 %)");
    // No detector grid: the nail-head row cannot agree and says why.
    const auto nail = find(gc::literature(r), "nail_head_steep");
    CHECK_FALSE(nail.agrees[0]);
    CHECK(nail.numbers[0] == "from none in the grid");
}

TEST_CASE("Gem viewer tilt series: tilt 0 is the face-up image to the bit, a tilted stone shows another pattern",
          "[gem][detectors]") {
    const Gem gem = build_brilliant(gc::tolkowsky_with_girdle(40.75));
    MetricOptions o;
    o.wavelengths = 3;
    const Image up = render_view(gem, "aset", 24, 1, o), zero = render_view(gem, "aset", 24, 1, o, 0.0),
                tilted = render_view(gem, "aset", 24, 1, o, 20.0);
    double same = 0, diff = 0;
    for (int j = 0; j < 24; ++j)
        for (int i = 0; i < 24; ++i) {
            same += (up.at(i, j) - zero.at(i, j)).norm();
            diff += (up.at(i, j) - tilted.at(i, j)).norm();
        }
    CHECK(same == 0.0);
    CHECK(diff > 1.0);
}
