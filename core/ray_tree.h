#pragma once
// The ray-tree walker (Yasuda et al. 1984 §3.1.3): the tree is never stored; its
// branches wait in a FIFO list, each with its cumulative attenuation, and a branch whose
// attenuation falls below the pruning threshold, or that would exceed the depth or the
// reflection/transmission limits, is dropped. The Fresnel-tree integrator, the spectral
// eye pass and the light pass all walk their trees with this one walker; they differ only
// in what happens where a branch ends (the `Ends` callbacks):
//   void background(const Entry&)              the branch left the scene
//   void leaf(const Entry&, const SurfaceHit&) it met a diffuse surface or an emitter
//   bool intercept(Walker&, const Entry&, const SurfaceHit&, List&)
//        before the hit's own interaction: true when the callback took the hit over
//        (the spectral split at the first dispersive hit)
//   double band_ior(const Entry&, const SurfaceHit&)   the index at the entry's band
//        (0: the material's own)
//   double wavelength(const Entry&)    the entry's wavelength in nm (0: an RGB ray), for
//        the absorption along a segment inside a dielectric (Beer–Lambert)
//
// Polarisation rides on the entries as a payload P (core/polarisation_state.h): nothing
// for natural light, the camera-side Mueller matrix for an eye pass, the photon's Stokes
// vector for a light pass; the walker updates it with each branch's Mueller matrix.
#include <cstdint>
#include <initializer_list>
#include <array>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/polarisation_state.h"
#include "core/tracer.h"
#include "geometry/lanes.h"

namespace refract {

template <class P>
struct TreeEntryT {
    Ray ray;
    Vec3 weight;           // cumulative attenuation per channel (eq. 12's coefficients)
    double bailout = 1.0;  // the scalar the threshold is compared with
    // Counters in 16 bits (max_depth <= 10000, bands <= 1003): a list entry of the
    // natural-light walk is 112 bytes (104 before the uniaxial crystals' `wave`).
    std::int16_t depth = 0;  // surface interactions before this ray
    std::int16_t reflections = 0, transmissions = 0;
    std::int16_t band = -1;  // spectral band of the ray; −1: an RGB ray
    biref::Wave wave = biref::Wave::Isotropic;  // inside a uniaxial crystal: o or e
    double travelled = 0;    // path length from the tree's root to this ray's origin
    [[no_unique_address]] P pol{};  // polarisation payload (none for natural light)
    RayOrigin from{};        // the hit this ray leaves (none for a root)
};
using TreeEntry = TreeEntryT<NaturalLight>;

struct TreeLimits {
    static constexpr int kUnlimited = 1 << 30;
    // Work bounds whatever the threshold (docs/limits.md): the branches waiting in one
    // tree's list (Whitted: the nodes of its stored tree), and the segments of one walk.
    static constexpr size_t kMaxEntries = size_t{1} << 20;
    static constexpr std::uint64_t kMaxSegments = std::uint64_t{1} << 26;
    double threshold = 0;  // RenderSettings::pruning_threshold()
    int max_depth = 16;
    int max_reflections = kUnlimited, max_transmissions = kUnlimited;
    // The spectral eye pass weighs a band's light by its RGB weight after the band's walk:
    // the weight a band's dropped branch would have carried is scaled by it. Bands past
    // the end (the shortcut's three test wavelengths) are not counted.
    const std::vector<Vec3>* band_weights = nullptr;
};

// Throws InputError naming the scene and its max_depth and threshold: one ray tree grew
// past TreeLimits::kMaxEntries waiting branches (`entries`) or kMaxSegments segments.
[[noreturn]] void tree_too_large(const Scene& scene, bool entries);

// The limits a scene's render settings set (no reflection/transmission limits).
inline TreeLimits tree_limits(const RenderSettings& s) {
    TreeLimits l;
    l.threshold = s.pruning_threshold();
    l.max_depth = s.max_depth;
    return l;
}

// The FIFO list: entries in a vector read from a moving head, so that a walk (and the
// next one, when the list is reused) allocates only while the list grows; the consumed
// front is reclaimed once it is half of the storage.
template <class T>
class FifoList {
public:
    FifoList() = default;
    FifoList(std::initializer_list<T> init) : items_(init) {}
    bool empty() const { return head_ == items_.size(); }
    size_t size() const { return items_.size() - head_; }
    T& front() { return items_[head_]; }
    void push_back(const T& t) { items_.push_back(t); }
    // A new entry at the back, to be filled in place (default-constructed), and its removal.
    T& emplace_back() { return items_.emplace_back(); }
    void pop_back() { items_.pop_back(); }
    // Room for n more entries: front() stays where it is through n push_back()s.
    void reserve_more(size_t n) {
        if (items_.capacity() < items_.size() + n) items_.reserve(2 * (items_.size() + n));
    }
    void pop_front() {
        if (++head_ == items_.size()) {
            items_.clear();
            head_ = 0;
        } else if (head_ >= 256 && 2 * head_ >= items_.size()) {
            items_.erase(items_.begin(), items_.begin() + static_cast<std::ptrdiff_t>(head_));
            head_ = 0;
        }
    }

private:
    std::vector<T> items_;
    size_t head_ = 0;
};

// A packet of the walk (RayTreeWalkerT::walk_lanes): up to kLanes rays that differ in their
// band (the wavelengths of one photon or of one split eye ray), each at the same place in
// its own tree (the same generation, and the same branch of its parent's packet). Per lane
// what a TreeEntry holds; shared the depth. Natural light only. Lanes not in use (`active`
// false) carry anything.
struct LaneEntry {
    LaneVec3 origin, dir;
    Lanes weight[3];  // per colour channel
    Lanes bailout, travelled;
    LaneMask active = LaneMask::Constant(false);
    std::array<std::int16_t, kLanes> band, reflections, transmissions;
    std::array<std::int32_t, kLanes> object, facet;  // the hit each ray leaves (-1: none)
    std::int16_t depth = 0;

