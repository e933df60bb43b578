// The heart (scenes/gems/designs/heart.asc, docs/gems.md "The heart"): a convex preform with a
// cleft ground in (the design's CL tiers, geometry/gem/gemcad.h), built exactly: closed,
// convex except at its cleft, its volume the preform's less the notch's; traced as its mesh
// (the notch is empty space), measured; refusals of a cleft that removes nothing or cuts the
// stone in two.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <refract/core/scene_json.h>
#include <refract/experiments/design_metrics.h>
#include <refract/experiments/gem_observation.h>
#include <refract/geometry/error.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/gem/gemcad.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
namespace fs = std::filesystem;
namespace dm = refract::experiments::design_metrics;

namespace {

std::string heart_path() { return std::string(REFRACT_SOURCE_DIR) + "/scenes/gems/designs/heart.asc"; }

bool is_cleft_label(const std::string& label) { return label.rfind("CL ", 0) == 0; }

// The design without its cleft tiers: the convex preform.
GemcadDesign preform_of(GemcadDesign d) {
    std::vector<GemcadTier> keep;
    for (std::size_t k = 0; k < d.tiers.size(); ++k)
        if (!is_cleft_tier(d.tiers[k], static_cast<int>(k) + 1)) keep.push_back(d.tiers[k]);
    d.tiers = keep;
    return d;
}

// The notch's part of the preform as a convex design: the preform's tiers and each cleft
// facet turned round (its outer side kept: index + 48 of gear 96, the distance negated).
GemcadDesign notch_of(GemcadDesign d) {
    for (std::size_t k = 0; k < d.tiers.size(); ++k) {
        GemcadTier& t = d.tiers[k];
        if (!is_cleft_tier(t, static_cast<int>(k) + 1)) continue;
        REQUIRE(t.angle == 90);  // the heart's cleft is vertical
        for (double& i : t.indices) i = std::fmod(i + 48, 96);
        for (std::string& n : t.names) n = n.empty() ? n : "N";
        t.distance = -t.distance;
    }
    return d;
}

double mesh_volume(const Gem& g) {
    double v = 0;
    for (const auto& t : g.mesh.triangles) {
        const Vec3 &a = g.mesh.vertices[static_cast<size_t>(t[0])], &b = g.mesh.vertices[static_cast<size_t>(t[1])],
                   &c = g.mesh.vertices[static_cast<size_t>(t[2])];
        v += a.dot(b.cross(c)) / 6;
    }
    return v;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// A 2 × 2 × 1 box (test_gemcad.cpp's) and `extra` tiers.
std::string box(const std::string& extra) {
    return "GemCad 5.0\ng 96 0.0\ny 4 y\nI 1.54\nH test box\n"
           "a -90 1 0 n G 24 48 72\n"
           "a 0 0.5 0 n T\n"
           "a -0 0.5 0 n C\n" +
           extra;
}

}  // namespace

TEST_CASE("The heart is its convex preform less the notch: closed, convex except at the cleft, volume of the preform "
          "less the notch's",
          "[gemcad][heart]") {
    const GemcadDesign design = read_gemcad(heart_path());
    const DesignGem d = build_design(design);
    const Gem& g = d.gem;
    CHECK_FALSE(g.convex);
    CHECK(d.cleft_facets == 3);
    CHECK(g.facets.size() == 71);  // 69 listed: G 48 and C1 48 each cut in two by the notch
    CHECK(d.planes == 69);
    CHECK(g.mesh.vertices.size() == 138);
    CHECK(d.volume == Approx(1.23759959).epsilon(1e-8));

    // The volumes built independently: the preform alone, and the notch's part of it as a
    // convex design of its own.
    const DesignGem pre = build_design(preform_of(design));
    const DesignGem notch = build_design(notch_of(design));
    CHECK(pre.gem.convex);
    CHECK(d.preform_volume == Approx(pre.volume).epsilon(1e-12));
    CHECK(d.notch_volume == Approx(notch.volume).epsilon(1e-12));
    CHECK(d.volume == Approx(pre.volume - notch.volume).epsilon(1e-12));
    CHECK(mesh_volume(g) == Approx(d.volume).epsilon(1e-12));
    CHECK(notch.volume > 0.02 * pre.volume);  // a real cleft, not a scratch
    CHECK(d.width == Approx(pre.width).epsilon(1e-12));

    // Closed: every directed edge once, its reverse once; Euler characteristic 2.
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : g.mesh.triangles)
        for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    int bad = 0;
    for (const auto& [e, n] : edges) {
        const auto back = edges.find({e.second, e.first});
        if (n != 1 || back == edges.end() || back->second != 1) ++bad;
    }
    CHECK(bad == 0);
    const long V = static_cast<long>(g.mesh.vertices.size()), E = static_cast<long>(edges.size() / 2),
               T = static_cast<long>(g.mesh.triangles.size());
    CHECK(V - E + T == 2);
    REQUIRE(g.triangle_facet.size() == g.mesh.triangles.size());

