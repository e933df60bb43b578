#pragma once
// Astronomical refraction: the refraction integral of a spherically symmetric atmosphere,
// the independent reference for rays traced through it, and two published formulas
// (docs/grin.md, "The air and the atmosphere").
#include <refract/core/grin/atmosphere.h>

namespace refract::grin {

struct RefractionIntegralOptions {
    double observer_height_m = 0.0;  // above the ground, r₀ = kEarthRadius_m + this
    double top_height_m = 150e3;     // where the integral stops (n − 1 < 10⁻¹³ there)
    double relative_tolerance = 1e-9;  // of the adaptive quadrature, per piece (at most 2¹² subintervals)
};

// The refraction R (radians) of a ray reaching the observer at apparent altitude
// `apparent_altitude_rad` in [0, π/2] (0: the horizon) through `atm` at wavelength λ (µm).
//
// Along the ray n r sin z = n₀ r₀ sin z₀ (Bouguer), z the zenith angle; with z as the
// variable (Auer & Standish, "Astronomical refraction: computational method for all zenith
// angles", AJ 119, 2472–2474, 2000) the integral is
//     R = −∫_{z_top}^{z₀} r (dn/dr) / (n + r dn/dr) dz,
// finite at the horizon. r(z) is found by Newton's method on n(r) r = n₀ r₀ sin z₀ / sin z;
// the integral by adaptive Gauss–Kronrod quadrature, split at the heights where the
// standard's lapse rate changes. InputError when the apparent altitude is outside
// [0, 90°], or where d(n r)/dr ≤ 0 on the path (the atmosphere ducts: no single path).
double refraction_integral(const Atmosphere& atm, double lambda_um, double apparent_altitude_rad,
                           const RefractionIntegralOptions& options = {});

// Bennett (1982), "The calculation of astronomical refraction in marine navigation",
// Journal of Navigation 35, 255–259: R = cot(h_a + 7.31/(h_a + 4.4)) arcminutes, h_a the
// apparent altitude in degrees, for 10 °C and 101.0 kPa, fitted to Garfinkel's (1967)
// algorithm and stated good to 0.07′ over 0–90°;
// other conditions scale it by (P / 101.0 kPa)(283 K / T) (as Meeus, Astronomical
// Algorithms, 2nd ed., ch. 16). Returns arcminutes.
double bennett_refraction_arcmin(double apparent_altitude_deg, double pressure_Pa = 101000.0,
                                 double temperature_K = 283.0);

// Bennett's formula with his correction R − 0.06 sin(14.7 R + 13°) (R in arcminutes, at
// 10 °C and 101.0 kPa; as Meeus, ch. 16, gives it "for greater accuracy"), scaled as above.
double bennett_corrected_refraction_arcmin(double apparent_altitude_deg, double pressure_Pa = 101000.0,
                                           double temperature_K = 283.0);

// Sæmundsson (1986), Sky & Telescope 72, 70: R = 1.02 cot(h + 10.3/(h + 5.11)) arcminutes,
// h the true (airless) altitude in degrees, same conditions and scaling; consistent with
// Bennett's to about 0.1′ (Meeus). Returns arcminutes.
double saemundsson_refraction_arcmin(double true_altitude_deg, double pressure_Pa = 101000.0,
                                     double temperature_K = 283.0);

}  // namespace refract::grin
