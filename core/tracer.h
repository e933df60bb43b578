#pragma once
// The scene kernel shared by every integrator: nearest hit, background, local shading of
// opaque surfaces (the leaves of the ray tree), and the branches a surface spawns (the
// nodes). Integrators differ only in how they walk the branches.
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/facet_graph.h"
#include "geometry/mesh_accel.h"
#include "geometry/object_bvh.h"
#include "geometry/sphere_set.h"

#include "core/interaction.h"
#include "core/render.h"
#include "core/scene.h"

namespace refract {

class SceneTracer {
public:
    // Builds the search structures: Embree's BVH for each mesh of kMinTriangles or more
    // (geometry/mesh_accel.h), and a BVH over the objects (geometry/object_bvh.h) when the
    // search cost, a sphere counting 1/kSpheresPerObject (they are tested together, eight at
    // a time) and any other object 1, reaches kBvhMinObjects; below it the spheres are
    // tested as a set (geometry/sphere_set.h) and the rest one by one. The scene must
    // outlive the tracer, unchanged.
    explicit SceneTracer(const Scene& scene);
    ~SceneTracer();
    // The cross-overs measured by `refract bench --objects` (docs/performance.md).
    static constexpr size_t kBvhMinObjects = 64, kSpheresPerObject = 8;
    static bool uses_object_bvh(const Scene& scene);
    // Plane sets given facet-local intersection (its facet polygons cost O(planes²) to build).
    static constexpr size_t kMinFacetPlanes = 8, kMaxFacetPlanes = 4096;

    const Scene& scene() const { return scene_; }
    const RenderSettings& settings() const { return scene_.settings; }

    // The nearest hit. A ray leaving a facet of a convex plane set (`from`, the hit it
    // leaves) is decided from the planes around that facet and the facet it is guessed to
    // leave through (geometry/facet_graph.h), else by the full plane loop: the same hit to
    // the last bit. Guesses are remembered per thread, per starting facet and direction:
    // the 31 rays of a spectral split cross mostly the same facets, one after another.
    std::optional<SurfaceHit> intersect(const Ray& ray, RenderStats& stats, RayOrigin from = {}) const;
    // The nearest hits of kLanes rays at once (a packet, geometry/lanes.h), each leaving the
    // object `from_object[lane]` (-1: none) from its facet: in every lane of `active`,
    // intersect()'s answer bit for bit (counted as one segment per lane). Spheres and planes
    // are tested on all lanes together, and so is a plane set by the lanes that leave one of
    // its facets (FacetGraph::intersect_lanes); other shapes, and scenes searched through the
    // object BVH, lane by lane.
    struct LaneHits {
        LaneMask hit;
        Lanes t;
        LaneVec3 point, normal;  // normal on the incident side
        LaneMask entering;
        std::array<const Object*, kLanes> object{};
        std::array<std::int32_t, kLanes> facet{};
    };
    using LaneIds = std::array<std::int32_t, kLanes>;
    LaneHits intersect_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                             const LaneIds& from_object, const LaneIds& from_facet, RenderStats& stats) const;
    // The lanes whose rays, leaving object `object[lane]` (an index in Scene::objects) from its
    // surface at `origin`, meet nothing: where the scene holds that one sphere and nothing
    // else, and the ray moves away from its centre (as intersect() decides it). Counted as
    // the segments intersect() would have traced.
    LaneMask escaping_lanes(const LaneIds& object, const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                            RenderStats& stats) const;
    // The same hit in every lane.
    static LaneHits lanes_of(const SurfaceHit& h);
    // Lane l of `h` as intersect() returns it.
    SurfaceHit surface_hit(const LaneHits& h, int l) const;
    // The RayOrigin of the branches leaving hit h.
    RayOrigin origin_of(const SurfaceHit& h) const {
        return {static_cast<std::int32_t>(h.object - scene_.objects.data()), h.hit.facet};
    }
    // Facet-local intersection on or off, for every tracer of the process (on by default;
    // tests and benchmarks compare the two).
    static void set_facet_local(bool on);
    static bool facet_local();
    // Packets of rays (geometry/lanes.h) for every tracer of the process: the wavelength
    // bands of a split in the spectral eye pass and the light pass (RayTreeWalkerT::walk_lanes),
    // the samples of a pixel in the stochastic integrator (stochastic_radiance_samples). On by
    // default; off: one ray at a time, the same images to the last bit.
    static void set_lanes(bool on);
    static bool lanes();
    // Whether this scene's band rays can be walked in packets: natural light, and no uniaxial
    // crystal (whose o and e waves the packets do not carry).
    bool lanes_apply() const { return lanes_apply_; }
    // The camera's ray through image position (x, y) (Camera::ray, its basis computed once).
    Ray camera_ray(double x, double y) const { return scene_.camera.ray(camera_basis_, x, y); }
    Vec3 background(const Vec3& dir) const;

    // The interaction at a hit (core/interaction.h): leaves (diffuse, emissive) end the
    // branch, mirrors spawn one branch, dielectrics two (reflection, refraction) or one on
    // total internal reflection. `band_ior` > 0: a dielectric's index at one wavelength
    // (spectral tracing) instead of its `ior`; the physical mode uses it for Fresnel and
    // Snell, the POV-Ray mode for the refraction direction and the TIR test only (Fresnel
    // keeps the nominal `ior`). `split`: POV-Ray mode, the band's share of an RGB ray
    // splitting at its first refraction.
    // `wave`, `wavelength_nm`, `adjoint`: what a uniaxial crystal's interaction needs
    // (InteractionContext).
    Interaction interact(const SurfaceHit& h, const Ray& ray, RenderStats& stats, double band_ior = 0,
                         bool split = false, biref::Wave wave = biref::Wave::Isotropic, double wavelength_nm = 0,
                         bool adjoint = false) const;

