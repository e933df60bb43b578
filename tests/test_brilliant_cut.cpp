// The exact round-brilliant construction (geometry/gem): topology, facet shapes, symmetry,
// proportions measured back against Tolkowsky (1919) and the closed forms, input errors,
// and agreement of the plane-set and triangle-mesh ray intersections.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include <refract/geometry/error.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/gem/gem_io.h>

using namespace refract;

namespace {

constexpr double kPi = 3.14159265358979323846;
double rad(double d) { return d * kPi / 180; }

BrilliantCut variant_culet32() {
    BrilliantCut c = brilliant_preset("gia-default");
    c.culet = 2;
    c.girdle_facets = 32;
    return c;
}
BrilliantCut variant_80() {
    BrilliantCut c;  // mid-domain, 80 girdle facets, a thick girdle
    c.table = 62;
    c.crown_angle = 31;
    c.pavilion_angle = 41.5;
    c.star = 45;
    c.lower_half = 70;
    c.girdle = 5;
    c.girdle_facets = 80;
    return c;
}

std::vector<std::pair<std::string, BrilliantCut>> cuts() {
    return {{"tolkowsky", brilliant_preset("tolkowsky")},
            {"gia-default", brilliant_preset("gia-default")},
            {"gia + culet 2 % + 32 girdle facets", variant_culet32()},
            {"62 %/31/41.5 + 80 girdle facets", variant_80()}};
}

const GemFacet& facet(const Gem& g, const std::string& label) {
    for (const auto& f : g.facets)
        if (f.label == label) return f;
    FAIL("no facet " << label);
    return g.facets.front();
}

Vec3 rotz(const Vec3& p, double deg) {
    const double c = std::cos(rad(deg)), s = std::sin(rad(deg));
    return {c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z()};
}

// Same vertex set within tol (polygons may start at different vertices).
bool same_polygon(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double tol) {
    if (a.size() != b.size()) return false;
    for (const Vec3& p : a) {
        bool found = false;
        for (const Vec3& q : b) found = found || (p - q).norm() < tol;
        if (!found) return false;
    }
    return true;
}

// Portable uniform doubles in [0, 1) from the standard-specified mt19937_64 sequence.
struct Uniform {
    std::mt19937_64 eng{20240531};
    double operator()() { return static_cast<double>(eng() >> 11) * 0x1.0p-53; }
};

}  // namespace

TEST_CASE("Round brilliant is a closed convex polyhedron with Euler characteristic 2", "[brilliant]") {
    for (const auto& [name, cut] : cuts()) {
        INFO(name);
        const Gem g = build_brilliant(cut);
        std::map<std::pair<int, int>, int> directed;
        double shortest = 1e9;
        for (const auto& f : g.facets) {
            const std::size_t n = f.vertex_ids.size();
            Vec3 newell = Vec3::Zero();
            for (std::size_t i = 0; i < n; ++i) {
                const int a = f.vertex_ids[i], b = f.vertex_ids[(i + 1) % n];
                ++directed[{a, b}];
                shortest = std::min(shortest, (f.polygon[i] - f.polygon[(i + 1) % n]).norm());
                newell += f.polygon[i].cross(f.polygon[(i + 1) % n]);
                CHECK(std::abs(f.plane.normal.dot(f.polygon[i]) - f.plane.offset) < 1e-12);  // planar
            }
            CHECK(newell.normalized().dot(f.plane.normal) > 1 - 1e-12);  // counter-clockwise outside
            CHECK(std::abs(f.plane.normal.norm() - 1) < 1e-15);
        }
        // Closed: every edge is used once in each direction.
        for (const auto& [e, count] : directed) {
            CHECK(count == 1);
            CHECK(directed.count({e.second, e.first}) == 1);
        }
        const long V = static_cast<long>(g.mesh.vertices.size());
        const long E = static_cast<long>(directed.size()) / 2;
        const long F = static_cast<long>(g.facets.size());
        CHECK(V - E + F == 2);
        // Convex: every vertex inside or on every plane; no spurious near-coincident vertices.
        for (const Vec3& v : g.mesh.vertices)
            for (const auto& p : g.solid.planes) CHECK(p.normal.dot(v) <= p.offset + 1e-12);
        CHECK(shortest > 1e-3);
        // The triangle mesh is the fan triangulation of the facets.
        std::size_t tris = 0;
        for (const auto& f : g.facets) tris += f.vertex_ids.size() - 2;
        CHECK(g.mesh.triangles.size() == tris);
        CHECK(g.triangle_facet.size() == tris);
        CHECK(g.solid.planes.size() == g.facets.size());
        CHECK(g.solid.labels.size() == g.facets.size());
    }
}

