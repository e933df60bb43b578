#include "core/integrators/whitted.h"

#include "core/ray_tree.h"

#include <optional>
#include <vector>

namespace refract {
namespace {

struct StoredNode {
    Vec3 local{0, 0, 0};
    int child[2] = {-1, -1};
    Vec3 factor[2];
};

}  // namespace

Vec3 whitted_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats) {
    const int max_depth = tracer.settings().max_depth;
    // 1. Build the tree: every node stores its hit's local light and its children.
    std::vector<StoredNode> tree;
    struct Pending {
        Ray ray;
        int depth;
    };
    std::vector<Pending> rays{{primary, 0}};
    tree.emplace_back();
    for (size_t k = 0; k < tree.size(); ++k) {
        const Pending p = rays[k];
        const auto hit = tracer.intersect(p.ray, stats);
        if (!hit) {
            tree[k].local = tracer.background(p.ray.dir);
            continue;
        }
        // Beer–Lambert over the ray that reached this node scales all its light: its
        // local light and its children's factors.
        const std::optional<Vec3> absorbed = tracer.absorption(*hit, 0.0);
        const Interaction n = tracer.interact(*hit, p.ray, stats);
        if (n.leaf) tree[k].local = tracer.local_light(*hit, stats);
        if (absorbed) tree[k].local = tree[k].local.cwiseProduct(*absorbed);
        for (int b = 0; b < n.branches; ++b) {
            if (p.depth + 1 > max_depth) {
                ++stats.depth_limited;
                continue;
            }
            if (tree.size() >= TreeLimits::kMaxEntries) tree_too_large(tracer.scene(), true);
            tree[k].child[b] = static_cast<int>(tree.size());
            tree[k].factor[b] = absorbed ? Vec3(n.branch[b].factor.cwiseProduct(*absorbed)) : n.branch[b].factor;
            tree.emplace_back();
            rays.push_back({n.branch[b].ray, p.depth + 1});
        }
    }
    if (tree.size() > stats.peak_list) stats.peak_list = tree.size();
    // 2. Evaluate bottom-up: children always come after their parent.
    std::vector<Vec3> I(tree.size());
    for (size_t k = tree.size(); k-- > 0;) {
        Vec3 v = tree[k].local;
        for (int b = 0; b < 2; ++b)
            if (tree[k].child[b] >= 0) v += tree[k].factor[b].cwiseProduct(I[tree[k].child[b]]);
        I[k] = v;
    }
    return I[0];
}

}  // namespace refract
