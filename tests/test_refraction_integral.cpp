// Astronomical refraction (core/grin/refraction_integral.h): the refraction integral through
// the standard atmosphere against an independent quadrature, Laplace's formula, and the
// formulas of Bennett (1982) and Sæmundsson (1986).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <refract/core/grin/refraction_integral.h>
#include <refract/geometry/error.h>

#include "input_error.h"

using namespace refract;
using namespace refract::grin;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;

namespace {
constexpr double kArcsec = 180.0 / M_PI * 3600.0;  // arcseconds per radian
double rad(double deg) { return deg * M_PI / 180.0; }

using refract::test::error_of;

// Bennett's conditions: 10 °C and 101.0 kPa at sea level.
Atmosphere bennett_atmosphere() {
    AtmosphereSpec s;
    s.sea_level_temperature_K = 283.15;
    s.sea_level_pressure_Pa = 101000.0;
    return Atmosphere(s);
}
}  // namespace

TEST_CASE("Refraction integral: the zenith-angle form equals the classical radius form to 1e-4 arcsec at 5 and 45 degrees",
          "[grin][refraction]") {
    // The classical form R = −∫ (dn/dr) c / (n √(n²r² − c²)) dr, c = n₀ r₀ sin z₀ (Smart,
    // Textbook on Spherical Astronomy), finite away from the horizon, by 61-point
    // Gauss–Kronrod between the layer boundaries: a quadrature in another variable.
    const Atmosphere atm;
    const CiddorReference ref = ciddor_reference(0.55, 450.0);
    for (double alt : {45.0, 5.0}) {
        const double r0 = kEarthRadius_m, n0 = atm.index(0.0, ref).n;
        const double c = n0 * r0 * std::sin(rad(90.0 - alt));
        auto f = [&](double h) {
            const Atmosphere::Index x = atm.index(h, ref);
            const double r = r0 + h;
            return -x.dn_dh * c / (x.n * std::sqrt(x.n * x.n * r * r - c * c));
        };
        std::vector<double> breaks{0.0};
        for (double h : atm.kink_heights()) breaks.push_back(h);
        breaks.push_back(150e3);
        double R = 0.0;
        for (size_t i = 0; i + 1 < breaks.size(); ++i) {
            const double mid = 0.5 * (breaks[i] + breaks[i + 1]), half = 0.5 * (breaks[i + 1] - breaks[i]);
            R += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
                [&](double u) { return f(mid + half * u) * half; }, -1.0, 1.0, 10, 1e-10);
        }
        INFO(alt << " deg");
        CHECK_THAT(refraction_integral(atm, 0.55, rad(alt)) * kArcsec, WithinAbs(R * kArcsec, 1e-4));
    }
}

TEST_CASE("Refraction at 45 degrees: (n0 - 1) tan z with Laplace's correction, to 0.002 arcsec", "[grin][refraction]") {
    // To first order R = (n₀ − 1) tan z. Laplace's formula adds the next terms, which depend only
    // on the air at the observer: R = κ(1 − β) tan z − κ(β − κ/2) tan³ z, κ = n₀ − 1, β = H/r₀,
    // H = R*T₀/(M₀g₀) the height of the homogeneous atmosphere (Laplace's A tan z + B tan³ z
    // of the spherical-astronomy texts). At 45° the correction is −0.14″ of 57″.
    const Atmosphere atm;
    const double kappa = atm.index(0.0, 0.5893).n - 1.0;
    const double beta = kStandardGasConstant * 288.15 / (kStandardAirMolarMass * kStandardGravity) / kEarthRadius_m;
    const double R = refraction_integral(atm, 0.5893, rad(45.0));
    CHECK_THAT(R / kappa, WithinAbs(1.0, 0.003));  // tan 45° = 1
    const double laplace = kappa * (1 - beta) - kappa * (beta - kappa / 2);
    CHECK_THAT(R * kArcsec, WithinAbs(laplace * kArcsec, 0.002));
    CHECK(refraction_integral(atm, 0.5893, rad(90.0)) == 0.0);
}

