#pragma once
// The nearest-hit search of a scene, for one ray and for packets of kLanes rays: Embree's
// BVH for each large mesh (geometry/mesh_accel.h), the scene's spheres tested together
// (geometry/sphere_set.h), facet-local intersection for rays leaving a facet of a convex
// plane set (geometry/facet_graph.h), and a BVH over the objects when the scene is large
// (geometry/object_bvh.h). Whatever the structure, the answer is the in-order search's to
// the last bit: objects are asked in the policy's search order (CompatRules::search_order)
// and a hit replaces the best only when strictly nearer, so on an exact tie the first wins.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <refract/core/compat.h>
#include <refract/core/compat/povray_mesh.h>
#include <refract/core/interaction.h>
#include <refract/core/render_stats.h>
#include <refract/core/scene.h>
#include <refract/core/trace_options.h>
#include <refract/geometry/facet_graph.h>
#include <refract/geometry/mesh_accel.h>
#include <refract/geometry/object_bvh.h>
#include <refract/geometry/sphere_set.h>

namespace refract {

class HitSearch {
public:
    // The scene and the rules must outlive the search, unchanged.
    HitSearch(const Scene& scene, const CompatRules& rules, const TraceOptions& options);
    ~HitSearch();
    const Scene& scene() const { return scene_; }

    // The cross-overs measured by `refract bench --objects` (docs/performance.md): the BVH
    // over objects from a search cost of kBvhMinObjects, a sphere counting 1/kSpheresPerObject
    // (they are tested together, eight at a time) and any other object 1.
    static constexpr size_t kBvhMinObjects = 64, kSpheresPerObject = 8;
    static bool uses_object_bvh(const Scene& scene);
    // Plane sets given facet-local intersection (its facet polygons cost O(planes²) to build).
    static constexpr size_t kMinFacetPlanes = 8, kMaxFacetPlanes = 4096;

    // The nearest hit of a ray leaving hit `from` (none: a camera ray, a photon). A ray
    // leaving a facet of a convex plane set is decided from the planes around that facet
    // and the facet it is guessed to leave through, else by the full plane loop: the same
    // hit to the last bit. Guesses are remembered per thread, per starting facet and
    // direction: the 31 rays of a spectral split cross mostly the same facets.
    std::optional<SurfaceHit> intersect(const Ray& ray, RenderStats& stats, RayOrigin from = {}) const;

    // The nearest hits of kLanes rays at once, each leaving `from[lane]`: in every lane of
    // `active`, intersect()'s answer bit for bit (counted as one segment per lane). Spheres
    // and planes are tested on all lanes together, and so is a plane set by the lanes that
    // leave one of its facets (FacetGraph::intersect_lanes); other shapes, and scenes
    // searched through the object BVH, lane by lane.
    struct LaneHits {
        LaneMask hit;
        Lanes t;
        LaneVec3 point, normal;  // normal on the incident side
        LaneMask entering;
        LaneMask inverted;  // SurfaceHit::inverted per lane (entering is then the list's)
        std::array<const Object*, kLanes> object{};
        std::array<std::int32_t, kLanes> facet{};
    };
    using LaneOrigins = std::array<RayOrigin, kLanes>;
    LaneHits intersect_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                             const LaneOrigins& from, RenderStats& stats) const;
    // The lanes whose rays, leaving `from[lane]` at `origin`, meet nothing: where the scene
    // holds one sphere and nothing else, and the ray moves away from its centre (as
    // intersect() decides it). Counted as the segments intersect() would have traced.
    LaneMask escaping_lanes(const LaneOrigins& from, const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                            RenderStats& stats) const;
    // The same hit in every lane; lane l of `h` as intersect() returns it.
    static LaneHits lanes_of(const SurfaceHit& h);
    SurfaceHit surface_hit(const LaneHits& h, int l) const;
    // The RayOrigin of the branches leaving hit h.
    RayOrigin origin_of(const SurfaceHit& h) const {
        return {static_cast<std::int32_t>(h.object - scene_.objects.data()), h.hit.facet, h.inverted};
    }

    // The nearest hit of a segment of `length` along unit ray.dir on the objects `objects`
    // (indices into Scene::objects) with 0 ≤ t ≤ length: no t_min, since the segment's start
    // may lie any distance from a surface (the chords of a curved ray, SceneTracer::curve);
    // otherwise as intersect() reports a hit (normal on the incident side).
    std::optional<SurfaceHit> first_on(const Ray& ray, double length, const std::vector<int>& objects) const;

