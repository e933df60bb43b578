#pragma once
// Materials: a Material is a name and one of the kinds of core/materials/, each a struct
// holding only its own fields, with its rulebook beside it (core/material_rules.h lists the
// rules). The list of kinds is here, once; every rule is visited over it, so a kind that
// lacks a rule does not compile (check_kind names what it lacks).
//
// Adding a kind: core/materials/NAME.h (the struct, its scene-file form, its rules), its
// entry in Material::Kind below, and its POV-Ray export or refusal
// (the POV-Ray exporter, validation/).
#include <string>
#include <variant>

#include <refract/core/materials/dielectric.h>
#include <refract/core/materials/diffuse.h>
#include <refract/core/materials/emissive.h>
#include <refract/core/materials/grin.h>
#include <refract/core/materials/lambertian.h>
#include <refract/core/materials/metal.h>
#include <refract/core/materials/mirror.h>
#include <refract/core/materials/uniaxial.h>

namespace refract {

struct Material {
    using Kind = std::variant<material::Diffuse, material::Lambertian, material::Mirror, material::Metal,
                              material::Emissive, material::Dielectric, material::Uniaxial, material::Grin>;
    std::string name;
    Kind kind;

    template <class T>
    bool is() const { return std::holds_alternative<T>(kind); }
    template <class T>
    const T* as() const { return std::get_if<T>(&kind); }
    template <class T>
    T* as() { return std::get_if<T>(&kind); }
    const material::Dielectric* dielectric() const { return as<material::Dielectric>(); }
};

namespace material {
template <class... K>
constexpr bool check_kinds(const std::variant<K...>*) {
    return (check_kind<K>() && ...);
}
static_assert(check_kinds(static_cast<const Material::Kind*>(nullptr)), "every material kind has every rule");
}  // namespace material

// The rules of a material, each visited over its kind (core/material_rules.h).
inline Interaction interact(const Material& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return std::visit([&](const auto& k) { return interact(k, h, ray, c); }, m.kind);
}
inline std::optional<Scatter> sample(const Material& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c,
                                     Rng& rng) {
    return std::visit([&](const auto& k) { return sample(k, h, ray, c, rng); }, m.kind);
}
inline LeafLight leaf_light(const Material& m) {
    return std::visit([](const auto& k) { return leaf_light(k); }, m.kind);
}
inline StochasticRole stochastic_role(const Material& m) {
    return std::visit([](const auto& k) { return stochastic_role(k); }, m.kind);
}
inline const Vec3* shadow_filter(const Material& m) {
    return std::visit([](const auto& k) { return shadow_filter(k); }, m.kind);
}
inline bool casts_shadow(const Material& m) {
    return std::visit([](const auto& k) { return casts_shadow(k); }, m.kind);
}
inline bool dispersive(const Material& m) {
    return std::visit([](const auto& k) { return dispersive(k); }, m.kind);
}
inline double band_index(const Material& m, double nm, const CompatRules& rules) {
    return std::visit([&](const auto& k) { return band_index(k, nm, rules); }, m.kind);
}
inline const spectrum::Absorption* absorption(const Material& m) {
    return std::visit([](const auto& k) { return absorption(k); }, m.kind);
}
inline bool in_packets(const Material& m) {
    return std::visit([](const auto& k) { return in_packets(k); }, m.kind);
}
inline bool carries_stokes(const Material& m) {
    return std::visit([](const auto& k) { return carries_stokes(k); }, m.kind);
}
inline const char* povray_lacks(const Material& m) {
    return std::visit([](const auto& k) { return povray_lacks(k); }, m.kind);
}
inline NodeRecord describe(const Material& m, const Interaction& in, const SurfaceHit& h, const Ray& ray,
                           double band_ior) {
    return std::visit([&](const auto& k) { return describe(k, in, h, ray, band_ior); }, m.kind);
}
inline void validate(const Material& m, const MaterialCheck& c) {
    std::visit([&](const auto& k) { validate(k, c); }, m.kind);
}
// A leaf's surface is lit by the lights (diffuse, Lambertian): where illumination maps go.
inline bool lit_surface(const Material& m) { return leaf_light(m).kind == LeafLight::Kind::Lit; }
// A crossing transmits light: a dielectric or a crystal (counted as a branching node).
inline bool transparent(const Material& m) { return shadow_filter(m) != nullptr; }

// The kind named `type` read from r (the names listed in the error when unknown).
Material::Kind read_material_kind(const JsonReader& r, const std::string& type, const std::string& file);

}  // namespace refract
