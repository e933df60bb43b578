#include "core/optics.h"

#include <cmath>

namespace refract::optics {

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2.0 * d.dot(n) * n; }

std::optional<double> cos_transmitted(double cos_i, double eta) {
    // Snell: sin θt = sin θi / eta.
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return std::nullopt;
    return std::sqrt(1.0 - sin2_t);
}

std::optional<Vec3> refract(const Vec3& d, const Vec3& n, double eta) {
    // RTIOW: R'⊥ = (η/η')(R + cosθ n), R'∥ = −sqrt(1 − |R'⊥|²) n, with η/η' = 1/eta.
    const double cos_i = std::fmin(-d.dot(n), 1.0);
    const auto cos_t = cos_transmitted(cos_i, eta);
    if (!cos_t) return std::nullopt;
    const Vec3 perp = (d + cos_i * n) / eta;
    return Vec3(perp - *cos_t * n);
}

WhittedDirections whitted_directions(const Vec3& V, const Vec3& N, double eta) {
    // Yasuda et al. 1984 eq. 4, 2, 5, 3.
    const Vec3 Vp = V / std::abs(V.dot(N));
    WhittedDirections out{Vp + 2.0 * N, std::nullopt};
    const double q = eta * eta * Vp.squaredNorm() - (Vp + N).squaredNorm();
    if (q > 0) out.transmitted = (1.0 / std::sqrt(q)) * (N + Vp) - N;
    return out;
}

std::optional<FresnelTerms> fresnel(double cos_i, double eta) {
    // Yasuda eq. 7 (n = eta, Ci = cos θi, Cr = cos θt): s and p amplitude ratios.
    const auto cos_t = cos_transmitted(cos_i, eta);
    if (!cos_t) return std::nullopt;
    const double rs = (cos_i - eta * *cos_t) / (cos_i + eta * *cos_t);
    const double rp = (eta * cos_i - *cos_t) / (eta * cos_i + *cos_t);
    return FresnelTerms{rs * rs, rp * rp, *cos_t};
}

double fresnel_reflectance(double cos_i, double eta) {
    const auto f = fresnel(cos_i, eta);
    return f ? f->R() : 1.0;
}

double schlick(double cos, double eta) {
    // RTIOW: R(θ) = R0 + (1 − R0)(1 − cos θ)^5, R0 = ((1 − η)/(1 + η))².
    const double r0 = (1.0 - eta) / (1.0 + eta);
    const double R0 = r0 * r0;
    return R0 + (1.0 - R0) * std::pow(1.0 - cos, 5);
}

std::optional<double> critical_angle(double eta) {
    if (eta >= 1.0) return std::nullopt;
    return std::asin(eta);
}

double brewster_angle(double eta) { return std::atan(eta); }

}  // namespace refract::optics