    // A shadow ray's nearest blocker with t_min < t < t_max, leaving `from` (none: a point
    // on an opaque surface): the objects that cast shadows (emitters do not, as POV-Ray's
    // no_shadow highlights). `stats`: where facet-local segments are counted (null: not).
    struct Blocker {
        Hit hit;
        const Object* object;
    };
    std::optional<Blocker> shadow_blocker(const Ray& ray, double t_min, double t_max, RayOrigin from,
                                          RenderStats* stats) const;

private:
    // The nearest hit over the objects (index into order_) for which `use(k)` holds, with
    // t in (t_min, t_max); on an exact tie the object first in order_.
    struct Nearest {
        Hit hit;
        size_t k;
    };
    // The spheres of a search tested together, the other objects one by one: order_ index
    // of each sphere of `set`, its index in `set` per order_ entry (SIZE_MAX: none) and the
    // order_ indices of the rest, in order.
    struct SphereGroup {
        SphereSet set;
        std::vector<std::size_t> order, index, rest;
    };
    // `from_k`, `from_facet`: the order_ entry and facet the ray leaves (-1: none), asked
    // through intersect_from. `group`: the spheres to test together (null: every object one
    // by one). Outside the object BVH.
    template <class Use>
    std::optional<Nearest> nearest(const Ray& ray, double t_min, double t_max, Use&& use, std::size_t from_k = SIZE_MAX,
                                   int from_facet = -1, RenderStats* stats = nullptr,
                                   const SphereGroup* group = nullptr) const;
    std::optional<Hit> intersect_object(size_t k, const Ray& ray, double t_min, double t_max) const;
    // Compat "povray" (CompatRules::interior_lists): POV-Ray decides whether a ray enters or
    // leaves a dielectric by the ray's interior list, which only its refractions change, and
    // refract by the outward normal. The two part after the ray crossed a non-convex mesh
    // closer than t_min (a ray refracted out near a reflex edge that re-enters within 1e-4
    // and next meets the mesh from inside: for POV-Ray, still an entry). Whether, at a hit on
    // order_ entry k (a dielectric mesh), the list's decision is the normal's flipped: an odd
    // number of crossings of k in (0, t_min) (povray::Mesh::crossings), the facet the ray
    // leaves excepted, or the difference the ray carries from its origin
    // (RayOrigin::inverted), not both. Another object crossed within t_min, or a ray
    // carrying a difference for one mesh that meets another object, is not followed.
    bool list_inverts(size_t k, const Ray& ray, const RayOrigin& from) const;
    // The same for the object the ray leaves, from its facet `from_facet` (a sphere: none
    // when the ray moves away from its centre).
    std::optional<Hit> intersect_from(size_t k, int from_facet, const Ray& ray, double t_min, double t_max,
                                      RenderStats& stats) const;
    size_t order_index(const RayOrigin& from) const {
        return from.object >= 0 ? order_of_[static_cast<size_t>(from.object)] : SIZE_MAX;
    }

    // intersect_lanes on one object k of the in-order search: the shapes with a lane kernel
    // (spheres, planes) or facet-local packets (plane sets) by their overload; any other
    // shape (meshes, through Embree or the linear search) lane by lane, the exact answer.
    struct LaneSearch;
    void lanes_on(const Sphere& s, size_t k, LaneSearch& q) const;
    void lanes_on(const Plane& p, size_t k, LaneSearch& q) const;
    void lanes_on(const ConvexPolyhedron& c, size_t k, LaneSearch& q) const;
    template <class OtherShape>
    void lanes_on(const OtherShape&, size_t k, LaneSearch& q) const;
    void lanes_one_by_one(size_t k, const LaneMask& lanes, LaneSearch& q) const;

    const Scene& scene_;
    double t_min_, t_max_;
    TraceOptions options_;
    // The order in which intersect() tests the objects.
    std::vector<const Object*> order_;
    std::vector<std::unique_ptr<MeshAccel>> mesh_accel_;  // per entry of order_, null when unused
    std::vector<std::unique_ptr<povray::Mesh>> pov_mesh_;  // per entry of order_: compat "povray"'s meshes
    std::optional<ObjectBvh> bvh_;                         // over order_'s indices
    // The spheres tested together (from kMinSphereSet of them, without the BVH): all of them
    // for intersect(), those that cast shadows for the shadow rays.
    static constexpr std::size_t kMinSphereSet = 2;
    std::optional<SphereGroup> spheres_, shadow_spheres_;
    std::vector<char> casts_shadow_;                        // per entry of order_
    std::vector<char> listed_;                              // per entry of order_: list_inverts applies
    bool any_listed_ = false;                               // some entry of listed_ is set
    std::vector<std::unique_ptr<FacetGraph>> facet_graph_;  // per entry of order_: bounded plane sets
    std::vector<std::int32_t> facet_base_;                  // per entry of order_: first id in the guess cache
    std::vector<std::size_t> order_of_;                     // Scene::objects index → order_ index
    std::size_t facet_ids_ = 0;
    std::uint64_t id_ = 0;                                  // this search, for the per-thread guesses
};

}  // namespace refract
