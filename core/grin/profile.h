#pragma once
// Gradient-index profiles n(x, λ) (docs/grin.md): analytic kinds as plain structs in one
// std::variant. Each kind has the overloads index, gradient and index_and_gradient; the
// variant is visited over them, so a kind without them does not compile.
//
// Units: x in scene units (any length; every length parameter in the same unit), λ in µm
// (the unit of the dispersion laws, core/spectrum/dispersion.h).
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include <refract/core/grin/atmosphere.h>
#include <refract/core/grin/grid.h>
#include <refract/core/grin/region.h>

namespace refract::grin {

// A base index and its dispersion: n₀(λ) = A + B/λ² (Cauchy 1836, spectrum::cauchy_index;
// λ in µm, B in µm²). B = 0: the same index at every wavelength.
struct CauchyIndex {
    double A = 1.5;
    double B = 0.0;
};
double value(const CauchyIndex& c, double lambda_um);

// Stratified along the unit vector `up`, h = up·x:
// n = n₀(λ) + slope·(h − h0).
struct LinearHeight {
    CauchyIndex n0{1.0, 0.0};
    double slope = 0.0;  // per unit length
    double h0 = 0.0;
    Vec3 up = Vec3::UnitZ();
};
// n = 1 + (n₀(λ) − 1)·exp(−(h − h0)/H): the isothermal atmosphere's form, H the scale height.
struct ExponentialHeight {
    CauchyIndex n0{1.000293, 0.0};
    double scale_height = 8000.0;
    double h0 = 0.0;
    Vec3 up = Vec3::UnitZ();
};
// Luneburg (1944): n = √(2 − (r/R)²) for r = |x − centre| ≤ R, 1 outside; a parallel
// bundle meets at the far side's surface point. Not dispersive by construction.
struct Luneburg {
    Vec3 centre = Vec3::Zero();
    double radius = 1.0;
};
// Maxwell's fish-eye (1854): n = n₀(λ)/(1 + (r/a)²), r = |x − centre|, in all space; every
// ray is a circle, and a point P is imaged at −a² P/|P|² (about the centre).
struct MaxwellFishEye {
    Vec3 centre = Vec3::Zero();
    CauchyIndex n0{2.0, 0.0};
    double a = 1.0;
};
// Hyperbolic-secant rod: n = n₀(λ)·sech(α r), r the distance from the axis (through
// `point` along unit `axis`); every meridional ray has the period 2π/α along the axis.
struct SechRod {
    Vec3 point = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    CauchyIndex n0{1.5, 0.0};
    double alpha = 1.0;
};
// Parabolic rod: n = n₀(λ)·(1 − A r²/2), r the distance from the axis; paraxial period
// 2π/√A, the exact one depends on the launch angle.
struct ParabolicRod {
    Vec3 point = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    CauchyIndex n0{1.5, 0.0};
    double A = 1.0;
};
// Spherically symmetric, tabulated: n at radii r_0 < r_1 < … (at least 3) about `centre`,
// a natural cubic spline between them (C²: n, n′ and n″ continuous), held at n(r_0)
// below r_0 and at n(r_last) above r_last (gradient 0 there); the gradient is n′(r) r̂.
// Not dispersive (one table, one wavelength). Build it with tabulated_radial(), which
// checks the table and computes the spline's second derivatives.
struct TabulatedRadial {
    Vec3 centre = Vec3::Zero();
    std::vector<double> r, n;
    std::vector<double> n2;  // the spline's second derivatives at the radii
};
TabulatedRadial tabulated_radial(const Vec3& centre, std::vector<double> r, std::vector<double> n,
                                 const std::string& path);

// The air over a spherical Earth (core/grin/atmosphere.h): n(h, λ) at the height
// h = |x − centre| − kEarthRadius_m (held at the ground's below it), its gradient
// dn/dh r̂; dispersive (Ciddor's index at each λ). Lengths in metres.
struct EarthAtmosphere {
    Vec3 centre = Vec3::Zero();
    Atmosphere air{};
};

// A sampled field of the index or of the air's temperature (core/grin/grid.h): the
// tricubic spline through the samples; dispersive for a temperature grid (Ciddor's air).
// Outside its box the field is held at the box's nearest point (validate refuses a grid
// that does not cover the medium's region).

using Profile = std::variant<LinearHeight, ExponentialHeight, Luneburg, MaxwellFishEye, SechRod, ParabolicRod,
                             TabulatedRadial, EarthAtmosphere, SampledGrid>;

struct IndexGradient {
    double n;
    Vec3 grad;  // ∇n
};

#define REFRACT_GRIN_PROFILE_OVERLOADS(Kind)                                 \
    double index(const Kind& p, const Vec3& x, double lambda_um);            \
    Vec3 gradient(const Kind& p, const Vec3& x, double lambda_um);           \
    IndexGradient index_and_gradient(const Kind& p, const Vec3& x, double lambda_um); \
    bool dispersive(const Kind& p);
REFRACT_GRIN_PROFILE_OVERLOADS(LinearHeight)
REFRACT_GRIN_PROFILE_OVERLOADS(ExponentialHeight)
REFRACT_GRIN_PROFILE_OVERLOADS(Luneburg)
REFRACT_GRIN_PROFILE_OVERLOADS(MaxwellFishEye)
REFRACT_GRIN_PROFILE_OVERLOADS(SechRod)
REFRACT_GRIN_PROFILE_OVERLOADS(ParabolicRod)
REFRACT_GRIN_PROFILE_OVERLOADS(TabulatedRadial)
REFRACT_GRIN_PROFILE_OVERLOADS(EarthAtmosphere)
REFRACT_GRIN_PROFILE_OVERLOADS(SampledGrid)
REFRACT_GRIN_PROFILE_OVERLOADS(Profile)
#undef REFRACT_GRIN_PROFILE_OVERLOADS
// dispersive(): the index depends on the wavelength (a base index with a Cauchy B ≠ 0, the air).

// The profile's parameters checked for the medium filling `where` over the wavelengths
// [lambda_min_um, lambda_max_um]: every parameter finite, lengths > 0, and the index
// finite and > 0 everywhere in `where` at every wavelength (e.g. a linear profile that
// falls to 0 inside the region, or a parabolic rod in an unbounded one, is refused).
// Axes are normalised in place. An InputError names `path` and the field:
// "s.json: /objects/0/grin/alpha: -1 must be > 0".
void validate(Profile& p, const Region& where, double lambda_min_um, double lambda_max_um, const std::string& path);

}  // namespace refract::grin
