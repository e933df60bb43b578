#pragma once
// A diffuse surface, POV-Ray's convention: ambient·pigment + Σ diffuse·pigment·light·
// max(0, N·L)·shadow. A leaf of every ray tree; the stochastic integrator ends its path
// there with that light too.
#include <refract/core/material_rules.h>

namespace refract::material {

struct Diffuse {
    Pigment pigment;
    double diffuse = 1.0;  // POV-Ray `diffuse`
    double ambient = 0.0;  // POV-Ray `ambient` (Whitted's Ia term)

    static constexpr const char* kType = "diffuse";
    static Diffuse read(const JsonReader& r, const std::string&) {
        r.only({"type", "color", "checker", "diffuse", "ambient"});
        return Diffuse{read_pigment(r), r.coefficient("diffuse", 1.0), r.coefficient("ambient", 0.0)};
    }
};

inline Interaction interact(const Diffuse&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf_interaction();
}
inline LeafLight leaf_light(const Diffuse& m) { return {LeafLight::Kind::Lit, &m.pigment, m.diffuse, m.ambient, {}}; }
inline StochasticRole stochastic_role(const Diffuse&) { return StochasticRole::Leaf; }
inline std::optional<Scatter> sample(const Diffuse&, const SurfaceHit&, const Ray&, const InteractionContext&, Rng&) {
    return std::nullopt;
}
inline const Vec3* shadow_filter(const Diffuse&) { return nullptr; }
inline bool casts_shadow(const Diffuse&) { return true; }
inline bool dispersive(const Diffuse&) { return false; }
inline double band_index(const Diffuse&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Diffuse&) { return nullptr; }
inline bool in_packets(const Diffuse&) { return true; }
inline bool carries_stokes(const Diffuse&) { return true; }
inline const char* povray_lacks(const Diffuse&) { return nullptr; }
inline NodeRecord describe(const Diffuse&, const Interaction&, const SurfaceHit&, const Ray&, double) {
    return NodeRecord{"diffuse"};
}
inline void validate(const Diffuse&, const MaterialCheck&) {}

}  // namespace refract::material
