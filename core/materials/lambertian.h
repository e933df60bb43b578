#pragma once
// RTIOW's Lambertian: a random diffuse bounce with albedo `pigment` in the stochastic
// integrator; the tree integrators light it directly, as a diffuse surface with diffuse 1
// and ambient 0.
#include <refract/core/material_rules.h>

namespace refract::material {

struct Lambertian {
    Pigment pigment;

    static constexpr const char* kType = "lambertian";
    static Lambertian read(const JsonReader& r, const std::string&) {
        r.only({"type", "color", "checker"});
        return Lambertian{read_pigment(r)};
    }
};

inline Interaction interact(const Lambertian&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf_interaction();
}
inline LeafLight leaf_light(const Lambertian& m) { return {LeafLight::Kind::Lit, &m.pigment, 1.0, 0.0, {}}; }
inline StochasticRole stochastic_role(const Lambertian&) { return StochasticRole::Scatters; }
// RTIOW's scatter: the normal plus a random unit vector (the normal where they cancel).
inline std::optional<Scatter> sample(const Lambertian& m, const SurfaceHit& h, const Ray&, const InteractionContext& c,
                                     Rng& rng) {
    const Vec3 pigment = pigment_at(*c.rules, m.pigment, h.hit.point);
    Vec3 dir = h.normal + rng.unit_vector();
    if (dir.squaredNorm() < 1e-16) dir = h.normal;
    return Scatter{dir, pigment};
}
inline const Vec3* shadow_filter(const Lambertian&) { return nullptr; }
inline bool casts_shadow(const Lambertian&) { return true; }
inline bool dispersive(const Lambertian&) { return false; }
inline double band_index(const Lambertian&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Lambertian&) { return nullptr; }
inline bool in_packets(const Lambertian&) { return true; }
inline bool carries_stokes(const Lambertian&) { return true; }
inline const char* povray_lacks(const Lambertian&) { return nullptr; }
inline NodeRecord describe(const Lambertian&, const Interaction&, const SurfaceHit&, const Ray&, double) {
    return NodeRecord{"diffuse"};
}
inline void validate(const Lambertian&, const MaterialCheck&) {}

}  // namespace refract::material
