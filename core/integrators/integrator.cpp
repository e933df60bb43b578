#include <refract/core/integrators/integrator.h>

#include <refract/core/integrators/spectral.h>
#include <refract/geometry/error.h>

namespace refract {

namespace {

// The integrators: name in scene files, factory, and what each can do.
struct Row {
    IntegratorKind kind;
    const char* name;
    std::unique_ptr<Integrator> (*make)(const SceneTracer&, const SpectralContext*);
    bool spectral;  // walks the spectral pass (a split at the first dispersive hit)
    bool exact;     // carries exact polarisation (Stokes vectors)
    bool crystal;   // carries a uniaxial crystal's o/e waves along the tree
    const char* spectral_why;  // why not, when it does not
};
const Row kTable[] = {
    {IntegratorKind::Whitted, "whitted", whitted_integrator, true, false, false, ""},
    {IntegratorKind::FresnelTree, "fresnel-tree", fresnel_tree_integrator, true, true, true, ""},
    {IntegratorKind::Stochastic, "stochastic", stochastic_integrator, false, false, false,
     "it samples one path per ray and has no spectral pass"},
};

const Row& row(IntegratorKind k) {
    for (const Row& r : kTable)
        if (r.kind == k) return r;
    return kTable[0];
}

}  // namespace

std::vector<std::string> integrator_names() {
    std::vector<std::string> n;
    for (const Row& r : kTable) n.emplace_back(r.name);
    return n;
}

std::optional<IntegratorKind> integrator_of(const std::string& name) {
    for (const Row& r : kTable)
        if (name == r.name) return r.kind;
    return std::nullopt;
}

const char* integrator_name(IntegratorKind kind) { return row(kind).name; }

void validate_integrator(const Scene& scene) {
    const std::string f = scene.source.empty() ? std::string("scene") : scene.source;
    const RenderSettings& s = scene.settings;
    const Row& r = row(s.integrator);
    if (s.spectral.enabled && !r.spectral)
        throw InputError(f + ": /render/integrator: \"" + r.name + "\" cannot render a spectral pass (render.spectral, "
                             "or a dispersive material): " + r.spectral_why + "; use \"fresnel-tree\"");
    if (polarisation_model(scene) == PolarisationModel::Exact && !r.exact)
        throw InputError(f + ": /render/polarisation: \"exact\" needs the fresnel-tree integrator (or the spectral eye pass)");
}

PolarisationModel polarisation_model(const Scene& scene) {
    const RenderSettings& s = scene.settings;
    if (s.requested_polarisation) return *s.requested_polarisation;
    if (s.compat != Compat::Physical || !row(s.integrator).exact) return PolarisationModel::Natural;
    for (const Material& m : scene.materials)
        if (!carries_stokes(m)) return PolarisationModel::Natural;
    return PolarisationModel::Exact;
}

std::unique_ptr<Integrator> make_integrator(const SceneTracer& tracer, const SpectralContext* spectral) {
    return row(tracer.settings().integrator).make(tracer, spectral);
}

StokesRGB Integrator::pixel_stokes(int, int, RenderStats&, LinearPolarisation&) const {
    throw InputError("exact polarisation needs the fresnel-tree integrator");
}

Ray Integrator::sample_ray(int i, int j, int k, Rng& rng) const {
    const Scene& scene = tracer_.scene();
    const RenderSettings& s = scene.settings;
    const std::uint64_t pixel = static_cast<std::uint64_t>(j) * scene.camera.width + i;
    rng = Rng(s.seed, pixel, static_cast<std::uint64_t>(k));
    double x = i + 0.5, y = j + 0.5;
    if (s.jitter) {
        x = i + rng.uniform();
        y = j + rng.uniform();
    }
    if (scene.camera.thin_lens()) {  // a lens point per sample, from the sample's stream
        const double u = rng.uniform(), v = rng.uniform();
        return tracer_.camera_ray(x, y, u, v);
    }
    return tracer_.camera_ray(x, y);
}

}  // namespace refract
