#pragma once
// The laws of reflection and refraction at a smooth interface, as small pure functions.
//
// η convention (written once, used everywhere): `eta` is the *relative* index of
// refraction n_t / n_i, transmitted side over incident side. A ray entering glass of
// index 1.5 from air has eta = 1.5; leaving it, eta = 1/1.5. cos_i is the cosine of the
// angle of incidence, measured on the incident side, in [0, 1].
#include <cmath>
#include <optional>

#include <refract/geometry/ray.h>

namespace refract::optics {

// The laws written once over the scalar type S (and a 3-vector type V with Scalar,
// dot(), squaredNorm(), +, −, S·V and V/S). The double functions further down are these
// templates at S = double, V = Vec3; other scalar types (experiments count the
// multiplications and divisions of a branching node with one) instantiate them as well.
namespace generic {

template <class S>
struct FresnelTerms {
    S Rs;     // s-polarised (TE) reflectance
    S Rp;     // p-polarised (TM) reflectance
    S cos_t;  // cosine of the refraction angle
    S R() const { return S(0.5) * (Rs + Rp); }  // natural light, eq. 7
    S T() const { return S(1.0) - R(); }        // eq. 8
};

template <class V>
struct WhittedDirections {
    V reflected;                   // R, not normalised (as in the paper)
    std::optional<V> transmitted;  // P, not normalised; empty on TIR
};

// a < b ? a : b (lane types, geometry/lanes.h, have their own, lane by lane).
template <class S>
S min_of(S a, S b) {
    return a < b ? a : b;
}
// a < b ? b : a (std::max's rule).
template <class S>
S max_of(S a, S b) {
    return a < b ? b : a;
}

// Snell's law: sin θt = sin θi / eta, as sin²θt (total internal reflection where it is
// >= 1), and cos θt from it.
template <class S>
S sin2_transmitted(S cos_i, S eta) {
    return (S(1.0) - cos_i * cos_i) / (eta * eta);
}
template <class S>
S cos_of_sin2(S sin2) {
    using std::sqrt;
    return sqrt(S(1.0) - sin2);
}
template <class S>
std::optional<S> cos_transmitted(S cos_i, S eta) {
    const S sin2_t = sin2_transmitted(cos_i, eta);
    if (sin2_t >= S(1.0)) return std::nullopt;
    return cos_of_sin2(sin2_t);
}

// Fresnel amplitude coefficients of the s and p components (Hecht, Optics, §4.6.2, in the
// basis ŝ = n × k̂, p̂ = k̂ × ŝ of each beam; core/polarisation.h):
//   rs = (cos θi − η cos θt)/(cos θi + η cos θt),  rp = (η cos θi − cos θt)/(η cos θi + cos θt),
//   ts = 2 cos θi/(cos θi + η cos θt),             tp = 2 cos θi/(η cos θi + cos θt).
template <class S>
struct SPPair {
    S s, p;
};
template <class S>
SPPair<S> fresnel_reflection_amplitudes(S cos_i, S cos_t, S eta) {
    const S n_ct = eta * cos_t, n_ci = eta * cos_i;
    return {(cos_i - n_ct) / (cos_i + n_ct), (n_ci - cos_t) / (n_ci + cos_t)};
}
template <class S>
SPPair<S> fresnel_transmission_amplitudes(S cos_i, S cos_t, S eta) {
    return {S(2.0) * cos_i / (cos_i + eta * cos_t), S(2.0) * cos_i / (eta * cos_i + cos_t)};
}

// Yasuda eq. 7 (n = eta, Ci = cos θi, Cr = cos θt): s and p amplitude ratios squared.
template <class S>
FresnelTerms<S> fresnel_terms(S cos_i, S cos_t, S eta) {
    const SPPair<S> r = fresnel_reflection_amplitudes(cos_i, cos_t, eta);
    return FresnelTerms<S>{r.s * r.s, r.p * r.p, cos_t};
}

template <class S>
std::optional<FresnelTerms<S>> fresnel(S cos_i, S eta) {
    const auto cos_t = cos_transmitted(cos_i, eta);
    if (!cos_t) return std::nullopt;
    return fresnel_terms(cos_i, *cos_t, eta);
}

template <class S>
S fresnel_reflectance(S cos_i, S eta) {
    const auto f = fresnel(cos_i, eta);
    return f ? f->R() : S(1.0);
}

// RTIOW: R(θ) = R0 + (1 − R0)(1 − cos θ)^5, R0 = ((1 − η)/(1 + η))².
template <class S>
S schlick(S cos, S eta) {
    const S r0 = (S(1.0) - eta) / (S(1.0) + eta);
    const S R0 = r0 * r0;
    const S x = S(1.0) - cos, x2 = x * x;
    return R0 + (S(1.0) - R0) * (x2 * x2 * x);  // (1 − cos)^5 by three products
}

template <class V>
V reflect(const V& d, const V& n) {
    using S = typename V::Scalar;
    return d - S(2.0) * d.dot(n) * n;
}

// cos θi of unit direction d at unit normal n (incident side), at most 1: fmin(−d·n, 1)
// written out (a NaN gives 1, as fmin does), so that it is inlined.
template <class V>
typename V::Scalar cos_incident(const V& d, const V& n) {
    using S = typename V::Scalar;
    return min_of(S(-d.dot(n)), S(1.0));
}

// RTIOW: R'⊥ = (η/η')(R + cosθ n), R'∥ = −sqrt(1 − |R'⊥|²) n, with η/η' = 1/eta, for
// cos θi and cos θt already known (Snell's law applied once per node).
template <class V>
V refracted_direction(const V& d, const V& n, typename V::Scalar cos_i, typename V::Scalar cos_t,
                      typename V::Scalar eta) {
    const V perp = (d + cos_i * n) / eta;
    return V(perp - cos_t * n);
}

template <class V>
std::optional<V> refract(const V& d, const V& n, typename V::Scalar eta) {
    const auto cos_i = cos_incident(d, n);
    const auto cos_t = cos_transmitted(cos_i, eta);
    if (!cos_t) return std::nullopt;
    return refracted_direction(d, n, cos_i, *cos_t, eta);
}

// Yasuda et al. 1984 eq. 4, 2, 5, 3.
template <class V>
WhittedDirections<V> whitted_directions(const V& Vin, const V& N, typename V::Scalar eta) {
    using S = typename V::Scalar;
    using std::abs;
    using std::sqrt;
    const V Vp = Vin / abs(S(Vin.dot(N)));
    WhittedDirections<V> out{Vp + S(2.0) * N, std::nullopt};
    const S q = eta * eta * Vp.squaredNorm() - (Vp + N).squaredNorm();
    if (q > S(0.0)) out.transmitted = (S(1.0) / sqrt(q)) * (N + Vp) - N;
    return out;
}

}  // namespace generic

// Mirror reflection of direction d about unit normal n (either orientation).
Vec3 reflect(const Vec3& d, const Vec3& n);

// Refraction in Heckbert / RTIOW form (RTIOW eq. for R'⊥ and R'∥). d: unit incident
// direction, n: unit normal on the incident side (d·n < 0), eta = n_t / n_i.
// Empty on total internal reflection. Returns a unit vector.
std::optional<Vec3> refract(const Vec3& d, const Vec3& n, double eta);

// Yasuda et al. 1984, eq. 2–5 (Whitted's form): V' = V/|V·N|, R = V' + 2N,
// kf = (n²|V'|² − |V'+N|²)^(-1/2), P = kf (N + V') − N. Here V is the incident
// direction, N the unit normal on the incident side, n = eta = n_t / n_i.
using WhittedDirections = generic::WhittedDirections<Vec3>;
WhittedDirections whitted_directions(const Vec3& V, const Vec3& N, double eta);

// Snell's law: cos θt for the given cos θi; empty on total internal reflection.
std::optional<double> cos_transmitted(double cos_i, double eta);

// Exact Fresnel reflectance of a smooth dielectric interface (Yasuda eq. 7; s and p
// terms as in Born & Wolf). Empty on total internal reflection (R = 1 for both).
// FresnelTerms: Rs (s-polarised, TE), Rp (p-polarised, TM), cos_t (refraction angle),
// R() = (Rs + Rp)/2 for natural light (eq. 7), T() = 1 − R() (eq. 8).
using FresnelTerms = generic::FresnelTerms<double>;
std::optional<FresnelTerms> fresnel(double cos_i, double eta);

// Unpolarised reflectance with TIR folded in (1 on total internal reflection).
double fresnel_reflectance(double cos_i, double eta);

// Schlick's approximation (RTIOW): R0 + (1 − R0)(1 − cos)^5, R0 = ((1−η)/(1+η))².
// RTIOW evaluates it with the incident cosine on both sides of the interface; pass
// cos_t instead for the variant that is exact at both ends when leaving the denser side.
double schlick(double cos, double eta);

// Critical angle (radians) for eta < 1; empty when eta >= 1 (no TIR).
std::optional<double> critical_angle(double eta);
// Brewster's angle (radians): tan θB = eta.
double brewster_angle(double eta);

}  // namespace refract::optics

namespace refract::optics {

// Beer–Lambert (Bouguer–Lambert) law: the fraction of light left after a path of
// length `distance` in a medium of absorption coefficient `alpha`, T = exp(−α d).
// α and d in reciprocal units (α in 1/m with d in m, …).
double beer_lambert(double alpha, double distance);

// The inverse of beer_lambert: the absorption coefficient α = −ln(T)/d of a medium that
// transmits the fraction `transmittance` over a path of length `thickness` (a
// "transmittance colour at a stated thickness", per channel). Empty unless
// 0 < T <= 1 and d > 0 (both finite), so it never yields NaN, infinity or α < 0.
std::optional<double> absorption_coefficient(double transmittance, double thickness);

// The absorption coefficient of a medium of extinction coefficient k (the imaginary part
// of the complex index n + ik) at vacuum wavelength λ: α = 4πk/λ, in the reciprocal unit
// of λ (the intensity decays as exp(−αz); Born & Wolf, Principles of Optics, §14.1).
double extinction_absorption(double k, double wavelength);

}  // namespace refract::optics