    // Lanes inactive; the rest left as it is (a packet is filled before use, and a list of
    // packets grows without zeroing it).
    LaneEntry() {}

    // Lane l as the walker's entry.
    TreeEntry lane(int l) const {
        const size_t i = static_cast<size_t>(l);
        TreeEntry e{Ray{origin.lane(l), dir.lane(l)}, Vec3(weight[0][l], weight[1][l], weight[2][l]), bailout[l]};
        e.depth = depth;
        e.reflections = reflections[i];
        e.transmissions = transmissions[i];
        e.band = band[i];
        e.travelled = travelled[l];
        e.from = RayOrigin{object[i], facet[i]};
        return e;
    }
    // Lane l takes entry e (at the packet's depth).
    void set(int l, const TreeEntry& e) {
        const size_t i = static_cast<size_t>(l);
        origin.set(l, e.ray.origin);
        dir.set(l, e.ray.dir);
        for (int c = 0; c < 3; ++c) weight[c][l] = e.weight[c];
        bailout[l] = e.bailout;
        travelled[l] = e.travelled;
        active[l] = true;
        band[i] = e.band;
        reflections[i] = e.reflections;
        transmissions[i] = e.transmissions;
        object[i] = e.from.object;
        facet[i] = e.from.facet;
        depth = e.depth;
    }
};

// Ends that take the lanes of a packet leaving the scene at once
// (`void background_lanes(const LaneEntry&, const LaneMask&)`, as background() for each).
template <class Ends, class = void>
struct BackgroundLanes : std::false_type {};
template <class Ends>
struct BackgroundLanes<Ends, std::void_t<decltype(std::declval<Ends&>().background_lanes(
                                 std::declval<const LaneEntry&>(), std::declval<const LaneMask&>()))>>
    : std::true_type {};

// The light each lane's dropped branches would have carried in a lane walk, per cause,
// each summed from zero in the order walk() would drop them.
struct LaneLosses {
    Lanes depth{0.0}, limits{0.0}, threshold{0.0};
};

template <class P>
class RayTreeWalkerT {
public:
    using Entry = TreeEntryT<P>;
    using List = FifoList<Entry>;

