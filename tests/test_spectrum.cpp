// Spectra, colour and dispersion: published values (core/spectrum/*).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/spectrum/cie.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/error.h>

#include "input_error.h"

using namespace refract;
using namespace refract::spectrum;
using Catch::Matchers::Contains;

namespace {
using refract::test::error_of;
}  // namespace

// ---------------------------------------------------------------------------------------
// Dispersion: published indices.

TEST_CASE("Peter 1923 diamond Sellmeier: n_D = 2.4173, B-G dispersion 0.044", "[spectrum]") {
    const Dispersion& d = catalogue("diamond");
    CHECK(d.n(589.29) == Approx(2.4173).margin(1e-4));
    CHECK(d.n(430.8) - d.n(686.7) == Approx(0.044).margin(1e-3));
}

TEST_CASE("SCHOTT N-BK7 Sellmeier: n_d, n_F, n_C and Abbe number V_d", "[spectrum]") {
    const Dispersion& g = catalogue("N-BK7");
    // SCHOTT data sheet: n_d = 1.51680, n_F = 1.52238, n_C = 1.51432, V_d = 64.17.
    CHECK(g.n(587.56) == Approx(1.5168).margin(1e-4));
    CHECK(g.n(fraunhofer::F) == Approx(1.52238).margin(2e-5));
    CHECK(g.n(fraunhofer::C) == Approx(1.51432).margin(2e-5));
    CHECK(g.abbe_number() == Approx(64.17).margin(0.05));
}

TEST_CASE("Malitson 1965 fused silica: n(587.6 nm) = 1.4585", "[spectrum]") {
    CHECK(catalogue("fused silica").n(587.6) == Approx(1.4585).margin(1e-4));
}

TEST_CASE("Daimon & Masumura 2007 water at 20 C: n(589.3 nm) close to 1.3330", "[spectrum]") {
    // Handbook value at 20 °C: 1.33299 (IAPWS 1997). The Daimon & Masumura 20 °C Sellmeier
    // fit evaluates to 1.33335 there: 3.5e-4 higher, hence the margin.
    CHECK(catalogue("water").n(589.3) == Approx(1.3330).margin(4e-4));
}

TEST_CASE("Wood & Nassau cubic zirconia and Wang 2013 moissanite o-ray at the D line",
          "[spectrum]") {
    // Gem tables give CZ n_D = 2.15–2.18 (often "2.17"); Wood & Nassau's fit (12 mol% Y₂O₃)
    // evaluates to 2.1585.
    CHECK(catalogue("cubic-zirconia").n(fraunhofer::D) == Approx(2.165).margin(0.015));
    CHECK(catalogue("moissanite").n(fraunhofer::D) == Approx(2.65).margin(0.01));
    // Normal dispersion: every catalogue material is denser for blue than for red.
    for (const auto& name : catalogue_names())
        CHECK(catalogue(name).n(450.0) > catalogue(name).n(650.0));
}

TEST_CASE("Cauchy's equation with the textbook BK7 coefficients gives n_d", "[spectrum]") {
    // A = 1.5046, B = 0.00420 µm² (BK7, the usual textbook pair).
    CHECK(cauchy_index(0.5875618, 1.5046, 0.00420, 0.0) == Approx(1.5168).margin(2e-4));
    CHECK(cauchy_index(0.5, 1.5, 0.0, 0.0) == 1.5);
}

TEST_CASE("Abbe-number model reproduces n_d and V_d of N-BK7", "[spectrum]") {
    const Dispersion d = parse_dispersion(nlohmann::json::parse(
                                              R"({"model":"abbe","nd":1.5168,"Vd":64.17})"),
                                          "m");
    CHECK(d.n(fraunhofer::d) == Approx(1.5168).margin(1e-12));
    CHECK(d.abbe_number() == Approx(64.17).epsilon(1e-12));
    // Close to the Sellmeier glass across the visible (two-term Cauchy).
    const Dispersion& g = catalogue("bk7");
    for (double l = 420; l <= 700; l += 20) CHECK(d.n(l) == Approx(g.n(l)).margin(5e-4));
}

