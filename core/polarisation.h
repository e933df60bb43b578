#pragma once
// Polarisation as small pure functions: Stokes vectors, Mueller matrices, the Fresnel
// amplitude coefficients and the Mueller matrices of a smooth dielectric interface.
//
// Conventions (written once, used everywhere):
//
// η: as in core/optics.h, `eta` = n_t / n_i (transmitted over incident side) and
//    cos_i in [0, 1] is measured on the incident side.
//
// Stokes vector S = (S0, S1, S2, S3) of a beam with complex transverse field
// (Ex, Ey), time dependence e^{−iωt} (Born & Wolf §1.4.2, §10.8):
//     S0 = |Ex|² + |Ey|²,   S1 = |Ex|² − |Ey|²,
//     S2 = 2 Re(Ex* Ey),    S3 = 2 Im(Ex* Ey),
// in a frame (x̂, ŷ, k̂) that is right-handed: ŷ = k̂ × x̂, k̂ the propagation direction.
// A Stokes vector means nothing without its frame; only x̂ needs carrying along (ŷ
// follows from k̂). S1 = +S0 is light linearly polarised along x̂; S2 = +S0 along
// (x̂ + ŷ)/√2. S3 > 0: the field turns from x̂ towards ŷ, i.e. counter-clockwise for an
// observer looking into the beam (towards the source): positive helicity, called
// *left*-circular in Born & Wolf's naming (§1.4.2), right-circular in the IEEE naming.
//
// s/p basis at an interface with unit normal n: ŝ = normalize(n × k̂), perpendicular to
// the plane of incidence, and p̂ = k̂ × ŝ for each beam (incident, reflected,
// transmitted), so one ŝ serves all three and each beam's (ŝ, p̂, k̂) is right-handed.
// The interface's Mueller matrices below act on Stokes vectors in the frame x̂ = ŝ of
// the incident beam and return them in the frame x̂ = ŝ of the outgoing beam. In this
// basis the Fresnel amplitudes are Hecht's (Optics, 4th ed., §4.6.2):
//     rs = (cos_i − η cos_t)/(cos_i + η cos_t),   ts = 2 cos_i/(cos_i + η cos_t),
//     rp = (η cos_i − cos_t)/(η cos_i + cos_t),   tp = 2 cos_i/(η cos_i + cos_t),
// with rs², rp² exactly optics::fresnel's Rs, Rp. At normal incidence rp = −rs: the
// reflected beam's p̂ is the incident one's reversed, and the helicity flips.
#include <complex>
#include <optional>

#include <Eigen/Core>

#include <refract/geometry/ray.h>

