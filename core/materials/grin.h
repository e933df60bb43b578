#pragma once
// A gradient-index medium (docs/grin.md): an object whose interior has the index n(x, λ)
// of its profile (core/grin/profile.h), in the air. Inside, rays follow the ray equation
// (core/grin/ray_equation.h: the walker's search bends them, SceneTracer::through); at its
// surface the exact Fresnel split of the dielectric node, with the profile's index at the
// hit point and the ray's wavelength on the inside (the sodium D line for an RGB ray). It
// needs the fresnel-tree integrator (or the spectral eye pass), the physical mode and one
// ray at a time. Exact polarisation: the Stokes frame is carried along the curved rays by
// Rytov's law (core/grin/rytov.h).
#include <string>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/profile_json.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/materials/dielectric.h>

namespace refract::material {

struct Grin {
    grin::Profile profile;
    grin::Settings settings;  // the integrator's tolerance and step budget
    Vec3 filter{1, 1, 1};     // a crossing transmits all colours (the shadow rays' filter)
    // Whether it blocks shadow rays as a dielectric does in the physical mode (its light
    // arrives through the light pass); false for air, whose index differs from the
    // surroundings' by 1e-4 and whose shadow rays pass as if straight.
    bool shadows = true;

    // The profile's index at x for a ray of wavelength `nm` (0: an RGB ray, at the D line).
    double index_at(const Vec3& x, double nm) const {
        return grin::index(profile, x, (nm > 0 ? nm : spectrum::fraunhofer::D) * 1e-3);
    }
    // The interface at x as a dielectric of the local index.
    Dielectric interface_at(const Vec3& x, double nm) const {
        Dielectric d;
        d.ior = index_at(x, nm);
        return d;
    }

    static constexpr const char* kType = "grin";
    static Grin read(const JsonReader& r, const std::string& file);
};

inline Interaction interact(const Grin& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    InteractionContext local = c;
    local.band_ior = 0;
    return dielectric_interaction(*c.rules, m.interface_at(h.hit.point, c.wavelength_nm), h, ray, local);
}
inline LeafLight leaf_light(const Grin&) { return {}; }
inline StochasticRole stochastic_role(const Grin&) { return StochasticRole::Branches; }
// Its first branch (validate refuses the stochastic integrator; this is for completeness).
inline std::optional<Scatter> sample(const Grin& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c,
                                     Rng&) {
    const Interaction in = interact(m, h, ray, c);
    if (in.branches == 0) return std::nullopt;
    return Scatter{in.branch[0].ray.dir, in.branch[0].factor};
}
inline const Vec3* shadow_filter(const Grin& m) { return &m.filter; }
inline bool casts_shadow(const Grin& m) { return m.shadows; }
inline bool dispersive(const Grin& m) { return grin::dispersive(m.profile); }
// The index varies from point to point: the interaction takes the wavelength instead.
inline double band_index(const Grin&, double, const CompatRules&) { return 0.0; }
inline const spectrum::Absorption* absorption(const Grin&) { return nullptr; }
inline bool in_packets(const Grin&) { return false; }
inline bool carries_stokes(const Grin&) { return true; }
inline const char* povray_lacks(const Grin&) { return "POV-Ray has no curved rays"; }
// The dielectric node of the local index (at the D line: the record has no wavelength).
inline NodeRecord describe(const Grin& m, const Interaction& in, const SurfaceHit& h, const Ray& ray, double) {
    return describe(m.interface_at(h.hit.point, 0.0), in, h, ray, 0.0);
}
inline void validate(const Grin&, const MaterialCheck& c) {
    if (!c.fresnel_tree)
        throw InputError(c.where +
                         ": a gradient-index medium needs the physical mode and the fresnel-tree integrator (or the "
                         "spectral eye pass): its rays are bent by the ray tree's walker");
}

// {"type": "grin", "profile": {"kind": …}, "tolerance": 1e-9, "max_steps": 100000,
//  "shadows": true}
// (docs/grin.md).
inline Grin Grin::read(const JsonReader& r, const std::string&) {
    r.only({"type", "profile", "tolerance", "max_steps", "shadows"});
    Grin m{grin::read_profile(r.child("profile")), grin::Settings{}, Vec3(1, 1, 1), r.boolean("shadows", true)};
    const double tol = r.number("tolerance", 1e-9);
    if (!(tol >= 1e-14 && tol <= 1e-2)) r.fail_at("tolerance", format_value(tol) + " must be in [1e-14, 1e-2]");
    m.settings.abs_tol = m.settings.rel_tol = tol;
    m.settings.max_steps = r.integer("max_steps", 100000, 10, 10000000);
    return m;
}

}  // namespace refract::material
