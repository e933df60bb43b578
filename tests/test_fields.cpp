// Field lists (core/fields.h): one declaration per result structure gives the CSV columns
// and cells (experiments/field_csv.h), RenderStats::merge and its --stats text.
#include <catch2/catch.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <refract/core/fields.h>
#include <refract/core/render_stats.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/optics_bench.h>
#include <refract/experiments/polarisation.h>

using namespace refract;
using namespace refract::experiments;

namespace {

struct Sample {
    int count = 0;
    double x = 0;
    std::string name;
    bool flag = false;
    std::optional<double> maybe;
};

}  // namespace

namespace refract {
template <>
struct Fields<Sample> {
    static auto list() {
        return std::make_tuple(field("count", &Sample::count), field("x", &Sample::x).digits(3),
                               field("name", &Sample::name).csv("label"), field("flag", &Sample::flag),
                               field("maybe", &Sample::maybe).digits(2),
                               derived<Sample>("twice", [](const Sample& s) { return 2 * s.x; }).csv_only(),
                               field("hidden", &Sample::x).python_only());
    }
};
}  // namespace refract

TEST_CASE("Field list to CSV: columns in list order, renamed, Python-only fields left out", "[fields]") {
    CHECK(csv_header<Sample>() == std::vector<std::string>{"count", "x", "label", "flag", "maybe", "twice"});
    CHECK(csv_header<Sample>({"twice", "count"}) == std::vector<std::string>{"twice", "count"});
    CHECK_THROWS_AS(csv_header<Sample>({"hidden"}), std::logic_error);
}

TEST_CASE("Field list to CSV: cells by type — digits, integers, 1/0, strings, an empty optional as an empty cell",
          "[fields]") {
    const Sample s{42, 3.14159, "glass", true, std::nullopt};
    CHECK(csv_cells(s) == std::vector<std::string>{"42", "3.14", "glass", "1", "", "6.28318"});
    Sample t = s;
    t.maybe = 0.123456;
    t.flag = false;
    CHECK(csv_cells(t, {"maybe", "flag"}) == std::vector<std::string>{"0.12", "0"});
    const Csv table = csv_table(std::vector<Sample>{s, t});
    CHECK(table.rows.size() == 2);
    CHECK(table.text().substr(0, table.text().find('\n')) == "count,x,label,flag,maybe,twice");
}

TEST_CASE("Field lists of the experiments give the CSV columns the files have always had", "[fields]") {
    CHECK(csv_header<optics_bench::DropClass>() ==
          std::vector<std::string>{"class", "path", "measured", "closed form", "difference", "max bin difference",
                                   "max bin z-score"});
    CHECK(csv_header<polarisation::Comparison>() ==
          std::vector<std::string>{"scene", "width", "height", "rmse", "max_abs", "de2000_mean", "de2000_p95",
                                   "de2000_max", "light_natural", "light_exact", "light_ratio", "object_pixels",
                                   "object_natural", "object_exact", "object_ratio", "seconds_natural", "seconds_exact"});
    polarisation::DepthRow d{3, 0, 0.5};
    CHECK(csv_cells(d) == std::vector<std::string>{"3", "0", "0.5", "0.5", ""});  // no relative difference of 0
}

TEST_CASE("RenderStats::merge by its field list: sums, the longest list a maximum, the wall time left alone",
          "[fields][render]") {
    RenderStats a, b;
    a.primary_rays = 10, b.primary_rays = 5;
    a.lost_depth = 0.25, b.lost_depth = 0.5;
    a.facet_local = 7, b.facet_full = 3;
    a.peak_list = 4, b.peak_list = 9;
    a.seconds = 2, b.seconds = 3;
    a.light_seconds = 1, b.light_seconds = 1.5;
    a.merge(b);
    CHECK(a.primary_rays == 15);
    CHECK(a.lost_depth == 0.75);
    CHECK(a.facet_local == 7);
    CHECK(a.facet_full == 3);
    CHECK(a.peak_list == 9);
    CHECK(a.seconds == 2);
    CHECK(a.light_seconds == 2.5);
    // Every member is in the list (all of them 8 bytes): a counter added to RenderStats but
    // not to its field list would be neither merged, printed nor seen from Python.
    size_t fields = 0;
    for_each_field<RenderStats>([&](const auto&) { ++fields; });
    CHECK(sizeof(RenderStats) == fields * sizeof(std::uint64_t));
}

TEST_CASE("RenderStats::summary: a line per labelled field, the spectral, facet and photon lines only when not 0",
          "[fields][render]") {
    RenderStats s;
    s.primary_rays = 12;
    s.segments = 30;
    s.seconds = 0.5;
    std::string t = s.summary();
    CHECK(t.find("primary rays      12\n") != std::string::npos);
    CHECK(t.find("wall time (s)     0.5\n") != std::string::npos);
    CHECK(t.find("segments/s        60\n") != std::string::npos);
    CHECK(t.find("facet") == std::string::npos);
    CHECK(t.find("photons") == std::string::npos);
    s.facet_local = 3;
    s.facet_full = 1;
    t = s.summary();
    CHECK(t.find("facet segs, local 3\n") != std::string::npos);
    CHECK(t.find("facet segs, full  1\n") != std::string::npos);
    CHECK(t.find("facet local (%)   75\n") != std::string::npos);
}
