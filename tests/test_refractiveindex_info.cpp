// refractiveindex.info entries as dispersion models (core/spectrum/refractiveindex_info.h):
// the kept entries (tests/data/refractiveindex/SOURCES.md) against their published values,
// each formula as the database defines it, k as absorption, and bad files refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/optics.h>
#include <refract/core/scene.h>
#include <refract/core/scene_json.h>
#include <refract/core/spectrum/refractiveindex_info.h>
#include <refract/geometry/error.h>

#include "input_error.h"

#include "tests/temp_dir.h"

using namespace refract;
using namespace refract::spectrum;
using Catch::Matchers::Contains;

namespace {

const std::string kData = std::string(REFRACT_SOURCE_DIR) + "/tests/data/refractiveindex/";

CataloguedConstants entry(const std::string& name) { return read_refractiveindex_info(kData + name); }

// A one-block entry written to a fresh file.
std::string write_entry(const std::string& name, const std::string& yaml) {
    static const std::filesystem::path dir = refract::test::fresh_dir("rii", "entries");
    const std::filesystem::path p = dir / name;
    std::ofstream{p} << yaml;
    return p.string();
}

double n_of(const std::string& yaml, double nm) {
    return read_refractiveindex_info(write_entry("f.yml", yaml)).dispersion.n(nm);
}

using refract::test::error_of;

}  // namespace

// ---------------------------------------------------------------------------------------
// The kept entries against their published values.

TEST_CASE("N-BK7 entry (formula 2): n_d = 1.5168 at 587.56 nm, the SCHOTT data sheet's value, and the "
          "catalogue's N-BK7 exactly",
          "[spectrum][refractiveindex]") {
    const auto e = entry("N-BK7.yml");
    CHECK(e.dispersion.n(fraunhofer::d) == Approx(1.5168).margin(5e-5));
    CHECK(e.dispersion.abbe_number() == Approx(64.17).margin(0.02));
    for (double nm : {360.0, 486.1327, 587.5618, 656.2725, 830.0}) CHECK(e.dispersion.n(nm) == catalogue("n-bk7").n(nm));
    CHECK(e.dispersion.label == "N-BK7.yml (refractiveindex.info formula 2)");
}

TEST_CASE("Malitson fused silica entry (formula 1): n = 1.4585 at 589.3 nm, the catalogue's fused silica exactly",
          "[spectrum][refractiveindex]") {
    const auto e = entry("SiO2-Malitson.yml");
    CHECK(e.dispersion.n(589.3) == Approx(1.4585).margin(1e-4));
    for (double nm : {360.0, 589.3, 830.0}) CHECK(e.dispersion.n(nm) == catalogue("fused-silica").n(nm));
    CHECK_FALSE(e.absorption);
}

TEST_CASE("Daimon water 20 C entry (formula 2, four terms): n = 1.3333 at 589.3 nm, within 4e-4 of the handbook's "
          "1.3330, and the catalogue's water exactly",
          "[spectrum][refractiveindex]") {
    const auto e = entry("H2O-Daimon-20.0C.yml");
    CHECK(e.dispersion.n(589.3) == Approx(1.33335).margin(1e-5));
    CHECK(e.dispersion.n(589.3) == Approx(1.3330).margin(4e-4));
    CHECK(e.dispersion.n(589.3) == catalogue("water").n(589.3));
}

TEST_CASE("LBO n_alpha entry (formula 4): n = 1.5656 at 1064 nm, and n^2 = 2.45768 + 0.0098877/(l^2 - 0.026095) - "
          "0.013847 l^2 at 532 nm",
          "[spectrum][refractiveindex]") {
    const auto e = entry("LiB3O5-Chen-alpha.yml");
    CHECK(e.dispersion.n(1064) == Approx(1.5656).margin(1e-4));
    const double l2 = 0.532 * 0.532;
    CHECK(e.dispersion.n(532) == Approx(std::sqrt(2.45768 + 0.0098877 / (l2 - 0.026095) - 0.013847 * l2)).epsilon(1e-14));
}

