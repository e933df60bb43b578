#include <refract/validation/analytic.h>

#include <cmath>

#include <refract/core/optics.h>

namespace refract::analytic {

std::optional<double> fresnel_sphere_pixel(const Camera& camera, const Sphere& sphere, double n, int i, int j) {
    const Ray ray = camera.ray(i + 0.5, j + 0.5);
    const auto hit = intersect(sphere, ray, 0.0, INFINITY);
    if (!hit) return std::nullopt;
    const double cos_i = std::fmin(1.0, -ray.dir.dot(hit->normal));
    return optics::fresnel_reflectance(cos_i, n);
}

}  // namespace refract::analytic
