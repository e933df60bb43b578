#pragma once
// A perfect mirror of reflectivity `color`: one branch, the mirror direction. A perfect
// conductor for exact polarisation: rs = −1, rp = +1 at every angle (the η → ∞ limit of
// Hecht's amplitudes), Mueller matrix diag(1, 1, −1, −1) in the s/p frames.
#include <refract/core/material_rules.h>

namespace refract::material {

struct Mirror {
    Vec3 color{1, 1, 1};

    static constexpr const char* kType = "mirror";
    static Mirror read(const JsonReader& r, const std::string&) {
        r.only({"type", "color"});
        return Mirror{read_pigment(r).color};
    }
};

inline Interaction interact(const Mirror& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return mirror_interaction(m.color, h, ray, c.exact);
}
inline LeafLight leaf_light(const Mirror&) { return {}; }
inline StochasticRole stochastic_role(const Mirror&) { return StochasticRole::Branches; }
// Its one branch (the interaction's direction, unit; the caller normalises it again).
inline std::optional<Scatter> sample(const Mirror& m, const SurfaceHit& h, const Ray& ray, const InteractionContext&,
                                     Rng&) {
    return Scatter{optics::reflect(ray.dir, h.normal).normalized(), m.color};
}
inline const Vec3* shadow_filter(const Mirror&) { return nullptr; }
inline bool casts_shadow(const Mirror&) { return true; }
inline bool dispersive(const Mirror&) { return false; }
inline double band_index(const Mirror&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Mirror&) { return nullptr; }
inline bool in_packets(const Mirror&) { return true; }
inline bool carries_stokes(const Mirror&) { return true; }
inline const char* povray_lacks(const Mirror&) { return nullptr; }
inline NodeRecord describe(const Mirror&, const Interaction& in, const SurfaceHit&, const Ray&, double) {
    NodeRecord r{"mirror"};
    r.R = in.reflectance;
    return r;
}
inline void validate(const Mirror&, const MaterialCheck&) {}

}  // namespace refract::material