namespace refract::polar {

using Stokes = Eigen::Vector4d;
using Mueller = Eigen::Matrix4d;

// Fresnel amplitude coefficients (Hecht §4.6.2, in the s/p basis above).
// Below the critical angle rs, rp are real (imaginary parts 0) and cos_t is cos θt.
// On total internal reflection (eta < 1, sin θi > eta): tir = true, ts = tp = 0, and
// cos θt is imaginary, cos θt = i·γ with γ = sqrt(sin²θi/η² − 1) >= 0 — the sign for which
// the e^{−iωt} evanescent wave decays away from the interface (Born & Wolf §1.5.4);
// cos_t then holds γ. rs, rp are then unit-modulus complex numbers,
//     rs = exp(−2i·atan(η γ / cos_i)),   rp = exp(−2i·atan(γ / (η cos_i))).
struct FresnelAmplitudes {
    std::complex<double> rs, rp;
    double ts, tp;
    double cos_t;  // cos θt; on TIR, γ = Im(cos θt)
    bool tir;
};
FresnelAmplitudes fresnel_amplitudes(double cos_i, double eta);

// Mueller matrix of the Jones matrix diag(a, b) (x̂ component times a, ŷ times b), from
// the Stokes definition above (Azzam & Bashara, Ellipsometry and Polarized
// Light, ch. 2; Chipman, "Polarimetry", Handbook of Optics vol. II): with z = conj(a)·b,
//     [ (|a|²+|b|²)/2  (|a|²−|b|²)/2  0     0    ]
//     [ (|a|²−|b|²)/2  (|a|²+|b|²)/2  0     0    ]
//     [ 0              0              Re z  −Im z ]
//     [ 0              0              Im z  Re z  ]
Mueller jones_diagonal_to_mueller(std::complex<double> a, std::complex<double> b);

// Mueller matrix of a general 2×2 Jones matrix J (E_out = J E_in, both in their own
// frames): from the coherency matrix Φ = E E† of the Stokes definition above,
// Φ = ½[[S0 + S1, S2 − iS3], [S2 + iS3, S0 − S1]], Φ' = J Φ J† (Azzam & Bashara ch. 2);
// jones_diagonal_to_mueller is its diagonal case.
Mueller jones_to_mueller(const Eigen::Matrix2cd& J);

// Reflection at a smooth dielectric interface: jones_diagonal_to_mueller(rs, rp).
// M00 = optics::fresnel R() for natural light; on TIR M00 = 1 and the lower block is
// the rotation by the phase difference δ = arg rs − arg rp (M23 = sin δ, M22 = cos δ).
Mueller mueller_reflection(double cos_i, double eta);

// Transmission through the interface: (η cos_t / cos_i) · jones_diagonal_to_mueller(ts,
// tp), the factor converting amplitude to power (Born & Wolf §1.5.3), so that
// M00 = 1 − R for natural light and Rs + Ts = Rp + Tp = 1. Empty on TIR.
std::optional<Mueller> mueller_transmission(double cos_i, double eta);

// Phase difference δ = δs − δp = arg rs − arg rp on total internal reflection, in
// closed form (Born & Wolf §1.5.4): tan(δ/2) = cos θ sqrt(sin²θ − η²) / sin²θ,
// δ in [0, π). Its maximum, at sin²θ = 2η²/(1 + η²), is tan(δm/2) = (1 − η²)/(2η).
// 0 when there is no TIR.
double tir_phase_difference(double cos_i, double eta);

// Change of frame about k̂: S' = R S is S in the frame turned by +angle about k̂,
// x̂' = cos a x̂ + sin a ŷ (Collett, Polarized Light, ch. 5):
//     R = [[1,0,0,0], [0,cos 2a,sin 2a,0], [0,−sin 2a,cos 2a,0], [0,0,0,1]].
Mueller rotator(double angle);

// Signed angle from x_from to x_to about k (all unit, x_from and x_to ⟂ k), positive
// from x̂ towards ŷ = k × x̂: rotator(frame_angle(a, b, k)) · S_in_frame_a = S_in_frame_b.
double frame_angle(const Vec3& x_from, const Vec3& x_to, const Vec3& k);

// ŝ = normalize(normal × k) for unit direction k; at normal incidence (normal ∥ k) the
// plane of incidence is undefined and ŝ is `fallback` projected ⟂ k, normalised (any
// choice is consistent, since the outgoing frame is defined by the same ŝ).
Vec3 s_axis(const Vec3& normal, const Vec3& k, const Vec3& fallback);

// Ideal linear polariser, transmission axis at `angle` from x̂ towards ŷ (Collett ch. 5):
// ½[[1,c,s,0],[c,c²,cs,0],[s,cs,s²,0],[0,0,0,0]], c = cos 2a, s = sin 2a.
Mueller linear_polariser(double angle);
// Ideal circular polariser passing the state with sign(S3) = handedness (+1: S3 > 0,
// left-circular in Born & Wolf's naming; −1: S3 < 0; any value > 0 counts as +1, any
// other as −1): ½[[1,0,0,h],[0,0,0,0],[0,0,0,0],[h,0,0,1]] (Collett ch. 5).
Mueller circular_polariser(int handedness);

// States (Born & Wolf §1.4.2, §10.8): natural light, linear at `angle` from x̂ towards ŷ,
// circular with sign(S3) = handedness (as circular_polariser), each of intensity I.
Stokes unpolarised(double I);
Stokes linear(double I, double angle);
Stokes circular(double I, int handedness);

// sqrt(S1² + S2² + S3²)/S0 and sqrt(S1² + S2²)/S0 (0 when S0 <= 0); the angle of the
// linear part, ½ atan2(S2, S1), radians in (−π/2, π/2], from x̂ towards ŷ.
double degree_of_polarisation(const Stokes& S);
double degree_of_linear_polarisation(const Stokes& S);
double angle_of_linear_polarisation(const Stokes& S);

}  // namespace refract::polar
