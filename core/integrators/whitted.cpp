#include <refract/core/integrators/whitted.h>

#include <optional>
#include <vector>

#include <refract/core/integrators/integrator.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/ray_tree.h>

namespace refract {
namespace {

// A node of the stored tree: its hit's local light and its children with their factors.
struct StoredNode {
    Vec3 local{0, 0, 0};
    int child[2] = {-1, -1};
    Vec3 factor[2];
};

// Whitted's policy on the one walker: the tree is stored as it is walked (the FIFO list
// meets the nodes breadth first, so node k's children are the next ones created), every
// node's branches kept whatever their weight (TreeLimits::keep_zero, threshold 0) up to the
// depth limit; the light is evaluated afterwards, bottom-up.
struct StoredTreeEnds {
    const SceneTracer& tracer;
    RenderStats& stats;
    std::vector<StoredNode> tree;
    int created = 1;  // the root

    // Node ids in the walk's order: node k is the k-th entry taken from the list.
    void background(const TreeEntry& e) { tree.emplace_back().local = tracer.background(e.ray.dir); }
    void leaf(const TreeEntry&, const SurfaceHit&) {}
    double band_ior(const TreeEntry&, const SurfaceHit&) const { return 0.0; }
    double wavelength(const TreeEntry&) const { return 0.0; }

    // Every hit is a node of the stored tree: its light, and its branches pushed onto the
    // walker's list with their factors. Beer–Lambert over the ray that reached the node
    // scales all its light: its local light and its children's factors.
    bool intercept(RayTreeWalker& w, const TreeEntry& e, const SurfaceHit& h, RayTreeWalker::List& list) {
        const size_t k = tree.size();
        tree.emplace_back();
        const std::optional<Vec3> absorbed = tracer.absorption(h, 0.0);
        const Interaction n = tracer.interact(h, e.ray, stats);
        if (n.leaf) tree[k].local = tracer.local_light(h, stats);
        if (absorbed) tree[k].local = tree[k].local.cwiseProduct(*absorbed);
        for (int b = 0; b < n.branches; ++b) {
            if (!w.push(e, h, n, b, n.transmitted[static_cast<size_t>(b)], list)) continue;
            if (static_cast<size_t>(created) >= TreeLimits::kMaxEntries) tree_too_large(tracer.scene(), true);
            const Vec3& f = n.branch[static_cast<size_t>(b)].factor;
            tree[k].child[b] = created++;
            tree[k].factor[b] = absorbed ? Vec3(f.cwiseProduct(*absorbed)) : f;
        }
        return true;
    }
};

}  // namespace

Vec3 whitted_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats) {
    // 1. Build the tree by walking it: every node stores its hit's local light and its children.
    TreeLimits limits = tree_limits(tracer.settings());
    limits.keep_zero = true;
    RayTreeWalker walker(tracer, limits, stats);
    StoredTreeEnds ends{tracer, stats, {}};
    RayTreeWalker::List list{TreeEntry{primary, Vec3(1, 1, 1)}};
    walker.walk(list, ends);
    const std::vector<StoredNode>& tree = ends.tree;
    if (tree.size() > stats.peak_list) stats.peak_list = tree.size();
    // 2. Evaluate bottom-up: children always come after their parent.
    std::vector<Vec3> I(tree.size());
    for (size_t k = tree.size(); k-- > 0;) {
        Vec3 v = tree[k].local;
        for (int b = 0; b < 2; ++b)
            if (tree[k].child[b] >= 0) v += tree[k].factor[b].cwiseProduct(I[static_cast<size_t>(tree[k].child[b])]);
        I[k] = v;
    }
    return I[0];
}

namespace {

// Whitted's stored tree per sample, the samples averaged.
class Whitted : public Integrator {
public:
    using Integrator::Integrator;
    Vec3 pixel(int i, int j, RenderStats& stats, std::vector<double>*) const override {
        return sample_mean<Vec3>(i, j, stats, [&](const Ray& ray) { return whitted_radiance(tracer_, ray, stats); });
    }
};

}  // namespace

// With a spectral pass: the spectral eye pass under Whitted's rule, which never prunes
// (RenderSettings::pruning_threshold), as POV-Ray renders it with adc_bailout 0.
std::unique_ptr<Integrator> whitted_integrator(const SceneTracer& tracer, const SpectralContext* spectral) {
    if (spectral) return spectral_integrator(tracer, *spectral);
    return std::make_unique<Whitted>(tracer);
}

}  // namespace refract
