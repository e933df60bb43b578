#pragma once
#include <refract/core/polarisation_state.h>
#include <refract/core/tracer.h>

namespace refract {

// Yasuda et al. 1984 §3.1.3, steps ①–⑥: the ray tree is never stored. A FIFO list holds
// (start point, direction, cumulative attenuation); each leaf that reaches an opaque
// surface or the background adds weight × shade to the pixel; a branch whose cumulative
// attenuation (eq. 9–12) falls under the threshold is dropped.
Vec3 fresnel_tree_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats);

// The same walk with exact polarisation: the Stokes vectors the camera records per
// colour channel, starting from the camera-side state `start` (frame, analyser).
StokesRGB fresnel_tree_stokes(const SceneTracer& tracer, const Ray& primary, const EyeStokes& start,
                              RenderStats& stats);

}  // namespace refract
