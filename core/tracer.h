#pragma once
// What every integrator asks of a scene, built once per render: the compatibility policy
// (core/compat.h), the nearest-hit search for one ray and for packets (core/hit_search.h),
// the lights and shadows (core/lighting.h), and the material rules applied at a hit (the
// interaction, Beer–Lambert over a segment, a leaf's light). Integrators differ only in
// how they walk the branches (core/ray_tree.h).
#include <memory>
#include <optional>

#include <refract/core/compat.h>
#include <refract/core/grin/media.h>
#include <refract/core/hit_search.h>
#include <refract/core/lighting.h>
#include <refract/core/render_stats.h>
#include <refract/core/scene.h>

namespace refract {

class SceneTracer {
public:
    // The scene must outlive the tracer, unchanged.
    explicit SceneTracer(const Scene& scene, const TraceOptions& options = {});
    ~SceneTracer();

    const Scene& scene() const { return scene_; }
    const RenderSettings& settings() const { return scene_.settings; }
    const CompatRules& rules() const { return rules_; }
    const TraceOptions& options() const { return options_; }
    const HitSearch& search() const { return *search_; }
    const Lighting& lighting() const { return *lighting_; }

    // The search (core/hit_search.h).
    using LaneHits = HitSearch::LaneHits;
    using LaneOrigins = HitSearch::LaneOrigins;
    std::optional<SurfaceHit> intersect(const Ray& ray, RenderStats& stats, RayOrigin from = {}) const {
        return search_->intersect(ray, stats, from);
    }
    LaneHits intersect_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                             const LaneOrigins& from, RenderStats& stats) const {
        return search_->intersect_lanes(origin, dir, active, from, stats);
    }
    LaneMask escaping_lanes(const LaneOrigins& from, const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                            RenderStats& stats) const {
        return search_->escaping_lanes(from, origin, dir, active, stats);
    }
    static LaneHits lanes_of(const SurfaceHit& h) { return HitSearch::lanes_of(h); }
    SurfaceHit surface_hit(const LaneHits& h, int l) const { return search_->surface_hit(h, l); }
    RayOrigin origin_of(const SurfaceHit& h) const { return search_->origin_of(h); }

    // Whether rays are walked in packets (the wavelength bands of a split, the samples of a
    // pixel): TraceOptions::packets, natural light, and every material in packets (a
    // uniaxial crystal's o and e waves ride one ray at a time).
    // Gradient-index media (core/grin/media.h, docs/grin.md): the medium a ray leaving
    // `from` (none: a root ray) travels in, null when none; and its curved segment there,
    // from the ray's origin to the medium's boundary at wavelength `nm` (0: an RGB ray, the
    // material's D line): the hit there, with the curved length as hit.t and ray.dir turned
    // to the direction it arrives in; none when the step budget ran out (lost light). With
    // `frame` (a Stokes frame vector ⟂ ray.dir): it is parallel-transported along the ray
    // (Rytov's law, core/grin/rytov.h) to the arrival.
    const grin::Medium* medium_of(const Ray& ray, RayOrigin from) const {
        return media_.empty() ? nullptr : grin::medium_of(media_, ray.origin, ray.dir, from.object);
    }
    std::optional<SurfaceHit> through(const grin::Medium& m, Ray& ray, double nm, RenderStats& stats,
                                      Vec3* frame = nullptr) const;
    // The integration behind through(): grin::advance from ray.origin along ray.dir with
    // `settings`, the medium's inside objects (Medium::inside) as its obstacles; with
    // `inside`, the hit on the one met (Status::met_obstacle). `trace` records a curved
    // path by the same call.
    grin::Result curve(const grin::Medium& m, const Ray& ray, double nm, grin::Settings settings,
                       std::optional<SurfaceHit>* inside = nullptr) const;
    bool graded() const { return !media_.empty(); }

    bool packets() const { return packets_; }
    // Whether the render carries exact polarisation (polarisation_model(), core/integrators/integrator.h).
    bool exact() const { return exact_; }
    // The camera's ray through image position (x, y) (Camera::ray, its basis computed once).
    Ray camera_ray(double x, double y) const { return scene_.camera.ray(camera_basis_, x, y); }
    Ray camera_ray(double x, double y, double u, double v) const { return scene_.camera.ray(camera_basis_, x, y, u, v); }
    Vec3 background(const Vec3& dir) const { return scene_.background.radiance(dir); }

    // The interaction at a hit, by the material's rules (core/material.h): leaves (diffuse,
    // emissive) end the branch, mirrors spawn one branch, dielectrics two (reflection,
    // refraction) or one on total internal reflection. `band_ior` > 0: a dielectric's index at
    // one wavelength (spectral tracing) instead of its `ior`; the physical mode uses it for
    // Fresnel and Snell, the POV-Ray mode for the refraction direction and the TIR test only
    // (Fresnel keeps the nominal `ior`). `split`: POV-Ray mode, the band's share of an RGB ray
    // splitting at its first refraction. `wave`, `wavelength_nm`, `adjoint`: what a uniaxial
    // crystal's interaction needs (InteractionContext). Transparent nodes are counted.
    Interaction interact(const SurfaceHit& h, const Ray& ray, RenderStats& stats, double band_ior = 0,
                         bool split = false, biref::Wave wave = biref::Wave::Isotropic, double wavelength_nm = 0,
                         bool adjoint = false) const;
    // The context of an interaction at the render's settings.
    InteractionContext context(double band_ior = 0, bool split = false, biref::Wave wave = biref::Wave::Isotropic,
                               double wavelength_nm = 0, bool adjoint = false) const;

    // Beer–Lambert over the segment that ended at h (CompatRules::segment_absorption).
    std::optional<Vec3> absorption(const SurfaceHit& h, double wavelength_nm) const {
        return rules_.segment_absorption(h, wavelength_nm);
    }
    // Whether any segment can be absorbed (the policy absorbs segments, a material absorbs).
    bool absorbing() const { return absorbing_; }

    // The light a leaf sends back along the ray, by its material's LeafLight: direct
    // lighting of a lit surface, an emitter's colour; none for the kinds that are not leaves.
    Vec3 local_light(const SurfaceHit& h, RenderStats& stats) const;
    Vec3 pigment(const Pigment& p, const Vec3& point) const { return rules_.pigment(p, point); }

    static constexpr double kEpsilon = CompatRules::kEpsilon;  // secondary rays ignore hits closer than this

private:
    const Scene& scene_;
    CompatRules rules_;
    TraceOptions options_;
    std::unique_ptr<HitSearch> search_;
    std::unique_ptr<Lighting> lighting_;
    std::vector<grin::Medium> media_;
    bool absorbing_ = false;
    bool exact_ = false;
    bool packets_ = true;
    Camera::Basis camera_basis_;
};

}  // namespace refract
