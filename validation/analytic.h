#pragma once
// Analytic references: what a correct renderer must produce for scenes whose answer is
// known in closed form.
#include <optional>

#include <refract/core/scene.h>

namespace refract::analytic {

// A sphere of index n that only reflects (its inside is black: the refracted light is
// absorbed) in front of a uniform white background: the pixel whose primary ray hits
// the sphere at incidence θ is exactly R(θ, n) (unpolarised Fresnel). Empty where the
// primary ray misses the sphere (the pixel is the background, 1).
std::optional<double> fresnel_sphere_pixel(const Camera& camera, const Sphere& sphere, double n, int i, int j);

}  // namespace refract::analytic
