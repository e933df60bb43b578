#pragma once
// Wavelength sampling and light-source spectra (docs/spectra.md).
//
// Wavelengths are in nanometres throughout this layer. Sampling is a uniform grid
// min, min + step, ..., max; each sample stands for a band of width `step` centred on it
// (midpoint rule). Light-source spectra are *relative* spectral power distributions:
// only their shape matters, because the colour converter (core/spectrum/cie.h)
// normalises to the chosen white.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace refract::spectrum {

// The range the colour-matching tables cover; sampling must stay inside it.
constexpr double kMinWavelength = 360.0;  // nm
constexpr double kMaxWavelength = 830.0;  // nm

struct WavelengthSampling {
    double min_nm = 400.0;
    double max_nm = 700.0;
    double step_nm = 10.0;  // 400–700 every 10 nm: 31 samples, as Ohtsuka & Kawai 1998
};

// Checks a sampling: kMinWavelength <= min <= max <= kMaxWavelength, step in [0.1, 470] nm
// and dividing max − min into whole steps. Throws InputError naming `where`/min, /max or
// /step (JSON-pointer style, as the scene reader: pass e.g. "scene.json: /render/wavelengths").
void validate(const WavelengthSampling& s, const std::string& where = "wavelengths");

// The sample wavelengths min + i·step, i = 0..n−1, the last one exactly max.
std::vector<double> sample_wavelengths(const WavelengthSampling& s = {},
                                       const std::string& where = "wavelengths");

// Width of the band each wavelength stands for (midpoint rule): the distance between the
// midpoints to its neighbours; the first and last cells are symmetric about their sample.
// Equals `step` for every sample of a uniform grid; 1 for a single wavelength.
// Wavelengths must be strictly increasing (InputError otherwise).
std::vector<double> band_widths(const std::vector<double>& wavelengths_nm);

// ---------------------------------------------------------------------------------------
// Light-source spectra (relative spectral power, dimensionless).

// Equal-energy illuminant E: 1 at every wavelength.
inline double equal_energy(double /*lambda_nm*/) { return 1.0; }

// CIE standard illuminant D65 (CIE 15:2004, table T.1), 300–830 nm at 5 nm, normalised to
// 1 at 560 nm (the CIE's 100 scaled by 1/100), linearly interpolated; 0 outside the table.
double cie_d65(double lambda_nm);

// Planck's law: spectral radiance of a black body, W·sr⁻¹·m⁻²·nm⁻¹,
// B_λ(T) = 2hc² / λ⁵ / (exp(hc / (λ k T)) − 1), with the exact SI 2019 constants.
double planck_radiance(double lambda_nm, double temperature_K);

// Planck's law normalised to 1 at 560 nm (the D65 normalisation wavelength).
double blackbody_relative(double lambda_nm, double temperature_K);

enum class Illuminant { EqualEnergy, D65, Blackbody };

struct LightSpectrum {
    Illuminant kind = Illuminant::EqualEnergy;
    double temperature_K = 6504.0;  // Blackbody only

    // Relative spectral power at lambda_nm (equal_energy, cie_d65 or blackbody_relative).
    double operator()(double lambda_nm) const;
    // The spectrum at each wavelength.
    std::vector<double> sample(const std::vector<double>& wavelengths_nm) const;
    // "equal-energy", "D65" or "blackbody 5000 K".
    std::string name() const;
};

// A black body; throws InputError naming `where` unless 100 K <= T <= 100000 K.
LightSpectrum blackbody(double temperature_K, const std::string& where = "blackbody temperature");

// From a scene-file value: "E" / "equal-energy", "D65", or {"blackbody": T_kelvin}.
// Errors name `path`.
LightSpectrum parse_light_spectrum(const nlohmann::json& j, const std::string& path);

}  // namespace refract::spectrum
