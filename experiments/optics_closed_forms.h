#pragma once
// Closed-form references for the optics bench: classic results of geometric optics for a
// sphere (rainbows), a prism, a plane-parallel slab and a ball lens, computed without any
// ray tracing. Every Fresnel and Snell evaluation goes through core/optics.h.
//
// Conventions: double precision; angles in radians; `n` is the relative index of
// refraction inside / outside (core/optics.h's eta for light entering the body).
// "s" and "p" are the polarisations perpendicular and parallel to the plane of incidence,
// which for a sphere is the scattering plane; "natural" is their mean.
#include <optional>
#include <vector>

namespace refract::experiments::closed_form {

struct Polarised {
    double s = 0.0, p = 0.0, natural = 0.0;  // natural = (s + p)/2
};

// ---- 1. Sphere, geometric optics ----------------------------------------------------
// A collimated beam falls uniformly on a sphere's cross-section; a ray with impact
// parameter b (sphere radius a) meets the surface at incidence angle i, sin i = b/a, and
// refracts to r (Snell). Event class p: p = 0 external reflection, p = 1 direct
// transmission, p = k + 1 after k internal reflections (p = 2 primary rainbow, p = 3
// secondary). References: van de Hulst, "Light Scattering by Small Particles" (1957),
// ch. 12 (geometrical optics of a sphere); Bohren & Huffman, "Absorption and Scattering
// of Light by Small Particles" (1983), ch. 7 (geometrical optics, rainbows).

// Total deviation (unfolded, radians) of class p at incidence i (van de Hulst ch. 12):
// D_0 = π − 2i; D_p = 2(i − r) + (p − 1)(π − 2r) for p >= 1. NaN when class p does not
// exist at i (p < 0, or p >= 1 and the ray is totally reflected at entry, n < 1).
double deviation(int p, double i, double n);

// Scattering angle θ ∈ [0, π] (0 = forward): D_p folded, θ = arccos(cos D_p). NaN as deviation.
double scattering_angle(int p, double i, double n);

// Fraction of a ray's power leaving in class p at incidence i, per polarisation
// (van de Hulst ch. 12): ε_0 = R, ε_p = (1 − R)² R^(p−1) (p >= 1), R = Rs or Rp at i; the
// internal reflections all meet the surface at r with the same R (reciprocity, Stokes
// relations). Total reflection at entry (n < 1) gives ε_0 = 1 and ε_p = 0.
Polarised sphere_class_fraction(int p, double i, double n);

// Power of the beam (cross-section normalised to 1, i.e. the measure d(sin² i) over
// sin² i ∈ [0, 1]) that class p sends into each scattering-angle bin [edges[k], edges[k+1]),
// and the class totals ∫ ε_p d(sin² i) over the whole cross-section.
struct SphereBins {
    std::vector<double> s, p, natural;  // one value per bin: edges.size() − 1 of them
    double total_s = 0.0, total_p = 0.0, total_natural = 0.0;
};
// Exact bin edges: θ(i) is split into monotone pieces (at the rainbow incidence, the
// critical angle and where D_p crosses a multiple of π), each bin edge is inverted on each
// piece by bisection, and ε_p d(sin² i) = ε_p sin 2i di is integrated between consecutive
// split points by tanh–sinh quadrature (accurate to ~1e-12 in practice; the tests compare it
// with a 2e5-point midpoint rule in sin² i). `edges_rad`: ascending, within [0, π].
SphereBins sphere_scattering(double n, int p, const std::vector<double>& edges_rad);

// Descartes' rainbow of class p >= 2 (minimum deviation, dD_p/di = 0): the incidence
// cos² i = (n² − 1)/(p² − 1) (Descartes 1637; van de Hulst ch. 12, Bohren & Huffman ch. 7,
// there written with k = p − 1 internal reflections as (n² − 1)/(k (k + 2))), and its
// scattering angle θ ∈ [0, π]. NaN when class p has no rainbow (p < 2, or not 1 < n < p).
double rainbow_incidence(int p, double n);
double rainbow_deviation(int p, double n);

// ---- 2. Prism (Born & Wolf, "Principles of Optics", §4.7.2) ---------------------------
// Deviation of a ray meeting the first face of a prism of apex angle A at signed incidence
// i1 (in the principal section): δ = i1 + arcsin(n sin(A − r1)) − A, sin r1 = sin i1 / n.
// Empty when the ray is totally reflected at the second face.
std::optional<double> prism_deviation(double apex, double incidence, double n);
// Minimum deviation, reached at symmetric passage r1 = A/2: δ_min = 2 arcsin(n sin(A/2)) − A.
// NaN when n sin(A/2) > 1 (no ray gets through at all).
double prism_minimum_deviation(double apex, double n);

// ---- 3. Plane-parallel non-absorbing slab, incoherent multiple reflections --------------
// (Born & Wolf §7.6.1, the plane-parallel plate, with the phases dropped; Hecht, "Optics",
// multiple-beam interference, likewise.) Both faces reflect R (reciprocity), so per
// polarisation T = (1 − R)² Σ R^(2k) = (1 − R)/(1 + R) and
// R_slab = R + (1 − R)² R Σ R^(2k) = 2R/(1 + R), with R = Rs or Rp at incidence θ.
// natural is the mean of the s and p results (not the formula applied to the mean R).
struct SlabTerms {
    Polarised T;  // transmittance
    Polarised R;  // reflectance
};
SlabTerms slab(double theta, double n);
// The terms of those series, for a single-interface reflectance R: transmitted after 2k
// internal reflections (1 − R)² R^(2k); reflected directly (k = 0) R, and after leaving
// through the first face following 2k − 1 internal reflections (1 − R)² R^(2k−1), k >= 1.
double slab_transmitted_class(int k, double R);
double slab_reflected_class(int k, double R);

// ---- 4. Ball lens, paraxial ---------------------------------------------------------------
// Thick-lens formula (Hecht §6.2, eq. 6.2) with R1 = a, R2 = −a, d = 2a: the effective focal
// length f = n a / (2 (n − 1)), measured from the centre (both principal planes pass
// through it); the back focal distance from the rear surface is f − a = a (2 − n)/(2 (n − 1)).
double ball_lens_focus_from_centre(double n, double radius);
double ball_lens_back_focal_distance(double n, double radius);

}  // namespace refract::experiments::closed_form
