// The standard atmosphere and its index (core/grin/atmosphere.h): the 1976 standard's
// published values, continuity at its layers, the autoconvective lapse rate, ducting.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <refract/core/grin/atmosphere.h>
#include <refract/geometry/error.h>

#include "input_error.h"

using namespace refract;
using namespace refract::grin;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
using refract::test::error_of;
}  // namespace

TEST_CASE("U.S. Standard Atmosphere 1976: temperature and pressure at the layer bases", "[grin][atmosphere]") {
    // U.S. Standard Atmosphere 1976, Table 4 (the layers' base values, geopotential km, K, Pa).
    struct Base {
        double H_km, T, p;
    };
    constexpr Base kBases[] = {{0, 288.15, 101325.0},    {11, 216.65, 22632.06},  {20, 216.65, 5474.889},
                               {32, 228.65, 868.0187},   {47, 270.65, 110.9063},  {51, 270.65, 66.93887},
                               {71, 214.65, 3.956420},   {84.852, 186.946, 0.3733836}};
    const Atmosphere atm;
    for (const Base& b : kBases) {
        INFO(b.H_km << " km");
        const AirProfilePoint s = atm.state(geometric_height(b.H_km * 1e3));
        CHECK_THAT(s.temperature_K, WithinAbs(b.T, 1e-3));
        CHECK_THAT(s.pressure_Pa, WithinRel(b.p, 2e-6));
    }
    // The standard's top, 84.852 km geopotential, is 86 km geometric (its r₀ = 6 356.766 km).
    CHECK_THAT(geometric_height(84852.0), WithinAbs(86000.0, 1.0));
    CHECK_THAT(geopotential_height(geometric_height(12345.0)), WithinAbs(12345.0, 1e-8));
}

TEST_CASE("Standard atmosphere index: n continuous at every layer boundary, dn/dh jumps by (dn/dT) times the lapse change",
          "[grin][atmosphere]") {
    const Atmosphere atm;
    const CiddorReference ref = ciddor_reference(0.55, 450.0);
    for (double h : atm.kink_heights()) {
        INFO(h << " m");
        const double e = 1e-4;
        const Atmosphere::Index below = atm.index(h - e, ref), above = atm.index(h + e, ref);
        CHECK_THAT(above.n - below.n, WithinAbs(e * (above.dn_dh + below.dn_dh), 5e-16));
        // T is continuous and dT/dh jumps with the lapse rate: dn/dh jumps by ∂n/∂T·Δ(dT/dh).
        const AirProfilePoint sb = atm.state(h - e), sa = atm.state(h + e);
        const double dT = 1e-3, T = sa.temperature_K;
        const double dn_dT = (ciddor_refractivity(ref, sa.pressure_Pa, T + dT, 0) -
                              ciddor_refractivity(ref, sa.pressure_Pa, T - dT, 0)) / (2 * dT);
        CHECK_THAT(sa.temperature_K, WithinAbs(sb.temperature_K, 1e-6));
        CHECK_THAT(above.dn_dh - below.dn_dh, WithinAbs(dn_dT * (sa.dT_dh - sb.dT_dh), 1e-6 * std::abs(below.dn_dh)));
    }
    // Between the boundaries dn/dh is the slope of n (central difference over 1 m at 5 km).
    const Atmosphere::Index mid = atm.index(5000.0, ref);
    CHECK_THAT((atm.index(5000.5, ref).n - atm.index(4999.5, ref).n), WithinRel(mid.dn_dh, 1e-6));
    // So it is with humidity (at 1 km) and in a hot road's surface layer (1 m thick, 10 K,
    // at 0.5 m, over ±1 mm); there the pressure also agrees with hydrostatic equilibrium.
    AtmosphereSpec wet_hot;
    wet_hot.relative_humidity = 0.8;
    wet_hot.surface_delta_T_K = 10.0;
    wet_hot.surface_height_m = 1.0;
    const Atmosphere wh(wet_hot);
    for (double h : {1000.0, 0.5}) {
        INFO(h << " m");
        const double e = h > 1 ? 0.5 : 1e-3;
        CHECK_THAT((wh.index(h + e, ref).n - wh.index(h - e, ref).n) / (2 * e), WithinRel(wh.index(h, ref).dn_dh, 1e-6));
        CHECK_THAT((wh.state(h + e).pressure_Pa - wh.state(h - e).pressure_Pa) / (2 * e),
                   WithinRel(wh.state(h).dp_dh, 1e-6));
    }
    // Humid air at the ground is Ciddor's air at the same state.
    AtmosphereSpec humid;
    humid.relative_humidity = 0.6;
    AirState s;
    s.relative_humidity = 0.6;
    CHECK(Atmosphere(humid).index(0.0, 0.55).n == ciddor_index(0.55, s));
    // The sampler gives the same values on its grid, ends included.
    const IndexSamples t = sample_index(atm, 0.55, 0.0, 20000.0, 5);
    REQUIRE(t.n.size() == 5);
    CHECK(t.height_m.back() == 20000.0);
    CHECK(t.n[2] == atm.index(10000.0, 0.55).n);
    CHECK(t.dn_dh[4] == atm.index(20000.0, 0.55).dn_dh);
}

