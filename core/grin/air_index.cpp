// The refractive index of air (air_index.h): Ciddor (1996), Birch & Downs (1993/94),
// Gladstone–Dale. Constants as the papers print them.
#include <refract/core/grin/air_index.h>

#include <cmath>

#include <refract/core/grin/check_range.h>
#include <refract/geometry/error.h>

namespace refract::grin {

namespace {
constexpr double kZeroCelsius = 273.15;    // K
constexpr double kGasConstant = 8.314510;  // J/(mol K), the value Ciddor uses
constexpr double kWaterMolarMass = 0.018015;  // kg/mol, Ciddor


double sigma2(double lambda_um) { return 1.0 / (lambda_um * lambda_um); }
}  // namespace

void check_air_state(double lambda_um, const AirState& s, const std::string& where) {
    using namespace air_limits;
    check_range(lambda_um, kMinWavelength_um, kMaxWavelength_um, where, "wavelength", " µm");
    check_range(s.temperature_K, kMinTemperature_K, kMaxTemperature_K, where, "temperature", " K");
    check_range(s.pressure_Pa, kMinPressure_Pa, kMaxPressure_Pa, where, "pressure", " Pa");
    if (s.vapour_pressure_Pa)
        check_range(*s.vapour_pressure_Pa, 0.0, s.pressure_Pa, where, "vapour_pressure", " Pa (the total pressure)");
    else
        check_range(s.relative_humidity, 0.0, 1.0, where, "relative_humidity", "");
    check_range(s.co2_ppm, 0.0, kMaxCO2_ppm, where, "co2", " ppm");
}

double ciddor_standard_air_refractivity(double lambda_um) {
    constexpr double k0 = 238.0185, k1 = 5792105.0, k2 = 57.362, k3 = 167917.0;  // µm⁻²
    const double s2 = sigma2(lambda_um);
    return 1e-8 * (k1 / (k0 - s2) + k3 / (k2 - s2));
}

double ciddor_co2_refractivity(double standard_refractivity, double co2_ppm) {
    return standard_refractivity * (1.0 + 0.534e-6 * (co2_ppm - 450.0));
}

double ciddor_water_vapour_refractivity(double lambda_um) {
    constexpr double w0 = 295.235, w1 = 2.6422, w2 = -0.032380, w3 = 0.004028;  // µm⁻²…µm⁻⁸
    const double s2 = sigma2(lambda_um);
    return 1.022e-8 * (w0 + s2 * (w1 + s2 * (w2 + s2 * w3)));
}

double dry_air_molar_mass(double co2_ppm) { return 1e-3 * (28.9635 + 12.011e-6 * (co2_ppm - 400.0)); }

namespace {
constexpr double kSvpA = 1.2378847e-5, kSvpB = -1.9121316e-2, kSvpC = 33.93711047, kSvpD = -6.3431645e3;
}

double saturation_vapour_pressure(double T) { return std::exp(kSvpA * T * T + kSvpB * T + kSvpC + kSvpD / T); }

double saturation_vapour_pressure_slope(double T) {
    return saturation_vapour_pressure(T) * (2.0 * kSvpA * T + kSvpB - kSvpD / (T * T));
}

double enhancement_factor(double p, double T) {
    const double t = T - kZeroCelsius;
    return 1.00062 + 3.14e-8 * p + 5.6e-7 * t * t;
}

double water_vapour_mole_fraction(double p, double T, double pw) {
    return p > 0.0 ? enhancement_factor(p, T) * pw / p : 0.0;
}

double air_compressibility(double p, double T, double xw) {
    constexpr double a0 = 1.58123e-6, a1 = -2.9331e-8, a2 = 1.1043e-10;  // K/Pa, 1/Pa, 1/(K Pa)
    constexpr double b0 = 5.707e-6, b1 = -2.051e-8;                      // K/Pa, 1/Pa
    constexpr double c0 = 1.9898e-4, c1 = -2.376e-6;                     // K/Pa, 1/Pa
    constexpr double d = 1.83e-11, e = -0.765e-8;                        // K²/Pa²
    const double t = T - kZeroCelsius, pt = p / T;
    return 1.0 - pt * (a0 + a1 * t + a2 * t * t + (b0 + b1 * t) * xw + (c0 + c1 * t) * xw * xw) +
           pt * pt * (d + e * xw * xw);
}

MoistAirDensity moist_air_density(double p, double T, double xw, double co2_ppm) {
    const double k = p / (air_compressibility(p, T, xw) * kGasConstant * T);
    return {k * dry_air_molar_mass(co2_ppm) * (1.0 - xw), k * kWaterMolarMass * xw};
}

double vapour_pressure(const AirState& s) {
    return s.vapour_pressure_Pa ? *s.vapour_pressure_Pa
                                : s.relative_humidity * saturation_vapour_pressure(s.temperature_K);
}

CiddorReference ciddor_reference(double lambda_um, double co2_ppm, const std::string& where) {
    check_range(lambda_um, air_limits::kMinWavelength_um, air_limits::kMaxWavelength_um, where, "wavelength", " µm");
    check_range(co2_ppm, 0.0, air_limits::kMaxCO2_ppm, where, "co2", " ppm");
    CiddorReference r;
    r.dry_refractivity = ciddor_co2_refractivity(ciddor_standard_air_refractivity(lambda_um), co2_ppm);
    r.vapour_refractivity = ciddor_water_vapour_refractivity(lambda_um);
    r.dry_density = moist_air_density(101325.0, 288.15, 0.0, co2_ppm).dry;
    r.vapour_density = moist_air_density(1333.0, 293.15, 1.0, co2_ppm).vapour;
    r.co2_ppm = co2_ppm;
    return r;
}

double ciddor_refractivity(const CiddorReference& ref, double p, double T, double pw) {
    const double xw = water_vapour_mole_fraction(p, T, pw);
    const MoistAirDensity rho = moist_air_density(p, T, xw, ref.co2_ppm);
    return rho.dry / ref.dry_density * ref.dry_refractivity + rho.vapour / ref.vapour_density * ref.vapour_refractivity;
}

double ciddor_index(double lambda_um, const AirState& s) {
    check_air_state(lambda_um, s);
    return 1.0 + ciddor_refractivity(ciddor_reference(lambda_um, s.co2_ppm), s.pressure_Pa, s.temperature_K,
                                     vapour_pressure(s));
}

double birch_downs_index(double lambda_um, const AirState& s) {
    check_air_state(lambda_um, s);
    const double s2 = sigma2(lambda_um), t = s.temperature_K - kZeroCelsius, p = s.pressure_Pa;
    const double ns = 1e-8 * (8342.54 + 2406147.0 / (130.0 - s2) + 15998.0 / (38.9 - s2));
    const double ntp = p * ns * (1.0 + 1e-8 * (0.601 - 0.00972 * t) * p) / (96095.43 * (1.0 + 0.003661 * t));
    return 1.0 + ntp - vapour_pressure(s) * (3.7345 - 0.0401 * s2) * 1e-10;
}

double gladstone_dale_index(double K, double rho) { return 1.0 + K * rho; }

double gladstone_dale_refractivity(double ref, double q) { return ref * q; }
double gladstone_dale_refractivity_at(double ref, double T_ref, double T) { return gladstone_dale_refractivity(ref, T_ref / T); }

}  // namespace refract::grin