TEST_CASE("Round brilliant facet count and polygon kinds (GIA facet names)", "[brilliant]") {
    const auto count = [](const Gem& g, const std::string& kind) {
        for (const auto& [k, n] : facet_counts(g))
            if (k == kind) return n;
        return 0;
    };
    for (const auto& [name, cut] : cuts()) {
        INFO(name);
        const Gem g = build_brilliant(cut);
        const int n_girdle = cut.girdle > 0 ? girdle_plane_count(cut) : 0;
        // 57 facets (table, 8 stars, 8 bezels, 16 upper halves, 16 lower halves, 8 mains),
        // 58 with a culet, plus the girdle facets.
        CHECK(g.facets.size() == static_cast<std::size_t>(57 + (cut.culet > 0 ? 1 : 0) + n_girdle));
        CHECK(count(g, "table") == 1);
        CHECK(count(g, "star") == 8);
        CHECK(count(g, "bezel") == 8);
        CHECK(count(g, "upper half") == 16);
        CHECK(count(g, "lower half") == 16);
        CHECK(count(g, "pavilion main") == 8);
        CHECK(count(g, "girdle") == n_girdle);
        CHECK(count(g, "culet") == (cut.culet > 0 ? 1 : 0));
        // A half facet is a triangle whose girdle side follows the girdle polygon: 3 vertices
        // on a knife edge, 3 + N/16 on a girdle of N planes.
        const std::size_t half = cut.girdle > 0 ? 3 + girdle_plane_count(cut) / 16 : 3;
        for (const auto& f : g.facets) {
            INFO(f.label);
            const std::string kind = facet_kind(f.label);
            const std::size_t n = f.polygon.size();
            if (kind == "table" || kind == "culet") CHECK(n == 8);
            if (kind == "star") CHECK(n == 3);
            if (kind == "upper half" || kind == "lower half") CHECK(n == half);
            if (kind == "bezel" || (kind == "pavilion main" && cut.culet == 0)) {
                REQUIRE(n == 4);  // a kite: two pairs of equal adjacent sides, symmetric about φk
                const auto side = [&](std::size_t i) { return (f.polygon[(i + 1) % 4] - f.polygon[i]).norm(); };
                const bool kite = (std::abs(side(0) - side(1)) < 1e-12 && std::abs(side(2) - side(3)) < 1e-12) ||
                                  (std::abs(side(1) - side(2)) < 1e-12 && std::abs(side(3) - side(0)) < 1e-12);
                CHECK(kite);
            }
            if (kind == "pavilion main" && cut.culet > 0) CHECK(n == 5);
            if (kind == "girdle") {
                // touched by a bezel/main or a half junction: 6 vertices, otherwise 4
                const int j = std::stoi(f.label.substr(7));
                CHECK(n == ((j % (girdle_plane_count(cut) / 16) == 0) ? 6u : 4u));
            }
        }
    }
}

