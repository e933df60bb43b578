#include <refract/core/tracer.h>

#include <refract/core/hit_search.h>
#include <refract/core/integrators/integrator.h>

namespace refract {

SceneTracer::SceneTracer(const Scene& scene, const TraceOptions& options)
    : scene_(scene),
      rules_(scene.settings),
      options_(options),
      search_(std::make_unique<HitSearch>(scene, rules_, options)),
      lighting_(std::make_unique<Lighting>(scene, rules_, *search_)),
      media_(grin::media(scene)),
      camera_basis_(scene.camera.basis()) {
    exact_ = polarisation_model(scene) == PolarisationModel::Exact;
    packets_ = options.packets && !exact_;
    for (const Material& m : scene.materials) {
        absorbing_ = absorbing_ || (rules_.absorbs_segments() && refract::absorption(m) != nullptr);
        packets_ = packets_ && in_packets(m);
    }
}

SceneTracer::~SceneTracer() = default;

namespace {

// The objects inside a medium as the integrator's obstacles: the nearest hit on them
// along each chord, from its very start (HitSearch::first_on). The last hit found is kept:
// the crossing the integrator reports.
class InsideObstacles final : public grin::Obstacles {
public:
    InsideObstacles(const HitSearch& search, const Scene& scene, const grin::Medium& m)
        : search_(search), scene_(scene), medium_(m) {}
    std::optional<grin::ObstacleHit> first(const Vec3& a, const Vec3& b) const override {
        const Vec3 d = b - a;
        const double length = d.norm();
        if (!(length > 0)) return std::nullopt;
        const auto h = search_.first_on(Ray{a, d / length}, length, medium_.inside);
        if (!h) return std::nullopt;
        const int k = static_cast<int>(h->object - scene_.objects.data());
        last = *h;
        return grin::ObstacleHit{h->hit.t / length, k};
    }
    mutable std::optional<SurfaceHit> last;

private:
    const HitSearch& search_;
    const Scene& scene_;
    const grin::Medium& medium_;
};

}  // namespace

grin::Result SceneTracer::curve(const grin::Medium& m, const Ray& ray, double nm, grin::Settings settings,
                                std::optional<SurfaceHit>* inside) const {
    const double lambda_um = (nm > 0 ? nm : spectrum::fraunhofer::D) * 1e-3;
    if (m.inside.empty()) return grin::advance(m.profile, m.region, ray.origin, ray.dir, lambda_um, settings);
    InsideObstacles obstacles(*search_, scene_, m);
    settings.obstacles = &obstacles;
    grin::Result r = grin::advance(m.profile, m.region, ray.origin, ray.dir, lambda_um, settings);
    if (inside && r.status == grin::Status::met_obstacle) *inside = obstacles.last;
    return r;
}

std::optional<SurfaceHit> SceneTracer::through(const grin::Medium& m, Ray& ray, double nm, RenderStats& stats,
                                               Vec3* frame) const {
    grin::Settings settings = m.settings;
    if (frame) {  // the payload's frame is across the ray; one along it (none in practice) takes any across
        const Vec3 across = *frame - frame->dot(ray.dir) * ray.dir;
        settings.frame = across.norm() > 1e-9 ? across : ray.dir.unitOrthogonal();
    }
    std::optional<SurfaceHit> inside;
    const grin::Result r = curve(m, ray, nm, settings, &inside);
    if (frame) *frame = r.exit_frame;
    ++stats.grin_segments;
    stats.grin_evaluations += static_cast<std::uint64_t>(r.evaluations);
    if (r.status == grin::Status::budget_exhausted) {
        ++stats.grin_exhausted;
        return std::nullopt;
    }
    if (r.status == grin::Status::met_obstacle) {
        // A surface inside the medium: its own hit (object, facet, outward normal), at the
        // crossing's point, reached after the curved length along the arrival direction.
        SurfaceHit h = *inside;
        h.hit.t = r.length;
        h.hit.point = r.exit_point;
        h.entering = h.hit.normal.dot(r.exit_dir) < 0;
        h.normal = h.entering ? h.hit.normal : Vec3(-h.hit.normal);
        ray.dir = r.exit_dir;
        return h;
    }
    const Object& o = scene_.objects[static_cast<size_t>(m.object)];
    SurfaceHit h;
    h.hit.t = r.length;
    h.hit.point = r.exit_point;
    h.hit.normal = grin::outward_normal(m.region, r.exit_point);
    h.hit.facet = grin::nearest_face(m.region, r.exit_point);
    h.object = &o;
    h.material = &scene_.materials[static_cast<size_t>(o.material)];
    h.entering = false;  // from inside: the normal on the incident side is the inward one
    h.normal = -h.hit.normal;
    ray.dir = r.exit_dir;
    return h;
}

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
