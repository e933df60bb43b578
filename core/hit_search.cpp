#include <refract/core/hit_search.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include <refract/core/material.h>

namespace refract {

namespace {

// The guesses of one thread for one tracer: per starting facet, the last few directions
// that left it (in single precision: they only choose a guess) and the facet each left
// through.
struct GuessCache {
    static constexpr int kSlots = 4;
    struct Slot {
        float dir[3];
        std::int32_t facet;
    };
    std::uint64_t owner = 0;
    std::vector<Slot> slots;       // kSlots per facet id
    std::vector<std::uint8_t> next;  // per facet id: the slot to overwrite next

    void reset(std::uint64_t id, size_t ids) {
        owner = id;
        slots.assign(ids * kSlots, Slot{{0, 0, 0}, -1});
        next.assign(ids, 0);
    }
    // The facet left by the remembered direction nearest to dir, and its slot.
    std::pair<int, int> guess(size_t id, const Vec3& dir) const {
        const Slot* s = &slots[id * kSlots];
        int best = -1, slot = -1;
        float best_dot = -2;
        const float d0 = static_cast<float>(dir.x()), d1 = static_cast<float>(dir.y()), d2 = static_cast<float>(dir.z());
        for (int i = 0; i < kSlots; ++i) {
            if (s[i].facet < 0) continue;
            const float dot = s[i].dir[0] * d0 + s[i].dir[1] * d1 + s[i].dir[2] * d2;
            if (dot > best_dot) {
                best_dot = dot;
                best = s[i].facet;
                slot = i;
            }
        }
        return {best, slot};
    }
    // Remembers that dir left through `facet`: in the slot that guessed it, else the oldest.
    void store(size_t id, const Vec3& dir, int facet, int slot, bool guessed) {
        if (!guessed) {
            slot = next[id];
            next[id] = static_cast<std::uint8_t>((slot + 1) % kSlots);
        }
        Slot& s = slots[id * kSlots + static_cast<size_t>(slot)];
        s = Slot{{static_cast<float>(dir.x()), static_cast<float>(dir.y()), static_cast<float>(dir.z())}, facet};
    }
};

thread_local GuessCache guess_cache;

// The fewest lanes leaving one facet that are tested as a packet (fewer: one by one, which
// costs less than a packet test of mostly empty lanes).
constexpr int kMinPacketLanes = 3;

}  // namespace

HitSearch::HitSearch(const Scene& scene, const CompatRules& rules, const TraceOptions& options)
    : scene_(scene), t_min_(rules.t_min()), t_max_(rules.t_max()), options_(options), order_(rules.search_order(scene)) {
    casts_shadow_.resize(order_.size());
    listed_.resize(order_.size());
    for (size_t k = 0; k < order_.size(); ++k) {
        const Material& m = scene.materials[static_cast<size_t>(order_[k]->material)];
        casts_shadow_[k] = casts_shadow(m) ? 1 : 0;
        listed_[k] = rules.interior_lists() && rules.single_precision_meshes() &&
                     std::holds_alternative<TriangleMesh>(order_[k]->shape) && m.dielectric();
        any_listed_ = any_listed_ || listed_[k];
    }
    mesh_accel_.resize(order_.size());
    pov_mesh_.resize(order_.size());
    for (size_t k = 0; k < order_.size(); ++k) {
        const auto* m = std::get_if<TriangleMesh>(&order_[k]->shape);
        if (m && rules.single_precision_meshes()) pov_mesh_[k] = std::make_unique<povray::Mesh>(*m);
        else if (m && m->triangles.size() >= MeshAccel::kMinTriangles) mesh_accel_[k] = std::make_unique<MeshAccel>(*m);
    }
    // Facet-local intersection for plane sets of kMinFacetPlanes to kMaxFacetPlanes planes.
    order_of_.assign(scene.objects.size(), 0);
    facet_graph_.resize(order_.size());
    facet_base_.assign(order_.size(), -1);
    for (size_t k = 0; k < order_.size(); ++k) {
        order_of_[static_cast<size_t>(order_[k] - scene.objects.data())] = k;
        const auto* c = std::get_if<ConvexPolyhedron>(&order_[k]->shape);
        if (!c || c->planes.size() < kMinFacetPlanes || c->planes.size() > kMaxFacetPlanes) continue;
        facet_graph_[k] = std::make_unique<FacetGraph>(*c);
        facet_base_[k] = static_cast<std::int32_t>(facet_ids_);
        facet_ids_ += c->planes.size();
    }
    // The spheres tested together, outside the BVH (shadow rays: those that cast shadows).
    const auto group = [&](bool shadows) {
        std::optional<SphereGroup> g;
        g.emplace();
        g->index.assign(order_.size(), SIZE_MAX);
        for (size_t k = 0; k < order_.size(); ++k) {
            const auto* s = std::get_if<Sphere>(&order_[k]->shape);
            if (shadows && !casts_shadow_[k]) continue;
            if (!s) {
                g->rest.push_back(k);
                continue;
            }
            g->index[k] = g->set.size();
            g->order.push_back(k);
            g->set.add(*s);
        }
        if (g->set.size() < kMinSphereSet) g.reset();
        return g;
    };
    const bool use_bvh = uses_object_bvh(scene);
    if (!use_bvh) {
        spheres_ = group(false);
        shadow_spheres_ = group(true);
    }
    static std::atomic<std::uint64_t> searches{0};
    id_ = ++searches;
    if (use_bvh) {
        std::vector<std::optional<Bounds>> boxes;
        for (const Object* o : order_) {
            // A polyhedron's bounding sphere where it has one (its vertices cost O(n⁴)).
            const auto* c = std::get_if<ConvexPolyhedron>(&o->shape);
            if (c && c->bound_radius > 0)
                boxes.push_back(Bounds{c->bound_center.array() - c->bound_radius, c->bound_center.array() + c->bound_radius});
            else
                boxes.push_back(bounds(o->shape));
        }
        bvh_.emplace(boxes);
    }
}

HitSearch::~HitSearch() = default;

bool HitSearch::uses_object_bvh(const Scene& scene) {
    size_t spheres = 0;
    for (const Object& o : scene.objects) spheres += std::holds_alternative<Sphere>(o.shape) ? 1 : 0;
    return (scene.objects.size() - spheres) + spheres / kSpheresPerObject >= kBvhMinObjects;
}

std::optional<Hit> HitSearch::intersect_object(size_t k, const Ray& ray, double t_min, double t_max) const {
    if (const auto& a = mesh_accel_[k]) return a->intersect(ray, t_min, t_max);
    if (const auto& p = pov_mesh_[k]) return p->intersect(ray, t_min, t_max);
    return refract::intersect(order_[k]->shape, ray, t_min, t_max);
}

std::optional<SurfaceHit> HitSearch::first_on(const Ray& ray, double length, const std::vector<int>& objects) const {
    std::optional<Hit> best;
    size_t best_k = 0;
    for (const int object : objects) {
        const size_t k = order_of_[static_cast<size_t>(object)];
        if (const auto h = intersect_object(k, ray, 0.0, best ? best->t : length)) {
            if (!(h->t <= length)) continue;
            best = h;
            best_k = k;
        }
    }
    if (!best) return std::nullopt;
    SurfaceHit out;
    out.hit = *best;
    out.object = order_[best_k];
    out.material = &scene_.materials[static_cast<size_t>(out.object->material)];
    out.entering = best->normal.dot(ray.dir) < 0;
    out.normal = out.entering ? best->normal : Vec3(-best->normal);
    return out;
}

bool HitSearch::list_inverts(size_t k, const Ray& ray, const RayOrigin& from) const {
    const std::int32_t object = static_cast<std::int32_t>(order_[k] - scene_.objects.data());
    const bool carried = from.inverted && from.object == object;
    const int crossed = pov_mesh_[k]->crossings(ray, t_min_, from.object == object ? from.facet : -1);
    return carried != (crossed % 2 == 1);
}

std::optional<Hit> HitSearch::intersect_from(size_t k, int from_facet, const Ray& ray, double t_min, double t_max,
                                               RenderStats& stats) const {
    if (const auto* s = std::get_if<Sphere>(&order_[k]->shape)) {
        // A ray leaving a point of a sphere away from its centre never meets it again (a
        // refracted ray leaving a drop, a reflection off its outside).
        if ((ray.origin - s->center).dot(ray.dir) > 0) return std::nullopt;
        return intersect_object(k, ray, t_min, t_max);
    }
    const FacetGraph* graph = facet_graph_[k].get();
    if (!graph || from_facet < 0 || !options_.facet_local) return intersect_object(k, ray, t_min, t_max);
    const auto& c = std::get<ConvexPolyhedron>(order_[k]->shape);
    GuessCache& cache = guess_cache;
    if (cache.owner != id_) cache.reset(id_, facet_ids_);
    const size_t id = static_cast<size_t>(facet_base_[k] + from_facet);
    const auto [guess, slot] = cache.guess(id, ray.dir);
    const FacetGraph::Local local = graph->intersect(c, ray, t_min, t_max, from_facet, guess);
    if (local.decided) {
        ++stats.facet_local;
        if (local.hit) cache.store(id, ray.dir, local.hit->facet, slot, true);
        return local.hit;
    }
    ++stats.facet_full;
    auto hit = intersect_object(k, ray, t_min, t_max);
    if (hit) cache.store(id, ray.dir, hit->facet, slot, false);
    return hit;
}

template <class Use>
std::optional<HitSearch::Nearest> HitSearch::nearest(const Ray& ray, double t_min, double t_max, Use&& use,
                                                         size_t from_k, int from_facet, RenderStats* stats,
                                                         const SphereGroup* group) const {
    std::optional<Nearest> best;
    const auto ask = [&](size_t k, double lo, double hi) {
        return k == from_k ? intersect_from(k, from_facet, ray, lo, hi, *stats) : intersect_object(k, ray, lo, hi);
    };
    if (!bvh_ && group) {
        // The spheres together, then the rest in order, each asked for hits up to and
        // including the best t when listed before the best object, strictly nearer when
        // after: the in-order search's answer, exact ties included.
        const size_t leaving = from_k < group->index.size() ? group->index[from_k] : SIZE_MAX;
        if (const auto s = group->set.nearest(ray, t_min, t_max, leaving))
            best = Nearest{sphere_hit(group->set.sphere(s->index), ray, s->t), group->order[s->index]};
        for (const size_t k : group->rest) {
            if (!use(k)) continue;
            const double limit = !best ? t_max
                                 : k < best->k ? std::nextafter(best->hit.t, std::numeric_limits<double>::infinity())
                                               : best->hit.t;
            const auto hit = ask(k, t_min, limit);
            if (hit) best = Nearest{*hit, k};
        }
        return best;
    }
    if (!bvh_) {
        // In order: a hit replaces the best one only when strictly nearer.
        for (size_t k = 0; k < order_.size(); ++k) {
            if (!use(k)) continue;
            const auto hit = ask(k, t_min, t_max);
            if (!hit) continue;
            t_max = hit->t;
            best = Nearest{*hit, k};
        }
        return best;
    }
    // Through the BVH, in any order, with the same result: each object is asked for hits
    // up to and including the best t so far, and replaces it when nearer or, at equal t,
    // first in order.
    double t_cull = t_max;
    bvh_->search(ray, t_min, t_cull, [&](int i) {
        const size_t k = static_cast<size_t>(i);
        if (!use(k)) return;
        const double limit = best ? std::nextafter(t_cull, std::numeric_limits<double>::infinity()) : t_max;
        const auto hit = ask(k, t_min, limit);
        if (!hit || (best && hit->t == best->hit.t && k > best->k)) return;
        t_cull = hit->t;
        best = Nearest{*hit, k};
    });
    return best;
}

std::optional<SurfaceHit> HitSearch::intersect(const Ray& ray, RenderStats& stats, RayOrigin from) const {
    ++stats.segments;
    std::optional<SurfaceHit> best;
    const auto n = nearest(ray, t_min_, t_max_, [](size_t) { return true; }, order_index(from), from.facet, &stats,
                           spheres_ ? &*spheres_ : nullptr);
    if (!n) return best;
    const Object& obj = *order_[n->k];
    best = SurfaceHit{n->hit, &obj, &scene_.materials[static_cast<size_t>(obj.material)], n->hit.normal, true};
    best->entering = best->hit.normal.dot(ray.dir) < 0;
    best->normal = best->entering ? best->hit.normal : Vec3(-best->hit.normal);
    if (listed_[n->k]) {  // POV-Ray's interior lists
        best->inverted = list_inverts(n->k, ray, from);
        best->entering = best->entering != best->inverted;
    }
    return best;
}

std::optional<HitSearch::Blocker> HitSearch::shadow_blocker(const Ray& ray, double t_min, double t_max, RayOrigin from,
                                                            RenderStats* stats) const {
    const auto n = nearest(ray, t_min, t_max, [&](size_t k) { return casts_shadow_[k] != 0; }, order_index(from), from.facet,
                           stats, shadow_spheres_ ? &*shadow_spheres_ : nullptr);
    if (!n) return std::nullopt;
    return Blocker{n->hit, order_[n->k]};
}

// The state of one packet's in-order search (intersect_lanes): each lane's best hit so far
// and the object it is on, written straight into the caller's result; nothing that is set
// before use is zeroed.
struct HitSearch::LaneSearch {
    LaneSearch(const LaneVec3& origin_, const LaneVec3& dir_, const LaneMask& active_, const LaneOrigins& from_,
               RenderStats& stats_, double t_min_, const SphereGroup* group_, LaneHits& out_, double t_max)
        : origin(origin_), dir(dir_), active(active_), from(from_), stats(stats_), t_min(t_min_), group(group_),
          out(out_), best(t_max) {}
    const LaneVec3& origin;
    const LaneVec3& dir;
    const LaneMask& active;
    const LaneOrigins& from;
    RenderStats& stats;
    double t_min;
    const SphereGroup* group;
    LaneHits& out;
    Lanes best;
    LaneVec3 outward;                  // per lane, where it hit: the outward normal
    std::array<size_t, kLanes> from_k;  // per lane, the order_ index of the object it leaves
    std::array<size_t, kLanes> best_k;  // per lane, the order_ index of the best object (SIZE_MAX: none)
    Lanes lim;                          // per lane, the bound of the object being asked

