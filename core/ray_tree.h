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
#include <type_traits>
#include <vector>

#include "core/polarisation_state.h"
#include "core/tracer.h"

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
        if (a.bailout <= 0 || a.bailout < limits_.threshold) {
            ++stats_.pruned;
            stats_.lost_threshold += dropped(e, h, br, a.weight.cwiseProduct(tint), M, band);
            return false;
        }
        const int refl = e.reflections + (transmitted ? 0 : 1), trans = e.transmissions + (transmitted ? 1 : 0);
        if (e.depth + 1 > limits_.max_depth) {
            ++stats_.depth_limited;
            stats_.lost_depth += dropped(e, h, br, a.weight.cwiseProduct(tint), M, band);
            return false;
        }
        if (refl > limits_.max_reflections || trans > limits_.max_transmissions) {
            ++stats_.depth_limited;
            stats_.lost_limits += dropped(e, h, br, a.weight.cwiseProduct(tint), M, band);
            return false;
        }
        list.push_back({br.ray, a.weight.cwiseProduct(tint), a.bailout, static_cast<std::int16_t>(e.depth + 1),
                        static_cast<std::int16_t>(refl), static_cast<std::int16_t>(trans),
                        static_cast<std::int16_t>(band == -2 ? e.band : band), br.wave, e.travelled + h.hit.t,
                        descend(e.pol, h.normal, e.ray.dir, M, br.frame_parent, br.frame_child), tracer_.origin_of(h)});
        return true;
    }

private:
    // The light a dropped child would have carried for unpolarised light: its colour
    // weight's mean, times the Fresnel part its polarisation payload holds.
    double dropped(const Entry& e, const SurfaceHit& h, const Branch& br, const Vec3& weight, const polar::Mueller& M,
                   int band) const {
        const int k = band == -2 ? e.band : band;
        Vec3 w = weight;
        if (k >= 0 && limits_.band_weights) {
            const auto& bw = *limits_.band_weights;
            if (static_cast<size_t>(k) >= bw.size()) return 0.0;
            w = w.cwiseProduct(bw[static_cast<size_t>(k)]);
        }
        return w.mean() * throughput(descend(e.pol, h.normal, e.ray.dir, M, br.frame_parent, br.frame_child));
    }

    const SceneTracer& tracer_;
    TreeLimits limits_;
    RenderStats& stats_;
};
using RayTreeWalker = RayTreeWalkerT<NaturalLight>;

}  // namespace refract
