#include <refract/core/compat.h>

#include <cmath>
#include <limits>

#include <refract/core/hit_search.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/render_stats.h>
#include <refract/core/scene.h>
#include <refract/core/spectrum/cie.h>
#include <refract/geometry/error.h>

namespace refract {

CompatRules::CompatRules(const RenderSettings& s)
    : mode_(s.compat),
      pov_(s.compat == Compat::PovRay),
      adc_(s.pruning_threshold()),
      t_min_(pov_ ? povray::kMinDepth : kEpsilon),
      t_max_(pov_ ? povray::kMaxDistance : std::numeric_limits<double>::infinity()) {}

const char* CompatRules::name(Compat c) { return c == Compat::PovRay ? "povray" : "physical"; }

std::optional<Compat> CompatRules::from_name(const std::string& name) {
    if (name == "physical") return Compat::Physical;
    if (name == "povray") return Compat::PovRay;
    return std::nullopt;
}

std::vector<const Object*> CompatRules::search_order(const Scene& scene) const {
    std::vector<const Object*> order;
    // POV-Ray: the order of the exported scene (validation/pov_export.cpp writes the opaque
    // objects first, then the transparent ones), which is the order in which POV-Ray tests them.
    for (int pass = pov_ ? 0 : 1; pass < 2; ++pass)
        for (const Object& obj : scene.objects)
            if (!pov_ || scene.materials[static_cast<size_t>(obj.material)].is<material::Dielectric>() == (pass == 1))
                order.push_back(&obj);
    return order;
}

Interaction CompatRules::dielectric(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray,
                                    const InteractionContext& c) const {
    const double nominal = nominal_index(m.ior);
    const double ior = c.band_ior > 0 ? c.band_ior : nominal;
    const NodeAt<Vec3> at{ray.dir, h.normal, h.hit.t, h.entering, h.entering ? ior : 1.0 / ior,
                          h.entering ? nominal : 1.0 / nominal};
    const NodeBranches<Vec3> b = dielectric(m, at, m.filter, c.split);
    Interaction n;
    n.reflectance = b.reflectance;
    n.split_mirror = b.split_mirror;
    n.branches = 1;
    if (c.exact) {  // physical mode only (CompatRules::validate)
        // The threshold keeps natural light's weights, so both models walk the same tree.
        const double cos_i = std::fmin(-ray.dir.dot(h.normal), 1.0);
        n.branch[0] = Branch{Ray{h.hit.point, b.dir[0]}, Vec3(1, 1, 1), b.bailout[0]};
        n.mueller[0] = polar::mueller_reflection(cos_i, at.eta);
        if (b.exists[1]) {
            n.branch[1] = Branch{Ray{h.hit.point, b.dir[1]}, m.filter, b.bailout[1]};
            n.mueller[1] = *polar::mueller_transmission(cos_i, at.eta);
            n.branches = 2;
        }
        return n;
    }
    n.branch[0] = Branch{Ray{h.hit.point, b.dir[0]}, b.factor[0], b.bailout[0]};
    if (b.exists[1]) {
        n.branch[1] = Branch{Ray{h.hit.point, b.dir[1]}, b.factor[1], b.bailout[1]};
        n.branches = 2;
    }
    return n;
}

Scatter CompatRules::sample_dielectric(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray,
                                       const InteractionContext& c, Rng& rng) const {
    if (pov_) {  // POV-Ray's node, one branch chosen
        const Interaction in = dielectric(m, h, ray, c);
        const bool refl = in.branches == 1 || rng.uniform() < in.reflectance;
        if (!refl) return Scatter{in.branch[1].ray.dir, m.filter};
        return Scatter{in.branch[0].ray.dir, Vec3(1, 1, 1)};
    }
    const double eta = h.entering ? m.ior : 1.0 / m.ior;
    const DielectricTerms<double> t = dielectric_terms(ray.dir, h.normal, eta, m.reflectance, m.constant_reflectivity);
    // A choice only where the node spawns two branches (DielectricNode::transmits).
    namespace gen = optics::generic;
    if (t.transmits() && !(rng.uniform() < t.R))
        return Scatter{gen::refracted_direction(ray.dir, h.normal, t.cos_i, t.cos_t, eta), m.filter};
    return Scatter{gen::reflect(ray.dir, h.normal), Vec3(1, 1, 1)};
}

Vec3 CompatRules::pigment(const Pigment& m, const Vec3& p) const {
    if (!m.checker) return m.color;
    // 3D checker (POV-Ray `checker`): parity of the sum of the cell indices. A small
    // offset keeps a surface lying on a cell boundary (a floor at y = 0) on one side.
    // Parities are taken on the doubles (no integer conversion to overflow on far hits or
    // tiny cells): odd(v) for a cell index v = floor(...).
    const auto odd = [](double v) { return std::fmod(v, 2.0) != 0.0; };
    const double s = m.checker->size;
    bool k;
    if (pov_) {
        // POV-Ray `checker ... scale s` (pattern.cpp checker_pattern): the point is taken
        // to pattern space by the inverse transform, a product with 1/s, then floor(v + 1e-10).
        const Vec3 q = p * (1.0 / s);
        k = odd(std::floor(q.x() + 1e-10)) != odd(std::floor(q.y() + 1e-10));
        k = k != odd(std::floor(q.z() + 1e-10));
    } else {
        const double e = 1e-9;
        k = odd(std::floor(p.x() / s + e)) != odd(std::floor(p.y() / s + e));
        k = k != odd(std::floor(p.z() / s + e));
    }
    return k ? m.checker->color2 : m.color;
}

std::optional<Vec3> CompatRules::segment_absorption(const SurfaceHit& h, double wavelength_nm) const {
    if (h.entering || pov_) return std::nullopt;
    const spectrum::Absorption* a = absorption(*h.material);
    if (!a) return std::nullopt;
    const double t = h.hit.t;
    if (wavelength_nm > 0) return Vec3::Constant(optics::beer_lambert(a->at(wavelength_nm), t));
    const Vec3& c = a->rgb;
    return Vec3(optics::beer_lambert(c.x(), t), optics::beer_lambert(c.y(), t), optics::beer_lambert(c.z(), t));
}

Vec3 CompatRules::light_transmittance(const HitSearch& search, const Vec3& from, const Vec3& to,
                                      RenderStats& stats) const {
    ++stats.shadow_rays;
    if (pov_) return povray::light_transmittance(search, from, to, stats);
    const Vec3 delta = to - from;
    const double dist = delta.norm();
    return search.shadow_blocker(Ray{from, delta / dist}, kEpsilon, dist, {}, nullptr) ? Vec3(0, 0, 0) : Vec3(1, 1, 1);
}

double CompatRules::dielectric_index(const material::Dielectric& m, double nm) const {
    double n = m.dispersion->n(nm);
    // POV-Ray's law is relative to the interior's ior (single precision there).
    if (m.dispersion->is_povray()) {
        const auto& p = std::get<spectrum::PovRayModel>(m.dispersion->model);
        n = spectrum::povray_index(nominal_index(m.ior), pov_ ? povray::stored_index(p.dispersion) : p.dispersion, nm);
    }
    return n;
}

void CompatRules::spectral_bands(const Scene& scene, SpectralContext& c) const {
    const SpectralSettings& s = scene.settings.spectral;
    const size_t materials = scene.materials.size();
    c.dispersive.assign(materials, 0);
    c.split_bands.assign(materials, {});
    c.shortcut = s.shortcut && !pov_;
    if (pov_) return povray::spectral_bands(scene, c);
    const std::string where = scene.source.empty() ? "scene" : scene.source;
    const spectrum::SpectrumToRGB conv(spectrum::sample_wavelengths(s.sampling, where + ": /render/spectral"),
                                       s.pipeline, spectrum::WhiteBalance::PerChannel, s.light);
    c.wavelengths = conv.wavelengths();
    c.weights = conv.weights();
    c.clip = s.pipeline == spectrum::ColourPipeline::CieRgb;
    std::vector<int> all_bands(c.bands());
    for (size_t b = 0; b < all_bands.size(); ++b) all_bands[b] = static_cast<int>(b);
    c.split_bands.assign(materials, all_bands);
    for (size_t mi = 0; mi < materials; ++mi) c.dispersive[mi] = dispersive(scene.materials[mi]) ? 1 : 0;
}

void CompatRules::validate(const Scene& scene) const {
    if (!pov_) return;
    const std::string f = scene.source.empty() ? std::string("scene") : scene.source;
    if (polarisation_model(scene) == PolarisationModel::Exact)
        throw InputError(f + ": /render/polarisation: \"exact\" has no POV-Ray counterpart (compat \"povray\" is natural light)");
    for (const Material& m : scene.materials)
        if (const char* lacks = povray_lacks(m))
            throw InputError(f + ": material '" + clip_echo(m.name) + "': a \"" +
                             std::visit([](const auto& k) { return std::string(std::decay_t<decltype(k)>::kType); }, m.kind) +
                             "\" material needs the physical mode (" + lacks + ")");
}

}  // namespace refract

namespace refract {

Vec3 pigment_at(const CompatRules& rules, const Pigment& p, const Vec3& point) { return rules.pigment(p, point); }

Interaction material::dielectric_interaction(const CompatRules& rules, const Dielectric& m, const SurfaceHit& h,
                                             const Ray& ray, const InteractionContext& c) {
    return rules.dielectric(m, h, ray, c);
}

Scatter material::sample_dielectric(const CompatRules& rules, const Dielectric& m, const SurfaceHit& h, const Ray& ray,
                                    const InteractionContext& c, Rng& rng) {
    return rules.sample_dielectric(m, h, ray, c, rng);
}

double material::dielectric_band_index(const CompatRules& rules, const Dielectric& m, double nm) {
    return rules.dielectric_index(m, nm);
}

}  // namespace refract