TEST_CASE("Ciddor standard air entry (formula 6): n - 1 = 2.77e-4 at 589.3 nm", "[spectrum][refractiveindex]") {
    const auto e = entry("air-Ciddor.yml");
    const double s = 1.0 / (0.5893 * 0.5893);
    CHECK(e.dispersion.n(589.3) - 1 == Approx(0.05792105 / (238.0185 - s) + 0.00167917 / (57.362 - s)).epsilon(1e-10));
    CHECK(e.dispersion.n(589.3) - 1 == Approx(2.77e-4).margin(1e-6));
}

TEST_CASE("Johnson & Christy gold entry (tabulated nk): n and k as tabulated at 548.6 nm, linear between samples, "
          "alpha = 4 pi k / lambda",
          "[spectrum][refractiveindex]") {
    const auto e = entry("Au-Johnson.yml");
    CHECK(e.dispersion.n(548.6) == Approx(0.43).epsilon(1e-12));
    CHECK(e.dispersion.n(0.5 * (548.6 + 582.1)) == Approx(0.5 * (0.43 + 0.29)).epsilon(1e-12));
    REQUIRE(e.absorption);
    // k = 2.455 at 548.6 nm = 5.486e-5 cm: α = 4π·2.455/5.486e-5 = 5.6235e5 per cm.
    CHECK(e.absorption->at(548.6) == Approx(4 * M_PI * 2.455 / 5.486e-5).epsilon(1e-12));
    CHECK(e.absorption->at(548.6) == Approx(5.6235e5).epsilon(1e-4));
    CHECK(optics::extinction_absorption(1.0, 1.0) == Approx(4 * M_PI));
}

TEST_CASE("N-BK7's tabulated k becomes its absorption: about 2.4e-3 per cm at 500 nm, per mm with unit_cm 0.1",
          "[spectrum][refractiveindex]") {
    const auto e = entry("N-BK7.yml");
    REQUIRE(e.absorption);
    CHECK(e.absorption->at(500) == Approx(4 * M_PI * 9.5781e-9 / 5e-5).epsilon(1e-12));
    const auto mm = read_refractiveindex_info(kData + "N-BK7.yml", 0.1);
    CHECK(mm.absorption->at(500) == Approx(0.1 * e.absorption->at(500)).epsilon(1e-12));
}

// ---------------------------------------------------------------------------------------
// The formulas as the database defines them.

TEST_CASE("formula 5 is Cauchy's law n = C1 + C2 l^C3 + C4 l^C5", "[spectrum][refractiveindex]") {
    const std::string y = "DATA:\n  - type: formula 5\n    wavelength_range: 0.3 1.0\n    coefficients: 1.5046 0.0042 -2 0.0001 -4\n";
    for (double nm : {400.0, 550.0, 800.0})
        CHECK(n_of(y, nm) == Approx(cauchy_index(nm * 1e-3, 1.5046, 0.0042, 0.0001)).epsilon(1e-14));
}

TEST_CASE("formula 3 (polynomial n^2), 7 (Herzberger), 8 (Lorentz-Lorenz) and 9 (exotic) at 500 nm",
          "[spectrum][refractiveindex]") {
    const double l = 0.5, l2 = l * l;
    const auto y = [](const char* f, const char* c) {
        return std::string("DATA:\n  - type: formula ") + f + "\n    wavelength_range: 0.2 2\n    coefficients: " + c + "\n";
    };
    CHECK(n_of(y("3", "2.27 -0.01 2 0.012 -2"), 500) == Approx(std::sqrt(2.27 - 0.01 * l2 + 0.012 / l2)).epsilon(1e-14));
    const double L = 1 / (l2 - 0.028);
    CHECK(n_of(y("7", "1.38 0.0016 -0.00002 -0.0025 0.0001 -0.00001"), 500) ==
          Approx(1.38 + 0.0016 * L - 0.00002 * L * L - 0.0025 * l2 + 0.0001 * l2 * l2 - 0.00001 * l2 * l2 * l2).epsilon(1e-14));
    const double R = 0.3 + 0.01 * l2 / (l2 - 0.01) + 0.002 * l2;  // (n² − 1)/(n² + 2)
    CHECK(n_of(y("8", "0.3 0.01 0.01 0.002"), 500) == Approx(std::sqrt((1 + 2 * R) / (1 - R))).epsilon(1e-14));
    const double x = l - 0.3;
    CHECK(n_of(y("9", "2.0 0.02 0.01 0.001 0.3 0.01"), 500) ==
          Approx(std::sqrt(2.0 + 0.02 / (l2 - 0.01) + 0.001 * x / (x * x + 0.01))).epsilon(1e-14));
}

