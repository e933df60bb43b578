#pragma once
// Catalogued optical constants: entries of the refractiveindex.info database (M. N.
// Polyanskiy, "Refractiveindex.info database of optical constants", Sci. Data 11, 94
// (2024)), one YAML file per entry, as a dispersion model (dispersion.h FormulaModel,
// TabulatedModel) and, where the entry gives the extinction coefficient k, an absorption
// (absorption.h) by α = 4πk/λ (optics::extinction_absorption).
//
// The file's DATA is a list of blocks, each with a `type`:
//   "formula N"      (N = 1…9) with `wavelength_range: a b` (µm) and `coefficients: C1 C2 …`
//   "tabulated n"    `data:` lines "λ n"
//   "tabulated k"    `data:` lines "λ k"
//   "tabulated nk"   `data:` lines "λ n k"
// with λ in µm. The formulas, as the database defines them ("Dispersion formulas",
// database/doc of the database's repository), λ in µm:
//   1 Sellmeier     n² − 1 = C1 + Σ C_i λ²/(λ² − C_{i+1}²),       i = 2, 4, …, 16
//   2 Sellmeier-2   n² − 1 = C1 + Σ C_i λ²/(λ² − C_{i+1})
//   3 Polynomial    n²     = C1 + Σ C_i λ^C_{i+1}
//   4 RefractiveIndex.INFO
//                   n²     = C1 + C2 λ^C3/(λ² − C4^C5) + C6 λ^C7/(λ² − C8^C9)
//                               + Σ C_i λ^C_{i+1},                 i = 10, 12, …, 16
//   5 Cauchy        n      = C1 + Σ C_i λ^C_{i+1},                 i = 2, 4, …, 10
//   6 Gases         n − 1  = C1 + Σ C_i/(C_{i+1} − λ^−2),          i = 2, 4, …, 10
//   7 Herzberger    n      = C1 + C2/(λ² − 0.028) + C3/(λ² − 0.028)² + C4 λ² + C5 λ⁴ + C6 λ⁶
//   8 Retro         (n² − 1)/(n² + 2) = C1 + C2 λ²/(λ² − C3) + C4 λ²
//   9 Exotic        n²     = C1 + C2/(λ² − C3) + C4 (λ − C5)/((λ − C5)² + C6)
// Tabulated values are linear in λ between the samples.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include <refract/core/spectrum/absorption.h>
#include <refract/core/spectrum/dispersion.h>

namespace refract::spectrum {

// The formula as its terms (dispersion.h LawTerms), λ in µm.
LawTerms formula_terms(const FormulaModel& m, double lambda_um);
// Its poles (C in µm², λ_pole = √C) with the coefficient they come from, and the λ (µm)
// where one of its terms turns (a maximum or minimum).
std::vector<std::pair<double, std::string>> formula_poles(const FormulaModel& m);
std::vector<double> formula_turns(const FormulaModel& m);
// y(x) linear between samples (x ascending), the end values beyond.
double tabulated_at(const std::vector<double>& x, const std::vector<double>& y, double xq);

// An entry: its index, and its absorption when it gives k.
struct CataloguedConstants {
    Dispersion dispersion;
    std::optional<Absorption> absorption;
};

// Reads the entry at `file`. `unit_cm` is the scene unit in cm (α is per scene unit). The
// entry must give one index (a formula, tabulated n or tabulated nk) and at most one k,
// each over the whole of 360–830 nm. Errors (unreadable file, malformed YAML, an unknown
// type, missing or non-finite numbers, a range short of 360–830 nm) are one InputError
// "<file>: /DATA/<i>/<item>: …".
CataloguedConstants read_refractiveindex_info(const std::string& file, double unit_cm = 1.0);

// A scene's `"dispersion": {"file": "N-BK7.yml", "unit_cm": 1}`: the file relative to the
// scene file's directory; errors name `path` (the field) and then the file's item.
CataloguedConstants read_dispersion_file(const nlohmann::json& j, const std::string& scene_file,
                                         const std::string& path);

}  // namespace refract::spectrum
