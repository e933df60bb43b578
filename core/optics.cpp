#include <refract/core/optics.h>

#include <cmath>

namespace refract::optics {

// Every law is written once, in core/optics.h's `generic` templates; these are the
// double instances.

Vec3 reflect(const Vec3& d, const Vec3& n) { return generic::reflect(d, n); }

std::optional<double> cos_transmitted(double cos_i, double eta) { return generic::cos_transmitted(cos_i, eta); }

std::optional<Vec3> refract(const Vec3& d, const Vec3& n, double eta) { return generic::refract(d, n, eta); }

WhittedDirections whitted_directions(const Vec3& V, const Vec3& N, double eta) {
    return generic::whitted_directions(V, N, eta);
}

std::optional<FresnelTerms> fresnel(double cos_i, double eta) { return generic::fresnel(cos_i, eta); }

double fresnel_reflectance(double cos_i, double eta) { return generic::fresnel_reflectance(cos_i, eta); }

double schlick(double cos, double eta) { return generic::schlick(cos, eta); }

std::optional<double> critical_angle(double eta) {
    if (eta >= 1.0) return std::nullopt;
    return std::asin(eta);
}

double brewster_angle(double eta) { return std::atan(eta); }

}  // namespace refract::optics

namespace refract::optics {

double beer_lambert(double alpha, double distance) { return std::exp(-alpha * distance); }

std::optional<double> absorption_coefficient(double transmittance, double thickness) {
    if (!(transmittance > 0.0 && transmittance <= 1.0)) return std::nullopt;
    if (!(thickness > 0.0 && std::isfinite(thickness))) return std::nullopt;
    return -std::log(transmittance) / thickness;
}

double extinction_absorption(double k, double wavelength) { return 4.0 * M_PI * k / wavelength; }

}  // namespace refract::optics
