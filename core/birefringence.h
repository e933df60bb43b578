#pragma once
// Double refraction at the surface of a uniaxial crystal, as small pure functions
// (docs/birefringence.md). The reference followed is A. Weidlich & A. Wilkie, "Realistic
// rendering of birefringency in uniaxial crystals", ACM TOG 27(1), 2008, derived anew from
// Born & Wolf, Principles of Optics, 7th ed., §15.2–15.3 (plane waves in anisotropic media),
// and solved here as one boundary-value problem (tangential E and H continuous) for the
// four outgoing plane waves, which covers entering, leaving and internal reflection alike.
//
// Conventions (units: wave vectors in units of k0 = ω/c, so |k| = n; μ = 1, H = k × E):
// - A uniaxial medium has ε = n_o² I + (n_e² − n_o²) â âᵀ, â the unit optic axis.
// - The ordinary wave (o) has |k| = n_o and D ∥ E ∥ k × â; the extraordinary wave (e) has
//   the index n(θ) of `extraordinary_index`, D in the plane of k and â (D ⟂ k), E = ε⁻¹ D,
//   and its ray (Poynting vector E × H) along ε k, at the walk-off angle ρ from k.
// - Along the optic axis (k ∥ â) both waves have n_o and any transverse basis serves; the
//   o wave is then taken along ŝ of the interface.
// - Stokes frames are those of core/polarisation.h: each beam's x̂ is ŝ = normalize(n × d)
//   for its ray direction d and the normal n on the incident side, ŷ = d × x̂; for a beam in
//   an isotropic medium this is the s/p basis, and the isotropic limit reproduces
//   polar::mueller_reflection / mueller_transmission.
#include <array>
#include <complex>
#include <cstdint>

#include <Eigen/Core>

#include <refract/core/polarisation.h>
#include <refract/geometry/ray.h>

namespace refract::biref {

using cplx = std::complex<double>;
using Vec3c = Eigen::Vector3cd;
using Jones = Eigen::Matrix2cd;

// The wave a ray-tree branch travels as: in an isotropic medium (any polarisation), or as
// the ordinary or the extraordinary wave inside a crystal.
enum class Wave : std::int8_t { Isotropic = 0, Ordinary = 1, Extraordinary = 2 };

// A medium at one wavelength: isotropic with index n_o when `axis` is zero, else uniaxial
// with indices n_o, n_e and unit optic axis `axis` (in the frame of the rays).
struct Medium {
    double n_o = 1.0, n_e = 1.0;
    Vec3 axis = Vec3::Zero();
    bool uniaxial() const { return axis.squaredNorm() > 0; }
};

// Index of the extraordinary wave whose wave normal makes angle θ with the optic axis
// (the index ellipsoid, Born & Wolf §15.3.3): 1/n(θ)² = cos²θ/n_o² + sin²θ/n_e².
double extraordinary_index(double n_o, double n_e, double cos_theta);

// Walk-off angle ρ between the extraordinary wave normal and its ray, for a wave normal at
// θ to the optic axis (Born & Wolf §15.3.3; Weidlich & Wilkie §4): with r = n_o²/n_e²,
// tan ρ = (r − 1) tan θ / (1 + r tan²θ); ρ > 0 when the ray lies farther from the axis
// than the wave normal (negative crystals, n_e < n_o).
double walk_off_angle(double n_o, double n_e, double theta);

// The wave vector of a wave of the medium whose ray runs along the unit direction `ray`:
// n_o·ray for o (or any wave in an isotropic medium); for e, k ∥ ε⁻¹·ray scaled to n(θ).
Vec3 wave_vector_of_ray(const Medium& m, Wave w, const Vec3& ray);

// One plane wave of a medium: its mode, complex wave vector (k·k = n² in the bilinear
// sense; complex when evanescent), field E of unit (Hermitian) norm and H = k × E, and for
// a propagating wave its unit ray direction (along Re(E × H*)).
struct PlaneWave {
    Wave wave;     // Ordinary/Extraordinary in a crystal; Isotropic for the s and p waves
    bool s_like;   // isotropic medium: the s wave (else p)
    Vec3c k, E, H;
    bool evanescent;
    Vec3 ray;      // unit; zero when evanescent
    // Power flux across the interface for unit amplitude: ½ Re(E × H*)·N̂ (0 when evanescent).
    double flux;
};

// The two waves of medium m with tangential wave-vector component t (t ⟂ N) travelling
// into the half-space on the side of the unit normal N (energy flux along +N, or, when
// evanescent, decaying along +N). For the e wave the normal component q of k = t + qN solves
// the ellipsoid's quadratic kᵀAk = 1, A = ε/(n_o² n_e²), taking the root with the ray along +N
// (Weidlich & Wilkie §4.1); the o wave has q = sqrt(n_o² − t²). `s` is the unit ŝ of the
// interface (⟂ N and t), used for the isotropic s wave and the degenerate direction k ∥ â.
std::array<PlaneWave, 2> plane_waves(const Medium& m, const Vec3& t, const Vec3& N, const Vec3& s);

// One outgoing beam at an interface: its ray, its wave, reflected or transmitted, the unit
// x̂ of its Stokes frame (ŷ = dir × x̂), and the power-normalised Jones matrix from the
// incident beam's frame to this one (|J e|² is the power carried for a unit-power incident
// state e). Its Mueller matrix is polar::jones_to_mueller(J); M00 = the power for natural
// light (for a crystal wave incident: for light of that wave, with J's row projecting on it).
struct Beam {
    Vec3 dir;
    Wave wave;
    bool transmitted;
    Vec3 x;
    Jones J;
    double power;  // ½(|J|²_F): the power for unpolarised incidence (M00)
};

// All propagating outgoing beams where a ray of direction `dir` travelling as `wave` in
// medium `from` meets the interface with `to` (unit normal `normal` on the incident side,
// normal·dir < 0): up to 2 reflected and 2 transmitted waves. In an isotropic medium the
// two waves (s, p) make one beam; in a crystal each wave is a beam of its own. Total
// internal reflection of either wave leaves it out (its power goes to the others).
// The incident beam's Stokes frame is x̂ = `x_in`.
struct InterfaceSplit {
    std::array<Beam, 4> beam;
    int count = 0;
    Vec3 x_in;
};
InterfaceSplit split_at_interface(const Medium& from, Wave wave, const Medium& to, const Vec3& dir,
                                  const Vec3& normal);

// Reciprocity (Lorentz; for lossless media with symmetric ε the power-normalised
// scattering matrix is symmetric, Born & Wolf §1.5; Weidlich & Wilkie §5): light running
// backwards along a beam of Jones matrix J (in the frames x̂_in, x̂_beam) and leaving along
// the reversed incident ray has Jones matrix D Jᵀ D, D = diag(1, −1), in the polar frames
// of the reversed rays with the same x̂ (ŷ = k̂ × x̂ flips with k̂).
Jones reversed(const Jones& J);

}  // namespace refract::biref