TEST_CASE("POV-Ray dispersion law: n(555) = ior and n(380)/n(730) = D", "[spectrum]") {
    CHECK(povray_index(2.417, 1.05, 555.0) == Approx(2.417).epsilon(1e-15));
    CHECK(povray_index(2.417, 1.05, 380.0) / povray_index(2.417, 1.05, 730.0) ==
          Approx(1.05).epsilon(1e-14));
    const auto bands = povray_bands(7);
    REQUIRE(bands.size() == 7);
    for (int i = 0; i < 7; ++i) {
        CHECK(bands[i].wavelength_nm == Approx(380.0 + 350.0 * (i + 0.5) / 7).margin(1e-4));
        CHECK(bands[i].bandwidth_nm == Approx(50.0).margin(1e-5));
    }
    CHECK_THAT(error_of([] { povray_bands(1); }), Contains("minimum is 2"));
}

TEST_CASE("POV-Ray band colours average to (0.9938, 1.0, 0.9962)", "[spectrum]") {
    for (int n : {2, 7, 31, 100}) {
        Vec3 mean = Vec3::Zero();
        for (const auto& b : povray_bands(n)) mean += b.hue / n;
        INFO("dispersion_samples " << n);
        CHECK(mean.x() == Approx(0.9938).margin(1e-5));
        CHECK(mean.y() == Approx(1.0).margin(1e-5));
        CHECK(mean.z() == Approx(0.9962).margin(1e-5));
    }
    // Short wavelengths are blue, long ones red.
    const auto b = povray_bands(7);
    CHECK(b.front().hue.z() > b.front().hue.x());
    CHECK(b.back().hue.x() > b.back().hue.z());
}

// ---------------------------------------------------------------------------------------
// Scene-file parsing.

TEST_CASE("Dispersion from scene-file values, errors naming the JSON path", "[spectrum]") {
    using nlohmann::json;
    CHECK(parse_dispersion(json("Diamond"), "m").n(589.29) == Approx(2.4173).margin(1e-4));
    CHECK(parse_dispersion_text("water", "m").n(589.3) == catalogue("water").n(589.3));
    CHECK(parse_dispersion_text("1.333", "m").n(400.0) == 1.333);
    const Dispersion s = parse_dispersion_text(
        R"({"model":"sellmeier","B":[1.03961212,0.231792344,1.01046945],)"
        R"("C":[0.00600069867,0.0200179144,103.560653]})",
        "m");
    CHECK(s.n(587.56) == Approx(1.5168).margin(1e-4));
    const Dispersion p =
        parse_dispersion(json::parse(R"({"model":"povray","ior":2.417,"dispersion":1.05})"), "m");
    CHECK(p.is_povray());
    CHECK(p.nominal() == 2.417);
    CHECK(p.dispersive());
    CHECK_FALSE(parse_dispersion(json(1.5), "m").dispersive());

    const std::string path = "scene.json: /materials/gem/dispersion";
    CHECK_THAT(error_of([&] { parse_dispersion(json("glass"), path); }),
               Contains(path) && Contains("diamond") && Contains("moissanite"));
    CHECK_THAT(error_of([&] { catalogue("opal"); }), Contains("n-bk7, fused-silica, water"));
    CHECK_THAT(error_of([&] {
                   parse_dispersion(json::parse(R"({"model":"sellmeier","B":[1],"C":"x"})"), path);
               }),
               Contains(path + "/C"));
    CHECK_THAT(error_of([&] {
                   parse_dispersion(json::parse(R"({"model":"abbe","nd":1.5,"vd":60})"), path);
               }),
               Contains(path + "/vd"));
    // A resonance inside the visible makes n² negative somewhere: rejected.
    CHECK_THAT(error_of([&] {
                   parse_dispersion(json::parse(R"({"model":"sellmeier","B":[1],"C":[0.25]})"),
                                    path);
               }),
               Contains("360–830 nm"));
    CHECK_THAT(error_of([&] { parse_dispersion_text("{oops", path); }), Contains("not valid JSON"));
}

// ---------------------------------------------------------------------------------------
// Wavelengths and light sources.

TEST_CASE("Wavelength sampling: 400-700 nm every 10 nm is 31 samples", "[spectrum]") {
    const auto w = sample_wavelengths();
    REQUIRE(w.size() == 31);
    CHECK(w.front() == 400.0);
    CHECK(w[15] == 550.0);
    CHECK(w.back() == 700.0);
    CHECK(sample_wavelengths({400, 700, 1}).size() == 301);
    CHECK(sample_wavelengths({400, 700, 50}).size() == 7);
    for (double d : band_widths(w)) CHECK(d == Approx(10.0).epsilon(1e-12));
    CHECK_THAT(error_of([] { sample_wavelengths({400, 700, 7}); }), Contains("wavelengths/step"));
    CHECK_THAT(error_of([] { sample_wavelengths({400, 700, 0}); }), Contains("wavelengths/step"));
    CHECK_THAT(error_of([] { sample_wavelengths({300, 700, 10}); }), Contains("wavelengths/min"));
    CHECK_THAT(error_of([] { sample_wavelengths({500, 450, 10}); }), Contains("wavelengths/max"));
}

