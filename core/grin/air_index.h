#pragma once
// The refractive index of air from its state and the wavelength (docs/grin.md, "The air and
// the atmosphere"): Ciddor's procedure, the revised Edlén equation of Birch & Downs, and
// the Gladstone–Dale law, each step a small pure function.
//
// Units: wavelength in vacuum in µm (as the dispersion laws of core/spectrum/), temperature
// in K, pressures in Pa, relative humidity as a fraction in [0, 1], CO₂ in µmol/mol (ppm).
//
// P. E. Ciddor, "Refractive index of air: new equations for the visible and near infrared",
// Applied Optics 35(9), 1566–1573 (1996). K. P. Birch & M. J. Downs, "An updated Edlén
// equation for the refractive index of air", Metrologia 30, 155–162 (1993), and
// "Correction to the updated Edlén equation for the refractive index of air", Metrologia
// 31, 315–316 (1994), which revise B. Edlén, "The refractive index of air", Metrologia 2,
// 71–80 (1966).
#include <optional>
#include <string>

namespace refract::grin {

// The state of moist air. The water vapour is given either as its partial pressure
// (vapour_pressure_Pa, when set) or as the relative humidity over water.
struct AirState {
    double temperature_K = 288.15;
    double pressure_Pa = 101325.0;
    double relative_humidity = 0.0;            // fraction, over liquid water
    std::optional<double> vapour_pressure_Pa;  // replaces relative_humidity when set
    double co2_ppm = 450.0;
};

// The ranges the functions below accept (docs/limits.md). Ciddor states his equations for
// 300–1690 nm (NIST's calculator of Stone & Zimmerman: 300–1700 nm), −40 to +100 °C and 80–120 kPa; outside those temperatures and pressures
// refract still scales the refractivities with density (his own procedure), which the
// Gladstone–Dale law makes exact to first order, so the standard atmosphere up to 86 km
// (down to 186.87 K and 0.37 Pa) stays inside.
namespace air_limits {
constexpr double kMinWavelength_um = 0.3, kMaxWavelength_um = 1.7;
constexpr double kMinTemperature_K = 180.0, kMaxTemperature_K = 373.15;
constexpr double kMinPressure_Pa = 0.0, kMaxPressure_Pa = 140000.0;
constexpr double kMaxCO2_ppm = 2000.0;
}  // namespace air_limits

// Throws InputError "WHERE/FIELD: must be in [a, b] UNIT, got X" for a wavelength or a
// state outside the ranges above, or not finite (fields: wavelength, temperature,
// pressure, relative_humidity, vapour_pressure, co2). A vapour pressure must also lie at
// or below the total pressure.
void check_air_state(double lambda_um, const AirState& s, const std::string& where = "air");

// ---------------------------------------------------------------------------------------
// Ciddor (1996), step by step (his appendix).

// Standard dry air (15 °C, 101 325 Pa, 450 ppm CO₂):
// 10⁸ (n_as − 1) = k₁/(k₀ − σ²) + k₃/(k₂ − σ²), σ = 1/λ in µm⁻¹.
double ciddor_standard_air_refractivity(double lambda_um);
// The same with x_c ppm of CO₂: (n_axs − 1) = (n_as − 1)[1 + 0.534·10⁻⁶ (x_c − 450)].
double ciddor_co2_refractivity(double standard_refractivity, double co2_ppm);
// Standard water vapour (20 °C, 1 333 Pa):
// 10⁸ (n_ws − 1) = 1.022 (w₀ + w₁σ² + w₂σ⁴ + w₃σ⁶).
double ciddor_water_vapour_refractivity(double lambda_um);
// Molar mass of dry air with x_c ppm of CO₂, kg/mol:
// M_a = 10⁻³ [28.9635 + 12.011·10⁻⁶ (x_c − 400)].
double dry_air_molar_mass(double co2_ppm);
// Saturation vapour pressure over water, Pa (Davis, Metrologia 29, 67–70, 1992, the form
// Ciddor uses): exp(A T² + B T + C + D/T).
double saturation_vapour_pressure(double temperature_K);
// Its derivative with T, Pa/K.
double saturation_vapour_pressure_slope(double temperature_K);
// Enhancement factor of water vapour in air (Davis 1992): f = α + β p + γ t², t in °C.
double enhancement_factor(double pressure_Pa, double temperature_K);
// Mole fraction of water vapour x_w = f p_w / p (Ciddor).
double water_vapour_mole_fraction(double pressure_Pa, double temperature_K, double vapour_pressure_Pa);
// Compressibility of moist air (the BIPM-1981/91 equation for the density of moist air,
// Davis 1992, as Ciddor gives it):
// Z = 1 − (p/T)[a₀ + a₁t + a₂t² + (b₀ + b₁t)x_w + (c₀ + c₁t)x_w²] + (p/T)²(d + e x_w²).
double air_compressibility(double pressure_Pa, double temperature_K, double x_w);
// The densities of the dry-air and the water-vapour components of moist air, kg/m³
// (BIPM, as Ciddor): ρ_a = p M_a (1 − x_w)/(Z R T), ρ_w = p M_w x_w/(Z R T).
struct MoistAirDensity {
    double dry = 0.0, vapour = 0.0;
};
MoistAirDensity moist_air_density(double pressure_Pa, double temperature_K, double x_w, double co2_ppm);

// The wavelength's and the CO₂ content's part of Ciddor's procedure: the refractivities of
// standard dry air with x_c ppm CO₂ (n_axs − 1) and of standard water vapour (n_ws − 1), and
// the densities of those references, ρ_axs (dry air with this CO₂ at 15 °C, 101 325 Pa)
// and ρ_ws (pure water vapour at 20 °C, 1 333 Pa). Checks the wavelength and the CO₂.
struct CiddorReference {
    double dry_refractivity = 0.0, vapour_refractivity = 0.0;  // n_axs − 1, n_ws − 1
    double dry_density = 0.0, vapour_density = 0.0;            // ρ_axs, ρ_ws, kg/m³
    double co2_ppm = 450.0;
};
CiddorReference ciddor_reference(double lambda_um, double co2_ppm, const std::string& where = "air");
// n − 1 of moist air at p, T and vapour pressure p_w (Ciddor):
// n − 1 = (ρ_a/ρ_axs)(n_axs − 1) + (ρ_w/ρ_ws)(n_ws − 1). No range check: the density scaling.
double ciddor_refractivity(const CiddorReference& ref, double pressure_Pa, double temperature_K,
                           double vapour_pressure_Pa);
// The index of moist air (Ciddor): n − 1 = (ρ_a/ρ_axs)(n_axs − 1) + (ρ_w/ρ_ws)(n_ws − 1),
// ρ_axs the density of standard dry air with x_c ppm CO₂, ρ_ws that of standard water vapour.
// Checks its input (check_air_state).
double ciddor_index(double lambda_um, const AirState& s);

// The water vapour's partial pressure for a state (its vapour_pressure_Pa, or the relative
// humidity times the saturation vapour pressure).
double vapour_pressure(const AirState& s);

// ---------------------------------------------------------------------------------------
// The revised Edlén equation, Birch & Downs (1993, corrected 1994), the alternative:
// 10⁸ (n − 1)_s = 8 342.54 + 2 406 147/(130 − σ²) + 15 998/(38.9 − σ²)  (15 °C, 101 325 Pa, 450 ppm);
// (n − 1)_tp = p (n − 1)_s [1 + 10⁻⁸ (0.601 − 0.009 72 t) p] / [96 095.43 (1 + 0.003 661 t)];
// n − n_tp = −p_w (3.7345 − 0.0401 σ²)·10⁻¹⁰. Ignores the CO₂ content (450 ppm assumed).
// Checks its input (check_air_state).
double birch_downs_index(double lambda_um, const AirState& s);

// ---------------------------------------------------------------------------------------
// Gladstone–Dale (1863): n − 1 = K ρ, K in m³/kg, ρ in kg/m³.
double gladstone_dale_index(double K_m3_per_kg, double density_kg_per_m3);
// The same law as a ratio: the refractivity of air at density ratio q = ρ/ρ_ref from the
// reference air's, n − 1 = (n_ref − 1)·q (linear in q, so its gradient is (n_ref − 1)∇q).
double gladstone_dale_refractivity(double reference_refractivity, double density_ratio);
// For air heated or cooled at constant pressure (an ideal gas, ρ ∝ 1/T, so q = T_ref/T):
// the refractivity at T from that at a reference temperature, n(T) − 1 = (n_ref − 1)·T_ref/T.
double gladstone_dale_refractivity_at(double reference_refractivity, double reference_temperature_K,
                                      double temperature_K);

}  // namespace refract::grin