    RayTreeWalkerT(const SceneTracer& tracer, const TreeLimits& limits, RenderStats& stats)
        : tracer_(tracer), limits_(limits), stats_(stats) {}

    const SceneTracer& tracer() const { return tracer_; }
    RenderStats& stats() { return stats_; }

    // Walks the list to the end.
    template <class Ends>
    void walk(List& list, Ends& ends) {
        std::uint64_t peak = list.size(), walked = 0;
        while (!list.empty()) {
            if (list.size() > TreeLimits::kMaxEntries || ++walked > TreeLimits::kMaxSegments)
                tree_too_large(tracer_.scene(), list.size() > TreeLimits::kMaxEntries);
            // ⑤ take the oldest entry and find its first surface.
            Entry e = list.front();
            list.pop_front();
            const auto hit = tracer_.intersect(e.ray, stats_, e.from);
            if (!hit) {
                ends.background(e);
                continue;
            }
            arrive(e, *hit, list, ends);
            if (list.size() > peak) peak = list.size();
        }
        if (peak > stats_.peak_list) stats_.peak_list = peak;
    }

    // Entry e's ray has met its first surface at `hit` (found by the walk, or once for
    // several entries along the same ray: the far field's wavelengths of one photon).
    template <class Ends>
    void arrive(Entry e, const SurfaceHit& hit, List& list, Ends& ends) {
        if (tracer_.absorbing() && !hit.entering) {  // Beer–Lambert over the segment inside
            if (const auto a = tracer_.absorption(hit, ends.wavelength(e))) {
                e.weight = e.weight.cwiseProduct(*a);
                e.bailout *= a->maxCoeff();
            }
        }
        if (!ends.intercept(*this, e, hit, list)) expand(e, hit, ends.band_ior(e, hit), list, ends);
    }

    // ②③④ the interaction at hit h: a leaf goes to the callback, branches to the list.
    template <class Ends>
    void expand(const Entry& e, const SurfaceHit& h, double band_ior, List& list, Ends& ends) {
        const Interaction in = tracer_.interact(h, e.ray, stats_, band_ior, false, e.wave, ends.wavelength(e),
                                                std::is_same_v<P, EyeStokes>);
        if (in.leaf) {
            ends.leaf(e, h);
            return;
        }
        for (int b = 0; b < in.branches; ++b) push(e, h, in, b, in.transmitted[static_cast<size_t>(b)], list);
    }

    // ⑥ a child along branch b of `in` with the parent's attenuation times the branch's
    // factor (and `tint`, a band's weight), unless the threshold or a limit drops it.
    // True when it was added.
    bool push(const Entry& e, const SurfaceHit& h, const Interaction& in, int b, bool transmitted, List& list,
              const Vec3& tint = Vec3(1, 1, 1), int band = -2) {
        return push(e, h, in.branch[static_cast<size_t>(b)], in.mueller[static_cast<size_t>(b)], transmitted, list, tint,
                    band);
    }
    // The same for a branch `br` with Mueller matrix M (read only with exact polarisation).
    bool push(const Entry& e, const SurfaceHit& h, const Branch& br, const polar::Mueller& M, bool transmitted,
              List& list, const Vec3& tint = Vec3(1, 1, 1), int band = -2) {
        const Attenuation<Vec3> a = attenuate(e.weight, e.bailout, br.factor, br.bailout_factor);
        const int refl = e.reflections + (transmitted ? 0 : 1), trans = e.transmissions + (transmitted ? 1 : 0);
        if (const Cut c = cut(e.depth, refl, trans, a.bailout); c != Cut::Kept) {
            count(c) += dropped(e, h, br, a.weight.cwiseProduct(tint), M, band);
            return false;
        }
        list.push_back({br.ray, a.weight.cwiseProduct(tint), a.bailout, static_cast<std::int16_t>(e.depth + 1),
                        static_cast<std::int16_t>(refl), static_cast<std::int16_t>(trans),
                        static_cast<std::int16_t>(band == -2 ? e.band : band), br.wave, e.travelled + h.hit.t,
                        descend(e.pol, h.normal, e.ray.dir, M, br.frame_parent, br.frame_child), tracer_.origin_of(h)});
        return true;
    }