TEST_CASE("CIE D65 table and Planck's law (Wien, Stefan-Boltzmann)", "[spectrum]") {
    CHECK(cie_d65(560.0) == 1.0);
    CHECK(cie_d65(460.0) == Approx(1.17812).epsilon(1e-9));
    CHECK(cie_d65(462.5) == Approx(0.5 * (1.17812 + 1.16336)).epsilon(1e-12));
    // Wien's displacement law: λ_max = 2.897771955e6 nm·K / T.
    const double T = 5000.0;
    double best = 0, best_l = 0;
    for (double l = 500.0; l <= 650.0; l += 0.01)
        if (planck_radiance(l, T) > best) best = planck_radiance(l, T), best_l = l;
    CHECK(best_l == Approx(2.897771955e6 / T).margin(0.02));
    // Stefan–Boltzmann: π ∫ B_λ dλ = σ T⁴ (trapezoid on a log grid, 10 nm – 1 mm).
    double integral = 0.0;
    const int n = 20000;
    const double a = std::log(10.0), b = std::log(1e6);
    for (int i = 0; i < n; ++i) {
        const double l0 = std::exp(a + (b - a) * i / n), l1 = std::exp(a + (b - a) * (i + 1) / n);
        integral += 0.5 * (planck_radiance(l0, T) + planck_radiance(l1, T)) * (l1 - l0);
    }
    CHECK(M_PI * integral == Approx(5.670374419e-8 * std::pow(T, 4)).epsilon(1e-5));
    CHECK(blackbody_relative(560.0, 3000.0) == Approx(1.0));
    CHECK_THAT(error_of([] { blackbody(-5.0); }), Contains("blackbody temperature"));
    CHECK(parse_light_spectrum(nlohmann::json::parse(R"({"blackbody": 3000})"), "l")(700.0) ==
          Approx(blackbody_relative(700.0, 3000.0)));
    CHECK(parse_light_spectrum(nlohmann::json("D65"), "l").kind == Illuminant::D65);
    CHECK_THAT(error_of([] { parse_light_spectrum(nlohmann::json("D50"), "/lights/0/spectrum"); }),
               Contains("/lights/0/spectrum"));
}

// ---------------------------------------------------------------------------------------
// CIE colorimetry.

TEST_CASE("CIE 1931 matching functions: ybar(555) = 1 and xbar peaks at 1.0622 near 600 nm",
          "[spectrum]") {
    CHECK(cie_xyz_cmf(555.0).y() == Approx(1.0).margin(1e-3));
    double best = 0, best_l = 0;
    for (double l = 360.0; l <= 830.0; l += 1.0)
        if (cie_xyz_cmf(l).x() > best) best = cie_xyz_cmf(l).x(), best_l = l;
    CHECK(best == Approx(1.0622).margin(1e-4));
    CHECK(best_l == Approx(600.0).margin(1.0));
    // CIE design: the equal-energy spectrum has X = Y = Z.
    Vec3 sum = Vec3::Zero();
    for (double l = 360.0; l <= 830.0; l += 1.0) sum += cie_xyz_cmf(l);
    CHECK(sum.x() / sum.y() == Approx(1.0).margin(1e-3));
    CHECK(sum.z() / sum.y() == Approx(1.0).margin(2e-3));
    CHECK(cie_xyz_cmf(300.0) == Vec3::Zero());
}

TEST_CASE("CIE 1931 RGB matching functions peak near 604, 543 and 446 nm", "[spectrum]") {
    const RGBPeaks p = cie_rgb_peaks();
    CHECK(p.r == Approx(604.0).margin(2.0));
    CHECK(p.g == Approx(543.0).margin(2.0));
    CHECK(p.b == Approx(446.0).margin(2.0));
    // The primaries: r̄ vanishes where ḡ and b̄ are matched alone, and has its negative lobe.
    CHECK(cie_rgb_cmf(500.0).x() < 0.0);
    CHECK(cie_rgb_cmf(700.0).y() == Approx(0.0).margin(1e-4));
}

