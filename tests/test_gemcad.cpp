// GemCad faceting designs (.asc, geometry/gem/gemcad.h): the format's conventions (signed
// angles, gear indices, names), the exact build (closed, convex, volume, width), the round
// brilliant written as a design and read back, the refusals (one line naming the file and
// the line or tier), the "gem" scene object and `refract cut asc`.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/gem/gem_io.h>
#include <refract/geometry/gem/gemcad.h>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

using namespace refract;
namespace fs = std::filesystem;

namespace {

// A 2 × 2 × 1 box: four girdle facets (indices 0, 24, 48, 72 of gear 96), a table and a
// pavilion culet (-0), then `extra` tiers.
std::string box(const std::string& extra = "") {
    return "GemCad 5.0\ng 96 0.0\ny 4 y\nI 1.54\nH test box\n"
           "a -90 1 0 n G 24 48 72\n"
           "a 0 0.5 0 n T\n"
           "a -0 0.5 0 n C\n" +
           extra;
}

const GemFacet& facet(const Gem& g, const std::string& label) {
    for (const GemFacet& f : g.facets)
        if (f.label == label) return f;
    FAIL("no facet " << label);
    throw;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("GemCad tiers: index 24 of gear 96 faces +x, a negative angle is the pavilion facet on the same side, -0 "
          "the culet",
          "[gemcad]") {
    const DesignGem d = build_design(parse_gemcad(box("a 45 0.9 24 n A\na -45 0.9 24 n P\n"), "t.asc"));
    CHECK(d.planes == 8);
    CHECK(d.gem.facets.size() == 8);
    const double s = std::sqrt(0.5);
    const Plane& a = facet(d.gem, "A 24").plane;
    CHECK(a.normal.x() == Approx(s).margin(1e-15));
    CHECK(a.normal.y() == Approx(0).margin(1e-15));
    CHECK(a.normal.z() == Approx(s).margin(1e-15));
    CHECK(a.offset == Approx(0.9));
    const Plane& p = facet(d.gem, "P 24").plane;
    CHECK(p.normal.x() == Approx(s).margin(1e-15));
    CHECK(p.normal.z() == Approx(-s).margin(1e-15));
    CHECK(facet(d.gem, "C 0").plane.normal.z() == -1);
    CHECK(facet(d.gem, "G 48").plane.normal.y() == 1);  // index 48: azimuth 90°
    CHECK(facet(d.gem, "G 0").plane.normal.y() == -1);  // index 0 (location 0): −y
    // The box less two wedges along its +x edges, x ± z <= 0.9√2: right prisms 2 long of
    // isosceles right cross-section with legs 1.5 − 0.9√2.
    const double leg = 1.5 - std::sqrt(2.0) * 0.9;
    CHECK(d.volume == Approx(4 - 2 * leg * leg / 2 * 2).epsilon(1e-12));
    CHECK(d.width == Approx(2).epsilon(1e-12));
    CHECK(d.length == Approx(2).epsilon(1e-12));
    CHECK(d.height == Approx(1).epsilon(1e-12));
}

TEST_CASE("GemCad gear location turns the indices: location 12 puts index 36 on +x", "[gemcad]") {
    std::string t = box();
    t.replace(t.find("g 96 0.0"), 8, "g 96 12");
    const DesignGem d = build_design(parse_gemcad(t + "a 45 0.9 36 n A\n", "t.asc"));
    const Plane& a = facet(d.gem, "A 36").plane;
    CHECK(a.normal.x() == Approx(std::sqrt(0.5)).margin(1e-15));
    CHECK(a.normal.y() == Approx(0).margin(1e-15));
}

TEST_CASE("The round brilliant written as a GemCad design reads back to its planes and vertices within 1e-9",
          "[gemcad]") {
    for (const char* preset : {"gia-default", "tolkowsky"}) {
        INFO(preset);
        const Gem b = build_brilliant(brilliant_preset(preset));
        const std::string text = gemcad_text(brilliant_design(b));
        const DesignGem d = build_design(parse_gemcad(text, "b.asc"));
        REQUIRE(d.gem.facets.size() == b.facets.size());
        for (std::size_t k = 0; k < b.facets.size(); ++k) {
            INFO(b.facets[k].label << " / " << d.gem.facets[k].label);
            CHECK((d.gem.facets[k].plane.normal - b.facets[k].plane.normal).norm() < 1e-9);
            CHECK(std::fabs(d.gem.facets[k].plane.offset - b.facets[k].plane.offset) < 1e-9);
        }
        // Every vertex of each within 1e-9 of a vertex of the other.
        const auto near = [](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
            double worst = 0;
            for (const Vec3& p : from) {
                double best = 1e300;
                for (const Vec3& q : to) best = std::min(best, (p - q).norm());
                worst = std::max(worst, best);
            }
            return worst;
        };
        CHECK(near(b.mesh.vertices, d.gem.mesh.vertices) < 1e-9);
        CHECK(near(d.gem.mesh.vertices, b.mesh.vertices) < 1e-9);
        CHECK(d.gem.mesh.vertices.size() == b.mesh.vertices.size());
        // W: across the girdle planes (2), or for a knife edge across the flats of the
        // 16-gon where the crown and pavilion halves meet on the unit circle.
        CHECK(d.width == Approx(b.cut.girdle > 0 ? 2 : 2 * std::cos(M_PI / 16)).epsilon(1e-12));
    }
}

TEST_CASE("Bad GemCad designs are refused with one line naming the file and the line or tier", "[gemcad][errors]") {
    const auto refused = [](const std::string& text, const std::string& what) {
        INFO(text);
        try {
            build_design(parse_gemcad(text, "bad.asc"));
            FAIL("accepted");
        } catch (const InputError& e) {
            const std::string m = e.what();
            INFO(m);
            CHECK(m.rfind("bad.asc: ", 0) == 0);
            CHECK(m.find('\n') == std::string::npos);
            CHECK(m.find(what) != std::string::npos);
        }
    };
    refused(box("a -42.5"), "line 9: truncated 'a' line: the distance is missing");
    refused(box("a -42.5 0.6"), "line 9: truncated 'a' line: a tier needs angle, distance and at least one gear index");
    refused("GemCad 5.0\ng 96 0.0\n", "line 2: the design has no tier ('a' line): truncated file?");
    refused("", "the file is empty");
    refused(box("Q 3\n"), "line 9: unknown keyword 'Q'");
    refused(box("a nan 1 0\n"), "line 9: angle 'nan' is not a finite number");
    refused(box("a 45 inf 0\n"), "line 9: distance 'inf' is not a finite number");
    refused(box("a 45 1 1e999\n"), "line 9: gear index '1e999' is not a finite number");
    refused(box("a 45 1.2 97\n"), "line 9: gear index 97 is outside 0 to 96 (gear 96)");
    refused(box("a 95 1.2 3\n"), "line 9: angle 95 is outside -90 to 90 degrees");
    refused("a 45 1 0\n", "line 1: a tier before the gear line 'g'");
    std::string many = "a 45 1.2";
    for (int k = 0; k < 4097; ++k) many += " 0";
    refused(box(many + "\n"), "line 9: more than 4096 facets");
    refused(box("a 0 -0.75 0 n T2\n"), "tier 4 ('T2', line 9) cuts the stone away: nothing of the stone is left");
    refused("g 96 0\na -90 1 0 24 48 72\na -0 0.5 0\n", "the tiers do not close the stone: it is unbounded towards +z");
    refused("g 96 0\na -90 1 0 48\na 0 0.5 0\na -0 0.5 0\n", "unbounded towards +x");
}

TEST_CASE("A gem design in a scene is placed like the brilliant: the brilliant's .asc with the same diameter gives its "
          "planes within 1e-9",
          "[gemcad][scene]") {
    const fs::path dir = refract::test::fresh_dir("gemcad", "scene");
    write(dir / "b.asc", gemcad_text(brilliant_design(build_brilliant(brilliant_preset("gia-default")))));
    const auto scene = [&](const std::string& object) {
        write(dir / "s.json", R"({"camera": {"location": [0, 0, -5]}, "materials": {"g": {"type": "dielectric",
            "ior": 2.417}}, "objects": [)" + object + "]}");
        return load_scene((dir / "s.json").string());
    };
    const std::string place = R"("position": [0.5, 1, -2], "rotation": [10, 20, 30], "material": "g")";
    const Scene a = scene(R"({"type": "brilliant", "diameter": 3, )" + place + "}");
    const Scene b = scene(R"({"type": "gem", "design": "b.asc", "diameter": 3, )" + place + "}");
    const auto& pa = std::get<ConvexPolyhedron>(a.objects[0].shape);
    const auto& pb = std::get<ConvexPolyhedron>(b.objects[0].shape);
    REQUIRE(pa.planes.size() == pb.planes.size());
    for (std::size_t k = 0; k < pa.planes.size(); ++k) {
        CHECK((pa.planes[k].normal - pb.planes[k].normal).norm() < 1e-9);
        CHECK(std::fabs(pa.planes[k].offset - pb.planes[k].offset) < 1e-9);
    }
    CHECK((pa.bound_center - pb.bound_center).norm() < 1e-9);

    write(dir / "bad.asc", box("a 45 1.2 97\n"));
    try {
        scene(R"({"type": "gem", "design": "bad.asc", "material": "g"})");
        FAIL("accepted");
    } catch (const InputError& e) {
        const std::string m = e.what();
        CHECK(m.find("s.json: /objects/0/design: ") != std::string::npos);
        CHECK(m.find("bad.asc: line 9: gear index 97 is outside 0 to 96") != std::string::npos);
    }
    fs::remove_all(dir);
}

