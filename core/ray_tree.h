#pragma once
// The ray-tree walker (Yasuda et al. 1984 §3.1.3): the tree is never stored; its
// branches wait in a FIFO list, each with its cumulative attenuation, and a branch whose
// attenuation falls below the pruning threshold, or that would exceed the depth or the
// reflection/transmission limits, is dropped. Every tree of refract is walked here — the
// Fresnel-tree and Whitted integrators, the spectral eye pass, the light pass, the far
// field, `trace` — one loop over the entries of the list, whether an entry is one ray or
// a packet of kLanes rays (TreeEntryT<P, Lanes>: the bands of one split, the wavelengths of
// one photon). The integrators differ only in what happens where a branch ends (the `Ends`
// callbacks):
//   void background(const Entry&)              the branch left the scene
//   void leaf(const Entry&, const SurfaceHit&) it met a diffuse surface or an emitter
//   bool intercept(Walker&, const Entry&, const SurfaceHit&, List&)
//        before the hit's own interaction: true when the callback took the hit over
//        (the spectral split at the first dispersive hit)
//   double band_ior(const Entry&, const SurfaceHit&)   the index at the entry's band
//        (0: the material's own)
//   double wavelength(const Entry&)    the entry's wavelength in nm (0: an RGB ray), for
//        the absorption along a segment inside a dielectric (Beer–Lambert)
//   Ends& lane(int l)                  packets: lane l's ends (the same object for every
//        lane where the sums do not depend on the order); optionally
//   void background_lanes(const LaneEntry&, const LaneMask&)   the lanes of a packet that
//        left the scene, at once
//   void intercept_lanes(const LaneEntry&, const LaneMask&, const LaneHits&)   the lanes of
//        a packet that met a surface, before their nodes (to look, not to take over)
//
// A step (⑤–⑥) is the same for one ray and for a packet: the search, the background of
// the rays that met nothing, Beer–Lambert over the segment (one place), then the node.
// Packets compute the node of the lanes at one dielectric together — the very function a
// single ray's interaction calls (CompatRules::dielectric, over the scalar type) — and
// every other lane through its own interaction; each lane's children go to the packet of
// their branch, so each lane meets its nodes, leaves and dropped branches in the order of
// its own walk, and its light is the one-ray walk's to the last bit.
//
// Polarisation rides on the entries as a payload P (core/polarisation_state.h): nothing
// for natural light, the camera-side Mueller matrix for an eye pass, the photon's Stokes
// vector for a light pass; the walker updates it with each branch's Mueller matrix.
// Packets carry natural light.
#include <array>
#include <cstdint>
#include <deque>
#include <cstring>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <refract/core/polarisation_state.h>
#include <refract/core/render_stats.h>
#include <refract/core/tracer.h>
#include <refract/geometry/width.h>

namespace refract {

// One entry of the list: one ray (S = double) or a packet of kLanes rays (S = Lanes), each
// lane what one ray's entry holds; the depth is shared (a packet's lanes are at the same
// place in their own trees: the same generation, the same branch of their parent).
template <class P, class S = double>
struct TreeEntryT {
    RayOf<S> ray;
    VecOf<S> weight;  // cumulative attenuation per channel (eq. 12's coefficients)
    S bailout;        // the scalar the threshold is compared with (a root: 1)
    // Counters in 16 bits (max_depth <= 10000, bands <= 1003): an entry of the
    // natural-light walk of one ray is 112 bytes.
    std::int16_t depth = 0;  // surface interactions before this ray
    EachOf<S, std::int16_t> reflections, transmissions;
    EachOf<S, std::int16_t> band;               // spectral band; −1: an RGB ray
    biref::Wave wave = biref::Wave::Isotropic;  // inside a uniaxial crystal: o or e
    S travelled;                                // path length from the tree's root to this ray's origin
    [[no_unique_address]] P pol{};              // polarisation payload (none for natural light)
    EachOf<S, RayOrigin> from;                  // the hit this ray leaves (none for a root)
    // Packets: the lanes in use (the others carry anything).
    struct AllLanes {};
    [[no_unique_address]] std::conditional_t<kPacketOf<S>, MaskOf<S>, AllLanes> active{};

    // One ray: a root's values. A packet: no lane in use, and nothing else written (a packet
    // is filled lane by lane, or as a whole, before it is read).
    TreeEntryT() {
        if constexpr (!kPacketOf<S>) {
            bailout = 1.0;
            reflections = transmissions = 0;
            band = -1;
            travelled = 0.0;
            from = RayOrigin{};
        }
    }
    TreeEntryT(const Ray& r, const Vec3& w) : TreeEntryT() {
        static_assert(!kPacketOf<S>, "a packet is filled lane by lane");
        ray = r;
        weight = w;
    }