TEST_CASE("range check: a formula 4 term that turns inside 360-830 nm (n^2 = 0.8 - l/(l^2 + 0.36), least at "
          "600 nm) is refused at its turn, though both ends are > 0",
          "[spectrum][refractiveindex][errors]") {
    const std::string f = write_entry("turn.yml", "DATA:\n  - type: formula 4\n    wavelength_range: 0.3 1\n"
                                                  "    coefficients: 0.8 -1 1 -0.36 1\n");
    const std::string e = error_of([&] { read_refractiveindex_info(f); });
    CHECK_THAT(e, Contains("turn.yml: /DATA/0: the model gives n² = -0.03333333333 at 600 nm"));
}

TEST_CASE("range check: a pole inside 360-830 nm names the coefficient", "[spectrum][refractiveindex][errors]") {
    const std::string f = write_entry("pole.yml", "DATA:\n  - type: formula 1\n    wavelength_range: 0.3 1\n"
                                                  "    coefficients: 0 1.0 0.5\n");
    CHECK_THAT(error_of([&] { read_refractiveindex_info(f); }),
               Contains("pole.yml: /DATA/0/coefficients: C3 has its pole at 500 nm, inside 360–830 nm"));
}

// ---------------------------------------------------------------------------------------
// Bad files: one line naming the file and the item.

TEST_CASE("bad refractiveindex.info files name the file and the item", "[spectrum][refractiveindex][errors]") {
    const auto refused = [](const std::string& name, const std::string& yaml) {
        const std::string f = write_entry(name, yaml);
        const std::string e = error_of([&] { read_refractiveindex_info(f); });
        CHECK(e.find('\n') == std::string::npos);
        CHECK(e.rfind(f + ": ", 0) == 0);
        return e;
    };
    CHECK_THAT(refused("unknown.yml", "DATA:\n  - type: formula 12\n    wavelength_range: 0.3 1\n    coefficients: 1\n"),
               Contains("unknown.yml: /DATA/0/type: unknown formula \"12\" (formula 1–9)"));
    CHECK_THAT(refused("type.yml", "DATA:\n  - type: tabulated x\n    data: 0.3 1\n"),
               Contains("/DATA/0/type: unknown type \"tabulated x\""));
    CHECK_THAT(refused("few.yml", "DATA:\n  - type: formula 2\n    wavelength_range: 0.3 2.5\n"
                                  "    coefficients: 0 1.03961212 0.00600069867 0.231792344\n"),
               Contains("few.yml: /DATA/0/coefficients: 4 coefficients; formula 2 takes C1 and pairs"));
    CHECK_THAT(refused("none.yml", "DATA:\n  - type: formula 2\n    wavelength_range: 0.3 2.5\n"),
               Contains("none.yml: /DATA/0: missing \"coefficients\""));
    CHECK_THAT(refused("nan.yml", "DATA:\n  - type: formula 1\n    wavelength_range: 0.3 2.5\n    coefficients: 0 nan 0.07\n"),
               Contains("nan.yml: /DATA/0/coefficients: \"nan\" is not a finite number"));
    CHECK_THAT(refused("huge.yml", "DATA:\n  - type: formula 1\n    wavelength_range: 0.3 2.5\n    coefficients: 0 1e400 0.07\n"),
               Contains("/DATA/0/coefficients: \"1e400\" is not a finite number"));
    CHECK_THAT(refused("malformed.yml", "DATA:\n  - type: [formula 1\n    coefficients: 0\n"), Contains("malformed.yml: malformed YAML at line"));
    CHECK_THAT(refused("nodata.yml", "REFERENCES: none\n"), Contains("nodata.yml: /DATA: missing"));
    CHECK_THAT(refused("columns.yml", "DATA:\n  - type: tabulated nk\n    data: |\n        0.3 1.5 0\n        0.9 1.4\n"),
               Contains("/DATA/0/data: line 2: 2 numbers; \"tabulated nk\" takes 3"));
    CHECK_THAT(refused("order.yml", "DATA:\n  - type: tabulated n\n    data: |\n        0.9 1.5\n        0.3 1.4\n"),
               Contains("/DATA/0/data: line 2: wavelengths must be > 0 and increase"));
    CHECK_THAT(refused("k.yml", "DATA:\n  - type: tabulated k\n    data: |\n        0.3 0\n        0.9 0\n"),
               Contains("k.yml: /DATA: no index"));
    CHECK_THAT(refused("two.yml", "DATA:\n  - type: formula 5\n    wavelength_range: 0.3 1\n    coefficients: 1.5\n"
                                  "  - type: tabulated n\n    data: |\n        0.3 1.5\n        0.9 1.4\n"),
               Contains("two.yml: /DATA/1: a second index (the first is /DATA/0)"));
}