TEST_CASE("refract cut asc writes the design's mesh y up, cut brilliant -o x.asc round-trips, bad designs exit 2",
          "[gemcad][cli]") {
    using refract::test::check_refused;
    using refract::test::run;
    const fs::path dir = refract::test::fresh_dir("gemcad", "cli");
    const Gem g = build_brilliant(brilliant_preset("gia-default"));
    REQUIRE(run("cut brilliant -o " + (dir / "b.asc").string(), dir).code == 0);
    REQUIRE(run("cut asc " + (dir / "b.asc").string() + " -o " + (dir / "b.obj").string(), dir).code == 0);
    // The OBJ holds the brilliant's vertices turned y up: (x, y, z) -> (x, z, -y); the table on top.
    std::istringstream obj(read(dir / "b.obj"));
    std::string line;
    double top = -1e300;
    std::vector<Vec3> vertices;
    while (std::getline(obj, line))
        if (line.rfind("v ", 0) == 0) {
            std::istringstream v(line.substr(2));
            double x, y, z;
            v >> x >> y >> z;
            top = std::max(top, y);
            vertices.emplace_back(x, y, z);
        }
    CHECK(vertices.size() == g.mesh.vertices.size());
    // Loaded as it is, the file is the brilliant a scene places at the origin (diameter 2): every
    // vertex on the placed polyhedron's boundary.
    write(dir / "s.json", R"({"camera": {"location": [0, 0, -5]}, "materials": {"g": {"type": "dielectric",
        "ior": 2.417}}, "objects": [{"type": "brilliant", "material": "g"}]})");
    const auto& placed = std::get<ConvexPolyhedron>(load_scene((dir / "s.json").string()).objects[0].shape);
    double worst = 0;
    for (const Vec3& v : vertices) {
        double out = -1e300;
        for (const Plane& p : placed.planes) out = std::max(out, p.normal.dot(v) - p.offset);
        worst = std::max(worst, std::fabs(out));
    }
    CHECK(worst < 1e-12);
    double zmax = -1e300;
    for (const Vec3& v : g.mesh.vertices) zmax = std::max(zmax, v.z());
    CHECK(top == Approx(zmax).epsilon(1e-12));
    CHECK(top == Approx(0.03 + (1 - 0.57) * std::tan(34.5 * M_PI / 180)).epsilon(1e-9));  // girdle radius 1

    write(dir / "bad.asc", box("a 45 1.2 97\n"));
    check_refused(run("cut asc " + (dir / "bad.asc").string() + " -o " + (dir / "bad.obj").string(), dir),
                  "bad.asc: line 9: gear index 97 is outside 0 to 96");
    CHECK_FALSE(fs::exists(dir / "bad.obj"));
    write(dir / "away.asc", box("a 0 -0.75 0 n T2\n"));
    check_refused(run("cut asc " + (dir / "away.asc").string() + " -o " + (dir / "away.obj").string(), dir),
                  "away.asc: tier 4 ('T2', line 9) cuts the stone away");
    check_refused(run("cut asc " + (dir / "b.asc").string() + " -o " + (dir / "b.stl").string(), dir),
                  "unknown extension '.stl' (allowed: .obj, .off, .ply, .pov, .asc)");
    fs::remove_all(dir);
}