TEST_CASE("Refraction through the standard atmosphere at Bennett's conditions against Bennett 1982 and Saemundsson 1986",
          "[grin][refraction]") {
    // 10 °C, 101.0 kPa at sea level, the 1976 standard's lapse rates, λ = 550 nm (visual).
    // Bennett fitted Garfinkel's (1967) algorithm and states his formula good to 0.07′ over
    // 0–90° (Meeus 1991, ch. 16); with his correction term the
    // integral agrees to 0.0001′ at 45° and 0.03′ at 5–10° (the standard atmosphere is not
    // the model of the tables Bennett fitted). Measured integral − Bennett (arcmin):
    // 45°: −0.028, 10°: −0.087, 5°: −0.054, 1°: −0.25, 0°: −0.59. Within 2° of the horizon the
    // refraction depends on the lapse rate of the lowest kilometres, and the two formulas
    // differ from each other by 0.14′ at 0°: there the tolerance is the formulas' spread
    // plus the lapse-rate difference, measured, not a published accuracy.
    const Atmosphere atm = bennett_atmosphere();
    struct Case {
        double alt, bennett_tol, corrected_tol, saemundsson_tol;  // arcmin
    };
    constexpr Case kCases[] = {{45, 0.07, 0.005, 0.07}, {10, 0.1, 0.04, 0.17}, {5, 0.07, 0.04, 0.1},
                               {1, 0.3, 0.3, 0.3},      {0, 0.7, 0.7, 0.6}};
    for (const Case& c : kCases) {
        const double R = refraction_integral(atm, 0.55, rad(c.alt)) * kArcsec / 60;  // arcmin
        INFO(c.alt << " deg: integral " << R << "'");
        const double p = 101000.0, T = 283.15;  // the atmosphere's sea level
        CHECK_THAT(R, WithinAbs(bennett_refraction_arcmin(c.alt, p, T), c.bennett_tol));
        CHECK_THAT(R, WithinAbs(bennett_corrected_refraction_arcmin(c.alt, p, T), c.corrected_tol));
        // Sæmundsson's formula takes the true altitude, the apparent one less the refraction.
        CHECK_THAT(R, WithinAbs(saemundsson_refraction_arcmin(c.alt - R / 60, p, T), c.saemundsson_tol));
    }
    // Bennett's formula gives 34.5′ at the horizon: cot(7.31/4.4 °) = 34.48′.
    CHECK_THAT(bennett_refraction_arcmin(0.0), WithinAbs(34.48, 0.01));
    // Both formulas scale with P/T.
    CHECK_THAT(bennett_refraction_arcmin(10.0, 101325.0, 288.15),
               WithinAbs(bennett_refraction_arcmin(10.0) * 101325.0 / 101000.0 * 283.0 / 288.15, 1e-12));
}

TEST_CASE("Green flash: horizon refraction at 520 nm exceeds that at 650 nm by 10-30 arcsec", "[grin][refraction]") {
    // The dispersion of n − 1 (Ciddor) makes green light refract more than red: the sun's green
    // image stands above its red one at the horizon by a few tens of arcseconds at most.
    const Atmosphere atm;
    const double d = (refraction_integral(atm, 0.52, 0.0) - refraction_integral(atm, 0.65, 0.0)) * kArcsec;
    CHECK(d > 10.0);
    CHECK(d < 30.0);
}

TEST_CASE("Refraction integral: an altitude out of range or a ducting atmosphere is an InputError", "[grin][refraction]") {
    const Atmosphere atm;
    CHECK_THAT(error_of([&] { refraction_integral(atm, 0.55, -0.01); }),
               Contains("refraction_integral/apparent_altitude: must be in [0, 1.570796327] rad, got -0.01"));
    CHECK_THAT(error_of([&] { refraction_integral(atm, 3.0, 0.1); }), Contains("refraction_integral/wavelength"));
    // A cold sea under a 0.3 K/m inversion: rays bend with the Earth, no single path.
    AtmosphereSpec cold;
    cold.surface_height_m = 10.0;
    cold.surface_delta_T_K = -3.0;
    CHECK_THAT(error_of([&] { refraction_integral(Atmosphere(cold), 0.55, 0.0); }),
               Contains("refraction_integral: the atmosphere ducts at height"));
    CHECK_THAT(error_of([&] { bennett_refraction_arcmin(91.0); }), Contains("bennett_refraction/apparent_altitude"));
}
