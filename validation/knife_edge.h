#pragma once
// Knife-edge pixels (docs/validation.md, "Random scenes"): a pixel whose value jumps when
// its camera ray moves by a thousandth of a pixel. Its ray passes that close to an edge,
// a silhouette or the critical angle somewhere in its tree, so which side it falls on
// depends on rounding (POV-Ray's float meshes, its own ray set-up and epsilons against
// refract's doubles), amplified bounce after bounce. Two correct renderers can differ
// there by the full contrast of the edge; the random suite sets such pixels aside as a
// class of their own, counted and bounded, never silently.
#include <vector>

#include <refract/core/image.h>
#include <refract/core/scene.h>
#include <refract/validation/compare.h>

namespace refract::validation {

// How far the camera ray is moved, in pixels.
constexpr double kKnifeEdgeShift = 1e-2;

// The camera with every pixel's ray moved by about (dx, dy) pixels (x right, y down): an
// orthographic camera translated (exactly), a perspective one turned so that its central
// ray moves by exactly that (off the centre its image plane tilts with it: within 20 % of
// the shift at the corners of a 50° view).
Camera shifted_camera(const Camera& camera, double dx, double dy);

// Per pixel of `scene` (row-major): true when one of the four renders with the camera
// shifted by kKnifeEdgeShift pixels left, right, up or down differs from `centre` (the
// render of `scene` itself, both clipped to [0, 1]) by more than `tolerance` in a channel.
std::vector<char> knife_edge_pixels(const Scene& scene, const Image& centre, double tolerance, int threads);

// The suite's rule with knife-edge pixels set aside: the pixels over the tolerance that are
// knife-edge count towards the fraction over but not towards the RMSE (their refract value
// is replaced by POV-Ray's). `set_aside` receives their number.
bool met_outside_knife_edges(const Image& refract, const Image& povray, const std::vector<char>& knife_edge,
                             const Targets& targets, int& set_aside, ImageDifference& outside);

}  // namespace refract::validation