TEST_CASE("Round brilliant has 8-fold rotational and mirror symmetry", "[brilliant]") {
    for (const auto& [name, cut] : cuts()) {
        INFO(name);
        const Gem g = build_brilliant(cut);
        std::map<std::string, const GemFacet*> by;
        for (const auto& f : g.facets) by[f.label] = &f;
        const int n_girdle = girdle_plane_count(cut);
        for (const auto& f : g.facets) {
            const std::string kind = facet_kind(f.label);
            if (kind == "table" || kind == "culet") {
                std::vector<Vec3> r;
                for (const Vec3& p : f.polygon) r.push_back(rotz(p, 45));
                CHECK(same_polygon(r, f.polygon, 1e-12));
                continue;
            }
            std::string tail = f.label.substr(kind.size() + 1);
            std::string sign;
            if (tail.back() == '+' || tail.back() == '-') {
                sign = tail.substr(tail.size() - 1);
                tail.pop_back();
            }
            const int k = std::stoi(tail);
            const int period = kind == "girdle" ? n_girdle : 8;
            const int step = kind == "girdle" ? n_girdle / 8 : 1;
            const std::string next = kind + " " + std::to_string((k + step) % period) + sign;
            INFO(f.label << " -> " << next);
            REQUIRE(by.count(next) == 1);
            std::vector<Vec3> r;
            for (const Vec3& p : f.polygon) r.push_back(rotz(p, 45));
            CHECK(same_polygon(r, by[next]->polygon, 1e-12));
        }
        // Mirror in the plane of azimuth 0: "upper half 0+" <-> "upper half 0-", etc.
        const auto mirror = [](std::vector<Vec3> v) {
            for (Vec3& p : v) p.y() = -p.y();
            return v;
        };
        CHECK(same_polygon(mirror(facet(g, "upper half 0+").polygon), facet(g, "upper half 0-").polygon, 1e-12));
        CHECK(same_polygon(mirror(facet(g, "lower half 0+").polygon), facet(g, "lower half 0-").polygon, 1e-12));
        CHECK(same_polygon(mirror(facet(g, "star 0").polygon), facet(g, "star 7").polygon, 1e-12));
        CHECK(same_polygon(mirror(facet(g, "bezel 0").polygon), facet(g, "bezel 0").polygon, 1e-12));
    }
}

TEST_CASE("Round brilliant half facets lie at azimuths phi_k +- 11.25 deg (even girdle)", "[brilliant]") {
    for (const auto& [name, cut] : cuts()) {
        INFO(name);
        const Gem g = build_brilliant(cut);
        for (int k = 0; k < 8; ++k)
            for (const char* kind : {"upper half ", "lower half "})
                for (const char* sign : {"+", "-"}) {
                    const Vec3 n = facet(g, kind + std::to_string(k) + sign).plane.normal;
                    const double want = 45.0 * k + (sign[0] == '+' ? 11.25 : -11.25);
                    const double az = std::atan2(n.y(), n.x()) * 180 / kPi;
                    CHECK(std::remainder(az - want, 360.0) == Approx(0).margin(1e-9));
                }
    }
}

TEST_CASE("Tolkowsky (1919) proportions: crown height 16.2 %, pavilion depth 43.1 %", "[brilliant]") {
    // Closed forms with R = 1 (D = 2): crown height = (1 − t)·tanβ / 2, pavilion depth =
    // tanα / 2 for a pointed culet and a knife-edge girdle.
    const Gem g = build_brilliant(brilliant_preset("tolkowsky"));
    const double t = 0.53, beta = rad(34.5), alpha = rad(40.75);
    CHECK(g.measured.crown_height == Approx(100 * 0.5 * (1 - t) * std::tan(beta)).margin(1e-9));
    CHECK(g.measured.pavilion_depth == Approx(100 * 0.5 * std::tan(alpha)).margin(1e-9));
    CHECK(g.measured.total_depth == Approx(100 * 0.5 * ((1 - t) * std::tan(beta) + std::tan(alpha))).margin(1e-9));
    // Tolkowsky's published (rounded) values; his 59.3 % total is the sum of the rounded parts.
    CHECK(std::abs(g.measured.crown_height - 16.2) < 0.05);
    CHECK(std::abs(g.measured.pavilion_depth - 43.1) < 0.05);
    CHECK(std::abs(g.measured.total_depth - 59.3) < 0.1);
    CHECK(g.measured.girdle == Approx(0).margin(1e-12));
}

