#pragma once
// POV-Ray 3.7's dispersion split (trace.cpp ComputeRefraction), the compatibility policy's
// half of the spectral eye pass (SpectralContext::Split::Refraction): an RGB ray splits at
// its first refraction only. Fresnel and the reflected ray use the nominal index (the
// reflection stays RGB); the refracted ray, when spawned, splits into the material's
// bands, each with its own direction and total-internal-reflection test (the policy's
// node with `split`); a band meeting total internal reflection there becomes a mirror ray
// made from the incoming ray, the same for every such band, so it is traced once, as a
// full ray (it splits again at its next dispersive hit), with the sum of their weights.
#include <optional>
#include <vector>

#include <refract/core/integrators/spectral.h>
#include <refract/core/ray_tree.h>

namespace refract {

// Entry e's split at hit h (its RGB reflection pushed onto `rgb_list`), with the spectral
// ends `ends` (SpectralEnds: fresh(), context(), stats(), walk_bands()); the bands' light,
// tinted by their weights, in band order.
template <class Walker, class Ends>
auto split_at_refraction(Walker& w, const typename Walker::Entry& e, const SurfaceHit& h, typename Walker::List& rgb_list,
                         Ends& ends) {
    const SpectralContext& ctx = ends.context();
    RenderStats& stats = ends.stats();
    const SceneTracer& tracer = w.tracer();
    const size_t mi = static_cast<size_t>(h.object->material);
    typename Ends::Acc sum;
    sum.setZero();
    const std::vector<int>& bands = ctx.split_bands[mi];
    const Interaction first = tracer.interact(h, e.ray, stats, ctx.index[static_cast<size_t>(bands[0])][mi], true);
    if (first.branches > 0) w.push(e, h, first, 0, false, rgb_list);
    if (first.branches < 2) return sum;  // nothing refracts
    // Each band's interaction, in band order: the mirror bands' weights summed, the others'
    // refracted rays walked.
    Vec3 mirror_weight(0, 0, 0);
    std::optional<Branch> mirror;  // natural light: no Mueller matrix
    struct BandRay {
        int band;
        Branch branch;
    };
    std::vector<BandRay> refracted;
    for (const int k : bands) {
        const size_t kb = static_cast<size_t>(k);
        const Interaction bn = k == bands[0] ? first : tracer.interact(h, e.ray, stats, ctx.index[kb][mi], true);
        if (bn.split_mirror) {
            mirror = bn.branch[1];
            mirror_weight += ctx.weights[kb];
            continue;
        }
        refracted.push_back(BandRay{k, bn.branch[1]});
    }
    ends.walk_bands(
        w, static_cast<int>(refracted.size()), [&](int i) { return refracted[static_cast<size_t>(i)].band; },
        [&](auto& s, int i) {
            const BandRay& r = refracted[static_cast<size_t>(i)];
            s.push(e, h, r.branch, true, Vec3(1, 1, 1), r.band);
        },
        sum);
    if (mirror) {
        typename Walker::List list;
        w.push(e, h, *mirror, polar::Mueller::Identity(), false, list);
        Ends sub = ends.fresh();
        w.walk(list, sub);
        sum += tinted(mirror_weight, sub.sum);
    }
    return sum;
}

}  // namespace refract
