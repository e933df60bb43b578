#pragma once
// A uniaxial crystal (core/birefringence.h, docs/birefringence.md) in the air: every ray
// splits into an ordinary and an extraordinary one. The indices of the two rays as
// functions of wavelength; the optic axis (unit, in the scene's frame). Its rays carry
// their o/e wave along the tree, so it needs the fresnel-tree integrator (or the spectral
// eye pass), the physical mode, and one ray at a time (no packets).
#include <string>

#include <refract/core/material_rules.h>

namespace refract::material {

struct Uniaxial {
    spectrum::Dispersion ordinary, extraordinary;
    Vec3 optic_axis{0, 0, 1};
    Vec3 filter{1, 1, 1};  // transmitted colour per crossing
    std::string crystal;   // the catalogue crystal, or empty
    // The medium at wavelength λ (nm); at the sodium D line when λ <= 0 (an RGB ray).
    double n_o(double lambda_nm) const { return ordinary.n(lambda_nm > 0 ? lambda_nm : spectrum::fraunhofer::D); }
    double n_e(double lambda_nm) const { return extraordinary.n(lambda_nm > 0 ? lambda_nm : spectrum::fraunhofer::D); }
    biref::Medium medium(double lambda_nm) const { return {n_o(lambda_nm), n_e(lambda_nm), optic_axis}; }

    static constexpr const char* kType = "uniaxial";
    static Uniaxial read(const JsonReader& r, const std::string& file);
};

// biref::split_at_interface's beams. Natural light: each branch's factor is its power for
// unpolarised incidence (a crystal wave: the power of that wave) times the filter on
// transmission; exact polarisation: its Mueller matrix, for an eye pass (c.adjoint) the one
// of the reversed path, light arriving along the child's ray and leaving along the
// parent's (biref::reversed, reciprocity). (core/interaction_uniaxial.cpp)
Interaction uniaxial_interaction(const Uniaxial& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);

inline Interaction interact(const Uniaxial& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return uniaxial_interaction(m, h, ray, c);
}
inline LeafLight leaf_light(const Uniaxial&) { return {}; }
inline StochasticRole stochastic_role(const Uniaxial&) { return StochasticRole::Branches; }
// Its first branch (validate refuses the stochastic integrator; this is for completeness).
inline std::optional<Scatter> sample(const Uniaxial& m, const SurfaceHit& h, const Ray& ray,
                                     const InteractionContext& c, Rng&) {
    const Interaction in = uniaxial_interaction(m, h, ray, c);
    if (in.branches == 0) return std::nullopt;
    return Scatter{in.branch[0].ray.dir, in.branch[0].factor};
}
inline const Vec3* shadow_filter(const Uniaxial& m) { return &m.filter; }
inline bool casts_shadow(const Uniaxial&) { return true; }
// Its two indices depend on the wavelength: it always splits (the interaction takes λ).
inline bool dispersive(const Uniaxial&) { return true; }
inline double band_index(const Uniaxial& m, double nm, const CompatRules&) { return m.n_o(nm); }
inline const spectrum::Absorption* absorption(const Uniaxial&) { return nullptr; }
inline bool in_packets(const Uniaxial&) { return false; }
inline bool carries_stokes(const Uniaxial&) { return true; }
inline const char* povray_lacks(const Uniaxial&) { return "POV-Ray has no birefringence: a uniaxial crystal's rays carry their o/e wave along the ray tree"; }
// Double refraction, or total internal reflection when no beam is transmitted.
inline NodeRecord describe(const Uniaxial&, const Interaction& in, const SurfaceHit&, const Ray&, double) {
    int transmitted = 0;
    for (int b = 0; b < in.branches; ++b) transmitted += in.transmitted[static_cast<size_t>(b)] ? 1 : 0;
    NodeRecord r{transmitted == 0 ? "total internal reflection" : "double refraction"};
    r.R = in.reflectance;
    return r;
}
inline void validate(const Uniaxial&, const MaterialCheck& c) {
    if (!c.fresnel_tree)
        throw InputError(c.where +
                         ": a uniaxial crystal needs the physical mode and the fresnel-tree integrator (or the "
                         "spectral eye pass): its rays carry their o/e wave along the ray tree");
}

// {"type": "uniaxial", "crystal": "calcite" | "ordinary": <dispersion>, "extraordinary":
//  <dispersion>, "optic_axis": [x, y, z], "filter": [r, g, b]} (docs/birefringence.md).
inline Uniaxial Uniaxial::read(const JsonReader& r, const std::string& file) {
    r.only({"type", "crystal", "ordinary", "extraordinary", "optic_axis", "filter"});
    Uniaxial m{spectrum::Dispersion{}, spectrum::Dispersion{}, Vec3(0, 0, 1), Vec3(1, 1, 1), ""};
    if (r.has("crystal")) {
        if (r.has("ordinary") || r.has("extraordinary"))
            r.fail_at("crystal", "give either a catalogue \"crystal\" or \"ordinary\" and \"extraordinary\"");
        m.crystal = r.string("crystal");
        const auto c = spectrum::uniaxial_crystal(m.crystal);
        if (!c) {
            std::string known;
            for (const auto& n : spectrum::uniaxial_crystal_names()) known += (known.empty() ? "" : ", ") + n;
            r.fail_at("crystal", "unknown crystal '" + clip_echo(m.crystal) + "' (" + known + ")");
        }
        m.ordinary = c->ordinary;
        m.extraordinary = c->extraordinary;
    } else {
        if (!r.has("ordinary") || !r.has("extraordinary"))
            r.fail_at("type", "a uniaxial material needs \"crystal\", or both \"ordinary\" and \"extraordinary\"");
        m.ordinary = spectrum::parse_dispersion(r.raw("ordinary"), file + ": " + r.path_of("ordinary"));
        m.extraordinary = spectrum::parse_dispersion(r.raw("extraordinary"), file + ": " + r.path_of("extraordinary"));
        if (m.ordinary.is_povray() || m.extraordinary.is_povray())
            r.fail_at("ordinary", "POV-Ray's dispersion law is not supported for a uniaxial crystal");
    }
    const auto axis = unit_vector(r.vec3("optic_axis", m.optic_axis));
    if (!axis) r.fail_at("optic_axis", "must be a non-zero vector");
    m.optic_axis = *axis;
    m.filter = r.colour("filter", m.filter);
    return m;
}

}  // namespace refract::material