    // Lane l's nearest hit so far: h, on object k.
    REFRACT_LANE_OP void keep(int l, size_t k, const Hit& h, const Object* o) {
        const size_t i = static_cast<size_t>(l);
        best_k[i] = k;
        best[l] = h.t;
        out.point.set(l, h.point);
        outward.set(l, h.normal);
        out.hit[l] = true;
        out.object[i] = o;
        out.facet[i] = h.facet;
    }
    // A hit of object k in the lanes of `m` (t, point, outward normal; facet -1).
    REFRACT_LANE_OP void take(size_t k, const LaneMask& m, const LaneShapeHits& h, const Object* o) {
        if (!m.any()) return;
        for_each_lane(m, [&](int l) { best_k[static_cast<size_t>(l)] = k; });
        best = select(m, h.t, best);
        if (out.hit.any()) {
            out.point = select(m, h.point, out.point);
            outward = select(m, h.normal, outward);
        } else {  // the first object hit (the lanes that missed it keep t_max)
            out.point = h.point;
            outward = h.normal;
        }
        out.hit = out.hit || m;
        for_each_lane(m, [&](int l) {
            out.object[static_cast<size_t>(l)] = o;
            out.facet[static_cast<size_t>(l)] = -1;
        });
    }
    // The lanes leaving object k.
    REFRACT_LANE_OP LaneMask leaving(size_t k) const {
        LaneMask m;
        for (int l = 0; l < kLanes; ++l) m[l] = active[l] && from_k[static_cast<size_t>(l)] == k;
        return m;
    }
};

REFRACT_LANE_OP void HitSearch::lanes_on(const Sphere& s, size_t k, LaneSearch& q) const {
    // The sphere the rays leave: none for those moving away from its centre (intersect_from).
    const LaneShapeHits h = refract::intersect_lanes(s, q.origin, q.dir, q.active, q.t_min, q.lim, q.leaving(k));
    q.take(k, h.hit, h, order_[k]);
}

REFRACT_LANE_OP void HitSearch::lanes_on(const Plane& p, size_t k, LaneSearch& q) const {
    const LaneShapeHits h = refract::intersect_lanes(p, q.origin, q.dir, q.active, q.t_min, q.lim);
    q.take(k, h.hit, h, order_[k]);
}

template <class OtherShape>
void HitSearch::lanes_on(const OtherShape&, size_t k, LaneSearch& q) const {
    lanes_one_by_one(k, q.active, q);
}

HitSearch::LaneHits HitSearch::intersect_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                                               const LaneOrigins& from, RenderStats& stats) const {
    LaneHits out;
    LaneSearch q(origin, dir, active, from, stats, t_min_, spheres_ ? &*spheres_ : nullptr, out, t_max_);
    out.hit = LaneMask::Constant(false);
    out.entering = LaneMask::Constant(false);
    out.inverted = LaneMask::Constant(false);
    out.facet.fill(-1);
    if (bvh_) {  // lane by lane
        out.t = Lanes(0.0);
        out.point = out.normal = LaneVec3::broadcast(Vec3::Zero());
        for_each_lane(active, [&](int l) {
            const size_t i = static_cast<size_t>(l);
            const auto h = intersect(Ray{origin.lane(l), dir.lane(l)}, stats, from[i]);
            if (!h) return;
            out.hit[l] = true;
            out.t[l] = h->hit.t;
            out.point.set(l, h->hit.point);
            out.normal.set(l, h->normal);
            out.entering[l] = h->entering;
            out.inverted[l] = h->inverted;
            out.object[i] = h->object;
            out.facet[i] = h->hit.facet;
        });
        return out;
    }
    stats.segments += static_cast<std::uint64_t>(active.count());
    for (size_t i = 0; i < static_cast<size_t>(kLanes); ++i)
        q.from_k[i] = active[static_cast<int>(i)] ? order_index(from[i]) : SIZE_MAX;
    q.best_k.fill(SIZE_MAX);
    // The spheres together first (the group's lane search), then the other objects in
    // order, each lane asking object k for hits up to and including its best t when k
    // comes before its best object, strictly nearer when after (nearest()'s rule).
    const SphereGroup* group = q.group;
    if (group) {
        std::array<std::int32_t, kLanes> leaving;
        for (size_t i = 0; i < leaving.size(); ++i)
            leaving[i] = q.from_k[i] < group->index.size() && group->index[q.from_k[i]] != SIZE_MAX
                             ? static_cast<std::int32_t>(group->index[q.from_k[i]])
                             : -1;
        SphereSet::LaneHits sh;
        sh.best = q.best;
        sh.index.fill(-1);
        group->set.nearest_lanes(origin, dir, active, t_min_, leaving, sh);
        if (sh.hit.any()) {
            q.best = sh.best;
            out.point = sh.point;
            q.outward = sh.normal;
            out.hit = sh.hit;
            for_each_lane(sh.hit, [&](int l) {
                const size_t i = static_cast<size_t>(l);
                q.best_k[i] = group->order[static_cast<size_t>(sh.index[i])];
                out.object[i] = order_[q.best_k[i]];
            });
        }
    }
    // In order, as nearest(): a hit replaces the best one only when strictly nearer.
    const size_t n_objects = group ? group->rest.size() : order_.size();
    for (size_t r = 0; r < n_objects; ++r) {
        const size_t k = group ? group->rest[r] : r;
        q.lim = q.best;
        if (group)
            for (int l = 0; l < kLanes; ++l)
                if (q.best_k[static_cast<size_t>(l)] != SIZE_MAX && k < q.best_k[static_cast<size_t>(l)])
                    q.lim[l] = std::nextafter(q.best[l], std::numeric_limits<double>::infinity());
        std::visit([&](const auto& shape) { lanes_on(shape, k, q); }, order_[k]->shape);
    }
    out.t = q.best;
    if (!out.hit.any()) return out;
    // As intersect(): entering where the outward normal faces the ray, the normal turned to
    // the incident side.
    out.entering = out.hit && (q.outward.dot(dir) < Lanes(0.0));
    out.normal = select(out.entering, q.outward, -q.outward);
    if (!any_listed_) return out;
    for_each_lane(out.hit, [&](int l) {  // POV-Ray's interior lists (intersect())
        const size_t i = static_cast<size_t>(l);
        if (!listed_[q.best_k[i]]) return;
        out.inverted[l] = list_inverts(q.best_k[i], Ray{origin.lane(l), dir.lane(l)}, from[i]);
        out.entering[l] = out.entering[l] != out.inverted[l];
    });
    return out;
}

