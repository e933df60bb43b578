#pragma once
// Dispersion: the index of refraction as a function of wavelength, a catalogue of gem and
// glass materials, and POV-Ray's dispersion law and band colours (docs/spectra.md).
//
// The laws take λ in micrometres (the unit of the published coefficients) except
// povray_index and Dispersion::n, which take nanometres.
#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include <refract/geometry/ray.h>

namespace refract::spectrum {

// Fraunhofer and helium lines, nm (the wavelengths of n_B, n_C, n_D, n_d, n_F, n_G).
namespace fraunhofer {
constexpr double B = 686.719;   // O₂ (telluric)
constexpr double C = 656.2725;  // H-α
constexpr double D = 589.2938;  // Na D doublet, centre
constexpr double d = 587.5618;  // He
constexpr double F = 486.1327;  // H-β
constexpr double G = 430.78;    // Fe / Ca
}  // namespace fraunhofer

// ---------------------------------------------------------------------------------------
// The laws, as small pure functions.

// Each law as the sum of its terms, q(λ) = Σ t_k (q = n, or n² where `squared`), each term
// monotone in λ between the law's poles: the index is that sum (or its root) taken left to
// right, and the range check (check_range) bounds it from the terms' values at an
// interval's ends. The formulas are written once, in the *_terms functions.
// The Lorentz–Lorenz form (refractiveindex.info formula 8) sums R = (n² − 1)/(n² + 2), so
// n² = (1 + 2R)/(1 − R); its range check asks 1 + 2R > 0 and 1 − R > 0 (both linear in
// the terms, so still monotone between the poles).
struct LawTerms {
    std::array<double, 10> t{};
    int count = 0;
    bool squared = false;         // the sum is n²
    bool lorentz_lorenz = false;  // the sum is (n² − 1)/(n² + 2)
    void add(double v) { t[static_cast<size_t>(count++)] = v; }
    double sum() const;    // left to right
    double index() const;  // the sum, its square root, or n from the Lorentz–Lorenz sum
};
// One Sellmeier resonance (Sellmeier 1871): B λ²/(λ² − C), from λ² (µm²) and C (µm²); the
// catalogue's Sellmeier law and refractiveindex.info's formulas 1 and 2 sum these.
inline double sellmeier_term(double lambda2_um2, double B, double C) { return B * lambda2_um2 / (lambda2_um2 - C); }
LawTerms cauchy_terms(double lambda_um, double A, double B, double C);
LawTerms sellmeier_terms(double lambda_um, const double* B, const double* C, int terms);
LawTerms moissanite_form_terms(double lambda_um, double A, double B, double C, double D);

// Cauchy (1836): n = A + B/λ² + C/λ⁴, λ in µm, B in µm², C in µm⁴.
double cauchy_index(double lambda_um, double A, double B, double C);
// Sellmeier (1871): n² = 1 + Σ_i B_i λ² / (λ² − C_i), λ in µm, C_i in µm² (terms <= 4).
double sellmeier_index(double lambda_um, const double* B, const double* C, int terms);
// Moissanite's form (Wang et al. 2013, 6H-SiC): n² = A + B/(λ² − C) − D·λ², λ in µm.
double moissanite_form_index(double lambda_um, double A, double B, double C, double D);
// POV-Ray 3.7 (colour/spectral.h, GetDispersionIOR): n(λ) = n · D^((555 − λ)/350), λ in nm,
// so n(380)/n(730) = D.
double povray_index(double ior, double dispersion, double lambda_nm);

// ---------------------------------------------------------------------------------------
// Models.

struct ConstantIndex {
    double n = 1.5;
};
struct CauchyModel {
    double A = 1.5, B = 0.0, C = 0.0;  // µm², µm⁴
};
struct SellmeierModel {
    std::array<double, 4> B{}, C{};  // C in µm²
    int terms = 0;
};
// Abbe-number model: the two-term Cauchy n = A + B/λ² through n(λ_d) = n_d whose
// n_F − n_C = (n_d − 1)/V_d, i.e. B = (n_d − 1)/V_d / (1/λ_F² − 1/λ_C²), A = n_d − B/λ_d².
struct AbbeModel {
    double nd = 1.5168, Vd = 64.17;
    double A = 0.0, B = 0.0;  // derived by abbe_model()
};
AbbeModel abbe_model(double nd, double Vd);
struct MoissaniteFormModel {
    double A = 0.0, B = 0.0, C = 0.0, D = 0.0;
};
// A refractiveindex.info database entry (core/spectrum/refractiveindex_info.h): one of
// its formulas 1–9 with its coefficients C1…C17 (λ in µm), or its tabulated n, linear in λ
// between the samples. `range_um` is the entry's stated range (it must cover 360–830 nm).
struct FormulaModel {
    int formula = 1;
    std::vector<double> c;
    double range_um[2] = {0, 0};
};
struct TabulatedModel {
    std::vector<double> um, n;  // λ ascending
};
// POV-Ray's law; `samples` is POV-Ray's dispersion_samples (number of bands, >= 2).
struct PovRayModel {
    double ior = 1.0;
    double dispersion = 1.0;
    int samples = 7;
};

using DispersionModel = std::variant<ConstantIndex, CauchyModel, SellmeierModel, AbbeModel,
                                     MoissaniteFormModel, PovRayModel, FormulaModel, TabulatedModel>;

struct Dispersion {
    DispersionModel model;
    std::string label;  // e.g. "diamond (Peter 1923)", "sellmeier"