    // ⑤–⑥ on packets (natural light): the rays of each packet are searched together
    // (SceneTracer::intersect_lanes); where they meet the same isotropic dielectric (physical
    // mode, Fresnel reflectance) its node is computed on all those lanes at once, from the
    // same laws; every other lane's hit goes through its own interaction, leaf or node, one
    // lane at a time. A lane's children go to the packet of their branch, so each lane meets
    // its nodes and leaves in the order walk() meets them for its ray, and its tree, its
    // light and its losses are walk()'s to the last bit. `ends.lane(l)` are lane l's ends
    // (the same object for all when their sums do not depend on order), which must not
    // intercept band rays; `lost` gathers what each lane's dropped branches carried, which
    // the caller adds to the walker's sums (add_losses).
    template <class LaneEnds>
    void walk_lanes(FifoList<LaneEntry>& list, LaneEnds& ends, LaneLosses& lost) {
        static_assert(std::is_same_v<P, NaturalLight>, "lane walks carry natural light");
        std::uint64_t walked = 0;
        while (!list.empty()) {
            if (list.size() > TreeLimits::kMaxEntries || ++walked > TreeLimits::kMaxSegments)
                tree_too_large(tracer_.scene(), list.size() > TreeLimits::kMaxEntries);
            list.reserve_more(2);  // p's children: p stays in place until it is popped
            const LaneEntry& p = list.front();
            const SceneTracer::LaneHits h = tracer_.intersect_lanes(p.origin, p.dir, p.active, p.object, p.facet, stats_);
            const LaneMask missed = p.active && !h.hit;
            if (missed.any()) background_lanes(p, missed, ends);
            arrive_lanes(p, h, list, ends, lost);
            list.pop_front();
        }
    }

    // Packet p has met its surfaces at h (found by walk_lanes, or once for all lanes): as
    // arrive() on every lane (Beer–Lambert over the segment inside, then the interaction).
    template <class LaneEnds>
    void arrive_lanes(const LaneEntry& p, const SceneTracer::LaneHits& h, FifoList<LaneEntry>& list, LaneEnds& ends,
                      LaneLosses& lost) {
        const LaneMask at = p.active && h.hit;
        if (!at.any()) return;
        if (!tracer_.absorbing()) return expand_lanes(p, at, h, list, ends, lost);
        LaneEntry q = p;
        for (int l = 0; l < kLanes; ++l) {
            if (!at[l] || h.entering[l]) continue;
            const TreeEntry e = p.lane(l);
            if (const auto a = tracer_.absorption(tracer_.surface_hit(h, l), ends.lane(l).wavelength(e))) {
                for (int c = 0; c < 3; ++c) q.weight[c][l] = e.weight[c] * (*a)[c];
                q.bailout[l] = e.bailout * a->maxCoeff();
            }
        }
        expand_lanes(q, at, h, list, ends, lost);
    }

    // ②③④ on the lanes `at` of packet p at their hits h: as expand() on every lane.
    template <class LaneEnds>
    __attribute__((flatten)) void expand_lanes(const LaneEntry& p, const LaneMask& at, const SceneTracer::LaneHits& h,
                                               FifoList<LaneEntry>& list, LaneEnds& ends, LaneLosses& lost) {
        // The lanes whose node is computed together: those at the first lane's isotropic
        // Fresnel dielectric in the physical mode, with natural light.
        const RenderSettings& settings = tracer_.settings();
        const bool natural = settings.polarisation != PolarisationModel::Exact;
        const bool pov = settings.compat == Compat::PovRay;
        const int first = at.first();
        const Material* m0 = &tracer_.scene().materials[h.object[static_cast<size_t>(first)]->material];
        const auto* d = m0->dielectric();
        // POV-Ray mode: band rays (no split here) in an interior without fading.
        const bool vector_node = natural && d && d->reflectance == ReflectanceModel::Fresnel && (!pov || !d->absorption);
        LaneMask together = LaneMask::Constant(false);
        bool all_together = vector_node;
        if (vector_node) {
            const Object* o0 = h.object[static_cast<size_t>(first)];
            for (int l = 0; l < kLanes; ++l) {
                const Object* o = h.object[static_cast<size_t>(l)];
                together[l] = at[l] && (o == o0 || &tracer_.scene().materials[o->material] == m0);
            }
            for (int l = 0; l < kLanes; ++l) all_together = all_together && together[l] == at[l];
        }
        // Lane walks carry isotropic media only (two branches at most per node).
        LaneEntry child[2];
        child[0].depth = child[1].depth = static_cast<std::int16_t>(p.depth + 1);
        if (together.any()) node_lanes(p, together, h, *m0, *d, child, ends, lost);
        // Every other lane through its own interaction.
        for (int l = 0; l < kLanes && !all_together; ++l)
            if (at[l] && !together[l]) interact_lane(p, l, h, child, ends, lost);
        queue(child, list, ends);
    }

