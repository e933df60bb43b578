#pragma once
// A smooth transparent interface with the surrounding air: reflection and refraction by
// its reflectance model (exact Fresnel, one polarisation, Schlick, or a constant ks), a
// filter colour per crossing, an optional dispersion (the index as a function of the
// wavelength) and Beer–Lambert absorption inside. Its node is the policy's
// (CompatRules::dielectric: the physical node of core/interaction.h, or POV-Ray's).
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include <refract/core/material_rules.h>
#include <refract/core/spectrum/refractiveindex_info.h>
#include <refract/geometry/error.h>

namespace refract::material {

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

    static constexpr const char* kType = "dielectric";
    static Dielectric read(const JsonReader& r, const std::string& file);
};

// The policy's node and sampled branch (core/compat.cpp).
Interaction dielectric_interaction(const CompatRules& rules, const Dielectric& m, const SurfaceHit& h, const Ray& ray,
                                   const InteractionContext& c);
Scatter sample_dielectric(const CompatRules& rules, const Dielectric& m, const SurfaceHit& h, const Ray& ray,
                          const InteractionContext& c, Rng& rng);
// Its index at wavelength λ (nm) when dispersive, under the policy (core/compat.cpp).
double dielectric_band_index(const CompatRules& rules, const Dielectric& m, double nm);

inline Interaction interact(const Dielectric& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return dielectric_interaction(*c.rules, m, h, ray, c);
}
inline LeafLight leaf_light(const Dielectric&) { return {}; }
inline StochasticRole stochastic_role(const Dielectric&) { return StochasticRole::Branches; }
inline std::optional<Scatter> sample(const Dielectric& m, const SurfaceHit& h, const Ray& ray,
                                     const InteractionContext& c, Rng& rng) {
    return sample_dielectric(*c.rules, m, h, ray, c, rng);
}
inline const Vec3* shadow_filter(const Dielectric& m) { return &m.filter; }
inline bool casts_shadow(const Dielectric&) { return true; }
inline bool dispersive(const Dielectric& m) { return m.dispersion.has_value(); }
inline double band_index(const Dielectric& m, double nm, const CompatRules& rules) {
    return m.dispersion ? dielectric_band_index(rules, m, nm) : 0.0;
}
inline const spectrum::Absorption* absorption(const Dielectric& m) { return m.absorption ? &*m.absorption : nullptr; }
inline bool in_packets(const Dielectric&) { return true; }
// Exact polarisation needs the amplitudes: the Fresnel reflectance.
inline bool carries_stokes(const Dielectric& m) { return m.reflectance == ReflectanceModel::Fresnel; }
inline const char* povray_lacks(const Dielectric&) { return nullptr; }
// The node's relative index and cosine (at the material's own ior or the band's) and its
// Fresnel terms (none: it reflects totally), as `refract trace` records them.
struct NodeFresnel {
    double eta, cos_i;
    std::optional<optics::FresnelTerms> terms;
};
inline NodeFresnel node_fresnel(const Dielectric& m, const SurfaceHit& h, const Vec3& dir, double band_ior) {
    const double ior = band_ior > 0 ? band_ior : m.ior;
    NodeFresnel n{h.entering ? ior : 1.0 / ior, std::fmin(-dir.dot(h.normal), 1.0), std::nullopt};
    n.terms = optics::fresnel(n.cos_i, n.eta);
    return n;
}
// The node's relative index, cosines and Fresnel reflectances (node_fresnel), and whether
// it reflected totally.
inline NodeRecord describe(const Dielectric& m, const Interaction& in, const SurfaceHit& h, const Ray& ray,
                           double band_ior) {
    NodeRecord r;
    r.dielectric = true;
    const NodeFresnel n = node_fresnel(m, h, ray.dir, band_ior);
    r.eta = n.eta;
    r.cos_i = n.cos_i;
    r.R = in.reflectance;
    if (const auto& f = n.terms) {
        r.Rs = f->Rs;
        r.Rp = f->Rp;
        r.cos_t = f->cos_t;
        r.event = in.branches == 2 ? "reflection and refraction" : "reflection only";
    } else {
        r.Rs = r.Rp = 1.0;
        r.event = "total internal reflection";
    }
    return r;
}
inline void validate(const Dielectric& m, const MaterialCheck& c) {
    if (!(m.ior > 0 && std::isfinite(m.ior))) throw InputError(c.where + ": ior must be a finite number > 0");
    if (c.exact && !carries_stokes(m))
        throw InputError(c.where + ": \"exact\" polarisation needs \"reflectance\": \"fresnel\" (the amplitudes)");
}

