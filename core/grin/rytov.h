#pragma once
// Polarisation along a curved ray (docs/grin.md, "Polarisation along curved rays"). In an
// isotropic medium whose index varies slowly on the scale of the wavelength, the field
// vector e (unit, ⟂ the ray's tangent t) is parallel-transported along the ray:
//
//   de/ds = −(e · dt/ds) t
//
// (S. M. Rytov, Doklady Akad. Nauk SSSR 18, 263 (1938); V. V. Vladimirskii, ibid. 31, 222
// (1941); Born & Wolf, Principles of Optics, §3.1.3). It changes only along t and never
// turns about it, so relative to the ray's Frenet frame (N, B) it turns by −∫τ ds, τ the
// torsion: the angle from N towards B falls by the integrated torsion (Rytov's law). A
// Stokes vector in the transported frame (x̂ = e, ŷ = t × e) is unchanged along the ray.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross

namespace refract::grin {

using Vec3 = Eigen::Vector3d;

// de/dt along the ray of the ray equation's form (core/grin/ray_equation.h): T = dr/dt, with
// dT/dt = G = n∇n. The frame turns at the angular velocity Ω = t̂ × dt̂/dt = (T × G)/|T|²,
// de/dt = Ω × e, which is −(e · dt̂/dt) t̂ for e ⟂ T; written as a rotation it keeps |e| and
// e · t̂ constant for any e, so the integrator's error does not accumulate in them.
inline Vec3 rytov_rate(const Vec3& T, const Vec3& G, const Vec3& e) {
    return (T.cross(G) / T.squaredNorm()).cross(e);
}

// v without its component along the unit vector t, normalised; zero when v is (nearly)
// parallel to t (within 1e-9 of |v|) or not finite.
inline Vec3 transverse_unit(const Vec3& v, const Vec3& t) {
    const Vec3 p = v - v.dot(t) * t;
    const double n = p.norm();
    return (n > 1e-9 * v.norm() && std::isfinite(n)) ? Vec3(p / n) : Vec3(Vec3::Zero());
}

}  // namespace refract::grin
