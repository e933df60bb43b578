#include <refract/core/ray_tree.h>

#include <refract/geometry/error.h>

namespace refract {

void tree_too_large(const Scene& scene, bool entries) {
    tree_too_large(scene, entries ? "grew past " + std::to_string(TreeLimits::kMaxEntries) + " waiting branches"
                                  : "took more than " + std::to_string(TreeLimits::kMaxSegments) + " segments");
}

void tree_too_large(const Scene& scene, const std::string& what) {
    const RenderSettings& s = scene.settings;
    const std::string fix = s.integrator == IntegratorKind::Whitted
                                ? "lower /render/max_depth (the Whitted tree is never pruned) or use fresnel-tree"
                                : "raise /render/threshold or lower /render/max_depth";
    throw InputError((scene.source.empty() ? std::string("scene") : scene.source) + ": /render: one ray tree " + what +
                     " (max_depth " + std::to_string(s.max_depth) + ", threshold " + format_value(s.pruning_threshold()) +
                     "): " + fix);
}

}  // namespace refract