inline Dielectric Dielectric::read(const JsonReader& r, const std::string& file) {
    r.only({"type", "ior", "reflectance", "reflectivity", "filter", "dispersion", "absorption"});
    Dielectric m;
    m.ior = r.number("ior", 1.5);
    if (!(m.ior > 0)) r.fail_at("ior", "must be > 0 (got " + std::to_string(m.ior) + ")");
    const std::string model = r.string("reflectance", "fresnel");
    static const std::map<std::string, ReflectanceModel> models{
        {"constant", ReflectanceModel::Constant}, {"fresnel", ReflectanceModel::Fresnel},
        {"fresnel-s", ReflectanceModel::FresnelS}, {"fresnel-p", ReflectanceModel::FresnelP},
        {"schlick", ReflectanceModel::Schlick}};
    const auto it = models.find(model);
    if (it == models.end())
        r.fail_at("reflectance", "unknown model '" + clip_echo(model) + "' (constant, fresnel, fresnel-s, fresnel-p, schlick)");
    m.reflectance = it->second;
    if (m.reflectance == ReflectanceModel::Constant) {
        m.constant_reflectivity = r.number("reflectivity");
        if (m.constant_reflectivity < 0 || m.constant_reflectivity > 1) r.fail_at("reflectivity", "must be in [0, 1]");
    } else if (r.has("reflectivity")) {
        r.fail_at("reflectivity", "only with \"reflectance\": \"constant\"");
    }
    m.filter = r.colour("filter", m.filter);
    // A refractiveindex.info file (core/spectrum/refractiveindex_info.h) gives the index and,
    // with k, the absorption: then an "absorption" of the scene's own contradicts it.
    std::optional<spectrum::Absorption> file_absorption;
    if (r.has("dispersion")) {
        const nlohmann::json& d = r.raw("dispersion");
        const std::string where = file + ": " + r.path_of("dispersion");
        if (d.is_object() && d.contains("file")) {
            auto c = spectrum::read_dispersion_file(d, file, where);
            m.dispersion = std::move(c.dispersion);
            file_absorption = std::move(c.absorption);
        } else {
            m.dispersion = spectrum::parse_dispersion(d, where);
        }
        // One index: the dispersion model's. A stated `ior` must agree with it: exactly for
        // POV-Ray's law (whose own ior is the interior's), to 5e-4 otherwise (a rounded n_d).
        const double nominal = m.dispersion->nominal();
        const double tolerance = m.dispersion->is_povray() ? 0.0 : 5e-4;
        if (r.has("ior") && !(std::fabs(m.ior - nominal) <= tolerance))
            r.fail_at("ior", format_value(m.ior) + " contradicts \"dispersion\", whose nominal index is " +
                                 format_value(nominal) + (tolerance > 0 ? " (allowed difference 5e-4)" : "") +
                                 "; give one or make them agree");
        m.ior = nominal;
    }
    if (r.has("absorption") && file_absorption)
        r.fail_at("absorption", "the dispersion file gives k (" + file_absorption->label + "); give one");
    if (r.has("absorption"))
        m.absorption = spectrum::parse_absorption(r.raw("absorption"), file + ": " + r.path_of("absorption"));
    else
        m.absorption = std::move(file_absorption);
    return m;
}

}  // namespace refract::material