    // Beer–Lambert over the segment that ended at h from inside an absorbing dielectric
    // (physical mode): exp(−α t) per channel, at `wavelength_nm` (all channels alike) or,
    // when 0, with the material's RGB coefficients. Empty when nothing is absorbed. A
    // segment lies in the material of the object it leaves, so absorbing solids must not
    // hold other objects. POV-Ray mode fades the way POV-Ray does, in the interaction.
    std::optional<Vec3> absorption(const SurfaceHit& h, double wavelength_nm) const;
    // Whether any segment can be absorbed (physical mode, a dielectric with absorption).
    bool absorbing() const { return absorbing_; }

    // The light a leaf sends back along the ray: direct lighting of a diffuse (or, in the
    // tree integrators, Lambertian) surface, an emitter's colour; 0 for other kinds.
    Vec3 local_light(const SurfaceHit& h, RenderStats& stats) const;

    // Direct lighting of an opaque surface by the point lights, POV-Ray convention:
    // ambient·pigment + Σ diffuse·pigment·light·max(0, N·L)·shadow.
    Vec3 shade_diffuse(const SurfaceHit& h, const Pigment& pigment, double diffuse, double ambient,
                       RenderStats& stats) const;
    Vec3 pigment(const Pigment& p, const Vec3& point) const;

    static constexpr double kEpsilon = 1e-6;  // secondary rays ignore hits closer than this

    // POV-Ray 3.7 constants used by the compat mode (source/backend: configbackend.h,
    // render/trace.cpp): hits are kept for MIN_ISECT_DEPTH <= t < MAX_DISTANCE; shadow
    // rays ignore hits within SMALL_TOLERANCE / SHADOW_TOLERANCE of either end; the
    // greyscale of a colour weighs r, g, b by RED/GREEN/BLUE_INTENSITY.
    static constexpr double kPovMinDepth = 1e-4;
    static constexpr double kPovMaxDistance = 1e7;
    static constexpr double kPovShadowTolerance = 1e-3;
    static inline const Vec3 kPovGreyscale{0.297, 0.589, 0.114};

private:
    // The nearest hit over the objects (index into order_) for which `use(k)` holds, with
    // t in (t_min, t_max); on an exact tie the object first in order_.
    struct Nearest {
        Hit hit;
        size_t k;
    };
    // `from_k`, `from_facet`: the order_ entry and facet the ray leaves (-1: none), asked
    // through intersect_from.
    // The spheres of a search tested together (geometry/sphere_set.h), the other objects one
    // by one: order_ index of each sphere of `set`, its index in `set` per order_ entry
    // (SIZE_MAX: none) and the order_ indices of the rest, in order.
    struct SphereGroup {
        SphereSet set;
        std::vector<std::size_t> order, index, rest;
    };
    // `group`: the spheres to test together (those for which `use` holds; null or too few:
    // every object one by one). Outside the object BVH.
    template <class Use>
    std::optional<Nearest> nearest(const Ray& ray, double t_min, double t_max, Use&& use, std::size_t from_k = SIZE_MAX,
                                   int from_facet = -1, RenderStats* stats = nullptr,
                                   const SphereGroup* group = nullptr) const;
    std::optional<Hit> intersect_object(size_t k, const Ray& ray, double t_min, double t_max) const;
    // The same for the object the ray leaves, from its facet `from_facet` (a sphere: none
    // when the ray moves away from its centre).
    std::optional<Hit> intersect_from(size_t k, int from_facet, const Ray& ray, double t_min, double t_max,
                                      RenderStats& stats) const;
    Vec3 light_transmittance(const Vec3& from, const Vec3& to, RenderStats& stats) const;
    Vec3 light_transmittance_pov(const Vec3& from, const Vec3& to, RenderStats& stats) const;
    const Scene& scene_;
    // The order in which intersect() tests the objects; a hit replaces the best one only
    // when strictly nearer, so on an exact tie (coincident surfaces) the first one wins.
    std::vector<const Object*> order_;
    std::vector<std::unique_ptr<MeshAccel>> mesh_accel_;  // per entry of order_, null when unused
    std::optional<ObjectBvh> bvh_;                         // over order_'s indices
    // The spheres tested together (from kMinSphereSet of them, without the BVH): all of them
    // for intersect(), those that cast shadows for the shadow rays.
    static constexpr std::size_t kMinSphereSet = 2;
    std::optional<SphereGroup> spheres_, shadow_spheres_;
    std::vector<std::unique_ptr<FacetGraph>> facet_graph_;  // per entry of order_: bounded plane sets
    std::vector<std::int32_t> facet_base_;                  // per entry of order_: first id in the guess cache
    std::vector<std::size_t> order_of_;                     // Scene::objects index → order_ index
    std::size_t facet_ids_ = 0;
    std::uint64_t id_ = 0;                                  // this tracer, for the per-thread guesses
    bool absorbing_ = false;
    bool lanes_apply_ = true;
    Camera::Basis camera_basis_;
};

}  // namespace refract