    // Packets: lane l as a one-ray entry, and lane l set from one.
    TreeEntryT<P> lane(int l) const {
        static_assert(kPacketOf<S>, "a packet's lane");
        TreeEntryT<P> e(Ray{ray.origin.lane(l), ray.dir.lane(l)}, weight.lane(l));
        e.bailout = bailout[l];
        e.depth = depth;
        e.reflections = lane_of(reflections, l);
        e.transmissions = lane_of(transmissions, l);
        e.band = lane_of(band, l);
        e.travelled = travelled[l];
        e.from = lane_of(from, l);
        return e;
    }
    void set(int l, const TreeEntryT<P>& e) {
        static_assert(kPacketOf<S>, "a packet's lane");
        ray.origin.set(l, e.ray.origin);
        ray.dir.set(l, e.ray.dir);
        weight.set(l, e.weight);
        bailout[l] = e.bailout;
        travelled[l] = e.travelled;
        active[l] = true;
        set_lane(band, l, e.band);
        set_lane(reflections, l, e.reflections);
        set_lane(transmissions, l, e.transmissions);
        set_lane(from, l, e.from);
        depth = e.depth;
    }
    // Packets: every lane e, none in use; set_band() then turns lane l on at its band (the
    // bands of one entry, seeded as one broadcast).
    void fill(const TreeEntryT<P>& e) {
        static_assert(kPacketOf<S>, "a packet's lanes");
        ray.origin = VecOf<S>::broadcast(e.ray.origin);
        ray.dir = VecOf<S>::broadcast(e.ray.dir);
        weight = VecOf<S>::broadcast(e.weight);
        bailout = S(e.bailout);
        travelled = S(e.travelled);
        active = MaskOf<S>::Constant(false);
        band.fill(e.band);
        reflections.fill(e.reflections);
        transmissions.fill(e.transmissions);
        from.fill(e.from);
        depth = e.depth;
    }
    void set_band(int l, std::int16_t b) {
        static_assert(kPacketOf<S>, "a packet's lane");
        active[l] = true;
        set_lane(band, l, b);
    }
};
using TreeEntry = TreeEntryT<NaturalLight>;
using LaneEntry = TreeEntryT<NaturalLight, Lanes>;

struct TreeLimits {
    static constexpr int kUnlimited = 1 << 30;
    // Work bounds whatever the threshold (docs/limits.md): the branches waiting in one
    // tree's list (Whitted: the nodes of its stored tree), and the segments of one walk.
    static constexpr size_t kMaxEntries = size_t{1} << 20;
    static constexpr std::uint64_t kMaxSegments = std::uint64_t{1} << 26;
    double threshold = 0;  // RenderSettings::pruning_threshold()
    int max_depth = 16;
    int max_reflections = kUnlimited, max_transmissions = kUnlimited;
    // Whitted's stored tree keeps the branches of zero weight (its nodes are counted as
    // they are built); the other walks drop them.
    bool keep_zero = false;
    // The spectral eye pass weighs a band's light by its RGB weight after the band's walk:
    // the weight a band's dropped branch would have carried is scaled by it. Bands past
    // the end (the shortcut's three test wavelengths) are not counted.
    const std::vector<Vec3>* band_weights = nullptr;
};

// Throws InputError naming the scene and its max_depth and threshold: one ray tree grew
// past TreeLimits::kMaxEntries waiting branches (`entries`) or kMaxSegments segments.
[[noreturn]] void tree_too_large(const Scene& scene, bool entries);
// The same for another bound: `what` says how the tree passed it ("took more than ...").
[[noreturn]] void tree_too_large(const Scene& scene, const std::string& what);

// The limits a scene's render settings set (no reflection/transmission limits).
inline TreeLimits tree_limits(const RenderSettings& s) {
    TreeLimits l;
    l.threshold = s.pruning_threshold();
    l.max_depth = s.max_depth;
    l.keep_zero = s.integrator == IntegratorKind::Whitted;
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

// The light dropped branches would have carried, per cause, over the scalar type: one
// walk's sums (S = double) or each lane's (S = Lanes), each summed from zero in the order
// the walk drops them.
template <class S>
struct LossesT {
    S depth = S(0.0), limits = S(0.0), threshold = S(0.0);
};
using LaneLosses = LossesT<Lanes>;

// Ends that take the lanes of a packet leaving the scene at once.
template <class Ends, class = void>
struct BackgroundLanes : std::false_type {};
template <class Ends>
struct BackgroundLanes<Ends, std::void_t<decltype(std::declval<Ends&>().background_lanes(
                                 std::declval<const LaneEntry&>(), std::declval<const LaneMask&>()))>>
    : std::true_type {};
// Ends that look at the lanes of a packet at their hits.
template <class Ends, class = void>
struct InterceptLanes : std::false_type {};
template <class Ends>
struct InterceptLanes<Ends, std::void_t<decltype(std::declval<Ends&>().intercept_lanes(
                                std::declval<const LaneEntry&>(), std::declval<const LaneMask&>(),
                                std::declval<const SceneTracer::LaneHits&>()))>> : std::true_type {};

template <class P>
class RayTreeWalkerT {
public:
    using Entry = TreeEntryT<P>;
    using List = FifoList<Entry>;
    using Packet = TreeEntryT<P, Lanes>;
    using Packets = FifoList<Packet>;

    RayTreeWalkerT(const SceneTracer& tracer, const TreeLimits& limits, RenderStats& stats)
        : tracer_(tracer), limits_(limits), stats_(stats) {
        // The interactions carry natural light's factors or Mueller matrices by the scene's
        // model (polarisation_model()): the payload must be that model's.
        if (tracer.exact() == std::is_same_v<P, NaturalLight>)
            throw std::logic_error("ray-tree walk: the payload is not the scene's polarisation model");
    }

    const SceneTracer& tracer() const { return tracer_; }
    RenderStats& stats() { return stats_; }

    // ⑤–⑥ walks the list to the end: its entries are single rays, or packets.
    template <class S, class Ends>
    void walk(FifoList<TreeEntryT<P, S>>& list, Ends& ends) {
        std::uint64_t peak = list.size(), walked = 0;
        while (!list.empty()) {
            if (list.size() > TreeLimits::kMaxEntries || ++walked > TreeLimits::kMaxSegments)
                tree_too_large(tracer_.scene(), list.size() > TreeLimits::kMaxEntries);
            // ⑤ take the oldest entry and find its first surface. A packet stays in place
            // until its children (two at most) are queued; a ray is copied out, as its
            // callbacks may queue many.
            if constexpr (kPacketOf<S>) {
                list.reserve_more(2);
                TreeEntryT<P, S>& e = list.front();
                const auto h = search(e);
                if (met(e, h, ends)) arrive(e, h, list, ends);
                list.pop_front();
            } else {
                TreeEntryT<P, S> e = list.front();
                list.pop_front();
                std::optional<SurfaceHit> h;
                if (!search(e, h, ends)) continue;  // lost in a gradient-index medium
                if (met(e, h, ends)) arrive(e, h, list, ends);
            }
            if (list.size() > peak) peak = list.size();
        }
        if constexpr (!kPacketOf<S>) {  // the longest list of one ray's tree
            if (peak > stats_.peak_list) stats_.peak_list = peak;
        }
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
        Entry c;
        const Extra x{tint, band, &M, br.wave, &br.frame_parent, &br.frame_child};
        if (!make_child(c, e, h, br.ray.dir, br.factor, br.bailout_factor, transmitted, x, sink_)) return false;
        list.push_back(c);
        return true;
    }

    // The subtrees of `n` bands, walked kLanes at a time (packets: the scene's tracer allows
    // them and the walk carries natural light) or one by one: `seed(s, i)` starts band i's
    // subtree through the BandSeed s (arrive or expand an entry at a hit, or push a branch);
    // `ends` are either one ends object for every band (whose sums do not depend on the
    // order) or a function giving band i's; `done(i, losses)` is called in band order after
    // band i's walk, with the light its dropped branches carried (summed from zero).
    // `one_by_one`: never in packets.
    class BandSeed;
    template <class Seed, class Ends, class Done>
    void walk_bands(int n, Seed&& seed, Ends&& ends, Done&& done, bool one_by_one = false) {
        if constexpr (std::is_same_v<P, NaturalLight>) {
            if (!one_by_one && tracer_.packets()) {
                Scratch<Packets> scratch(packet_lists_);  // reused: it allocates only while it grows
                Packets& packets = scratch.list;
                LaneLosses* const saved = packet_lost_;
                for (int i0 = 0; i0 < n; i0 += kLanes) {
                    const int m = std::min(kLanes, n - i0);
                    auto&& lanes = lane_ends(ends, i0);
                    LaneLosses lost;
                    packet_lost_ = &lost;
                    BandSeed s(*this, lost);
                    for (int l = 0; l < m; ++l) {
                        s.lane_ = l;
                        seed(s, i0 + l);
                    }
                    s.start(packets, lanes);
                    walk(packets, lanes);
                    for (int l = 0; l < m; ++l)
                        done(i0 + l, LossesT<double>{lost.depth[l], lost.limits[l], lost.threshold[l]});
                }
                packet_lost_ = saved;
                return;
            }
        }
        Scratch<List> scratch(lists_);
        List& list = scratch.list;
        for (int i = 0; i < n; ++i) {
            LossesT<double> lost;
            const Sink saved = sink_;
            sink_ = Sink{&lost.depth, &lost.limits, &lost.threshold};
            auto&& one = band_ends(ends, i);
            BandSeed s(*this, list);
            seed(s, i);
            s.start(list, one);
            walk(list, one);
            sink_ = saved;
            done(i, lost);
        }
    }

    // A band's start (walk_bands): one ray's, or lane lane_ of a packet's.
    class BandSeed {
    public:
        // Entry e (at its band) arriving at hit h: Beer–Lambert, then its node.
        void arrive(const Entry& e, const SurfaceHit& h) { take(e, h, true, 0.0); }
        // Entry e (at its band) at hit h: its node with the band's index (0: the material's).
        void expand(const Entry& e, const SurfaceHit& h, double band_ior) { take(e, h, false, band_ior); }
        // The same for entry e at band `band`, where e (but its band) and h are the same for
        // every band of the walk: a packet's lanes are seeded by one broadcast.
        void arrive_band(const Entry& e, const SurfaceHit& h, int band) { take_band(e, h, true, band, 0.0); }
        void expand_band(const Entry& e, const SurfaceHit& h, int band, double band_ior) {
            take_band(e, h, false, band, band_ior);
        }
        // Entry e's child along branch br at hit h (natural light), tinted and at `band`: a
        // reflected branch first, a transmitted one after it.
        void push(const Entry& e, const SurfaceHit& h, const Branch& br, bool transmitted, const Vec3& tint, int band) {
            static const polar::Mueller none = polar::Mueller::Identity();  // natural light: not read
            push(e, h, br, none, transmitted, tint, band);
        }
        // The same for branch b of interaction `in` (its Mueller matrix with exact polarisation).
        void push(const Entry& e, const SurfaceHit& h, const Interaction& in, int b, const Vec3& tint, int band) {
            const size_t k = static_cast<size_t>(b);
            push(e, h, in.branch[k], in.mueller[k], in.transmitted[k], tint, band);
        }

    private:
        friend class RayTreeWalkerT;
        BandSeed(RayTreeWalkerT& w, List& list) : w_(w), list_(&list) {}
        BandSeed(RayTreeWalkerT& w, LaneLosses& lost) : w_(w), lost_(&lost) {}

        void push(const Entry& e, const SurfaceHit& h, const Branch& br, const polar::Mueller& M, bool transmitted,
                  const Vec3& tint, int band) {
            if (!lost_) {
                w_.push(e, h, br, M, transmitted, *list_, tint, band);
                return;
            }
            pushed_ = true;
            Entry c;
            const Extra x{tint, band, &M, br.wave, &br.frame_parent, &br.frame_child};
            const Sink one{&lost_->depth[lane_], &lost_->limits[lane_], &lost_->threshold[lane_]};
            if (w_.make_child(c, e, h, br.ray.dir, br.factor, br.bailout_factor, transmitted, x, one))
                children_[transmitted ? 1 : 0].set(lane_, c);
        }
        void take_band(const Entry& e, const SurfaceHit& h, bool absorb, int band, double band_ior) {
            if (!lost_) {
                Entry eb = e;
                eb.band = static_cast<std::int16_t>(band);
                take(eb, h, absorb, band_ior);
                return;
            }
            if (!entry_.active.any()) {  // the packet's first band
                hit_ = h;
                absorb_ = absorb;
                entry_.fill(e);
            }
            entry_.set_band(lane_, static_cast<std::int16_t>(band));
        }
        void take(const Entry& e, const SurfaceHit& h, bool absorb, double band_ior) {
            if (lost_) {
                if (!entry_.active.any()) {  // a packet's lanes share their hit
                    hit_ = h;
                    absorb_ = absorb;
                }
                entry_.set(lane_, e);
                return;
            }
            hit_ = h;
            absorb_ = absorb;
            one_ = e;
            band_ior_ = band_ior;
            has_one_ = true;
        }

        // The seeded start into `list` (one ray) with `ends`.
        template <class Ends>
        void start(List& list, Ends& ends) {
            if (!has_one_) return;
            if (absorb_) {
                w_.arrive(one_, hit_, list, ends);
            } else {
                w_.expand(one_, hit_, band_ior_, list, ends);
            }
        }
        // The seeded lanes into `packets` with lane ends `ends`.
        template <class Ends>
        void start(Packets& packets, Ends& ends) {
            if (pushed_) {
                w_.queue(children_, packets, ends);
                return;
            }
            if (!entry_.active.any()) return;
            const SceneTracer::LaneHits h = SceneTracer::lanes_of(hit_);
            if (absorb_) w_.absorb(entry_, h, ends);
            w_.expand_packet(entry_, entry_.active, h, packets, ends, *lost_);
        }

        RayTreeWalkerT& w_;
        List* list_ = nullptr;
        LaneLosses* lost_ = nullptr;
        int lane_ = 0;
        Entry one_;
        SurfaceHit hit_;
        bool absorb_ = false, has_one_ = false, pushed_ = false;
        double band_ior_ = 0;
        Packet entry_;
        Packet children_[2];
    };

private:
    // Entry e's ray has met its first surface(s) at h (found by the walk, or once for several
    // entries along the same ray: the far field's wavelengths of one photon): Beer–Lambert
    // over the segment inside, then the callback's intercept, then the node.
    template <class S, class H, class Ends>
    void arrive(TreeEntryT<P, S>& e, const H& h, FifoList<TreeEntryT<P, S>>& list, Ends& ends) {
        absorb(e, h, ends);
        if constexpr (!kPacketOf<S>) {
            if (ends.intercept(*this, e, hit_of(h), list)) return;
        } else if constexpr (InterceptLanes<Ends>::value) {
            ends.intercept_lanes(e, e.active && h.hit, h);
        }
        expand(e, h, list, ends);
    }

    // ②③④ the interaction at hit h of one ray: a leaf goes to the callback, branches to
    // the list (the band's index `band_ior`, 0: the material's own).
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

    // Lists for band walks, one per level of nesting (a band walk's RGB mirror ray may split
    // again), reused so that they allocate only while they grow.
    template <class L>
    struct Scratch {
        std::deque<L>& pool;
        L& list;
        explicit Scratch(std::pair<std::deque<L>, size_t>& p) : pool(p.first), list(take(p)), depth(p.second) {}
        ~Scratch() { --depth; }
        static L& take(std::pair<std::deque<L>, size_t>& p) {
            if (p.second == p.first.size()) p.first.emplace_back();
            return p.first[p.second++];
        }
        size_t& depth;
    };
    std::pair<std::deque<List>, size_t> lists_{};
    std::pair<std::deque<Packets>, size_t> packet_lists_{};

    // Where a walk sums the light of its dropped branches (the stats, or a band's own sums).
    struct Sink {
        double *depth, *limits, *threshold;
    };
    // What a one-ray child carries besides its ray and factors.
    struct Extra {
        Vec3 tint;
        int band;
        const polar::Mueller* M;
        biref::Wave wave;
        const Vec3 *frame_parent, *frame_child;
    };

    // Lane ends of a band group: lane l is band i0 + l's.
    template <class EndsOf>
    struct LaneEnds {
        EndsOf& ends_of;
        int i0;
        auto& lane(int l) { return ends_of(i0 + l); }
    };
    // A band group's lane ends, and band i's ends: from a function of the band, or one
    // ends object for all.
    template <class Ends>
    static decltype(auto) lane_ends(Ends& ends, int i0) {
        if constexpr (std::is_invocable_v<Ends&, int>) {
            return LaneEnds<Ends>{ends, i0};
        } else {
            return (ends);
        }
    }
    template <class Ends>
    static decltype(auto) band_ends(Ends& ends, int i) {
        if constexpr (std::is_invocable_v<Ends&, int>) {
            return ends(i);
        } else {
            return (ends);
        }
    }

    // ⑤ the search: the nearest hit of one ray, or of each lane of a packet.
    std::optional<SurfaceHit> search(const Entry& e) { return tracer_.intersect(e.ray, stats_, e.from); }
    // One ray inside a gradient-index medium (docs/grin.md): its curved segment to the
    // medium's boundary (SceneTracer::through, which turns e.ray to the direction it arrives
    // in, hit.t its curved length, and carries an exact payload's Stokes frame along the ray
    // by Rytov's law: the Stokes vector is unchanged in the transported frame), else the
    // straight search. False when the step budget ran
    // out on the way: its light is lost, counted with the limits'. (Packets never meet one:
    // a medium's rays ride alone, in_packets.)
    template <class Ends>
    bool search(Entry& e, std::optional<SurfaceHit>& h, Ends& ends) {
        if (const grin::Medium* m = tracer_.medium_of(e.ray, e.from)) {
            if constexpr (std::is_same_v<P, NaturalLight>) {
                h = tracer_.through(*m, e.ray, ends.wavelength(e), stats_);
            } else {  // the Stokes frame transported along the curved ray (Rytov's law)
                h = tracer_.through(*m, e.ray, ends.wavelength(e), stats_, &e.pol.x);
            }
            if (!h) *sink_.limits += band_weighted_mean(e.weight, e.band) * throughput(e.pol);
            return h.has_value();
        }
        h = search(e);
        return true;
    }
    SceneTracer::LaneHits search(const Packet& p) {
        return tracer_.intersect_lanes(p.ray.origin, p.ray.dir, p.active, p.from, stats_);
    }
    static const SurfaceHit& hit_of(const std::optional<SurfaceHit>& h) { return *h; }
    static const SurfaceHit& hit_of(const SurfaceHit& h) { return h; }
    // The rays that met nothing end at the background; true when any ray met a surface.
    template <class Ends>
    bool met(const Entry& e, const std::optional<SurfaceHit>& h, Ends& ends) {
        if (!h) ends.background(e);
        return h.has_value();
    }
    template <class Ends>
    bool met(const Packet& p, const SceneTracer::LaneHits& h, Ends& ends) {
        const LaneMask missed = p.active && !h.hit;
        if (missed.any()) background_lanes(p, missed, ends);
        return (p.active && h.hit).any();
    }

    // Beer–Lambert over the segment that ended inside an absorbing dielectric, lane by lane
    // (the policy's: physical mode; POV-Ray fades in its node).
    template <class Ends>
    void absorb(Entry& e, const std::optional<SurfaceHit>& h, Ends& ends) {
        absorb(e, *h, ends);
    }
    template <class Ends>
    void absorb(Entry& e, const SurfaceHit& h, Ends& ends) {
        if (!tracer_.absorbing() || h.entering) return;
        if (const auto a = tracer_.absorption(h, ends.wavelength(e))) {
            e.weight = e.weight.cwiseProduct(*a);
            e.bailout *= a->maxCoeff();
        }
    }
    template <class Ends>
    void absorb(Packet& p, const SceneTracer::LaneHits& h, Ends& ends) {
        if (!tracer_.absorbing()) return;
        for_each_lane(p.active && h.hit && !h.entering, [&](int l) {
            Entry e = p.lane(l);
            absorb(e, tracer_.surface_hit(h, l), ends.lane(l));
            p.weight.set(l, e.weight);
            p.bailout[l] = e.bailout;
        });
    }

    // ②③④ a one ray's node (expand, above) or a packet's.
    template <class Ends>
    void expand(const Entry& e, const std::optional<SurfaceHit>& h, List& list, Ends& ends) {
        expand(e, *h, ends.band_ior(e, *h), list, ends);
    }
    template <class Ends>
    void expand(const Packet& p, const SceneTracer::LaneHits& h, Packets& list, Ends& ends) {
        static_assert(std::is_same_v<P, NaturalLight>, "packets carry natural light");
        expand_packet(p, p.active && h.hit, h, list, ends, *packet_lost_);
    }

    // The lanes `at` of packet p at their hits h: the lanes at the first lane's dielectric
    // through its node together, every other lane through its own interaction; the children
    // queued by branch (reflected, then transmitted).
    template <class Ends>
    __attribute__((flatten)) void expand_packet(const Packet& p, const LaneMask& at, const SceneTracer::LaneHits& h, Packets& list, Ends& ends,
                       LaneLosses& lost) {
        const int first = at.first();
        const Material* m0 = &tracer_.scene().materials[static_cast<size_t>(h.object[static_cast<size_t>(first)]->material)];
        const material::Dielectric* d = m0->dielectric();
        LaneMask together = LaneMask::Constant(false);
        if (d) {
            const Object* o0 = h.object[static_cast<size_t>(first)];
            for_each_lane(at, [&](int l) {
                const Object* o = h.object[static_cast<size_t>(l)];
                together[l] = o == o0 || &tracer_.scene().materials[static_cast<size_t>(o->material)] == m0;
            });
        }
        // Packets carry isotropic media only (two branches at most per node).
        Packet child[2];
        if (together.any()) node(p, together, h, *m0, *d, child, ends, lost);
        const LaneMask rest = at && !together;
        for_each_lane(rest, [&](int l) { interact_lane(p, l, h, child, ends, lost); });
        queue(child, list, ends);
    }

    // The node of dielectric d (material `mat`) on the lanes `m` of packet p: the policy's
    // node over lanes (CompatRules::dielectric), both children into child[0] (reflected)
    // and child[1] (refracted).
    template <class Ends>
    __attribute__((flatten)) void node(const Packet& p, const LaneMask& m, const SceneTracer::LaneHits& h, const Material& mat,
              const material::Dielectric& d, Packet (&child)[2], Ends& ends, LaneLosses& lost) {
        stats_.tree_nodes += static_cast<std::uint64_t>(m.count());
        const CompatRules& rules = tracer_.rules();
        const double nominal = rules.nominal_index(d.ior);
        // Each lane's index at its band (the ends' band_ior, a function of the band and the
        // material), kept for the next node in the same material with the same bands.
        // (The key compared as words read from the packet: no store of eight bands to reload.)
        static_assert(sizeof(p.band) == 2 * sizeof(std::uint64_t), "eight 16-bit bands");
        std::uint64_t bands[2];
        std::memcpy(bands, p.band.data(), sizeof bands);
        for (int k = 0; k < 2; ++k) {  // lanes not in m: band −2 (0xfffe)
            const std::uint64_t in_m = kLaneWords[(m.bits >> (4 * k)) & 0xfu];
            bands[k] = (bands[k] & in_m) | (0xfffefffefffefffeull & ~in_m);
        }
        if (&mat != ior_material_ || bands[0] != ior_bands_[0] || bands[1] != ior_bands_[1]) {
            ior_material_ = &mat;
            ior_bands_[0] = bands[0];
            ior_bands_[1] = bands[1];
            ior_ = Lanes(nominal);
            const SurfaceHit h0 = tracer_.surface_hit(h, m.first());
            for_each_lane(m, [&](int l) {
                const double b = ends.lane(l).band_ior(p.lane(l), h0);
                if (b > 0) ior_[l] = b;
            });
            inverse_ior_ = Lanes(1.0) / ior_;
        }
        const NodeAt<LaneVec3> at{p.ray.dir, h.normal, h.t, h.entering, select(h.entering, ior_, inverse_ior_),
                                  select(h.entering, Lanes(nominal), Lanes(1.0 / nominal)), m};
        const NodeBranches<LaneVec3> b = rules.dielectric(d, at, LaneVec3::broadcast(d.filter), false);
        for (int k = 0; k < 2; ++k) {
            const LaneMask on = m && b.exists[k];
            if (on.any()) lanes_child(child[k], p, on, h, b.dir[k], b.factor[k], b.bailout[k], k == 1, lost);
        }
    }

    // Lane l of packet p at its hit through its own interaction (a leaf to its ends, its
    // children into the packets `child`), its losses into lane l of `lost`.
    template <class Ends>
    __attribute__((noinline)) void interact_lane(const Packet& p, int l, const SceneTracer::LaneHits& h,
                                                 Packet (&child)[2], Ends& ends, LaneLosses& lost) {
        const Entry e = p.lane(l);
        const SurfaceHit hl = tracer_.surface_hit(h, l);
        auto& el = ends.lane(l);
        const Interaction in = tracer_.interact(hl, e.ray, stats_, el.band_ior(e, hl), false, e.wave, el.wavelength(e));
        if (in.leaf) {
            el.leaf(e, hl);
            return;
        }
        static const polar::Mueller none = polar::Mueller::Identity();  // natural light: not read
        const Sink one{&lost.depth[l], &lost.limits[l], &lost.threshold[l]};
        for (int b = 0; b < in.branches && b < 2; ++b) {
            const Branch& br = in.branch[static_cast<size_t>(b)];
            Entry c;
            const Extra x{Vec3(1, 1, 1), -2, &none, br.wave, &br.frame_parent, &br.frame_child};
            if (make_child(c, e, hl, br.ray.dir, br.factor, br.bailout_factor, in.transmitted[static_cast<size_t>(b)], x,
                      one))
                child[b].set(l, c);
        }
    }

    // The packets `child` (in this order) onto the list, the lanes known to leave the scene
    // ended at once (as the walk would end them).
    template <class Ends>
    void queue(Packet (&child)[2], Packets& list, Ends& ends) {
        for (Packet& c : child) {
            if (!c.active.any()) continue;
            const LaneMask gone = tracer_.escaping_lanes(c.from, c.ray.origin, c.ray.dir, c.active, stats_);
            if (gone.any()) {
                background_lanes(c, gone, ends);
                c.active = c.active && !gone;
            }
            if (c.active.any()) list.push_back(c);
        }
    }

    // Why a child is dropped: the threshold, the depth limit, the reflection/transmission
    // limits (in this order), or not at all.
    enum class Cut { Kept, Threshold, Depth, Limits };
    Cut cut(int depth, int refl, int trans, double bailout) const {
        if (bailout < limits_.threshold || (bailout <= 0 && !limits_.keep_zero)) return Cut::Threshold;
        if (depth + 1 > limits_.max_depth) return Cut::Depth;
        if (refl > limits_.max_reflections || trans > limits_.max_transmissions) return Cut::Limits;
        return Cut::Kept;
    }
    // Counts a dropped child; the sum its light is added to.
    double& count(Cut c, const Sink& s) {
        if (c == Cut::Threshold) ++stats_.pruned;
        else ++stats_.depth_limited;
        return c == Cut::Threshold ? *s.threshold : c == Cut::Depth ? *s.depth : *s.limits;
    }

    // ⑥ the child c of one ray's entry e leaving hit h along `dir`: the parent's attenuation
    // times `factor` (then the tint), unless the threshold or a limit drops it (its light
    // then added to the sink). True when it is kept.
    bool make_child(Entry& c, const Entry& e, const SurfaceHit& h, const Vec3& dir, const Vec3& factor, double bf,
               bool transmitted, const Extra& x, const Sink& sink) {
        const Attenuation<Vec3> a = attenuate(e.weight, e.bailout, factor, bf);
        const int refl = e.reflections + (transmitted ? 0 : 1), trans = e.transmissions + (transmitted ? 1 : 0);
        const Vec3 weight = a.weight.cwiseProduct(x.tint);
        const Vec3 zero = Vec3::Zero();
        const Vec3& xp = x.frame_parent ? *x.frame_parent : zero;
        const Vec3& xc = x.frame_child ? *x.frame_child : zero;
        if (const Cut why = cut(e.depth, refl, trans, a.bailout); why != Cut::Kept) {
            const int k = x.band == -2 ? e.band : x.band;
            if (k >= 0 && limits_.band_weights && static_cast<size_t>(k) >= limits_.band_weights->size()) {
                count(why, sink) += 0.0;
            } else {
                count(why, sink) += band_weighted_mean(weight, k) * throughput(descend(e.pol, h.normal, e.ray.dir, *x.M, xp, xc));
            }
            return false;
        }
        c.ray = Ray{h.hit.point, dir};
        c.weight = weight;
        c.bailout = a.bailout;
        c.depth = static_cast<std::int16_t>(e.depth + 1);
        c.reflections = static_cast<std::int16_t>(refl);
        c.transmissions = static_cast<std::int16_t>(trans);
        c.band = static_cast<std::int16_t>(x.band == -2 ? e.band : x.band);
        c.wave = x.wave;
        c.travelled = e.travelled + h.hit.t;
        c.pol = descend(e.pol, h.normal, e.ray.dir, *x.M, xp, xc);
        c.from = tracer_.origin_of(h);
        return true;
    }
    // The same on the lanes `m` of a fresh packet child c (no lane set yet) of packet p, each
    // lane as child() above (no tint: node children); its other lanes get values they do
    // not use.
    void lanes_child(Packet& c, const Packet& p, const LaneMask& m, const SceneTracer::LaneHits& h, const LaneVec3& dir,
                     const LaneVec3& f, const Lanes& bf, bool transmitted, LaneLosses& lost) {
        const Lanes bailout = p.bailout * bf;
        const LaneVec3 weight = cwise(p.weight, f);
        const std::int16_t dr = transmitted ? 0 : 1, dt = transmitted ? 1 : 0;
        for (size_t i = 0; i < static_cast<size_t>(kLanes); ++i) {
            c.reflections[i] = static_cast<std::int16_t>(p.reflections[i] + dr);
            c.transmissions[i] = static_cast<std::int16_t>(p.transmissions[i] + dt);
        }
        // The lanes cut() may drop, found over the packet (the threshold, then the depth and
        // the limits); each of them then through cut() itself, in lane order.
        LaneMask maybe = bailout < Lanes(limits_.threshold);
        if (!limits_.keep_zero) maybe = maybe || (Lanes(0.0) >= bailout);
        if (p.depth + 1 > limits_.max_depth) maybe = LaneMask::Constant(true);
        if (limits_.max_reflections < TreeLimits::kUnlimited || limits_.max_transmissions < TreeLimits::kUnlimited)
            for (int l = 0; l < kLanes; ++l)
                maybe[l] = maybe[l] || c.reflections[static_cast<size_t>(l)] > limits_.max_reflections ||
                           c.transmissions[static_cast<size_t>(l)] > limits_.max_transmissions;
        LaneMask keep = m;
        for_each_lane(m && maybe, [&](int l) {
            const size_t i = static_cast<size_t>(l);
            const Cut why = cut(p.depth, c.reflections[i], c.transmissions[i], bailout[l]);
            if (why == Cut::Kept) return;
            keep[l] = false;
            const Sink one{&lost.depth[l], &lost.limits[l], &lost.threshold[l]};
            count(why, one) += band_weighted_mean(weight.lane(l), p.band[i]);
        });
        if (!keep.any()) return;
        c.ray.origin = h.point;
        c.ray.dir = dir;
        c.weight = weight;
        c.bailout = bailout;
        c.travelled = p.travelled + h.t;
        c.active = keep;
        c.band = p.band;
        c.depth = static_cast<std::int16_t>(p.depth + 1);
        const Object* objects = tracer_.scene().objects.data();
        for (size_t i = 0; i < static_cast<size_t>(kLanes); ++i)
            c.from[i] = keep[static_cast<int>(i)]
                            ? RayOrigin{static_cast<std::int32_t>(h.object[i] - objects), h.facet[i], h.inverted[static_cast<int>(i)]}
                            : RayOrigin{};
    }

    // The lanes m of packet p left the scene.
    template <class Ends>
    static void background_lanes(const Packet& p, const LaneMask& m, Ends& ends) {
        if constexpr (BackgroundLanes<Ends>::value) {
            ends.background_lanes(p, m);
        } else {
            for_each_lane(m, [&](int l) { ends.lane(l).background(p.lane(l)); });
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

    const SceneTracer& tracer_;
    TreeLimits limits_;
    RenderStats& stats_;
    Sink sink_{&stats_.lost_depth, &stats_.lost_limits, &stats_.lost_threshold};
    // Where a packet walk sums each lane's losses (walk_bands: the group's).
    LaneLosses lost_;
    LaneLosses* packet_lost_ = &lost_;
    // Packets: the indices of the last packet's bands in the last material met.
    const Material* ior_material_ = nullptr;
    std::uint64_t ior_bands_[2] = {0, 0};
    // Four lanes' bits as four 16-bit masks (lane j of the four: bits 16j to 16j + 15).
    static constexpr std::uint64_t kLaneWords[16] = {
        0x0000000000000000ull, 0x000000000000ffffull, 0x00000000ffff0000ull, 0x00000000ffffffffull,
        0x0000ffff00000000ull, 0x0000ffff0000ffffull, 0x0000ffffffff0000ull, 0x0000ffffffffffffull,
        0xffff000000000000ull, 0xffff00000000ffffull, 0xffff0000ffff0000ull, 0xffff0000ffffffffull,
        0xffffffff00000000ull, 0xffffffff0000ffffull, 0xffffffffffff0000ull, 0xffffffffffffffffull};
    Lanes ior_{0.0}, inverse_ior_{0.0};
};
using RayTreeWalker = RayTreeWalkerT<NaturalLight>;

}  // namespace refract
