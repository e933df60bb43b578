#pragma once
// The laws of reflection and refraction at a smooth interface, as small pure functions.
//
// η convention (written once, used everywhere): `eta` is the *relative* index of
// refraction n_t / n_i, transmitted side over incident side. A ray entering glass of
// index 1.5 from air has eta = 1.5; leaving it, eta = 1/1.5. cos_i is the cosine of the
// angle of incidence, measured on the incident side, in [0, 1].
#include <optional>

#include "geometry/ray.h"

namespace refract::optics {

// Mirror reflection of direction d about unit normal n (either orientation).
Vec3 reflect(const Vec3& d, const Vec3& n);

// Refraction in Heckbert / RTIOW form (RTIOW eq. for R'⊥ and R'∥). d: unit incident
// direction, n: unit normal on the incident side (d·n < 0), eta = n_t / n_i.
// Empty on total internal reflection. Returns a unit vector.
std::optional<Vec3> refract(const Vec3& d, const Vec3& n, double eta);

// Yasuda et al. 1984, eq. 2–5 (Whitted's form): V' = V/|V·N|, R = V' + 2N,
// kf = (n²|V'|² − |V'+N|²)^(-1/2), P = kf (N + V') − N. Here V is the incident
// direction, N the unit normal on the incident side, n = eta = n_t / n_i.
struct WhittedDirections {
    Vec3 reflected;                   // R, not normalised (as in the paper)
    std::optional<Vec3> transmitted;  // P, not normalised; empty on TIR
};
WhittedDirections whitted_directions(const Vec3& V, const Vec3& N, double eta);

// Snell's law: cos θt for the given cos θi; empty on total internal reflection.
std::optional<double> cos_transmitted(double cos_i, double eta);

// Exact Fresnel reflectance of a smooth dielectric interface (Yasuda eq. 7; s and p
// terms as in Born & Wolf). Empty on total internal reflection (R = 1 for both).
struct FresnelTerms {
    double Rs;     // s-polarised (TE) reflectance
    double Rp;     // p-polarised (TM) reflectance
    double cos_t;  // cosine of the refraction angle
    double R() const { return 0.5 * (Rs + Rp); }  // natural light, eq. 7
    double T() const { return 1.0 - R(); }        // eq. 8
};
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