// Object k asked for the lanes `lanes` one by one, as nearest() asks it.
void HitSearch::lanes_one_by_one(size_t k, const LaneMask& lanes, LaneSearch& q) const {
    for_each_lane(lanes, [&](int l) {
        const size_t i = static_cast<size_t>(l);
        const Ray r{q.origin.lane(l), q.dir.lane(l)};
        const auto h = q.from_k[i] == k ? intersect_from(k, q.from[i].facet, r, q.t_min, q.lim[l], q.stats)
                                        : intersect_object(k, r, q.t_min, q.lim[l]);
        if (h) q.keep(l, k, *h, order_[k]);
    });
}



void HitSearch::lanes_on(const ConvexPolyhedron& c, size_t k, LaneSearch& q) const {
    LaneMask rest = q.active;
    const FacetGraph* graph = facet_graph_[k].get();
    LaneMask todo = LaneMask::Constant(false);
    if (graph && options_.facet_local) {
        const LaneMask leaving = q.leaving(k);
        for (int l = 0; l < kLanes; ++l) todo[l] = leaving[l] && q.from[static_cast<size_t>(l)].facet >= 0;
    }
    if (todo.any()) {
        // The lanes leaving a facet f of this plane set: decided together from the planes
        // around f and their guesses (intersect_from on every lane), facet by facet.
        GuessCache& cache = guess_cache;
        if (cache.owner != id_) cache.reset(id_, facet_ids_);
        while (todo.any()) {
            const int first = todo.first();
            const int f = q.from[static_cast<size_t>(first)].facet;
            const size_t id = static_cast<size_t>(facet_base_[k] + f);
            LaneMask local;
            for (int l = 0; l < kLanes; ++l) local[l] = todo[l] && q.from[static_cast<size_t>(l)].facet == f;
            todo = todo && !local;
            if (local.count() < kMinPacketLanes) continue;  // cheaper one by one (below)
            rest = rest && !local;
            // Lane l by the full plane loop, its leaving facet remembered (intersect_from
            // when its guess fails).
            const auto full = [&](int l) {
                ++q.stats.facet_full;
                const Ray r{q.origin.lane(l), q.dir.lane(l)};
                const auto hit = intersect_object(k, r, q.t_min, q.lim[l]);
                if (!hit) return;
                cache.store(id, r.dir, hit->facet, 0, false);
                q.keep(l, k, *hit, order_[k]);
            };
            // A direction never seen from this facet: the first lane fills the cache.
            if (cache.guess(id, q.dir.lane(first)).first < 0) {
                full(first);
                local[first] = false;
            }
            // Until every lane is decided: the packet test, then the first undecided lane
            // by the full loop, whose facet is the others' next guess; the last few lanes
            // one by one.
            while (local.count() >= kMinPacketLanes) {
                std::array<std::int32_t, kLanes> guess;
                std::array<int, kLanes> slot{};
                for (int l = 0; l < kLanes; ++l) {
                    const auto [g, sl] = local[l] ? cache.guess(id, q.dir.lane(l)) : std::pair<int, int>{-1, -1};
                    guess[static_cast<size_t>(l)] = g;
                    slot[static_cast<size_t>(l)] = sl;
                }
                const FacetGraph::LocalLanes loc = graph->intersect_lanes(c, q.origin, q.dir, local, q.t_min, q.lim, f, guess);
                const LaneMask decided = local && loc.decided;
                q.stats.facet_local += static_cast<std::uint64_t>(decided.count());
                for (int l = 0; l < kLanes; ++l) {
                    if (!decided[l] || !loc.hit[l]) continue;
                    const int g = loc.facet[static_cast<size_t>(l)];
                    cache.store(id, q.dir.lane(l), g, slot[static_cast<size_t>(l)], true);
                    q.keep(l, k, Hit{loc.t[l], loc.point.lane(l), c.planes[static_cast<size_t>(g)].normal, g}, order_[k]);
                }
                local = local && !decided;
                const int u = local.first();
                if (u < 0) break;
                full(u);
                local[u] = false;
            }
            rest = rest || local;
        }
    }
    lanes_one_by_one(k, rest, q);
}

