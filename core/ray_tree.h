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

// A packet of the walk (RayTreeWalkerT::walk_lanes): the same node of the trees of up to
// kLanes rays that differ only in their band (the wavelengths of one photon), which follow
// the same branches through the same surfaces. Per lane what a TreeEntry holds; shared the
// counters and the object the rays leave. Natural light only. Lanes not in use keep a
// valid band (the index of a band is looked up for every lane).
struct LaneEntry {
    LaneVec3 origin, dir;
    Lanes weight[3];  // per colour channel
    Lanes bailout, travelled;
    LaneMask active;
    std::array<std::int16_t, kLanes> band{};
    std::array<std::int32_t, kLanes> facet{};  // the facet each ray leaves
    std::int32_t object = -1;                  // the object they leave (−1: none)
    std::int16_t depth = 0, reflections = 0, transmissions = 0;

    // Lane l as the walker's entry.
    TreeEntry lane(int l) const {
        TreeEntry e{Ray{origin.lane(l), dir.lane(l)}, Vec3(weight[0][l], weight[1][l], weight[2][l]), bailout[l]};
        e.depth = depth;
        e.reflections = reflections;
        e.transmissions = transmissions;
        e.band = band[static_cast<size_t>(l)];
        e.travelled = travelled[l];
        e.from = RayOrigin{object, facet[static_cast<size_t>(l)]};
        return e;
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

    // ⑤–⑥ on packets (natural light): the rays of each packet are searched together, and
    // where all of them meet the same isotropic dielectric (physical mode, Fresnel
    // reflectance, no absorption) its node is computed on every lane at once and both
    // branches go on as packets; a lane that meets anything else leaves the packet and its
    // tree is walked alone by walk(). Each lane's tree is the one walk() walks for its ray,
    // to the last bit. `lost` gathers what each lane's dropped branches carried. The ends
    // must not intercept hits (intercept() false).
    template <class Ends>
    void walk_lanes(FifoList<LaneEntry>& list, Ends& ends, LaneLosses& lost) {
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

    // Packet p has met its surfaces at h (found by walk_lanes, or once for all lanes).
    template <class Ends>
    __attribute__((flatten)) void arrive_lanes(const LaneEntry& p, const SceneTracer::LaneHits& h, FifoList<LaneEntry>& list, Ends& ends,
                      LaneLosses& lost) {
        const LaneMask at = p.active && h.hit;
        int first = -1;
        for (int l = kLanes - 1; l >= 0; --l)
            if (at[l]) first = l;
        if (first < 0) return;
        const SurfaceHit h0 = tracer_.surface_hit(h, first);
        const RenderSettings& settings = tracer_.settings();
        const auto* d = h0.material->dielectric();
        bool together = d && d->reflectance == ReflectanceModel::Fresnel && !tracer_.absorbing() &&
                        settings.compat == Compat::Physical && settings.polarisation != PolarisationModel::Exact;
        for (int l = 0; l < kLanes && together; ++l)
            together = !at[l] || (h.object[static_cast<size_t>(l)] == h0.object && h.entering[l] == h0.entering);
        if (!together) {  // lane by lane
            for (int l = 0; l < kLanes; ++l)
                if (at[l]) walk_alone(p.lane(l), tracer_.surface_hit(h, l), ends, lost, l);
            return;
        }
        stats_.tree_nodes += static_cast<std::uint64_t>(at.count());
        // The node of core/interaction.h dielectric_node on every lane, from the same laws.
        // Each lane's index at its band (the ends' band_ior, a function of the band and the
        // material), kept for the next node in the same material with the same bands.
        if (h0.material != ior_material_ || p.band != ior_bands_) {
            ior_material_ = h0.material;
            ior_bands_ = p.band;
            ior_ = Lanes(d->ior);
            Entry probe = p.lane(first);
            for (int l = 0; l < kLanes; ++l) {
                probe.band = p.band[static_cast<size_t>(l)];
                const double b = ends.band_ior(probe, h0);
                if (b > 0) ior_[l] = b;
            }
            inverse_ior_ = Lanes(1.0) / ior_;
        }
        namespace gen = optics::generic;
        const Lanes& eta = h0.entering ? ior_ : inverse_ior_;  // as dielectric interact(): ior or 1 / ior
        const Lanes cos_i = gen::cos_incident(p.dir, h.normal);
        const Lanes sin2_t = gen::sin2_transmitted(cos_i, eta);
        const LaneMask tir = sin2_t >= Lanes(1.0);
        const Lanes cos_t = gen::cos_of_sin2(sin2_t);  // NaN under total internal reflection
        const Lanes R = select(tir, Lanes(1.0), gen::fresnel_terms(cos_i, cos_t, eta).R());
        const LaneVec3 reflected = gen::reflect(p.dir, h.normal).normalized();
        const LaneVec3 refracted = gen::refracted_direction(p.dir, h.normal, cos_i, cos_t, eta).normalized();
        Lanes transmit_factor[3];
        for (int c = 0; c < 3; ++c) transmit_factor[c] = (Lanes(1.0) - R) * Lanes(d->filter[c]);
        Lanes transmit_bailout = transmit_factor[0];  // the largest component, as maxCoeff
        for (int c = 1; c < 3; ++c)
            transmit_bailout = select(transmit_factor[c] > transmit_bailout, transmit_factor[c], transmit_bailout);
        const Lanes reflect_factor[3] = {R, R, R};
        const std::int32_t object = tracer_.origin_of(h0).object;
        push_lanes(p, h, object, at, reflected, reflect_factor, R, false, list, ends, lost);
        push_lanes(p, h, object, at && !tir && (R < Lanes(1.0)), refracted, transmit_factor, transmit_bailout, true,
                   list, ends, lost);
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
        if (c == Cut::Threshold) {
            ++stats_.pruned;
            return stats_.lost_threshold;
        }
        ++stats_.depth_limited;
        return c == Cut::Depth ? stats_.lost_depth : stats_.lost_limits;
    }

    // Lane l of a lane walk on its own: its tree by walk(), its losses into lane l.
    template <class Ends>
    void walk_alone(const Entry& e, const SurfaceHit& h, Ends& ends, LaneLosses& lost, int l) {
        const double d0 = stats_.lost_depth, l0 = stats_.lost_limits, t0 = stats_.lost_threshold;
        stats_.lost_depth = stats_.lost_limits = stats_.lost_threshold = 0;
        List alone;
        arrive(e, h, alone, ends);
        walk(alone, ends);
        lost.depth[l] += stats_.lost_depth;
        lost.limits[l] += stats_.lost_limits;
        lost.threshold[l] += stats_.lost_threshold;
        stats_.lost_depth += d0;
        stats_.lost_limits += l0;
        stats_.lost_threshold += t0;
    }

    // ⑥ on packets: the children of packet p along one branch (direction `dir`, colour
    // factors f, threshold factor bf) in the lanes of `mask`, unless push()'s rules drop them.
    template <class Ends>
    void push_lanes(const LaneEntry& p, const SceneTracer::LaneHits& h, std::int32_t object, const LaneMask& mask,
                    const LaneVec3& dir, const Lanes (&f)[3], const Lanes& bf, bool transmitted,
                    FifoList<LaneEntry>& list, Ends& ends, LaneLosses& lost) {
        if (!mask.any()) return;
        LaneEntry c;
        c.bailout = p.bailout * bf;
        for (int k = 0; k < 3; ++k) c.weight[k] = p.weight[k] * f[k];
        c.active = mask;
        const int refl = p.reflections + (transmitted ? 0 : 1), trans = p.transmissions + (transmitted ? 1 : 0);
        for (int l = 0; l < kLanes; ++l) {
            if (!mask[l]) continue;
            const Cut why = cut(p.depth, refl, trans, c.bailout[l]);
            if (why == Cut::Kept) continue;
            c.active[l] = false;
            const Vec3 w(c.weight[0][l], c.weight[1][l], c.weight[2][l]);
            const double amount = band_weighted_mean(w, p.band[static_cast<size_t>(l)]);
            count(why) += amount;
            (why == Cut::Threshold ? lost.threshold : why == Cut::Depth ? lost.depth : lost.limits)[l] += amount;
        }
        if (!c.active.any()) return;
        c.origin = h.point;
        c.dir = dir;
        c.travelled = p.travelled + h.t;
        c.band = p.band;
        c.facet = h.facet;
        c.object = object;
        c.depth = static_cast<std::int16_t>(p.depth + 1);
        c.reflections = static_cast<std::int16_t>(refl);
        c.transmissions = static_cast<std::int16_t>(trans);
        // Children known to leave the scene end here, as the walk would end them.
        const LaneMask gone = tracer_.escaping_lanes(object, c.origin, c.dir, c.active, stats_);
        if (gone.any()) {
            background_lanes(c, gone, ends);
            c.active = c.active && !gone;
            if (!c.active.any()) return;
        }
        list.push_back(c);
    }

    // The lanes m of packet p left the scene.
    template <class Ends>
    static void background_lanes(const LaneEntry& p, const LaneMask& m, Ends& ends) {
        if constexpr (BackgroundLanes<Ends>::value) {
            ends.background_lanes(p, m);
        } else {
            for (int l = 0; l < kLanes; ++l)
                if (m[l]) ends.background(p.lane(l));
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
};
using RayTreeWalker = RayTreeWalkerT<NaturalLight>;

}  // namespace refract