    // Lane l of packet p at its hit through its own interaction, as expand(): a leaf to its
    // ends, its children into the packets `child`.
    template <class LaneEnds>
    __attribute__((noinline)) void interact_lane(const LaneEntry& p, int l, const SceneTracer::LaneHits& h,
                                                 LaneEntry (&child)[2], LaneEnds& ends, LaneLosses& lost) {
        const TreeEntry e = p.lane(l);
        const SurfaceHit hl = tracer_.surface_hit(h, l);
        auto& el = ends.lane(l);
        const Interaction in = tracer_.interact(hl, e.ray, stats_, el.band_ior(e, hl), false, e.wave, el.wavelength(e));
        if (in.leaf) {
            el.leaf(e, hl);
            return;
        }
        for (int b = 0; b < in.branches && b < 2; ++b)
            push_lane(child[b], l, e, hl, in.branch[static_cast<size_t>(b)], in.transmitted[static_cast<size_t>(b)], lost);
    }

    // Lane l of packet `child` takes entry e's child along branch br (at hit h), unless
    // push()'s rules drop it (its light then counted in lane l of `lost`); with push()'s
    // tint and band. True when it was added.
    __attribute__((noinline)) bool push_lane(LaneEntry& child, int l, const Entry& e, const SurfaceHit& h, const Branch& br, bool transmitted,
                   LaneLosses& lost, const Vec3& tint = Vec3(1, 1, 1), int band = -2) {
        static const polar::Mueller none = polar::Mueller::Identity();  // natural light: not read
        bool added = false;
        as_lane(lost, l, [&] { added = push(e, h, br, none, transmitted, scratch_, tint, band); });
        if (!added) return false;
        child.set(l, scratch_.front());
        scratch_.pop_front();
        return true;
    }

    // The packets `child` (in this order) onto the list, the lanes known to leave the scene
    // ended at once (as the walk would end them).
    template <class LaneEnds>
    void queue(LaneEntry (&child)[2], FifoList<LaneEntry>& list, LaneEnds& ends) {
        for (LaneEntry& c : child) {
            end_escaping(c, ends);
            if (c.active.any()) list.push_back(c);
        }
    }
    // The lanes of packet c known to leave the scene (SceneTracer::escaping_lanes) end here,
    // as the walk would end them.
    template <class LaneEnds>
    void end_escaping(LaneEntry& c, LaneEnds& ends) {
        if (!c.active.any()) return;
        const LaneMask gone = tracer_.escaping_lanes(c.object, c.origin, c.dir, c.active, stats_);
        if (!gone.any()) return;
        background_lanes(c, gone, ends);
        c.active = c.active && !gone;
    }

    // Runs f with the walker's dropped-light sums started from zero, then added to what they
    // were: one band's losses summed on their own, as add_losses() adds a lane's.
    template <class F>
    void own_losses(F&& f) {
        const double d0 = stats_.lost_depth, l0 = stats_.lost_limits, t0 = stats_.lost_threshold;
        stats_.lost_depth = stats_.lost_limits = stats_.lost_threshold = 0;
        f();
        stats_.lost_depth = d0 + stats_.lost_depth;
        stats_.lost_limits = l0 + stats_.lost_limits;
        stats_.lost_threshold = t0 + stats_.lost_threshold;
    }