LaneMask HitSearch::escaping_lanes(const LaneOrigins& from, const LaneVec3& origin, const LaneVec3& dir,
                                   const LaneMask& active, RenderStats& stats) const {
    if (order_.size() != 1 || !std::holds_alternative<Sphere>(order_[0]->shape)) return LaneMask::Constant(false);
    const Sphere& s = std::get<Sphere>(order_[0]->shape);
    LaneMask gone = active && ((origin - LaneVec3::broadcast(s.center)).dot(dir) > Lanes(0.0));
    for (int l = 0; l < kLanes; ++l) gone[l] = gone[l] && from[static_cast<size_t>(l)].object >= 0;
    stats.segments += static_cast<std::uint64_t>(gone.count());
    return gone;
}

HitSearch::LaneHits HitSearch::lanes_of(const SurfaceHit& s) {
    LaneHits h;
    h.hit = LaneMask::Constant(true);
    h.t = Lanes(s.hit.t);
    h.point = LaneVec3::broadcast(s.hit.point);
    h.normal = LaneVec3::broadcast(s.normal);
    h.entering = LaneMask::Constant(s.entering);
    h.inverted = LaneMask::Constant(s.inverted);
    h.object.fill(s.object);
    h.facet.fill(s.hit.facet);
    return h;
}

SurfaceHit HitSearch::surface_hit(const LaneHits& h, int l) const {
    const Object* o = h.object[static_cast<size_t>(l)];
    const Vec3 n = h.normal.lane(l);
    const bool outward = h.entering[l] != h.inverted[l];  // n faces the ray; the outward normal as intersect() keeps it
    return SurfaceHit{Hit{h.t[l], h.point.lane(l), outward ? n : Vec3(-n), h.facet[static_cast<size_t>(l)]}, o,
                      &scene_.materials[static_cast<size_t>(o->material)], n, h.entering[l], h.inverted[l]};
}

}  // namespace refract
