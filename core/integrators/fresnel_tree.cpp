#include "core/integrators/fresnel_tree.h"

#include <deque>

namespace refract {

Vec3 fresnel_tree_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats) {
    const RenderSettings& s = tracer.settings();
    struct Entry {
        Ray ray;
        Vec3 weight;    // cumulative attenuation per channel (eq. 12's coefficients)
        double bailout; // the scalar the threshold is compared with
        int depth;
    };
    Vec3 pixel(0, 0, 0);  // the shading accumulator, 0 at the start
    std::deque<Entry> list;
    // ① the primary ray, weight 1.
    list.push_back({primary, Vec3(1, 1, 1), 1.0, 0});
    std::uint64_t peak = 1;
    while (!list.empty()) {
        // ⑤ take the oldest entry and find its first surface.
        const Entry e = list.front();
        list.pop_front();
        const auto hit = tracer.intersect(e.ray, stats);
        if (!hit) {
            pixel += e.weight.cwiseProduct(tracer.background(e.ray.dir));
            continue;
        }
        // ②③ hit, normal, R and P directions, reflectance and transmittance.
        const Node n = tracer.node(*hit, e.ray, stats);
        pixel += e.weight.cwiseProduct(n.local);  // leaves: opaque surface shade
        // ④⑥ children with the parent's attenuation times r or 1 − r; small ones dropped.
        for (int b = 0; b < n.branches; ++b) {
            const Branch& br = n.branch[b];
            const double bail = e.bailout * br.bailout_factor;
            if (bail <= 0 || bail < s.pruning_threshold()) {
                ++stats.pruned;
                continue;
            }
            if (e.depth + 1 > s.max_depth) {
                ++stats.depth_limited;
                continue;
            }
            list.push_back({br.ray, e.weight.cwiseProduct(br.factor), bail, e.depth + 1});
        }
        if (list.size() > peak) peak = list.size();
    }
    if (peak > stats.peak_list) stats.peak_list = peak;
    return pixel;
}

}  // namespace refract
