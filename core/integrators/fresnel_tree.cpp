#include "core/integrators/fresnel_tree.h"

#include "core/ray_tree.h"

namespace refract {

namespace {

// Where a branch ends: its weight times the light there is added to the pixel.
struct PixelEnds {
    const SceneTracer& tracer;
    RenderStats& stats;
    Vec3 pixel{0, 0, 0};  // the shading accumulator, 0 at the start

    void background(const TreeEntry& e) { pixel += e.weight.cwiseProduct(tracer.background(e.ray.dir)); }
    void leaf(const TreeEntry& e, const SurfaceHit& h) { pixel += e.weight.cwiseProduct(tracer.local_light(h, stats)); }
    bool intercept(RayTreeWalker&, const TreeEntry&, const SurfaceHit&, RayTreeWalker::List&) { return false; }
    double band_ior(const TreeEntry&, const SurfaceHit&) const { return 0.0; }
};

}  // namespace

Vec3 fresnel_tree_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats) {
    RayTreeWalker walker(tracer, tree_limits(tracer.settings()), stats);
    PixelEnds ends{tracer, stats};
    // ① the primary ray, weight 1.
    RayTreeWalker::List list{TreeEntry{primary, Vec3(1, 1, 1)}};
    walker.walk(list, ends);
    return ends.pixel;
}

}  // namespace refract
