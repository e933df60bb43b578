// The gem-geometry experiment: a quick run writes its files, the proportions table it
// writes equals the closed forms (crown height = (1 - t) tan(beta) / 2, pavilion depth =
// (1 - c) tan(alpha) / 2, total = crown + girdle + pavilion) and the requested parameters,
// the line drawings show the facets a convex solid shows, and the plane set and the mesh
// agree on every timed ray.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <unistd.h>

#include <refract/core/scene_json.h>
#include <refract/experiments/common.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/gem_geometry.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/gem/brilliant.h>

using namespace refract;
using namespace refract::experiments;
namespace fs = std::filesystem;

namespace {

struct QuickGemRun {
    fs::path dir;
    QuickGemRun() {
        dir = fs::temp_directory_path() / ("refract-gem-experiment-" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        find("gem-geometry").run({dir.string(), 2, true});
    }
    ~QuickGemRun() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

const fs::path& quick_dir() {
    static QuickGemRun run;
    return run.dir;
}

size_t column(const Csv& t, const std::string& name) {
    for (size_t k = 0; k < t.header.size(); ++k)
        if (t.header[k] == name) return k;
    FAIL("no column " << name);
    return 0;
}

}  // namespace

TEST_CASE("gem-geometry quick run writes drawings, tables, renders and scenes", "[gem][experiment]") {
    const fs::path& dir = quick_dir();
    for (const char* f : {"summary.md", "gem_proportions.csv", "gem_proportions.md", "gem_facets.csv",
                          "gem_intersection.csv", "gem_renders.csv", "gem_drawings.gp"})
        CHECK(fs::file_size(dir / f) > 0);
    if (gnuplot_available())
        for (const char* f : {"gem_drawings.png", "gem_drawings.pdf", "gem_renders.png", "gem_renders.pdf"})
            CHECK(fs::file_size(dir / f) > 0);
    for (const auto& p : brilliant_preset_names()) {
        INFO(p);
        CHECK(fs::file_size(dir / ("gem_outline_" + p + ".csv")) > 0);
        CHECK(fs::file_size(dir / ("gem_render_" + p + ".png")) > 0);
        // The scene beside the image is a valid scene with the preset's gem in it.
        const Scene s = load_scene((dir / ("gem_render_" + p + ".json")).string());
        CHECK(s.objects.size() == 2);
        CHECK(std::holds_alternative<ConvexPolyhedron>(s.objects[1].shape));
    }
}

TEST_CASE("gem-geometry proportions table: measured equals requested and the closed-form heights", "[gem][experiment]") {
    const Csv t = read_csv((quick_dir() / "gem_proportions.csv").string());
    const size_t cp = column(t, "preset"), cq = column(t, "quantity"), ce = column(t, "expected"),
                 cm = column(t, "measured");
    REQUIRE(t.rows.size() == 10 * brilliant_preset_names().size());
    int derived = 0;
    for (const auto& row : t.rows) {
        INFO(row[cp] << " " << row[cq]);
        const BrilliantCut cut = brilliant_preset(row[cp]);
        const double tb = std::tan(cut.crown_angle * M_PI / 180), ta = std::tan(cut.pavilion_angle * M_PI / 180);
        const double crown = 100 * (1 - cut.table / 100) * tb / 2, pav = 100 * (1 - cut.culet / 100) * ta / 2;
        const std::map<std::string, double> closed{
            {"table", cut.table},          {"crown_angle", cut.crown_angle}, {"pavilion_angle", cut.pavilion_angle},
            {"star", cut.star},            {"lower_half", cut.lower_half},   {"girdle", cut.girdle},
            {"culet", cut.culet},          {"crown_height", crown},          {"pavilion_depth", pav},
            {"total_depth", crown + cut.girdle + pav}};
        REQUIRE(closed.count(row[cq]) == 1);
        const double want = closed.at(row[cq]);
        CHECK(std::stod(row[ce]) == Approx(want).margin(1e-12));
        CHECK(std::abs(std::stod(row[cm]) - want) <= 1e-9);
        derived += row[cq] == "crown_height";
    }
    CHECK(derived == static_cast<int>(brilliant_preset_names().size()));
    // Tolkowsky (1919): crown height 16.2 %, pavilion depth 43.1 % (rounded).
    const Gem g = build_brilliant(brilliant_preset("tolkowsky"));
    CHECK(g.measured.crown_height == Approx(16.2).margin(0.05));
    CHECK(g.measured.pavilion_depth == Approx(43.1).margin(0.05));
}

TEST_CASE("gem-geometry drawings: a convex solid shows the facets facing the viewer", "[gem][experiment]") {
    const Gem g = build_brilliant(brilliant_preset("gia-default"));
    const auto crown = gem_geometry::outlines(g, "crown");
    const auto pav = gem_geometry::outlines(g, "pavilion");
    const auto side = gem_geometry::outlines(g, "side");
    // Crown: table + 8 stars + 8 bezels + 16 upper halves; pavilion: 8 mains + 16 lower halves.
    CHECK(crown.size() == 33);
    CHECK(pav.size() == 24);
    // Side: half the facets that are not horizontal (the table faces up, not the viewer).
    CHECK(side.size() > 0);
    CHECK(side.size() < g.facets.size());
    for (const auto& o : crown) CHECK(o.points.front() == o.points.back());
}

TEST_CASE("gem-geometry timing: plane set and triangle mesh agree on every timed ray", "[gem][experiment]") {
    const Csv t = read_csv((quick_dir() / "gem_intersection.csv").string());
    REQUIRE(t.rows.size() == brilliant_preset_names().size());
    for (const auto& row : t.rows) {
        INFO(row[0]);
        CHECK(row[column(t, "agree")] == row[column(t, "rays")]);
        CHECK(std::stol(row[column(t, "hits")]) > std::stol(row[column(t, "rays")]) / 4);
    }
}
