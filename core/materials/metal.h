#pragma once
// RTIOW's metal: reflection with fuzz, albedo `color`. The stochastic integrator samples
// the fuzz; the tree integrators take the mirror direction.
#include <refract/core/material_rules.h>

namespace refract::material {

struct Metal {
    Vec3 color{1, 1, 1};
    double fuzz = 0.0;

    static constexpr const char* kType = "metal";
    static Metal read(const JsonReader& r, const std::string&) {
        r.only({"type", "color", "fuzz"});
        const double fuzz = r.number("fuzz", 0.0);
        if (fuzz < 0 || fuzz > 1) r.fail_at("fuzz", "must be in [0, 1]");
        return Metal{read_pigment(r).color, fuzz};
    }
};

inline Interaction interact(const Metal& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return mirror_interaction(m.color, h, ray, c.exact);
}
inline LeafLight leaf_light(const Metal&) { return {}; }
inline StochasticRole stochastic_role(const Metal&) { return StochasticRole::Scatters; }
// RTIOW's fuzzy reflection: the mirror direction plus fuzz times a random point of the unit
// ball; absorbed when it points into the surface.
inline std::optional<Scatter> sample(const Metal& m, const SurfaceHit& h, const Ray& ray, const InteractionContext&,
                                     Rng& rng) {
    const Vec3 dir = optics::reflect(ray.dir, h.normal) + m.fuzz * rng.in_unit_sphere();
    if (dir.dot(h.normal) <= 0) return std::nullopt;
    return Scatter{dir, m.color};
}
inline const Vec3* shadow_filter(const Metal&) { return nullptr; }
inline bool casts_shadow(const Metal&) { return true; }
inline bool dispersive(const Metal&) { return false; }
inline double band_index(const Metal&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Metal&) { return nullptr; }
inline bool in_packets(const Metal&) { return true; }
inline bool carries_stokes(const Metal&) { return true; }
inline const char* povray_lacks(const Metal&) { return nullptr; }
inline NodeRecord describe(const Metal&, const Interaction& in, const SurfaceHit&, const Ray&, double) {
    NodeRecord r{"mirror"};
    r.R = in.reflectance;
    return r;
}
inline void validate(const Metal&, const MaterialCheck&) {}

}  // namespace refract::material