TEST_CASE("Equal-energy white of radiance 1 maps to RGB (1,1,1) (per-channel balance)",
          "[spectrum]") {
    const auto w = sample_wavelengths();
    for (auto p : {ColourPipeline::CieRgb, ColourPipeline::XyzSrgb}) {
        const SpectrumToRGB conv(w, p);
        const Vec3 white = conv.to_rgb(std::vector<double>(w.size(), 1.0));
        CHECK(white.x() == Approx(1.0).epsilon(1e-12));
        CHECK(white.y() == Approx(1.0).epsilon(1e-12));
        CHECK(white.z() == Approx(1.0).epsilon(1e-12));
    }
    // The paper's pipeline clips negative final values; xyz-srgb keeps them.
    const SpectrumToRGB cie(w, ColourPipeline::CieRgb);
    const SpectrumToRGB srgb(w, ColourPipeline::XyzSrgb);
    std::vector<double> cyan(w.size(), 0.0);
    cyan[10] = 1.0;  // 500 nm alone: r̄ < 0
    CHECK(cie.accumulate(cyan).x() < 0.0);
    CHECK(cie.to_rgb(cyan).x() == 0.0);
    CHECK(srgb.to_rgb(cyan).x() < 0.0);
    CHECK_THAT(error_of([] { parse_colour_pipeline("aces", "colour"); }), Contains("cie-rgb"));
}

TEST_CASE("Luminance-balanced white points: E under cie-rgb, D65 under xyz-srgb give (1,1,1)",
          "[spectrum]") {
    const auto w = sample_wavelengths({360, 830, 5});
    const SpectrumToRGB srgb(w, ColourPipeline::XyzSrgb, WhiteBalance::Luminance);
    const Vec3 d65 = srgb.to_rgb(std::vector<double>(w.size(), 1.0));  // D65 is the white
    CHECK(d65.x() == Approx(1.0).margin(1e-3));
    CHECK(d65.y() == Approx(1.0).margin(1e-3));
    CHECK(d65.z() == Approx(1.0).margin(1e-3));
    const SpectrumToRGB cie(w, ColourPipeline::CieRgb, WhiteBalance::Luminance);
    const Vec3 e = cie.to_rgb(std::vector<double>(w.size(), 1.0));
    CHECK(e.x() == Approx(1.0).margin(2e-3));
    CHECK(e.y() == Approx(1.0).margin(2e-3));
    CHECK(e.z() == Approx(1.0).margin(2e-3));
    // Equal energy is not neutral in sRGB: reddish, with less blue.
    const SpectrumToRGB srgbE(w, ColourPipeline::XyzSrgb, WhiteBalance::Luminance, LightSpectrum{});
    const Vec3 ee = srgbE.to_rgb(std::vector<double>(w.size(), 1.0));
    CHECK(ee.x() > 1.1);
    CHECK(ee.z() < 0.95);
}

TEST_CASE("CIEDE2000 against Sharma, Wu & Dalal 2005 test data", "[spectrum]") {
    // Table 1 of Sharma et al. 2005: L1 a1 b1 L2 a2 b2 ΔE00.
    const double data[34][7] = {
        {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
        {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
        {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
        {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
        {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
        {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
        {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
        {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
        {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
        {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
        {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
        {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
        {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
        {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
        {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
        {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
        {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
        {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
        {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
        {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
        {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
        {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
        {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
        {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
        {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
        {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
        {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
        {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
        {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
        {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
        {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
        {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
        {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
        {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
    };
    for (int i = 0; i < 34; ++i) {
        const Vec3 a(data[i][0], data[i][1], data[i][2]);
        const Vec3 b(data[i][3], data[i][4], data[i][5]);
        INFO("pair " << i + 1);
        CHECK(ciede2000(a, b) == Approx(data[i][6]).margin(1e-4));
        CHECK(ciede2000(b, a) == Approx(data[i][6]).margin(1e-4));
    }
    // Through linear sRGB: white is L* = 100, neutral; white against black is 100.
    const Vec3 lab = linear_srgb_to_lab(Vec3::Ones());
    CHECK(lab.x() == Approx(100.0).epsilon(1e-12));
    CHECK(lab.y() == Approx(0.0).margin(1e-9));
    CHECK(lab.z() == Approx(0.0).margin(1e-9));
    CHECK(delta_e2000(Vec3::Ones(), Vec3::Zero()) == Approx(100.0).epsilon(1e-12));
    CHECK(delta_e2000(Vec3(0.2, 0.3, 0.4), Vec3(0.2, 0.3, 0.4)) == 0.0);
}
