#include <refract/core/tracer.h>

#include <refract/core/integrators/integrator.h>

namespace refract {

SceneTracer::SceneTracer(const Scene& scene, const TraceOptions& options)
    : scene_(scene),
      rules_(scene.settings),
      options_(options),
      search_(std::make_unique<HitSearch>(scene, rules_, options)),
      lighting_(std::make_unique<Lighting>(scene, rules_, *search_)),
      camera_basis_(scene.camera.basis()) {
    exact_ = polarisation_model(scene) == PolarisationModel::Exact;
    packets_ = options.packets && !exact_;
    for (const Material& m : scene.materials) {
        absorbing_ = absorbing_ || (rules_.absorbs_segments() && refract::absorption(m) != nullptr);
        packets_ = packets_ && in_packets(m);
    }
}

SceneTracer::~SceneTracer() = default;

InteractionContext SceneTracer::context(double band_ior, bool split, biref::Wave wave, double wavelength_nm,
                                        bool adjoint) const {
    InteractionContext c;
    c.rules = &rules_;
    c.band_ior = band_ior;
    c.split = split;
    c.exact = exact_;
    c.wave = wave;
    c.wavelength_nm = wavelength_nm;
    c.adjoint = adjoint;
    return c;
}

Interaction SceneTracer::interact(const SurfaceHit& h, const Ray& ray, RenderStats& stats, double band_ior, bool split,
                                  biref::Wave wave, double wavelength_nm, bool adjoint) const {
    if (transparent(*h.material)) ++stats.tree_nodes;
    return refract::interact(*h.material, h, ray, context(band_ior, split, wave, wavelength_nm, adjoint));
}

Vec3 SceneTracer::local_light(const SurfaceHit& h, RenderStats& stats) const {
    return lighting_->leaf(h, leaf_light(*h.material), stats);
}

}  // namespace refract