    // Runs f with push()'s dropped light going to lane l of `lost` (a lane's own sums).
    template <class F>
    void as_lane(LaneLosses& lost, int l, F&& f) {
        LaneLosses* const saved = lane_lost_;
        const int saved_lane = lane_;
        lane_lost_ = &lost;
        lane_ = l;
        f();
        lane_lost_ = saved;
        lane_ = saved_lane;
    }
    // Lane l's losses added to the walker's sums (a band's own sums, as walk()'s caller adds them).
    void add_losses(const LaneLosses& lost, int l) {
        stats_.lost_depth += lost.depth[l];
        stats_.lost_limits += lost.limits[l];
        stats_.lost_threshold += lost.threshold[l];
    }

private:
    // Why push() drops a child: the threshold, the depth limit, the reflection/transmission
    // limits (in this order), or not at all.
    enum class Cut { Kept, Threshold, Depth, Limits };
    Cut cut(int depth, int refl, int trans, double bailout) const {
        if (bailout <= 0 || bailout < limits_.threshold) return Cut::Threshold;
        if (depth + 1 > limits_.max_depth) return Cut::Depth;
        if (refl > limits_.max_reflections || trans > limits_.max_transmissions) return Cut::Limits;
        return Cut::Kept;
    }
    // Counts a dropped child; the sum its light is added to.
    double& count(Cut c) {
        if (c == Cut::Threshold) ++stats_.pruned;
        else ++stats_.depth_limited;
        if (lane_lost_) {  // as_lane
            Lanes& sum = c == Cut::Threshold ? lane_lost_->threshold : c == Cut::Depth ? lane_lost_->depth : lane_lost_->limits;
            return sum[lane_];
        }
        return c == Cut::Threshold ? stats_.lost_threshold : c == Cut::Depth ? stats_.lost_depth : stats_.lost_limits;
    }

    // The node of core/interaction.h dielectric_node on the lanes `m` of packet p, all at
    // dielectric d (material `mat`), from the same laws: both children into child[0]
    // (reflected) and child[1] (refracted), under push()'s rules.
    template <class LaneEnds>
    __attribute__((flatten)) void node_lanes(const LaneEntry& p, const LaneMask& m, const SceneTracer::LaneHits& h, const Material& mat,
                    const material::Dielectric& d, LaneEntry (&child)[2], LaneEnds& ends, LaneLosses& lost) {
        stats_.tree_nodes += static_cast<std::uint64_t>(m.count());
        const int first = m.first();
        // Each lane's index at its band (the ends' band_ior, a function of the band and the
        // material), kept for the next node in the same material with the same bands.
        std::array<std::int16_t, kLanes> bands;
        for (int l = 0; l < kLanes; ++l) bands[static_cast<size_t>(l)] = m[l] ? p.band[static_cast<size_t>(l)] : -2;
        const bool pov = tracer_.settings().compat == Compat::PovRay;
        // POV-Ray stores an interior's ior in single precision (as dielectric interact()).
        const double nominal = pov ? static_cast<double>(static_cast<float>(d.ior)) : d.ior;
        if (&mat != ior_material_ || bands != ior_bands_) {
            ior_material_ = &mat;
            ior_bands_ = bands;
            ior_ = Lanes(nominal);
            const SurfaceHit h0 = tracer_.surface_hit(h, first);
            for (int l = 0; l < kLanes; ++l) {
                if (!m[l]) continue;
                const double b = ends.lane(l).band_ior(p.lane(l), h0);
                if (b > 0) ior_[l] = b;
            }
            inverse_ior_ = Lanes(1.0) / ior_;
        }
        namespace gen = optics::generic;
        const Lanes eta = select(h.entering, ior_, inverse_ior_);  // as dielectric interact(): ior or 1 / ior
        const Lanes cos_i = gen::cos_incident(p.dir, h.normal);
        if (pov) return node_lanes_pov(p, m, h, d, child, nominal, eta, cos_i, lost);
        const Lanes sin2_t = gen::sin2_transmitted(cos_i, eta);
        const LaneMask tir = sin2_t >= Lanes(1.0);
        const Lanes cos_t = gen::cos_of_sin2(sin2_t);  // NaN under total internal reflection
        const Lanes R = select(tir, Lanes(1.0), gen::fresnel_terms(cos_i, cos_t, eta).R());
        Lanes transmit[3];
        for (int c = 0; c < 3; ++c) transmit[c] = (Lanes(1.0) - R) * Lanes(d.filter[c]);
        const Lanes transmit_bailout = largest_of(transmit[0], transmit[1], transmit[2]);  // maxCoeff
        const LaneMask refracts = m && !tir && (R < Lanes(1.0));
        fill_child(child[0], p, h, m, gen::reflect(p.dir, h.normal).normalized(), {R, R, R}, R, false, lost);
        if (refracts.any())
            fill_child(child[1], p, h, refracts,
                       gen::refracted_direction(p.dir, h.normal, cos_i, cos_t, eta).normalized(), transmit,
                       transmit_bailout, true, lost);
    }