TEST_CASE("Every cut of the catalogue (scenes/gems/designs) builds closed and convex, with its facet count and volume",
          "[gemcad][catalogue]") {
    struct Cut {
        const char* name;
        std::size_t facets;
        double volume;  // width W = 2
    };
    const Cut cuts[] = {{"princess", 29, 1.856967904},  {"emerald", 53, 3.672026008}, {"asscher", 57, 2.386214486},
                        {"radiant", 33, 2.786792793},   {"cushion", 65, 1.956784065}, {"oval", 81, 2.342391835},
                        {"pear", 76, 2.071100825},      {"marquise", 63, 3.20301157}, {"old-european", 90, 1.802178271},
                        {"single", 33, 1.759019646}};
    for (const Cut& c : cuts) {
        INFO(c.name);
        const fs::path file = fs::path(REFRACT_SOURCE_DIR) / "scenes/gems/designs" / (std::string(c.name) + ".asc");
        const GemcadDesign design = read_gemcad(file.string());
        const DesignGem d = build_design(design);  // throws unless closed and convex
        CHECK(d.gem.facets.size() == c.facets);
        CHECK(static_cast<std::size_t>(d.planes) == c.facets);  // the design lists no facet the stone loses
        CHECK(d.volume == Approx(c.volume).epsilon(1e-9));
        CHECK(d.width == Approx(2).epsilon(1e-9));
        CHECK(design.headings.size() >= 3);  // name, source, reference proportions
    }
}
