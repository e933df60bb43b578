#pragma once
// A highlight light: a surface that shines `color` (tens of times brighter than lights). A
// leaf; it casts no shadow (POV-Ray's no_shadow).
#include <refract/core/material_rules.h>

namespace refract::material {

struct Emissive {
    Vec3 color{1, 1, 1};

    static constexpr const char* kType = "emissive";
    static Emissive read(const JsonReader& r, const std::string&) {
        r.only({"type", "color"});
        return Emissive{read_pigment(r).color};
    }
};

inline Interaction interact(const Emissive&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf_interaction();
}
inline LeafLight leaf_light(const Emissive& m) { return {LeafLight::Kind::Emits, nullptr, 0, 0, m.color}; }
inline StochasticRole stochastic_role(const Emissive&) { return StochasticRole::Leaf; }
inline std::optional<Scatter> sample(const Emissive&, const SurfaceHit&, const Ray&, const InteractionContext&, Rng&) {
    return std::nullopt;
}
inline const Vec3* shadow_filter(const Emissive&) { return nullptr; }
inline bool casts_shadow(const Emissive&) { return false; }
inline bool dispersive(const Emissive&) { return false; }
inline double band_index(const Emissive&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Emissive&) { return nullptr; }
inline bool in_packets(const Emissive&) { return true; }
inline bool carries_stokes(const Emissive&) { return true; }
inline const char* povray_lacks(const Emissive&) { return nullptr; }
inline NodeRecord describe(const Emissive&, const Interaction&, const SurfaceHit&, const Ray&, double) {
    return NodeRecord{"emissive"};
}
inline void validate(const Emissive&, const MaterialCheck&) {}

}  // namespace refract::material