    // POV-Ray mode's dielectric node (core/interaction.cpp dielectric_pov) for band rays in
    // an interior without fading, on the lanes `m`: Fresnel with the nominal index, the
    // refraction and its total internal reflection with each band's (eta), a refraction
    // spawned only when its filter's greyscale exceeds adc_bailout, and turned into a mirror
    // ray where the band meets total internal reflection.
    void node_lanes_pov(const LaneEntry& p, const LaneMask& m, const SceneTracer::LaneHits& h,
                        const material::Dielectric& d, LaneEntry (&child)[2], double nominal, const Lanes& eta,
                        const Lanes& cos_i, LaneLosses& lost) {
        namespace gen = optics::generic;
        const Lanes eta_nominal = select(h.entering, Lanes(nominal), Lanes(1.0 / nominal));
        const Lanes sin2_n = gen::sin2_transmitted(cos_i, eta_nominal);
        const Lanes R = select(sin2_n >= Lanes(1.0), Lanes(1.0),
                               gen::fresnel_terms(cos_i, gen::cos_of_sin2(sin2_n), eta_nominal).R());
        const Lanes sin2_t = gen::sin2_transmitted(cos_i, eta);
        const LaneMask tir = sin2_t >= Lanes(1.0);
        Lanes filter[3];
        for (int c = 0; c < 3; ++c) filter[c] = (Lanes(1.0) - R) * Lanes(d.filter[c]);
        const Lanes grey = pov_filter_greyscale(filter, SceneTracer::kPovGreyscale);
        const Lanes largest = largest_of(abs(filter[0]), abs(filter[1]), abs(filter[2]));
        const LaneMask spawn = grey > Lanes(tracer_.settings().pruning_threshold());
        const LaneMask mirror = m && spawn && tir;  // the refracted ray turned into total internal reflection
        const LaneMask normal = m && !mirror;
        const LaneVec3 reflected = gen::reflect(p.dir, h.normal).normalized();
        const Lanes one(1.0);
        const Lanes mirror_factor[3] = {one, one, one};
        const Lanes reflect_factor[3] = {R, R, R};
        Lanes f[3];
        for (int c = 0; c < 3; ++c) f[c] = select(mirror, mirror_factor[c], reflect_factor[c]);
        fill_child(child[0], p, h, m, reflected, f, select(mirror, largest, R), false, lost);
        const LaneMask refracts = normal && spawn;
        if (refracts.any())
            fill_child(child[1], p, h, refracts,
                       gen::refracted_direction(p.dir, h.normal, cos_i, gen::cos_of_sin2(sin2_t), eta).normalized(),
                       filter, largest, true, lost);
    }