TEST_CASE("Round brilliant proportions measured back equal the requested and closed-form values", "[brilliant]") {
    for (const auto& [name, cut] : cuts()) {
        INFO(name);
        const Gem g = build_brilliant(cut);
        const BrilliantProportions& m = g.measured;
        const double t = cut.table / 100, c = cut.culet / 100;
        const double crown = 100 * 0.5 * (1 - t) * std::tan(rad(cut.crown_angle));
        const double pavilion = 100 * 0.5 * (1 - c) * std::tan(rad(cut.pavilion_angle));
        CHECK(m.table == Approx(cut.table).margin(1e-9));
        CHECK(m.crown_angle == Approx(cut.crown_angle).margin(1e-9));
        CHECK(m.pavilion_angle == Approx(cut.pavilion_angle).margin(1e-9));
        CHECK(m.star == Approx(cut.star).margin(1e-9));
        CHECK(m.lower_half == Approx(cut.lower_half).margin(1e-9));
        CHECK(m.girdle == Approx(cut.girdle).margin(1e-9));
        CHECK(m.culet == Approx(cut.culet).margin(1e-9));
        CHECK(m.crown_height == Approx(crown).margin(1e-9));
        CHECK(m.pavilion_depth == Approx(pavilion).margin(1e-9));
        CHECK(m.total_depth == Approx(crown + cut.girdle + pavilion).margin(1e-9));
        // The library's closed forms agree with these.
        const BrilliantProportions e = closed_form_proportions(cut);
        CHECK(e.crown_height == Approx(crown).margin(1e-12));
        CHECK(e.total_depth == Approx(crown + cut.girdle + pavilion).margin(1e-12));
    }
}

