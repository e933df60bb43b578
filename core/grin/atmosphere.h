#pragma once
// A stratified atmosphere over a spherical Earth and its refractive index n(h, λ) and
// dn/dh(h, λ) at geometric height h (docs/grin.md, "The air and the atmosphere").
//
// Temperature and pressure follow the U.S. Standard Atmosphere 1976 (NOAA/NASA/USAF,
// U.S. Government Printing Office, 1976) up to its 84.852 km geopotential (86 km
// geometric): linear in geopotential height layer by layer, pressure by hydrostatic
// equilibrium within each layer. Above, the last temperature continues isothermally, so
// n − 1 falls smoothly to 0 (it is 1.6·10⁻⁹ at 86 km). Optional: a relative humidity at
// the ground falling with a scale height, and a surface layer (a temperature difference
// ΔT at the ground decaying as ΔT·exp(−h/height): a hot road, a cold sea) for mirages.
// The index of the air at each height is Ciddor's (core/grin/air_index.h).
#include <string>
#include <vector>

#include <refract/core/grin/air_index.h>

namespace refract::grin {

constexpr double kEarthRadius_m = 6371e3;          // mean radius, the optical geometry's sphere
constexpr double kStandardEarthRadius_m = 6356766;  // r₀ of the 1976 standard's geopotential
constexpr double kStandardGravity = 9.80665;       // g₀, m/s²
constexpr double kStandardAirMolarMass = 0.0289644;  // M₀, kg/mol (1976 standard)
constexpr double kStandardGasConstant = 8.31432;   // R*, J/(mol K), the 1976 standard's value
constexpr double kStandardTopGeopotential_m = 84852.0;

// Geopotential height H = r₀ h / (r₀ + h) of geometric height h (1976 standard, r₀ above),
// and its inverse h = r₀ H / (r₀ − H).
double geopotential_height(double geometric_m);
double geometric_height(double geopotential_m);

// The autoconvective lapse rate g₀ M₀ / R* ≈ 0.0342 K/m: air whose temperature falls this
// fast with height has the same density at every height.
constexpr double kAutoconvectiveLapse_K_per_m = kStandardGravity * kStandardAirMolarMass / kStandardGasConstant;

struct AtmosphereSpec {
    double sea_level_temperature_K = 288.15;  // every layer's temperature shifts with it
    double sea_level_pressure_Pa = 101325.0;
    double relative_humidity = 0.0;           // at the ground, fraction over water
    double humidity_scale_height_m = 2000.0;  // RH(h) = RH(0)·exp(−h/this)
    double co2_ppm = 450.0;
    double surface_delta_T_K = 0.0;           // ΔT of the surface layer (0: none)
    double surface_height_m = 1.0;            // its e-folding height
};

// The air's state at a height, with its derivatives along geometric height.
struct AirProfilePoint {
    double temperature_K = 0.0, dT_dh = 0.0;
    double pressure_Pa = 0.0, dp_dh = 0.0;
    double vapour_pressure_Pa = 0.0, dpw_dh = 0.0;
};

class Atmosphere {
public:
    // Checks the spec (InputError "WHERE/FIELD: …" naming sea_level_temperature,
    // sea_level_pressure, relative_humidity, humidity_scale_height, co2,
    // surface_delta_T, surface_height; docs/limits.md) and precomputes the layers.
    explicit Atmosphere(const AtmosphereSpec& spec = {}, const std::string& where = "atmosphere");

    const AtmosphereSpec& spec() const { return spec_; }
    // The state at geometric height h ≥ 0 (InputError naming `height` otherwise).
    AirProfilePoint state(double h_m) const;
    // n(h, λ) and dn/dh(h, λ), λ in µm (InputError naming `wavelength` outside 0.3–1.69 µm).
    struct Index {
        double n = 1.0, dn_dh = 0.0;
    };
    Index index(double h_m, double lambda_um) const;
    Index index(double h_m, const CiddorReference& ref) const;  // λ and CO₂ prepared once
    // The geometric heights where the lapse rate changes (11, 20, 32, 47, 51, 71 km
    // geopotential, and the top): n is continuous there, dn/dh jumps by (∂n/∂T)·Δ(dT/dh).
    // A tabulated profile or a ray integrator should put a node or a step end on each.
    std::vector<double> kink_heights() const;

private:
    struct Layer {
        double base_H = 0.0, base_T = 0.0, base_p = 0.0, lapse = 0.0;  // m, K, Pa, K/m
    };
    const Layer& layer_at(double geopotential_m) const;
    double surface_integrand(double h) const;   // (1/T − 1/T_std) dH/dh
    double surface_correction(double h) const;  // ∫₀ʰ of it

    AtmosphereSpec spec_;
    std::string where_;
    std::vector<Layer> layers_;
    // The surface layer's hydrostatic correction ∫₀ʰ (1/T − 1/T_std) dH, at equal steps
    // (Hermite interpolation with its exact slope), to 40 e-folding heights.
    std::vector<double> surface_integral_;
    double surface_step_ = 0.0;
};

// n and dn/dh on count ≥ 2 equally spaced heights from h_min to h_max (a tabulated
// spherically symmetric profile, r = kEarthRadius_m + h).
struct IndexSamples {
    std::vector<double> height_m, n, dn_dh;
};
IndexSamples sample_index(const Atmosphere& atm, double lambda_um, double h_min_m, double h_max_m, int count);

}  // namespace refract::grin
