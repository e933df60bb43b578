#pragma once
#include <refract/core/tracer.h>

namespace refract {

// Whitted (1980) as Yasuda et al. 1984 §2 describe it: build the whole ray tree to the
// maximum depth and store it, then evaluate it bottom-up from the leaves, eq. 1:
// I = local + ks·S + kt·T at every node. No pruning threshold (the paper's baseline).
Vec3 whitted_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats);

}  // namespace refract
