#pragma once
// Absorption inside a dielectric (Beer–Lambert, core/optics.h beer_lambert): an absorption
// coefficient α per scene unit, as a spectrum α(λ) and as three RGB values, and a
// catalogue of coloured materials (docs/spectra.md, "Absorption").
//
// The two forms are tied as follows: given a spectrum, the RGB coefficients are α at
// 610, 545 and 445 nm (the 1998 paper's three wavelengths); given RGB coefficients (or
// a transmittance colour at a thickness), the spectrum is the piecewise-linear curve
// through (445, α_B), (545, α_G), (610, α_R), constant beyond.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include <refract/geometry/ray.h>

namespace refract::spectrum {

struct Absorption {
    std::vector<double> nm, alpha;  // α(λ), per scene unit, λ ascending
    Vec3 rgb{0, 0, 0};              // α of the R, G, B channels, per scene unit
    std::string label;

    double at(double lambda_nm) const;  // α(λ), linear between samples, constant beyond
    // From RGB coefficients (>= 0), or from a spectrum (sorted by the caller).
    static Absorption from_rgb(const Vec3& alpha_rgb, std::string label);
    static Absorption from_spectrum(std::vector<double> nm, std::vector<double> alpha, std::string label);
};

// The catalogue of coloured materials, α in 1/cm (one scene unit = 1 cm unless the scene
// says otherwise): ruby, blue-sapphire, emerald, green-glass. Each is a documented model
// (absorption bands placed where the literature puts them, strengths chosen), not a
// measurement; docs/spectra.md gives the sources. Throws InputError listing the names.
Absorption absorption_catalogue(const std::string& name, double unit_cm = 1.0);
std::vector<std::string> absorption_catalogue_names();

// From a scene-file value; errors name `path`:
//   "ruby"                                       catalogue, 1 scene unit = 1 cm
//   {"model": "ruby", "unit_cm": 0.1}            catalogue, 1 scene unit = 1 mm
//   {"coefficients": [aR, aG, aB]}                α per scene unit
//   {"transmittance": [tR, tG, tB], "thickness": d}  the colour seen through thickness d
//   {"spectrum": [[nm, α], ...]}                 α per scene unit, at least two samples
Absorption parse_absorption(const nlohmann::json& j, const std::string& path);

}  // namespace refract::spectrum