    // Convex except at the cleft: inside every other facet's plane; some vertex lies outside
    // a cleft facet's plane (the stone is not convex).
    double worst_other = -1, worst_cleft = -1;
    int cleft_seen = 0;
    for (const GemFacet& f : g.facets) {
        cleft_seen += is_cleft_label(f.label);
        for (const Vec3& v : g.mesh.vertices) {
            const double out = f.plane.normal.dot(v) - f.plane.offset;
            (is_cleft_label(f.label) ? worst_cleft : worst_other) =
                std::max(is_cleft_label(f.label) ? worst_cleft : worst_other, out);
        }
    }
    CHECK(cleft_seen == 3);
    CHECK(worst_other < 1e-9);
    CHECK(worst_cleft > 0.1);
}

TEST_CASE("A vertical ray into the heart's cleft passes through the notch: the preform stops it, the heart and its "
          "tracer do not, and a ray through a lobe meets both alike",
          "[gemcad][heart]") {
    const GemcadDesign design = read_gemcad(heart_path());
    const DesignGem d = build_design(design);
    const DesignGem pre = build_design(preform_of(design));
    const Ray into_notch{Vec3(0, 0.55, 5), Vec3(0, 0, -1)};
    CHECK(intersect(tracing_shape(pre.gem), into_notch, 0, 1e30));
    CHECK_FALSE(intersect(tracing_shape(d.gem), into_notch, 0, 1e30));
    const Ray lobe{Vec3(-0.45, 0.15, 5), Vec3(0, 0, -1)};
    const auto a = intersect(tracing_shape(pre.gem), lobe, 0, 1e30), b = intersect(tracing_shape(d.gem), lobe, 0, 1e30);
    REQUIRE(a);
    REQUIRE(b);
    CHECK(b->t == Approx(a->t).epsilon(1e-12));
    CHECK(d.gem.facets[static_cast<size_t>(hit_facets(d.gem)[static_cast<size_t>(b->facet)])].label ==
          pre.gem.solid.labels[static_cast<size_t>(a->facet)]);

    gem_metrics::MetricOptions o;
    o.wavelengths = 3;
    gem_metrics::GemTracer tracer(d.gem, o);
    std::vector<gem_metrics::GemTracer::Exit> exits;
    tracer.trace(into_notch, 0, exits);
    REQUIRE(exits.size() == 1);
    CHECK(exits[0].kind == -1);  // missed the stone
    tracer.trace(lobe, 0, exits);
    CHECK(exits.size() > 1);
}

