#pragma once
// The polarisation a ray-tree branch carries (core/ray_tree.h), one type per model, and
// how each is carried across an interface (`descend`). Conventions: core/polarisation.h.
//
// Every branch's Stokes frame is x̂ = ŝ of the interface it came from: ŝ = n × d is
// perpendicular to the plane of incidence, so it is across both the incoming and the
// outgoing ray, and the interface's Mueller matrix needs no rotation on its own side.
// Only the rotation from the previous frame to this ŝ is applied.
#include <Eigen/Core>

#include <refract/core/polarisation.h>

namespace refract {

struct Scene;

// Natural light (Yasuda eq. 7 at every node): nothing to carry.
struct NaturalLight {};
inline NaturalLight descend(const NaturalLight&, const Vec3&, const Vec3&, const polar::Mueller&, const Vec3& = Vec3::Zero(),
                            const Vec3& = Vec3::Zero()) {
    return {};
}
inline double throughput(const NaturalLight&) { return 1.0; }

// Eye pass: `C` maps the Stokes vector of light arriving at this ray's origin from its
// direction (propagating along −dir, in frame x) to what the camera records (its frame,
// after the analyser). Light leaving a surface into the branch contributes C·S.
struct EyeStokes {
    polar::Mueller C = polar::Mueller::Identity();
    Vec3 x{1, 0, 0};
};
// At a hit with normal n of the ray `dir` (parent), the child's matrix is
// C · R(ŝ → x about −dir) · M, where M is the interface's Mueller matrix for light going
// from the child's ray into the parent's (reflection and transmission are reciprocal).
// The rotation R(a) = polar::rotator(polar::frame_angle(s, x, k)) is applied to C's
// columns 1 and 2 directly, with cos 2a and sin 2a from cos a = s·x, sin a = k·(s × x).
// A uniaxial crystal's branch gives its frames: x̂ on the parent's side (`xp`, ⟂ dir) and on
// the child's (`xc`); zero: ŝ on both.
inline EyeStokes descend(const EyeStokes& p, const Vec3& n, const Vec3& dir, const polar::Mueller& M,
                         const Vec3& xp = Vec3::Zero(), const Vec3& xc = Vec3::Zero()) {
    const Vec3 k = -dir;  // the light's direction on the parent's segment
    const Vec3 s = xp.isZero() ? polar::s_axis(n, k, p.x) : xp;
    const double ca = s.dot(p.x), sa = k.dot(s.cross(p.x));
    const double c2 = ca * ca - sa * sa, s2 = 2.0 * ca * sa;
    polar::Mueller CR = p.C;
    CR.col(1) = c2 * p.C.col(1) - s2 * p.C.col(2);
    CR.col(2) = s2 * p.C.col(1) + c2 * p.C.col(2);
    return {CR * M, xc.isZero() ? s : xc};
}

// The share of unpolarised light arriving along the branch that reaches the camera.
inline double throughput(const EyeStokes& p) { return p.C(0, 0); }

// Light pass: the photon's Stokes vector (S0 = 1 at the light; the power is in the
// entry's weight) in frame x, propagating along the ray.
struct LightStokes {
    polar::Stokes S = polar::unpolarised(1.0);
    Vec3 x{1, 0, 0};
};
// R(a) = polar::rotator(polar::frame_angle(x, s, dir)) applied to (S1, S2) directly.
inline LightStokes descend(const LightStokes& p, const Vec3& n, const Vec3& dir, const polar::Mueller& M,
                           const Vec3& xp = Vec3::Zero(), const Vec3& xc = Vec3::Zero()) {
    const Vec3 s = xp.isZero() ? polar::s_axis(n, dir, p.x) : xp;
    const double ca = p.x.dot(s), sa = dir.dot(p.x.cross(s));
    const double c2 = ca * ca - sa * sa, s2 = 2.0 * ca * sa;
    const polar::Stokes R(p.S[0], c2 * p.S[1] + s2 * p.S[2], -s2 * p.S[1] + c2 * p.S[2], p.S[3]);
    return {M * R, xc.isZero() ? s : xc};
}

inline double throughput(const LightStokes& p) { return p.S[0]; }

// The Stokes vectors of the three colour channels, one per column (S0 row = RGB).
using StokesRGB = Eigen::Matrix<double, 4, 3>;

// Light L (RGB, unpolarised) reaching the camera along an entry with colour weight w.
inline Vec3 seen(const NaturalLight&, const Vec3& w, const Vec3& L) { return w.cwiseProduct(L); }
inline StokesRGB seen(const EyeStokes& p, const Vec3& w, const Vec3& L) {
    return p.C.col(0) * w.cwiseProduct(L).transpose();
}

// A band's RGB weight applied to its light; the RGB part of a result.
inline Vec3 tinted(const Vec3& w, const Vec3& v) { return w.cwiseProduct(v); }
inline StokesRGB tinted(const Vec3& w, const StokesRGB& v) { return v * w.asDiagonal(); }
inline Vec3 rgb_of(const Vec3& v) { return v; }
inline Vec3 rgb_of(const StokesRGB& v) { return v.row(0).transpose(); }

// The camera's side of a primary ray: frame x̂ = the image's right across the ray, and the
// scene's analyser (render.polarisation.analyser; its angle is measured on the image from
// the right towards the top) as the starting matrix.
EyeStokes camera_stokes(const Scene& scene, const Ray& primary);

// Degree and angle of linear polarisation of a pixel's Stokes vectors, from the sum of
// the three channels (clamped to 1: spectral channels are sums with weights of both
// signs); the angle on the image, from its right towards its top (radians).
struct LinearPolarisation {
    double dolp, aolp;
};
LinearPolarisation linear_polarisation(const StokesRGB& s, const Scene& scene, const Ray& primary);

}  // namespace refract
