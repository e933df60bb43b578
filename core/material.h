#pragma once
// Materials: one type per kind, each holding only its own fields. A Material is a name
// and one of these kinds; what a kind does at a hit (its branches) lives with it in
// core/interaction.h.
#include <optional>
#include <string>
#include <variant>

#include "core/spectrum/absorption.h"
#include "core/spectrum/dispersion.h"
#include "geometry/ray.h"

namespace refract {

enum class ReflectanceModel {
    Constant,  // Whitted: ks = constant_reflectivity, kt = 1 − ks
    Fresnel,   // exact, natural light (Yasuda eq. 7)
    FresnelS,  // s-polarised only
    FresnelP,  // p-polarised only
    Schlick,   // RTIOW approximation
};

struct Checker {
    Vec3 color2{0, 0, 0};  // the second colour; the first is the pigment's `color`
    double size = 1;       // edge of one square (3D checker as in POV-Ray)
};

// A surface colour: plain, or a 3D checker of `color` and `checker->color2`.
struct Pigment {
    Vec3 color{1, 1, 1};
    std::optional<Checker> checker;
};

namespace material {

// POV-Ray convention: ambient·pigment + Σ diffuse·pigment·light·max(0, N·L).
struct Diffuse {
    Pigment pigment;
    double diffuse = 1.0;  // POV-Ray `diffuse`
    double ambient = 0.0;  // POV-Ray `ambient` (Whitted's Ia term)
};

// RTIOW: random diffuse bounce with albedo `pigment` (stochastic integrator); the tree
// integrators light it directly as a Diffuse with diffuse 1, ambient 0.
struct Lambertian {
    Pigment pigment;
};

// Perfect mirror, reflectivity `color`.
struct Mirror {
    Vec3 color{1, 1, 1};
};

// RTIOW metal: reflection with fuzz (stochastic integrator; the tree takes the mirror
// direction), albedo `color`.
struct Metal {
    Vec3 color{1, 1, 1};
    double fuzz = 0.0;
};

// Highlight light: a surface that shines `color` (tens of times brighter than lights).
struct Emissive {
    Vec3 color{1, 1, 1};
};

// Smooth transparent interface with the surrounding air.
struct Dielectric {
    double ior = 1.5;  // index relative to the surrounding air (nominal when dispersive)
    ReflectanceModel reflectance = ReflectanceModel::Fresnel;
    double constant_reflectivity = 0.0;  // Constant model
    Vec3 filter{1, 1, 1};                // transmitted colour per crossing
    // Index as a function of wavelength (catalogue name or model in the scene file);
    // `ior` stays the nominal index (Dispersion::nominal() when `ior` is absent).
    std::optional<spectrum::Dispersion> dispersion;
    // Beer–Lambert absorption inside (per scene unit); none: clear.
    std::optional<spectrum::Absorption> absorption;
};

// A uniaxial crystal (core/birefringence.h, docs/birefringence.md) in the air: every ray
// splits into an ordinary and an extraordinary one. The indices of the two rays as
// functions of wavelength; the optic axis (unit, in the scene's frame).
struct Uniaxial {
    spectrum::Dispersion ordinary, extraordinary;
    Vec3 optic_axis{0, 0, 1};
    Vec3 filter{1, 1, 1};  // transmitted colour per crossing
    std::string crystal;   // the catalogue crystal, or empty
    // The medium at wavelength λ (nm); at the sodium D line when λ <= 0 (an RGB ray).
    double n_o(double lambda_nm) const { return ordinary.n(lambda_nm > 0 ? lambda_nm : spectrum::fraunhofer::D); }
    double n_e(double lambda_nm) const { return extraordinary.n(lambda_nm > 0 ? lambda_nm : spectrum::fraunhofer::D); }
};

}  // namespace material

struct Material {
    using Kind = std::variant<material::Diffuse, material::Lambertian, material::Mirror, material::Metal,
                              material::Emissive, material::Dielectric, material::Uniaxial>;
    std::string name;
    Kind kind;

    template <class T>
    bool is() const { return std::holds_alternative<T>(kind); }
    template <class T>
    const T* as() const { return std::get_if<T>(&kind); }
    template <class T>
    T* as() { return std::get_if<T>(&kind); }
    // Surfaces that end a ray-tree branch and are shaded there (diffuse, Lambertian).
    bool diffuse_surface() const { return is<material::Diffuse>() || is<material::Lambertian>(); }
    const material::Dielectric* dielectric() const { return as<material::Dielectric>(); }
    // Transparent kinds (dielectric, uniaxial): the colour a crossing transmits; else null.
    const Vec3* transparent_filter() const {
        if (const auto* d = dielectric()) return &d->filter;
        if (const auto* u = as<material::Uniaxial>()) return &u->filter;
        return nullptr;
    }
};

}  // namespace refract