TEST_CASE("Autoconvective lapse rate: dn/dh = 0 where the temperature falls at g/R_air = 34.2 K/km", "[grin][atmosphere]") {
    CHECK_THAT(kAutoconvectiveLapse_K_per_m, WithinAbs(0.034163, 1e-6));
    // A hot road: a surface layer 10 m thick whose gradient at the ground, with the standard's
    // −6.5 K/km, makes dT/dh = −g₀M₀/R*.
    AtmosphereSpec hot;
    hot.surface_height_m = 10.0;
    hot.surface_delta_T_K = (kAutoconvectiveLapse_K_per_m - 6.5e-3) * hot.surface_height_m;
    const Atmosphere atm(hot);
    const AirProfilePoint s = atm.state(0.0);
    CHECK_THAT(s.dT_dh, WithinAbs(-kAutoconvectiveLapse_K_per_m, 1e-12));
    // The ideal-gas density p/T is then constant with height.
    CHECK_THAT(s.dp_dh / s.pressure_Pa - s.dT_dh / s.temperature_K, WithinAbs(0.0, 1e-15));
    // n − 1 follows the density but for the compressibility Z(p, T) (4e-4 from 1, varying with
    // t at fixed p/T: d ln Z/dh ≈ 3.5e-7 per metre), so dn/dh is 0 to 1e-10 per metre,
    // 0.4 % of the standard atmosphere's −2.6e-8.
    const double standard = Atmosphere().index(0.0, 0.55).dn_dh;
    CHECK(std::abs(atm.index(0.0, 0.55).dn_dh) < 1e-2 * std::abs(standard));
    // A steeper fall makes the index grow with height (the inferior mirage); the pressure at
    // the ground stays the sea-level pressure.
    hot.surface_delta_T_K *= 2;
    CHECK(Atmosphere(hot).index(0.0, 0.55).dn_dh > 0);
    CHECK_THAT(Atmosphere(hot).state(0.0).pressure_Pa, WithinRel(101325.0, 1e-15));
}

TEST_CASE("Ducting threshold dn/dh = -1/R_Earth: a temperature inversion of about 0.11 K/m at 0 C", "[grin][atmosphere]") {
    // A cold sea surface: a surface layer 10 m thick whose inversion dT/dh at the ground is
    // G. dn/dh at the ground is linear in G; solve dn/dh = −1/R_Earth for it.
    auto slope = [](double sea_level_K, double G) {
        AtmosphereSpec cold;
        cold.sea_level_temperature_K = sea_level_K;
        cold.surface_height_m = 10.0;
        cold.surface_delta_T_K = -(G + 6.5e-3) * cold.surface_height_m;
        return Atmosphere(cold).index(0.0, 0.55).dn_dh;
    };
    auto threshold = [&](double sea_level_K) {  // the secant method
        double g0 = 0.0, g1 = 0.2, f0 = slope(sea_level_K, g0) + 1.0 / kEarthRadius_m;
        for (int i = 0; i < 20; ++i) {
            const double f1 = slope(sea_level_K, g1) + 1.0 / kEarthRadius_m;
            if (f1 == f0) break;
            const double g2 = g1 - f1 * (g1 - g0) / (f1 - f0);
            g0 = g1, f0 = f1, g1 = g2;
        }
        return g1;
    };
    // Sea-level air at 0 °C (the inversion makes the surface 1.2 K colder): 0.11–0.12 K/m.
    const double G0 = threshold(273.15);
    CHECK(G0 > 0.11);
    CHECK(G0 < 0.12);
    CHECK_THAT(slope(273.15, G0), WithinAbs(-1.0 / kEarthRadius_m, 1e-15));
    // The same from the ideal-gas density law by hand: n − 1 ∝ p/T, dn/dh = (n−1)(−g₀M₀/(R*T) − G/T).
    const AirProfilePoint s = [&] {
        AtmosphereSpec cold;
        cold.sea_level_temperature_K = 273.15;
        cold.surface_height_m = 10.0;
        cold.surface_delta_T_K = -(G0 + 6.5e-3) * 10.0;
        return Atmosphere(cold).state(0.0);
    }();
    AirState st;
    st.temperature_K = s.temperature_K;
    const double n1 = ciddor_index(0.55, st) - 1;
    const double by_hand = (1.0 / kEarthRadius_m - n1 * kAutoconvectiveLapse_K_per_m / s.temperature_K) /
                           (n1 / s.temperature_K);
    // (The compressibility's temperature dependence adds 0.3 % to ∂n/∂T: 0.4 % apart.)
    CHECK_THAT(G0, WithinRel(by_hand, 5e-3));
    // Warmer air needs a stronger inversion: at 15 °C about 0.13 K/m.
    CHECK(threshold(288.15) > G0);
}

TEST_CASE("Atmosphere: an out-of-range spec, height or wavelength is an InputError naming the field", "[grin][atmosphere]") {
    AtmosphereSpec s;
    s.surface_height_m = 0.0;
    s.surface_delta_T_K = 5.0;
    CHECK(error_of([&] { Atmosphere a(s); }) == "atmosphere/surface_height: must be in [0.01, 100] m, got 0");
    s = AtmosphereSpec{};
    s.sea_level_temperature_K = std::nan("");
    CHECK_THAT(error_of([&] { Atmosphere a(s, "scene.json: /atmosphere"); }),
               Contains("scene.json: /atmosphere/sea_level_temperature: must be in [233.15, 323.15] K"));
    s = AtmosphereSpec{};
    s.relative_humidity = -0.1;
    CHECK(error_of([&] { Atmosphere a(s); }) == "atmosphere/relative_humidity: must be in [0, 1], got -0.1");
    const Atmosphere atm;
    CHECK(error_of([&] { atm.state(-1.0); }) == "atmosphere/height: must be in [0, 1e7] m, got -1");
    CHECK(error_of([&] { atm.index(0.0, 2.0); }) == "atmosphere/wavelength: must be in [0.3, 1.7] µm, got 2");
    CHECK_THAT(error_of([&] { sample_index(atm, 0.55, 10.0, 5.0, 3); }), Contains("sample_index/height"));
    CHECK_THAT(error_of([&] { sample_index(atm, 0.55, 0.0, 5.0, 1); }), Contains("sample_index/count"));
}