TEST_CASE("Round brilliant rejects parameters outside the domain or infeasible, naming them", "[brilliant]") {
    const auto message = [](BrilliantCut c) -> std::string {
        try {
            build_brilliant(c);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    const BrilliantCut gia = brilliant_preset("gia-default");
    BrilliantCut c = gia;
    c.table = 80;
    CHECK_THAT(message(c), Catch::Contains("table = 80 %") && Catch::Contains("44 to 72"));
    c = gia;
    c.crown_angle = 45;
    CHECK_THAT(message(c), Catch::Contains("crown angle = 45 deg") && Catch::Contains("20 to 41.5"));
    c = gia;
    c.pavilion_angle = std::nan("");
    CHECK_THAT(message(c), Catch::Contains("pavilion angle = nan"));
    c = gia;
    c.star = 90;
    CHECK_THAT(message(c), Catch::Contains("star length = 90 %"));
    c = gia;
    c.girdle = 1.6;  // inside GIA's 1.5–11 %, but too thin for these halves
    CHECK_THAT(message(c), Catch::Contains("girdle thickness = 1.6 %") && Catch::Contains("halves would meet"));
    c = gia;
    c.girdle = 0.5;
    CHECK_THAT(message(c), Catch::Contains("girdle thickness = 0.5 %") && Catch::Contains("knife edge"));
    c = gia;
    c.culet = 5;
    c.lower_half = 95;  // the lower-half points would lie beyond the culet corners
    CHECK_THAT(message(c), Catch::Contains("lower-half length = 95 %") && Catch::Contains("culet"));
    c = gia;
    c.girdle_facets = 40;
    CHECK_THAT(message(c), Catch::Contains("girdle facets = 40") && Catch::Contains("multiple of 16"));
    c = gia;
    c.culet = -1;
    CHECK_THAT(message(c), Catch::Contains("culet = -1 %"));
    CHECK_THROWS_WITH(brilliant_preset("marquise"), Catch::Contains("marquise") && Catch::Contains("tolkowsky"));
    // Every message is one line starting with the cut's name.
    c = gia;
    c.lower_half = 20;
    const std::string m = message(c);
    CHECK(m.rfind("brilliant cut: lower-half length = 20 %", 0) == 0);
    CHECK(m.find('\n') == std::string::npos);
}

TEST_CASE("Round brilliant girdle thickness feasibility limit is sharp", "[brilliant]") {
    // Just above the minimum every girdle facet survives (exact construction); just below,
    // validation names the girdle thickness.
    for (int facets : {0, 16, 32}) {
        BrilliantCut c = brilliant_preset("gia-default");
        c.girdle_facets = facets;
        const double g_min = min_girdle_percent(c);
        INFO("girdle facets " << facets << ", minimum " << g_min << " %");
        REQUIRE(g_min > 1.5);  // inside GIA's domain, so only feasibility decides
        c.girdle = g_min + 1e-6;
        const Gem g = build_brilliant(c);
        CHECK(g.facets.size() == static_cast<std::size_t>(57 + girdle_plane_count(c)));
        CHECK(g.measured.girdle == Approx(c.girdle).margin(1e-9));
        c.girdle = g_min - 1e-6;
        CHECK_THROWS_WITH(build_brilliant(c), Catch::Contains("girdle thickness"));
    }
}

TEST_CASE("Round brilliant plane set and triangle mesh give the same hits on random rays", "[brilliant]") {
    for (const auto& [name, cut] : cuts()) {
        INFO(name);
        const Gem g = build_brilliant(cut);
        Uniform u;
        int hits = 0, agree = 0;
        const int n = 2000;
        for (int i = 0; i < n; ++i) {
            Ray r;
            if (i % 4 == 3) {  // from inside: the exit facet
                r.origin = Vec3(0.6 * (u() - 0.5), 0.6 * (u() - 0.5), -0.3 + 0.4 * u());
            } else {  // from a sphere of radius 3 towards a point of the bounding box
                const double z = 2 * u() - 1, phi = 2 * kPi * u(), s = std::sqrt(1 - z * z);
                r.origin = 3 * Vec3(s * std::cos(phi), s * std::sin(phi), z);
            }
            const Vec3 target(2.2 * (u() - 0.5), 2.2 * (u() - 0.5), -1 + 1.3 * u());
            r.dir = (target - r.origin).normalized();
            const auto hp = intersect(g.solid, r, 1e-9, 1e30);
            const auto hm = intersect(g.mesh, r, 1e-9, 1e30);
            REQUIRE(hp.has_value() == hm.has_value());
            if (!hp) continue;
            ++hits;
            CHECK(hp->t == Approx(hm->t).margin(1e-9));
            const std::string& lp = g.solid.labels[static_cast<std::size_t>(hp->facet)];
            const std::string& lm = g.facets[static_cast<std::size_t>(g.triangle_facet[static_cast<std::size_t>(hm->facet)])].label;
            CHECK(lp == lm);
            CHECK((hp->normal - hm->normal).norm() < 1e-9);
            agree += (lp == lm);
        }
        CHECK(hits > n / 2);
        CHECK(agree == hits);
    }
}

TEST_CASE("Gem export writes OBJ, OFF, PLY and POV-Ray by extension, atomically", "[brilliant]") {
    namespace fs = std::filesystem;
    const Gem g = build_brilliant(brilliant_preset("gia-default"));
    const fs::path dir = fs::temp_directory_path() / ("refract-gem-test-" + std::to_string(std::random_device{}()));
    fs::create_directories(dir);
    const auto read = [](const fs::path& p) {
        std::ifstream in(p);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    };
    write_gem(g, (dir / "gem.off").string());
    {
        std::istringstream in(read(dir / "gem.off"));
        std::string line;
        std::getline(in, line);
        CHECK(line == "OFF");
        std::getline(in, line);  // comment
        std::size_t v = 0, f = 0, e = 0;
        in >> v >> f >> e;
        CHECK(v == g.mesh.vertices.size());
        CHECK(f == g.facets.size());
        CHECK(static_cast<long>(v) - static_cast<long>(e) + static_cast<long>(f) == 2);
    }
    write_gem(g, (dir / "gem.obj").string());
    const std::string obj = read(dir / "gem.obj");
    CHECK(obj.find("g upper_half_2+\nf ") != std::string::npos);
    write_gem(g, (dir / "gem.PLY").string());
    CHECK(read(dir / "gem.PLY").find("element face " + std::to_string(g.facets.size())) != std::string::npos);
    write_gem(g, (dir / "gem.pov").string());
    const std::string pov = read(dir / "gem.pov");
    CHECK(pov.find("#declare Gem = intersection {") != std::string::npos);
    std::size_t planes = 0;
    for (std::size_t p = pov.find("plane {"); p != std::string::npos; p = pov.find("plane {", p + 1)) ++planes;
    CHECK(planes == g.facets.size());
    CHECK_THROWS_WITH(write_gem(g, (dir / "gem.stl").string()), Catch::Contains("gem.stl") && Catch::Contains(".obj"));
    CHECK_FALSE(fs::exists(dir / "gem.stl"));
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    CHECK(files == 4);  // no temporary left behind
    fs::remove_all(dir);
}
