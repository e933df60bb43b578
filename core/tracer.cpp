#include "core/tracer.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/optics.h"

namespace refract {

SceneTracer::SceneTracer(const Scene& scene) : scene_(scene), camera_basis_(scene.camera.basis()) {
    // POV-Ray mode: the order of the exported scene (validation/pov_export.cpp writes the
    // opaque objects first, then the transparent ones), which is the order in which POV-Ray
    // tests them; this decides exact ties, e.g. a gem's facet lying in the floor plane,
    // where POV-Ray shades the floor.
    const bool pov = scene.settings.compat == Compat::PovRay;
    for (int pass = pov ? 0 : 1; pass < 2; ++pass)
        for (const Object& obj : scene.objects)
            if (!pov || scene.materials[obj.material].is<material::Dielectric>() == (pass == 1))
                order_.push_back(&obj);
    for (const Material& m : scene.materials) {
        absorbing_ = absorbing_ || (!pov && m.dielectric() && m.dielectric()->absorption);
        lanes_apply_ = lanes_apply_ && !m.is<material::Uniaxial>();
    }
    lanes_apply_ = lanes_apply_ && scene.settings.polarisation != PolarisationModel::Exact;
    mesh_accel_.resize(order_.size());
    for (size_t k = 0; k < order_.size(); ++k)
        if (const auto* m = std::get_if<TriangleMesh>(&order_[k]->shape); m && m->triangles.size() >= MeshAccel::kMinTriangles)
            mesh_accel_[k] = std::make_unique<MeshAccel>(*m);
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
            if (shadows && scene.materials[order_[k]->material].is<material::Emissive>()) continue;
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
    static std::atomic<std::uint64_t> tracers{0};
    id_ = ++tracers;
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

SceneTracer::~SceneTracer() = default;

bool SceneTracer::uses_object_bvh(const Scene& scene) {
    size_t spheres = 0;
    for (const Object& o : scene.objects) spheres += std::holds_alternative<Sphere>(o.shape) ? 1 : 0;
    return (scene.objects.size() - spheres) + spheres / kSpheresPerObject >= kBvhMinObjects;
}

std::optional<Hit> SceneTracer::intersect_object(size_t k, const Ray& ray, double t_min, double t_max) const {
    if (const auto& a = mesh_accel_[k]) return a->intersect(ray, t_min, t_max);
    return refract::intersect(order_[k]->shape, ray, t_min, t_max);
}

namespace {

std::atomic<bool> facet_local_on{true};
std::atomic<bool> lanes_on{true};

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

}  // namespace

void SceneTracer::set_facet_local(bool on) { facet_local_on.store(on, std::memory_order_relaxed); }
bool SceneTracer::facet_local() { return facet_local_on.load(std::memory_order_relaxed); }
void SceneTracer::set_lanes(bool on) { lanes_on.store(on, std::memory_order_relaxed); }
bool SceneTracer::lanes() { return lanes_on.load(std::memory_order_relaxed); }

std::optional<Hit> SceneTracer::intersect_from(size_t k, int from_facet, const Ray& ray, double t_min, double t_max,
                                               RenderStats& stats) const {
    if (const auto* s = std::get_if<Sphere>(&order_[k]->shape)) {
        // A ray leaving a point of a sphere away from its centre never meets it again (a
        // refracted ray leaving a drop, a reflection off its outside).
        if ((ray.origin - s->center).dot(ray.dir) > 0) return std::nullopt;
        return intersect_object(k, ray, t_min, t_max);
    }
    const FacetGraph* graph = facet_graph_[k].get();
    if (!graph || from_facet < 0 || !facet_local()) return intersect_object(k, ray, t_min, t_max);
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
std::optional<SceneTracer::Nearest> SceneTracer::nearest(const Ray& ray, double t_min, double t_max, Use&& use,
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

std::optional<SurfaceHit> SceneTracer::intersect(const Ray& ray, RenderStats& stats, RayOrigin from) const {
    ++stats.segments;
    std::optional<SurfaceHit> best;
    // POV-Ray keeps hits with kPovMinDepth <= t < kPovMaxDistance (every ray, primary too).
    const bool pov = scene_.settings.compat == Compat::PovRay;
    const double t_min = pov ? kPovMinDepth : kEpsilon;
    const double t_max = pov ? kPovMaxDistance : std::numeric_limits<double>::infinity();
    const size_t from_k = from.object >= 0 ? order_of_[static_cast<size_t>(from.object)] : SIZE_MAX;
    if (const auto n = nearest(ray, t_min, t_max, [](size_t) { return true; }, from_k, from.facet, &stats,
                               spheres_ ? &*spheres_ : nullptr)) {
        const Object& obj = *order_[n->k];
        best = SurfaceHit{n->hit, &obj, &scene_.materials[obj.material], n->hit.normal, true};
    }
    if (best) {
        best->entering = best->hit.normal.dot(ray.dir) < 0;
        best->normal = best->entering ? best->hit.normal : Vec3(-best->hit.normal);
    }
    return best;
}

namespace {
// The fewest lanes leaving one facet that are tested as a packet (fewer: one by one, which
// costs less than a packet test of mostly empty lanes).
constexpr int kMinPacketLanes = 3;
}  // namespace

SceneTracer::LaneHits SceneTracer::intersect_lanes(const LaneVec3& origin, const LaneVec3& dir, const LaneMask& active,
                                                   const LaneIds& from_object, const LaneIds& from_facet,
                                                   RenderStats& stats) const {
    LaneHits out;
    out.hit = LaneMask::Constant(false);
    out.entering = LaneMask::Constant(false);
    out.facet.fill(-1);
    if (bvh_) {  // lane by lane
        out.t = Lanes(0.0);
        out.point = out.normal = LaneVec3::broadcast(Vec3::Zero());
        for (int l = 0; l < kLanes; ++l) {
            if (!active[l]) continue;
            const size_t i = static_cast<size_t>(l);
            const auto h = intersect(Ray{origin.lane(l), dir.lane(l)}, stats, RayOrigin{from_object[i], from_facet[i]});
            if (!h) continue;
            out.hit[l] = true;
            out.t[l] = h->hit.t;
            out.point.set(l, h->hit.point);
            out.normal.set(l, h->normal);
            out.entering[l] = h->entering;
            out.object[i] = h->object;
            out.facet[i] = h->hit.facet;
        }
        return out;
    }
    stats.segments += static_cast<std::uint64_t>(active.count());
    const bool pov = scene_.settings.compat == Compat::PovRay;
    const double t_min = pov ? kPovMinDepth : kEpsilon;
    Lanes best(pov ? kPovMaxDistance : std::numeric_limits<double>::infinity());
    std::array<size_t, kLanes> from_k;
    for (size_t i = 0; i < static_cast<size_t>(kLanes); ++i)
        from_k[i] = active[static_cast<int>(i)] && from_object[i] >= 0 ? order_of_[static_cast<size_t>(from_object[i])]
                                                                       : SIZE_MAX;
    LaneVec3 outward;
    // Per lane, the order_ index of the best object so far (SIZE_MAX: none).
    std::array<size_t, kLanes> best_k;
    best_k.fill(SIZE_MAX);
    // A hit of object k in the lanes of `m` (t, point, outward normal; facet -1).
    const auto take = [&](size_t k, const LaneMask& m, const LaneShapeHits& h) {
        if (!m.any()) return;
        for (int l = 0; l < kLanes; ++l)
            if (m[l]) best_k[static_cast<size_t>(l)] = k;
        best = select(m, h.t, best);
        if (out.hit.any()) {
            out.point = select(m, h.point, out.point);
            outward = select(m, h.normal, outward);
        } else {  // the first object hit (the lanes that missed it keep t_max)
            out.point = h.point;
            outward = h.normal;
        }
        out.hit = out.hit || m;
        for (int l = 0; l < kLanes; ++l)
            if (m[l]) {
                out.object[static_cast<size_t>(l)] = order_[k];
                out.facet[static_cast<size_t>(l)] = -1;
            }
    };
    // Lane l's nearest hit so far: h, on object k.
    const auto keep = [&](int l, size_t k, const Hit& h) {
        const size_t i = static_cast<size_t>(l);
        best_k[i] = k;
        best[l] = h.t;
        out.point.set(l, h.point);
        outward.set(l, h.normal);
        out.hit[l] = true;
        out.object[i] = order_[k];
        out.facet[i] = h.facet;
    };
    // The spheres together first (the group's lane search), then the other objects in
    // order, each lane asking object k for hits up to and including its best t when k
    // comes before its best object, strictly nearer when after (nearest()'s rule).
    const SphereGroup* group = spheres_ ? &*spheres_ : nullptr;
    if (group) {
        std::array<std::int32_t, kLanes> leaving;
        for (size_t i = 0; i < leaving.size(); ++i)
            leaving[i] = from_k[i] < group->index.size() && group->index[from_k[i]] != SIZE_MAX
                             ? static_cast<std::int32_t>(group->index[from_k[i]])
                             : -1;
        SphereSet::LaneHits sh;
        sh.best = best;
        sh.index.fill(-1);
        group->set.nearest_lanes(origin, dir, active, t_min, leaving, sh);
        if (sh.hit.any()) {
            best = sh.best;
            out.point = sh.point;
            outward = sh.normal;
            out.hit = sh.hit;
            for (int l = 0; l < kLanes; ++l) {
                if (!sh.hit[l]) continue;
                const size_t i = static_cast<size_t>(l);
                best_k[i] = group->order[static_cast<size_t>(sh.index[i])];
                out.object[i] = order_[best_k[i]];
            }
        }
    }
    const auto limit = [&](size_t k) {
        if (!group) return best;
        Lanes lim = best;
        for (int l = 0; l < kLanes; ++l)
            if (best_k[static_cast<size_t>(l)] != SIZE_MAX && k < best_k[static_cast<size_t>(l)])
                lim[l] = std::nextafter(best[l], std::numeric_limits<double>::infinity());
        return lim;
    };
    // Object k asked for lane l alone, as nearest() asks it.
    const auto one = [&](size_t k, int l, double hi) {
        const size_t i = static_cast<size_t>(l);
        const Ray r{origin.lane(l), dir.lane(l)};
        const auto h = from_k[i] == k ? intersect_from(k, from_facet[i], r, t_min, hi, stats)
                                      : intersect_object(k, r, t_min, hi);
        if (h) keep(l, k, *h);
    };
    // In order, as nearest(): a hit replaces the best one only when strictly nearer.
    const size_t n_objects = group ? group->rest.size() : order_.size();
    for (size_t r = 0; r < n_objects; ++r) {
        const size_t k = group ? group->rest[r] : r;
        const Lanes lim = limit(k);
        LaneMask leaving;
        for (int l = 0; l < kLanes; ++l) leaving[l] = active[l] && from_k[static_cast<size_t>(l)] == k;
        const Shape& shape = order_[k]->shape;
        if (const auto* s = std::get_if<Sphere>(&shape)) {
            // The sphere the rays leave: none for those moving away from its centre (intersect_from).
            const LaneShapeHits h = refract::intersect_lanes(*s, origin, dir, active, t_min, lim, leaving);
            take(k, h.hit, h);
            continue;
        }
        if (const auto* p = std::get_if<Plane>(&shape)) {
            const LaneShapeHits h = refract::intersect_lanes(*p, origin, dir, active, t_min, lim);
            take(k, h.hit, h);
            continue;
        }
        LaneMask rest = active;
        const FacetGraph* graph = facet_graph_[k].get();
        LaneMask todo = LaneMask::Constant(false);
        if (graph && facet_local())
            for (int l = 0; l < kLanes; ++l) todo[l] = leaving[l] && from_facet[static_cast<size_t>(l)] >= 0;
        if (todo.any()) {
            // The lanes leaving a facet f of this plane set: decided together from the planes
            // around f and their guesses (intersect_from on every lane), facet by facet.
            const auto& c = std::get<ConvexPolyhedron>(shape);
            GuessCache& cache = guess_cache;
            if (cache.owner != id_) cache.reset(id_, facet_ids_);
            while (todo.any()) {
                const int first = todo.first();
                const int f = from_facet[static_cast<size_t>(first)];
                const size_t id = static_cast<size_t>(facet_base_[k] + f);
                LaneMask local;
                for (int l = 0; l < kLanes; ++l) local[l] = todo[l] && from_facet[static_cast<size_t>(l)] == f;
                todo = todo && !local;
                if (local.count() < kMinPacketLanes) continue;  // cheaper one by one (below)
                rest = rest && !local;
                // Lane l by the full plane loop, its leaving facet remembered (intersect_from
                // when its guess fails).
                const auto full = [&](int l) {
                    ++stats.facet_full;
                    const Ray r{origin.lane(l), dir.lane(l)};
                    const auto hit = intersect_object(k, r, t_min, lim[l]);
                    if (!hit) return;
                    cache.store(id, r.dir, hit->facet, 0, false);
                    keep(l, k, *hit);
                };
                // A direction never seen from this facet: the first lane fills the cache.
                if (cache.guess(id, dir.lane(first)).first < 0) {
                    full(first);
                    local[first] = false;
                }
                // Until every lane is decided: the packet test, then the first undecided lane
                // by the full loop, whose facet is the others' next guess; the last few lanes
                // one by one.
                while (local.count() >= kMinPacketLanes) {
                    LaneIds guess;
                    std::array<int, kLanes> slot{};
                    for (int l = 0; l < kLanes; ++l) {
                        const auto [g, sl] = local[l] ? cache.guess(id, dir.lane(l)) : std::pair<int, int>{-1, -1};
                        guess[static_cast<size_t>(l)] = g;
                        slot[static_cast<size_t>(l)] = sl;
                    }
                    const FacetGraph::LocalLanes loc = graph->intersect_lanes(c, origin, dir, local, t_min, lim, f, guess);
                    const LaneMask decided = local && loc.decided;
                    stats.facet_local += static_cast<std::uint64_t>(decided.count());
                    for (int l = 0; l < kLanes; ++l) {
                        if (!decided[l] || !loc.hit[l]) continue;
                        const int g = loc.facet[static_cast<size_t>(l)];
                        cache.store(id, dir.lane(l), g, slot[static_cast<size_t>(l)], true);
                        keep(l, k, Hit{loc.t[l], loc.point.lane(l), c.planes[static_cast<size_t>(g)].normal, g});
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
        for (int l = 0; l < kLanes; ++l)
            if (rest[l]) one(k, l, lim[l]);
    }
    out.t = best;
    if (!out.hit.any()) return out;
    // As intersect(): entering where the outward normal faces the ray, the normal turned to
    // the incident side.
    out.entering = outward.dot(dir) < Lanes(0.0);
    out.normal = select(out.entering, outward, -outward);
    return out;
}

LaneMask SceneTracer::escaping_lanes(const LaneIds& object, const LaneVec3& origin, const LaneVec3& dir,
                                     const LaneMask& active, RenderStats& stats) const {
    if (order_.size() != 1 || !std::holds_alternative<Sphere>(order_[0]->shape)) return LaneMask::Constant(false);
    const Sphere& s = std::get<Sphere>(order_[0]->shape);
    LaneMask gone = active && ((origin - LaneVec3::broadcast(s.center)).dot(dir) > Lanes(0.0));
    for (int l = 0; l < kLanes; ++l) gone[l] = gone[l] && object[static_cast<size_t>(l)] >= 0;
    stats.segments += static_cast<std::uint64_t>(gone.count());
    return gone;
}

SceneTracer::LaneHits SceneTracer::lanes_of(const SurfaceHit& s) {
    LaneHits h;
    h.hit = LaneMask::Constant(true);
    h.t = Lanes(s.hit.t);
    h.point = LaneVec3::broadcast(s.hit.point);
    h.normal = LaneVec3::broadcast(s.normal);
    h.entering = LaneMask::Constant(s.entering);
    h.object.fill(s.object);
    h.facet.fill(s.hit.facet);
    return h;
}

SurfaceHit SceneTracer::surface_hit(const LaneHits& h, int l) const {
    const Object* o = h.object[static_cast<size_t>(l)];
    const Vec3 n = h.normal.lane(l);
    SurfaceHit s{Hit{h.t[l], h.point.lane(l), h.entering[l] ? n : Vec3(-n), h.facet[static_cast<size_t>(l)]}, o,
                 &scene_.materials[o->material], n, h.entering[l]};
    return s;
}

Vec3 SceneTracer::background(const Vec3& dir) const { return scene_.background.radiance(dir); }

Vec3 SceneTracer::pigment(const Pigment& m, const Vec3& p) const {
    if (!m.checker) return m.color;
    // 3D checker (POV-Ray `checker`): parity of the sum of the cell indices. A small
    // offset keeps a surface lying on a cell boundary (a floor at y = 0) on one side.
    // Parities are taken on the doubles (no integer conversion to overflow on far hits or
    // tiny cells): odd(v) for a cell index v = floor(...).
    const auto odd = [](double v) { return std::fmod(v, 2.0) != 0.0; };
    const double s = m.checker->size;
    bool k;
    if (scene_.settings.compat == Compat::PovRay) {
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

Vec3 SceneTracer::light_transmittance(const Vec3& from, const Vec3& to, RenderStats& stats) const {
    // Shadow ray. Opaque objects block. Dielectrics: in physical mode light does not go
    // straight through a refracting surface (that light arrives as a caustic, which only
    // a light pass computes), so they block; in POV-Ray mode the ray goes straight on and
    // each crossing multiplies by the filter colour (clear glass casts no shadow).
    // Emissive highlight spheres never cast shadows (POV-Ray looks_like).
    ++stats.shadow_rays;
    if (scene_.settings.compat == Compat::PovRay) return light_transmittance_pov(from, to, stats);
    const Vec3 delta = to - from;
    const double dist = delta.norm();
    const Ray ray{from, delta / dist};
    const auto blocker = nearest(
        ray, kEpsilon, dist, [&](size_t k) { return !scene_.materials[order_[k]->material].is<material::Emissive>(); },
        SIZE_MAX, -1, nullptr, shadow_spheres_ ? &*shadow_spheres_ : nullptr);
    return blocker ? Vec3(0, 0, 0) : Vec3(1, 1, 1);
}

Vec3 SceneTracer::light_transmittance_pov(const Vec3& from, const Vec3& to, RenderStats& stats) const {
    // POV-Ray 3.7 point-light shadow ray (trace.cpp TracePointLightShadowRay): a straight
    // ray; the nearest hit farther than kPovShadowTolerance from the current origin and
    // nearer than kPovShadowTolerance to the light is taken; an opaque object blocks, a
    // transparent one multiplies by its filter colour and the search goes on from that
    // hit. no_shadow objects (the emissive highlight spheres) are not seen.
    Vec3 origin = from;
    double remaining = (to - from).norm();
    const Vec3 dir = (to - from) / remaining;
    Vec3 t(1, 1, 1);
    size_t from_k = SIZE_MAX;  // after the first crossing: the object and facet the ray leaves
    int from_facet = -1;
    while (true) {
        const Ray ray{origin, dir};
        const auto n = nearest(
            ray, kPovShadowTolerance, remaining,
            [&](size_t k) { return !scene_.materials[order_[k]->material].is<material::Emissive>(); }, from_k, from_facet,
            &stats, shadow_spheres_ ? &*shadow_spheres_ : nullptr);
        if (!n || n->hit.t >= remaining - kPovShadowTolerance) return t;
        const Hit* best = &n->hit;
        const Material* best_m = &scene_.materials[order_[n->k]->material];
        const Vec3* filter = best_m->transparent_filter();
        if (!filter) return Vec3(0, 0, 0);
        t = t.cwiseProduct(*filter);
        // Leaving a fading interior: its fade over the chord (ComputeShadowTexture).
        const auto* glass = best_m->dielectric();
        if (glass && glass->absorption && best->normal.dot(dir) > 0)
            t = t.cwiseProduct(pov_fade(glass->absorption->rgb, best->t));
        origin = best->point;
        remaining -= best->t;
        from_k = n->k;
        from_facet = best->facet;
    }
}

Vec3 SceneTracer::shade_diffuse(const SurfaceHit& h, const Pigment& pigment_, double diffuse, double ambient,
                                RenderStats& stats) const {
    const Vec3 pig = pigment(pigment_, h.hit.point);
    Vec3 c = ambient * pig;
    for (const Light& l : scene_.lights) {
        const auto to = l.toward(h.hit.point);
        if (!to) continue;
        const double cos_l = h.normal.dot(to->dir);
        if (cos_l <= 0) continue;
        const Vec3 tr = light_transmittance(h.hit.point, to->end, stats);
        c += diffuse * cos_l * pig.cwiseProduct(l.color).cwiseProduct(tr);
    }
    return c;
}

std::optional<Vec3> SceneTracer::absorption(const SurfaceHit& h, double wavelength_nm) const {
    if (h.entering || scene_.settings.compat == Compat::PovRay) return std::nullopt;
    const auto* d = h.material->dielectric();
    if (!d || !d->absorption) return std::nullopt;
    const double t = h.hit.t;
    if (wavelength_nm > 0) return Vec3::Constant(optics::beer_lambert(d->absorption->at(wavelength_nm), t));
    const Vec3& a = d->absorption->rgb;
    return Vec3(optics::beer_lambert(a.x(), t), optics::beer_lambert(a.y(), t), optics::beer_lambert(a.z(), t));
}

Vec3 SceneTracer::local_light(const SurfaceHit& h, RenderStats& stats) const {
    const Material& m = *h.material;
    if (const auto* d = m.as<material::Diffuse>()) return shade_diffuse(h, d->pigment, d->diffuse, d->ambient, stats);
    if (const auto* l = m.as<material::Lambertian>()) return shade_diffuse(h, l->pigment, 1.0, 0.0, stats);
    if (const auto* e = m.as<material::Emissive>()) return e->color;
    return Vec3(0, 0, 0);
}

Interaction SceneTracer::interact(const SurfaceHit& h, const Ray& ray, RenderStats& stats, double band_ior,
                                  bool split, biref::Wave wave, double wavelength_nm, bool adjoint) const {
    if (h.material->transparent_filter()) ++stats.tree_nodes;
    const InteractionContext c{scene_.settings.compat == Compat::PovRay,
                               scene_.settings.pruning_threshold(),
                               band_ior,
                               split,
                               scene_.settings.polarisation == PolarisationModel::Exact,
                               wave,
                               wavelength_nm,
                               adjoint};
    return refract::interact(*h.material, h, ray, c);
}

}  // namespace refract
