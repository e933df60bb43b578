// The far-field detector (core/far_field.h), collimated beams and a sun's angular size.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/far_field.h>
#include <refract/core/optics.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

using namespace refract;
using nlohmann::json;

namespace {

// A unit sphere of index n lit by a beam along +z that just covers it.
json drop_scene(double n, const json& render = json::object()) {
    return json{{"camera", {{"location", {0, 0, -5}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 8}, {"height", 8}}},
                {"materials", {{"glass", {{"type", "dielectric"}, {"ior", n}}}}},
                {"objects", {{{"type", "sphere"}, {"name", "drop"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
                {"lights", {{{"type", "beam"}, {"position", {0, 0, -3}}, {"direction", {0, 0, 1}}, {"radius", 1}}}},
                {"render", render}};
}

FarFieldSettings axis_bins(int bins, std::uint64_t photons) {
    FarFieldSettings s;
    s.binning = FarFieldSettings::Binning::Axis;
    s.axis = Vec3(0, 0, 1);
    s.angle_bins = bins;
    s.photons = photons;
    return s;
}

double class_total(const FarFieldResult& r, int c, int s = 0) {
    double t = 0;
    for (int b = 0; b < r.bins; ++b) t += r.at(0, c, s, b);
    return t;
}

// ∫ R(i) d(sin² i) over the sphere's cross-section: the externally reflected fraction.
double reflected_fraction(double n) {
    const int N = 200000;
    double sum = 0;
    for (int k = 0; k < N; ++k) {
        const double u = (k + 0.5) / N;  // sin² i
        sum += optics::fresnel_reflectance(std::sqrt(1.0 - u), n) / N;
    }
    return sum;
}

}  // namespace

TEST_CASE("Far field: energy is conserved (scattered + dropped = the beam's power)", "[far-field]") {
    const Scene s = parse_scene(drop_scene(1.5, {{"max_depth", 12}, {"threshold", 1e-4}}), "drop.json");
    const FarFieldResult r = far_field(s, axis_bins(90, 20000), 2);
    double total = r.unscattered[0] + r.absorbed[0] + r.dropped[0];
    for (int c = 0; c < r.classes; ++c) total += class_total(r, c);
    CHECK(total == Approx(1.0).margin(1e-12));
    CHECK(r.dropped[0] > 0);
    CHECK(r.unscattered[0] == 0);  // the beam just covers the sphere
}

TEST_CASE("Far field: an index-1 sphere sends the whole beam straight on, in class 0 internal reflections",
          "[far-field]") {
    const Scene s = parse_scene(drop_scene(1.0), "clear.json");
    const FarFieldResult r = far_field(s, axis_bins(36, 5000), 1);
    CHECK(r.at(0, 1, 0, 0) == Approx(1.0).margin(1e-12));
    CHECK(class_total(r, 0) == 0);
}

TEST_CASE("Far field: the externally reflected fraction of a sphere is the disk average of Fresnel's R",
          "[far-field]") {
    // Van de Hulst's p = 0 class: ∫ R d(sin² i), 0.0665 for water.
    const Scene s = parse_scene(drop_scene(1.333), "water.json");
    const FarFieldResult r = far_field(s, axis_bins(180, 200000), 2);
    const double expected = reflected_fraction(1.333);
    CHECK(expected == Approx(0.0665).margin(5e-4));
    CHECK(class_total(r, 0) == Approx(expected).margin(1.5e-3));  // 200 000 photons: σ ≈ 4e-4
}

TEST_CASE("Far field: the physical mode's default, exact polarisation, gives water's primary rainbow share 0.04060 "
          "(per-bounce natural light: 0.04392, 8 % more)",
          "[far-field][polarisation]") {
    // Van de Hulst's class p = 2 (one internal reflection) of a water drop: the exact
    // share is the mean over s and p of ∫ (1 − R)² R d(sin² i), 0.04060; natural light at
    // every interface puts the mean R in that product instead, 0.04392, 8 % too much.
    const double n = 1.333;
    double exact = 0, natural = 0;
    const int N = 200000;
    for (int k = 0; k < N; ++k) {
        const double u = (k + 0.5) / N;  // sin² i
        const auto f = optics::fresnel(std::sqrt(1.0 - u), n);
        const double R = 0.5 * (f->Rs + f->Rp);
        exact += 0.5 * ((1 - f->Rs) * (1 - f->Rs) * f->Rs + (1 - f->Rp) * (1 - f->Rp) * f->Rp) / N;
        natural += (1 - R) * (1 - R) * R / N;
    }
    CHECK(exact == Approx(0.04060).margin(5e-6));
    CHECK(natural == Approx(0.04392).margin(5e-6));
    // 100 000 photons: σ ≈ 6e-4 on a class total; the two models lie 3.4e-3 apart.
    const json render = {{"max_depth", 8}, {"threshold", 1e-6}};
    const FarFieldResult d = far_field(parse_scene(drop_scene(n, render), "water.json"), axis_bins(180, 100000), 2);
    CHECK(d.components == 4);  // Stokes vectors: exact polarisation without asking
    CHECK(class_total(d, 2) == Approx(exact).margin(1.5e-3));
    json nat = render;
    nat["polarisation"] = "natural";
    const FarFieldResult a = far_field(parse_scene(drop_scene(n, nat), "water.json"), axis_bins(180, 100000), 2);
    CHECK(a.components == 1);
    CHECK(class_total(a, 2) == Approx(natural).margin(1.5e-3));
    CHECK(class_total(a, 2) - class_total(d, 2) > 2e-3);
}

TEST_CASE("Far field: the result does not depend on the thread count", "[far-field]") {
    const Scene s = parse_scene(drop_scene(1.333, {{"polarisation", "exact"}}), "water.json");
    const FarFieldResult a = far_field(s, axis_bins(60, 20000), 1), b = far_field(s, axis_bins(60, 20000), 2);
    CHECK(a.power == b.power);
    CHECK(a.dropped == b.dropped);
}

TEST_CASE("Far field: light reflected at Brewster's angle is polarised perpendicular to the scattering plane",
          "[far-field]") {
    // External reflection at θ_B leaves at scattering angle 180° − 2θ_B (73.7° for n = 1.333)
    // with Rp = 0: S1 = +S0 in the detector's frame (x̂ ⊥ the scattering plane).
    const double n = 1.333;
    const Scene s = parse_scene(drop_scene(n, {{"polarisation", "exact"}}), "water.json");
    const FarFieldResult r = far_field(s, axis_bins(180, 200000), 2);
    const double theta = 180.0 - 2.0 * optics::brewster_angle(n) * 180.0 / M_PI;
    const int b = r.bin_of(Vec3(std::sin(theta * M_PI / 180), 0, std::cos(theta * M_PI / 180)));
    REQUIRE(r.at(0, 0, 0, b) > 0);
    CHECK(r.at(0, 0, 1, b) / r.at(0, 0, 0, b) > 0.999);
    // Natural light in, so the reflected light's polarisation is linear: S3 = 0.
    CHECK(std::abs(r.at(0, 0, 3, b)) < 1e-12);
}

TEST_CASE("Far field: the bins' solid angles cover the sphere", "[far-field]") {
    FarFieldResult r;
    r.settings.binning = FarFieldSettings::Binning::Sphere;
    r.settings.azimuth_bins = 12;
    r.settings.polar_bins = 7;
    r.bins = 84;
    double sum = 0;
    for (int b = 0; b < r.bins; ++b) sum += r.solid_angle(b);
    CHECK(sum == Approx(4 * M_PI).epsilon(1e-14));
    CHECK(r.bin_of(Vec3(0, 0, 1)) == 0);                // θ = 0: the first row
    CHECK(r.bin_of(Vec3(0, 0, -1)) / 12 == 6);          // θ = 180°: the last row
    CHECK(r.bin_of(Vec3(0, 1, 0.01)) % 12 == 3);        // φ = 90° from the reference x
    r.settings.binning = FarFieldSettings::Binning::Axis;
    r.bins = 180;
    sum = 0;
    for (int b = 0; b < r.bins; ++b) sum += r.solid_angle(b);
    CHECK(sum == Approx(4 * M_PI).epsilon(1e-14));
    CHECK(r.bin_of(Vec3(std::sin(0.7), 0, std::cos(0.7))) == static_cast<int>(0.7 * 180 / M_PI));
}

TEST_CASE("Far field: an angle bin is the one whose edges bracket the polar angle, at the poles and on the edges",
          "[far-field]") {
    // θ-bin k holds cos θ in (cos θ_{k+1}, cos θ_k], θ_k = 180° k / n: the count of edges
    // −cos θ_k (k = 1 … n − 1) at or below −cos θ, as std::upper_bound finds it.
    for (const int n : {1, 2, 7, 180, 1000, 5000}) {
        FarFieldResult r;
        r.settings.binning = FarFieldSettings::Binning::Axis;
        r.settings.axis = Vec3(0, 0, 1);
        r.settings.angle_bins = n;
        r.bins = n;
        std::vector<double> edges;
        for (int k = 1; k < n; ++k) edges.push_back(-std::cos(M_PI * k / n));
        const auto expected = [&](const Vec3& d) {
            const double c = std::clamp(d.normalized().dot(Vec3(0, 0, 1)), -1.0, 1.0);
            return static_cast<int>(std::upper_bound(edges.begin(), edges.end(), -c) - edges.begin());
        };
        std::vector<Vec3> dirs{Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(1e-9, 0, 1), Vec3(1e-9, 0, -1)};
        for (int k = 0; k <= n; ++k) {  // on each edge, and a hair either side
            const double t = M_PI * k / n;
            for (const double e : {-1e-13, 0.0, 1e-13}) dirs.emplace_back(std::sin(t + e), 0, std::cos(t + e));
        }
        for (int i = 0; i < 20000; ++i) {
            const double z = -1 + 2 * (i + 0.5) / 20000, phi = i * 2.399963;
            dirs.emplace_back(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
        }
        const std::vector<int> got = r.bins_of(dirs);
        int wrong = 0;
        for (size_t i = 0; i < dirs.size(); ++i) wrong += got[i] != expected(dirs[i]);
        INFO("bins " << n);
        CHECK(wrong == 0);
        CHECK(r.bin_of(Vec3(0, 0, 1)) == 0);
        CHECK(r.bin_of(Vec3(0, 0, -1)) == n - 1);
    }
}

TEST_CASE("Sun of angular diameter alpha: the light through an index-1 sphere spreads over its cone", "[far-field]") {
    json j = drop_scene(1.0);
    j["lights"] = {{{"type", "directional"}, {"direction", {0, 0, 1}}, {"angular_diameter_deg", 10}}};
    const Scene s = parse_scene(j, "sun.json");
    FarFieldSettings set;  // sphere binning about the sun's direction
    set.axis = Vec3(0, 0, 1);
    set.azimuth_bins = 4;
    set.polar_bins = 4000;  // rows of 1/2000 in cos θ
    set.photons = 200000;
    const FarFieldResult r = far_field(s, set, 2);
    // Radiance is uniform over the sun's disk and the sphere shows every direction the
    // same cross-section: the power through it is uniform in solid angle over the cone of
    // half-angle 5°. The rows inside 2.5° end at cos θ = 1 − rows/2000.
    double inner = 0, all = 0;
    int rows = 0;
    for (int b = 0; b < r.bins; ++b) {
        const double p = r.at(0, 1, 0, b);
        all += p;
        if (r.theta_deg(b) < 2.5) {
            inner += p;
            if (b % 4 == 0) ++rows;
        }
    }
    CHECK(all > 0.5);
    const double expected = (rows / 2000.0) / (1.0 - std::cos(5 * M_PI / 180));
    CHECK(inner / all == Approx(expected).margin(0.005));
    for (int b = 0; b < r.bins; ++b)
        if (r.theta_deg(b) > 5.2) CHECK(r.at(0, 1, 0, b) == 0);
}

TEST_CASE("Collimated beam: a point is lit only inside the beam's cylinder, ahead of its start", "[light]") {
    Light beam;
    beam.kind = Light::Kind::Beam;
    beam.position = Vec3(0, 0, 0);
    beam.direction = Vec3(0, 0, 1);
    beam.radius = 0.5;
    REQUIRE(beam.toward(Vec3(0.3, 0.3, 2)).has_value());
    CHECK(beam.toward(Vec3(0.3, 0.3, 2))->end.z() == Approx(0).margin(1e-15));
    CHECK(beam.toward(Vec3(0.3, 0.3, 2))->dir.z() == -1);
    CHECK_FALSE(beam.toward(Vec3(0.4, 0.4, 2)).has_value());   // outside the radius
    CHECK_FALSE(beam.toward(Vec3(0.0, 0.0, -1)).has_value());  // behind the start
}

TEST_CASE("Far field and beams: bad settings are refused, naming the setting", "[far-field]") {
    const Scene s = parse_scene(drop_scene(1.5), "drop.json");
    FarFieldSettings set = axis_bins(0, 10);
    CHECK_THROWS_WITH(far_field(s, set), Catch::Contains("angle bins"));
    set = axis_bins(10, 10);
    set.axis = Vec3(0, 0, 0);
    CHECK_THROWS_WITH(far_field(s, set), Catch::Contains("axis"));
    set = axis_bins(10, 10);
    set.wavelengths = {300};
    CHECK_THROWS_WITH(far_field(s, set), Catch::Contains("wavelength"));
    json j = drop_scene(1.5);
    j["lights"][0]["radius"] = -1;
    CHECK_THROWS_WITH(parse_scene(j, "beam.json"), Catch::Contains("/lights/0/radius"));
    j = drop_scene(1.5);
    j["lights"] = {{{"type", "directional"}, {"direction", {0, 0, 1}}, {"angular_diameter_deg", 95}}};
    CHECK_THROWS_WITH(parse_scene(j, "sun.json"), Catch::Contains("/lights/0/angular_diameter_deg"));
    j = drop_scene(1.5);
    j["lights"].push_back({{"type", "point"}, {"position", {0, 5, 0}}, {"spectrum", "D65"}});
    j["lights"][0]["spectrum"] = {{"blackbody", 5778}};
    CHECK_THROWS_WITH(parse_scene(j, "two.json"), Catch::Contains("/lights/1/spectrum"));
}

TEST_CASE("A light's spectrum becomes the scene's light spectrum", "[light]") {
    json j = drop_scene(1.5);
    j["lights"][0]["spectrum"] = {{"blackbody", 5778}};
    const Scene s = parse_scene(j, "sun.json");
    CHECK(s.settings.spectral.light.kind == spectrum::Illuminant::Blackbody);
    CHECK(s.settings.spectral.light.temperature_K == 5778);
}

TEST_CASE("Environment light as an emitter: a constant sky seen through an index-1 sphere is the same from every "
          "direction", "[far-field]") {
    json j = drop_scene(1.0);
    j["lights"] = json::array();
    j["background"] = {{"type", "environment"}, {"color", {1, 1, 1}}, {"scale", 2}};
    const Scene s = parse_scene(j, "sky.json");
    FarFieldSettings set;
    set.azimuth_bins = 8;
    set.polar_bins = 4;
    set.photons = 100000;
    const FarFieldResult r = far_field(s, set, 2);
    // Photons cross the disk of radius R' = 1.01 R + 1e-6 across their direction: the
    // sphere takes (R/R')² of them; the power emitted is L · πR'² · 4π.
    const double Rp = 1.01 + 1e-6, hit = 1.0 / (Rp * Rp);
    CHECK(r.emitted_power == Approx(2.0 * M_PI * Rp * Rp * 4.0 * M_PI).epsilon(1e-12));
    CHECK(class_total(r, 1) == Approx(hit).margin(2e-3));  // binomial: σ ≈ 4.4e-4
    CHECK(class_total(r, 1) + r.unscattered[0] == Approx(1.0).margin(1e-12));
    for (int b = 0; b < r.bins; ++b) CHECK(r.at(0, 1, 0, b) == Approx(hit / 32).epsilon(0.06));  // σ ≈ 2 %
}

TEST_CASE("No NaN from finite input: a sphere at 1e200 is no hit, and a light colour out of range is refused",
          "[far-field][limits]") {
    json j = drop_scene(1.5);
    j["objects"][0]["center"] = {0, 0, 1e200};
    const Scene far = parse_scene(j, "far.json");
    const FarFieldResult r = far_field(far, axis_bins(10, 1000), 1);
    CHECK(r.unscattered[0] == Approx(1.0).margin(1e-12));  // the beam meets nothing
    for (double v : r.power) CHECK(v == 0);
    for (const double bad : {-1.0, 1e308}) {
        json k = drop_scene(1.5);
        k["lights"][0]["color"] = {1, bad, 1};
        CHECK_THROWS_WITH(parse_scene(k, "colour.json"), Catch::Contains("/lights/0/color"));
    }
    const Scene s = parse_scene(drop_scene(1.5), "drop.json");
    CHECK_THROWS_WITH(far_field(s, axis_bins(10, 10), 70000), Catch::Contains("--threads"));
}

TEST_CASE("Beams, environments and far-away lights: values that would overflow the photons' power are refused",
          "[far-field][limits]") {
    json j = drop_scene(1.5);
    j["lights"][0]["radius"] = 1e300;
    CHECK_THROWS_WITH(parse_scene(j, "beam.json"), Catch::Contains("/lights/0/radius"));
    j = drop_scene(1.5);
    j["background"] = {{"type", "environment"}, {"color", {1, 1, 1}}, {"scale", 1e300}};
    CHECK_THROWS_WITH(parse_scene(j, "env.json"), Catch::Contains("/background/scale"));
    // A point light 1e200 away: its photons' power (∝ distance²) overflows.
    j = drop_scene(1.5);
    j["lights"] = {{{"type", "point"}, {"position", {0, 0, -1e200}}}};
    const Scene far = parse_scene(j, "far.json");
    CHECK_THROWS_WITH(far_field(far, axis_bins(10, 100), 1), Catch::Contains("far.json: /lights/0") &&
                                                                 Catch::Contains("overflows"));
}

namespace {

// A far field walked with the wavelengths of each photon in packets and one by one.
struct LanePair {
    FarFieldResult lanes, alone;
};
LanePair lanes_and_alone(const json& scene, FarFieldSettings s) {
    const Scene sc = parse_scene(scene, "lanes.json");
    s.trace.packets = true;
    LanePair p{far_field(sc, s, 2), {}};
    s.trace.packets = false;
    p.alone = far_field(sc, s, 2);
    return p;
}

// Scattered power, unscattered and absorbed light and segments equal to the last bit; the
// dropped light summed in the same order (`dropped_exact`) or to rounding.
void check_same(const LanePair& p, bool dropped_exact) {
    REQUIRE(p.lanes.power.size() == p.alone.power.size());
    long differing = 0;
    for (size_t k = 0; k < p.lanes.power.size(); ++k) differing += p.lanes.power[k] != p.alone.power[k];
    CHECK(differing == 0);
    CHECK(p.lanes.unscattered == p.alone.unscattered);
    CHECK(p.lanes.absorbed == p.alone.absorbed);
    CHECK(p.lanes.segments == p.alone.segments);
    for (size_t w = 0; w < p.lanes.dropped.size(); ++w) {
        if (dropped_exact)
            CHECK(p.lanes.dropped[w] == p.alone.dropped[w]);
        else
            CHECK(p.lanes.dropped[w] == Approx(p.alone.dropped[w]).margin(1e-14));
    }
}

json dispersive_drop() {
    json j = drop_scene(1.333);
    j["materials"]["glass"]["dispersion"] = "water";
    return j;
}

}  // namespace

// Bit-identity holds for any count: the sanitizer build (ten times slower) walks fewer.
#ifdef REFRACT_SANITIZED
constexpr std::uint64_t kPacketPhotons = 1000, kSmallPhotons = 500;
#else
constexpr std::uint64_t kPacketPhotons = 20000, kSmallPhotons = 5000;
#endif

TEST_CASE("Far field: the wavelengths of a photon walked in packets give the one-by-one result to the last bit",
          "[far-field]") {
    SECTION("a dispersive drop, 31 wavelengths") {
        check_same(lanes_and_alone(dispersive_drop(), axis_bins(180, kPacketPhotons)), true);
    }
    SECTION("a drop with a bubble and a second drop (several spheres)") {
        json j = dispersive_drop();
        j["objects"].push_back({{"type", "sphere"}, {"center", {0.2, 0.1, 0}}, {"radius", -0.3}, {"material", "glass"}});
        j["objects"].push_back({{"type", "sphere"}, {"center", {0.5, 0.2, 3}}, {"radius", 0.7}, {"material", "glass"}});
        FarFieldSettings s = axis_bins(90, kPacketPhotons / 2);
        s.binning = FarFieldSettings::Binning::Sphere;
        s.azimuth_bins = 24;
        s.polar_bins = 12;
        check_same(lanes_and_alone(j, s), true);
    }
    SECTION("a prism (plane set) and a Schlick drop: nodes lane by lane") {
        json j = dispersive_drop();
        // A slab behind the drop, 1.5 < z < 2.5, bounded sideways: a plane set.
        j["objects"].push_back({{"type", "polyhedron"},
                                {"material", "glass"},
                                {"planes", {{0, 0, 1, 2.5}, {0, 0, -1, -1.5}, {1, 0, 0, 1.5}, {-1, 0, 0, 1.5},
                                            {0, 1, 0, 1.5}, {0, -1, 0, 1.5}}}});
        check_same(lanes_and_alone(j, axis_bins(90, kSmallPhotons)), false);
        json k = dispersive_drop();
        k["materials"]["glass"]["reflectance"] = "schlick";
        check_same(lanes_and_alone(k, axis_bins(90, kSmallPhotons)), false);
    }
}