    double n(double lambda_nm) const;
    std::vector<double> indices(const std::vector<double>& wavelengths_nm) const;
    // The index to use where one index is needed: n for constant, ior for POV-Ray's law
    // (POV-Ray's Fresnel uses it), n_d (587.56 nm) for the others.
    double nominal() const;
    // False for a constant index and for POV-Ray's law with dispersion 1.
    bool dispersive() const;
    bool is_povray() const { return std::holds_alternative<PovRayModel>(model); }
    // V_d = (n_d − 1)/(n_F − n_C).
    double abbe_number() const;
};

// The material catalogue. Names (case-insensitive, ' ' or '_' for '-'): diamond, n-bk7
// (alias bk7), fused-silica, water, cubic-zirconia (alias cz), moissanite.
// Throws InputError listing the known names.
const Dispersion& catalogue(const std::string& name);
std::vector<std::string> catalogue_names();

// The uniaxial crystals (core/birefringence.h): the index of the ordinary and of the
// extraordinary ray. calcite and quartz: Ghosh, Opt. Commun. 163, 95 (1999); sapphire:
// Malitson & Dodge, JOSA 62, 1405 (1972); moissanite (6H-SiC): Wang et al., Laser
// Photonics Rev. 7, 831 (2013), whose ordinary ray is the catalogue's "moissanite". The
// single rays are also catalogue entries "calcite-o", "calcite-e", …, "moissanite-e".
// Empty when `name` is not one of uniaxial_crystal_names().
struct UniaxialCrystal {
    Dispersion ordinary, extraordinary;
};
std::optional<UniaxialCrystal> uniaxial_crystal(const std::string& name);
std::vector<std::string> uniaxial_crystal_names();

// From a scene-file value; errors name `path` and the JSON-pointer path below it, as the
// scene reader does (path "scene.json: /materials/gem/dispersion" → ".../dispersion/B: ..."):
//   "diamond"                                  a catalogue name
//   1.5 or {"model":"constant","n":1.5}
//   {"model":"cauchy","A":1.5046,"B":0.0042,"C":0}          (µm², µm⁴)
//   {"model":"sellmeier","B":[...],"C":[...]}              (1–4 terms, C in µm²)
//   {"model":"abbe","nd":1.5168,"Vd":64.17}
//   {"model":"moissanite-form","A":..,"B":..,"C":..,"D":..}
//   {"model":"povray","ior":2.417,"dispersion":1.05,"samples":7}   (samples optional)
// The result must give a finite index > 0 over 360–830 nm. A file entry,
//   {"file": "N-BK7.yml"}                      a refractiveindex.info entry
// is read by read_dispersion_file (refractiveindex_info.h), relative to the scene file;
// here it is refused (no scene file to be relative to).
Dispersion parse_dispersion(const nlohmann::json& j, const std::string& path);
// The continuous check over 360–830 nm (finite, > 0, no pole inside); errors name `path`.
void check_range(const Dispersion& d, const std::string& path);
// The same from text: a catalogue name, or JSON (an object or a number).
Dispersion parse_dispersion_text(const std::string& text, const std::string& path);

// ---------------------------------------------------------------------------------------
// POV-Ray's spectral bands (colour/spectral.h/.cpp, POV-Ray 3.7): band i of N has
// λ_i = 380 + 350·(i + 0.5)/N nm, bandwidth 350/N (both rounded to float, as POV-Ray
// stores them) and colour hue_i = (I(λ_i + bw/2) − I(λ_i − bw/2))·350/bw, I the cumulative
// hue table ("Variant 3") linearly interpolated. The hues average to I(730) − I(380) =
// (0.9938, 1.0, 0.9962) for every N.
struct PovBand {
    double wavelength_nm;
    double bandwidth_nm;
    Vec3 hue;
};
Vec3 povray_hue_integral(double lambda_nm);
// Throws InputError unless samples >= 2 (POV-Ray's minimum).
std::vector<PovBand> povray_bands(int samples);

}  // namespace refract::spectrum