    // The lanes `m` of a fresh child c (no lane set yet): leaving hit h of packet p along
    // `dir`, with colour factors f and threshold factor bf (push()'s attenuation), unless
    // push()'s rules drop them (their light then counted in `lost`). Its other lanes get
    // values they will not use.
    void fill_child(LaneEntry& c, const LaneEntry& p, const SceneTracer::LaneHits& h, const LaneMask& m,
                    const LaneVec3& dir, const Lanes (&f)[3], const Lanes& bf, bool transmitted, LaneLosses& lost) {
        const Lanes bailout = p.bailout * bf;
        const std::int16_t dr = transmitted ? 0 : 1, dt = transmitted ? 1 : 0;
        for (size_t i = 0; i < static_cast<size_t>(kLanes); ++i) {
            c.reflections[i] = static_cast<std::int16_t>(p.reflections[i] + dr);
            c.transmissions[i] = static_cast<std::int16_t>(p.transmissions[i] + dt);
        }
        LaneMask keep = m;
        for (int l = 0; l < kLanes; ++l) {
            if (!m[l]) continue;
            const size_t i = static_cast<size_t>(l);
            const Cut why = cut(p.depth, c.reflections[i], c.transmissions[i], bailout[l]);
            if (why == Cut::Kept) continue;
            keep[l] = false;
            const Vec3 w(p.weight[0][l] * f[0][l], p.weight[1][l] * f[1][l], p.weight[2][l] * f[2][l]);
            as_lane(lost, l, [&] { count(why) += band_weighted_mean(w, p.band[i]); });
        }
        if (!keep.any()) return;
        c.origin = h.point;
        c.dir = dir;
        for (int k = 0; k < 3; ++k) c.weight[k] = p.weight[k] * f[k];
        c.bailout = bailout;
        c.travelled = p.travelled + h.t;
        c.active = keep;
        c.band = p.band;
        c.facet = h.facet;
        const Object* objects = tracer_.scene().objects.data();
        for (size_t i = 0; i < static_cast<size_t>(kLanes); ++i)
            c.object[i] = keep[static_cast<int>(i)] ? static_cast<std::int32_t>(h.object[i] - objects) : -1;
    }

    // The lanes m of packet p left the scene.
    template <class LaneEnds>
    static void background_lanes(const LaneEntry& p, const LaneMask& m, LaneEnds& ends) {
        if constexpr (BackgroundLanes<LaneEnds>::value) {
            ends.background_lanes(p, m);
        } else {
            for (int l = 0; l < kLanes; ++l)
                if (m[l]) ends.lane(l).background(p.lane(l));
        }
    }

    // A dropped child's colour weight for the threshold's bookkeeping: its mean, after the
    // band's RGB weight where the walk has one (0 for bands past the end).
    double band_weighted_mean(const Vec3& weight, int k) const {
        Vec3 w = weight;
        if (k >= 0 && limits_.band_weights) {
            const auto& bw = *limits_.band_weights;
            if (static_cast<size_t>(k) >= bw.size()) return 0.0;
            w = w.cwiseProduct(bw[static_cast<size_t>(k)]);
        }
        return w.mean();
    }

    // The light a dropped child would have carried for unpolarised light: its colour
    // weight's mean, times the Fresnel part its polarisation payload holds.
    double dropped(const Entry& e, const SurfaceHit& h, const Branch& br, const Vec3& weight, const polar::Mueller& M,
                   int band) const {
        const int k = band == -2 ? e.band : band;
        if (k >= 0 && limits_.band_weights && static_cast<size_t>(k) >= limits_.band_weights->size()) return 0.0;
        return band_weighted_mean(weight, k) *
               throughput(descend(e.pol, h.normal, e.ray.dir, M, br.frame_parent, br.frame_child));
    }

    const SceneTracer& tracer_;
    TreeLimits limits_;
    RenderStats& stats_;
    // Lane walks: the indices of the last packet's bands in the last material met.
    const Material* ior_material_ = nullptr;
    std::array<std::int16_t, kLanes> ior_bands_{};
    Lanes ior_{0.0}, inverse_ior_{0.0};
    // as_lane: where push() counts dropped light instead of the stats.
    LaneLosses* lane_lost_ = nullptr;
    int lane_ = 0;
    List scratch_;  // a lane's children on their way into packets
};
using RayTreeWalker = RayTreeWalkerT<NaturalLight>;

}  // namespace refract