TEST_CASE("an entry whose range falls short of 360-830 nm is refused naming its range (Devore rutile, 0.43-1.53 um)",
          "[spectrum][refractiveindex][errors]") {
    CHECK_THAT(error_of([] { entry("TiO2-Devore-o.yml"); }),
               Contains("TiO2-Devore-o.yml: /DATA/0/wavelength_range: the range 0.43–1.53 µm (430–1530 nm) does not "
                        "cover the rendered 360–830 nm"));
    CHECK_THAT(error_of([] {
                   read_refractiveindex_info(write_entry("short.yml", "DATA:\n  - type: tabulated nk\n    data: |\n"
                                                                      "        0.3 1.5 0\n        0.8 1.4 0\n"));
               }),
               Contains("short.yml: /DATA/0/data: the range 0.3–0.8 µm"));
}

// ---------------------------------------------------------------------------------------
// In a scene.

TEST_CASE("scene dielectric with \"dispersion\": {\"file\": ...}: the file relative to the scene, its k as absorption",
          "[spectrum][refractiveindex][scene]") {
    const auto scene = [](const std::string& material) {
        return nlohmann::json::parse(R"({"camera": {"width": 4, "height": 3},
            "materials": {"glass": )" + material + R"(},
            "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"}]})");
    };
    const std::string path = kData + "scene.json";  // the directory the file is relative to
    const Scene s = parse_scene(scene(R"({"type": "dielectric", "dispersion": {"file": "N-BK7.yml"}})"), path);
    const material::Dielectric* d = s.materials.at(0).dielectric();
    REQUIRE(d);
    CHECK(d->ior == Approx(1.5168).margin(5e-5));
    REQUIRE(d->absorption);
    CHECK(d->absorption->at(500) == Approx(4 * M_PI * 9.5781e-9 / 5e-5).epsilon(1e-12));
    CHECK_THROWS_WITH(parse_scene(scene(R"({"type": "dielectric", "dispersion": {"file": "N-BK7.yml"}, "absorption": "ruby"})"), path),
                      Contains("scene.json: /materials/glass/absorption: the dispersion file gives k (N-BK7.yml (k)); give one"));
    CHECK_THROWS_WITH(parse_scene(scene(R"({"type": "dielectric", "dispersion": {"file": "missing.yml"}})"), path),
                      Contains("scene.json: /materials/glass/dispersion/file: ") && Contains("missing.yml"));
    CHECK_THROWS_WITH(parse_scene(scene(R"({"type": "dielectric", "dispersion": {"file": "N-BK7.yml", "unit": 1}})"), path),
                      Contains("/materials/glass/dispersion/unit: unknown key for a dispersion file; allowed: file, unit_cm"));
}