TEST_CASE("The heart's gem metrics are measured on its mesh: finite, every eye ray meets the stone, the energy "
          "balances",
          "[gemcad][heart][design-metrics]") {
    const DesignGem m = dm::build_at_width_2(read_gemcad(heart_path()));
    CHECK_FALSE(m.gem.convex);
    gem_metrics::MetricOptions o;
    o.rays = 256;
    o.wavelengths = 3;
    o.spot_rotations = 4;
    const gem_metrics::GemMetrics g = dm::measure(m, o);
    const auto& b = g.balance;
    CHECK(b.missed == 0);
    CHECK(b.crown + b.girdle + b.pavilion + b.lost == Approx(1).epsilon(1e-9));
    CHECK(g.light_return.value > 0.1);
    CHECK(g.light_return.value < 1);
    CHECK(std::isfinite(g.fire.value));
    CHECK(g.fire.value > 0);
    CHECK(std::isfinite(g.scintillation.value));
    CHECK(std::isfinite(g.leakage.value));
}

TEST_CASE("A cleft that removes nothing or cuts the stone in two is refused with one line naming the file and the "
          "tier, exit 2",
          "[gemcad][heart][errors]") {
    using refract::test::check_refused;
    using refract::test::run;
    const auto refusal = [](const std::string& text) {
        try {
            build_design(parse_gemcad(text, "cl.asc"));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    // y <= 5 keeps the whole box: nothing lies outside every cleft facet.
    CHECK(refusal(box("a 90 5 48 n CL\n")) ==
          "cl.asc: tier 4 ('CL', line 9): the cleft removes nothing (no part of the stone lies outside every cleft "
          "facet)");
    // x <= -0.1 or x >= 0.1: a slot through the middle.
    CHECK(refusal(box("a 90 -0.1 24 n CL 72\n")) == "cl.asc: tier 4 ('CL', line 9): the cleft cuts the stone in 2 pieces");
    // A notch at one side (x > 0.5 and x + y > 0.5·√2) leaves one stone, the box less it.
    const DesignGem ok = build_design(parse_gemcad(box("a 90 0.5 24 n CL1 36\n"), "cl.asc"));
    CHECK_FALSE(ok.gem.convex);
    CHECK(ok.preform_volume == Approx(4).epsilon(1e-12));
    CHECK(ok.volume < ok.preform_volume);

    const fs::path dir = refract::test::fresh_dir("gemcad", "heart");
    write(dir / "none.asc", box("a 90 5 48 n CL\n"));
    check_refused(run("cut asc " + (dir / "none.asc").string() + " -o " + (dir / "none.obj").string(), dir),
                  "none.asc: tier 4 ('CL', line 9): the cleft removes nothing");
    CHECK_FALSE(fs::exists(dir / "none.obj"));
    write(dir / "two.asc", box("a 90 -0.1 24 n CL 72\n"));
    check_refused(run("cut asc " + (dir / "two.asc").string() + " -o " + (dir / "two.obj").string(), dir),
                  "two.asc: tier 4 ('CL', line 9): the cleft cuts the stone in 2 pieces");
    CHECK_FALSE(fs::exists(dir / "two.obj"));
    fs::remove_all(dir);
}

TEST_CASE("refract cut asc writes the heart's mesh and a scene's gem object with the heart is its closed mesh",
          "[gemcad][heart][cli]") {
    using refract::test::run;
    const fs::path dir = refract::test::fresh_dir("gemcad", "heart-cli");
    const auto r = run("cut asc " + heart_path() + " -o " + (dir / "heart.obj").string(), dir);
    REQUIRE(r.code == 0);
    CHECK(fs::file_size(dir / "heart.obj") > 1000);
    fs::copy_file(heart_path(), dir / "heart.asc");
    write(dir / "s.json", R"({"camera": {"location": [0, 0, -5]}, "materials": {"g": {"type": "dielectric",
        "ior": 2.417}}, "objects": [{"type": "gem", "design": "heart.asc", "diameter": 2, "material": "g"}]})");
    const Scene s = load_scene((dir / "s.json").string());
    const auto& mesh = std::get<TriangleMesh>(s.objects[0].shape);
    const DesignGem d = build_design(read_gemcad(heart_path()));
    CHECK(mesh.triangles.size() == d.gem.mesh.triangles.size());
    fs::remove_all(dir);
}
