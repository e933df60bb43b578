// Polarisation along curved rays (core/grin/rytov.h, Settings::frame of core/grin/ray_equation.h):
// the frame vector transported by Rytov's law against the closed forms of a helical ray in
// a GRIN rod (it turns by −∫τ ds in the Frenet frame), a straight ray (unchanged) and a
// meridional ray (zero torsion: the angle to the ray's plane is kept).
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/grin/region.h>

using namespace refract;
using namespace refract::grin;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kLambda = 0.5876;  // µm

Settings tol(double t, const Vec3& frame) {
    Settings s;
    s.abs_tol = s.rel_tol = t;
    s.frame = frame;
    return s;
}

// A rod about the z axis with n(r): a ray launched at radius a along the cylinder, at the
// elevation θ whose curvature cos²θ/a (that of the helix of radius a) equals the ray's,
// −n′(a)/n(a), stays on the cylinder: a circular helix x = (a cos u, h a sin u, a tan θ u),
// h = ±1 its handedness, of torsion τ = h sin θ cos θ / a (the Frenet convention
// B′ = −τN; τ = c/(a² + c²) for the pitch 2πc = 2πa tan θ).
struct Helix {
    Profile rod;
    double a, cos2;  // radius, cos²θ = −a n′(a)/n(a)
};
Helix sech_helix() {  // n = n₀ sech(αr): −n′/n = α tanh(αr)
    const double alpha = 1.0, a = 0.5;
    return {SechRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, alpha}, a, alpha * a * std::tanh(alpha * a)};
}
Helix parabolic_helix() {  // n = n₀(1 − A r²/2): −n′/n = A r/(1 − A r²/2)
    const double A = 0.5, a = 0.6;
    return {ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, A}, a, A * a * a / (1 - A * a * a / 2)};
}

// The Frenet frame of the helix at a point x with tangent t: N towards the axis, B = t × N.
std::pair<Vec3, Vec3> frenet(const Vec3& x, const Vec3& t) {
    Vec3 inward(-x.x(), -x.y(), 0.0);
    const Vec3 N = (inward - inward.dot(t) * t).normalized();
    return {N, t.cross(N)};
}

// The polarisation vector's angle in the Frenet frame, from N towards B, after a rod of
// length Z, against the start's angle φ0 minus τ·(Z / sin θ): the largest difference.
struct Twist {
    double worst = 0.0, turned = 0.0, radius = 0.0, length = 0.0, moved = 0.0;
};
Twist helix_twist(const Helix& hx, double Z, double t) {
    Profile rod = hx.rod;
    Region box = Box{Vec3(-1, -1, 0), Vec3(1, 1, Z)};
    validate(box, "r");
    validate(rod, box, 0.36, 0.83, "p");
    const double c = std::sqrt(hx.cos2), s = std::sqrt(1 - hx.cos2);
    Twist w;
    for (double h : {1.0, -1.0}) {
        const Vec3 x0(hx.a, 0, 0), d0(0, h * c, s);
        const double tau = h * s * c / hx.a, L = Z / s;
        const auto [N0, B0] = frenet(x0, d0);
        for (double phi0 : {0.0, 0.3, 1.9, -2.6}) {
            const Result r = advance(rod, box, x0, d0, kLambda, tol(t, std::cos(phi0) * N0 + std::sin(phi0) * B0));
            REQUIRE(r.status == Status::left_region);
            const auto [N, B] = frenet(r.exit_point, r.exit_dir);
            const double phi = std::atan2(r.exit_frame.dot(B), r.exit_frame.dot(N));
            w.worst = std::max(w.worst, std::abs(std::remainder(phi - (phi0 - tau * L), 2 * kPi)));
            w.turned = std::max(w.turned, std::abs(tau * L));
            w.radius = std::max(w.radius, std::abs(r.exit_point.head<2>().norm() - hx.a));
            w.length = std::max(w.length, std::abs(r.length - L));
            CHECK(std::abs(r.exit_frame.norm() - 1) <= 1e-15);
            CHECK(std::abs(r.exit_frame.dot(r.exit_dir)) <= 1e-15);
            // The ray itself, with the frame and without: the same to the tolerance.
            Settings off = tol(t, Vec3::Zero());
            w.moved = std::max(w.moved, (advance(rod, box, x0, d0, kLambda, off).exit_point - r.exit_point).norm());
        }
    }
    return w;
}
}  // namespace

TEST_CASE("Rytov's law: on a helical ray in a GRIN rod the polarisation turns by minus the integrated torsion",
          "[grin][rytov]") {
    for (const Helix& hx : {sech_helix(), parabolic_helix()}) {
        const Twist w = helix_twist(hx, 10.0, 1e-13);
        CHECK(w.turned > 5.0);      // radians of torsion integrated along the ray
        CHECK(w.radius <= 1e-10);   // the ray stayed on its helix
        CHECK(w.length <= 1e-10);   // and its length is the helix's
        CHECK(w.worst <= 1e-8);     // the limit
        CHECK(w.moved <= 1e-10);    // the ray with the frame is the ray without it
    }
    // At the default tolerance (1e-10) too.
    CHECK(helix_twist(sech_helix(), 10.0, 1e-10).worst <= 1e-8);
}

TEST_CASE("Rytov's law: in a homogeneous medium the polarisation vector of a straight ray is unchanged",
          "[grin][rytov]") {
    LinearHeight flat;
    flat.n0 = {1.3, 0.0};
    flat.slope = 0.0;
    Profile p = flat;
    Region box = Box{};
    validate(box, "r");
    validate(p, box, 0.36, 0.83, "p");
    const Vec3 d = Vec3(0.3, -0.4, 0.8).normalized();
    const Vec3 e = d.cross(Vec3(1, 0.2, 0)).normalized();
    const Result r = advance(p, box, Vec3(-0.2, 0.3, -1.0), d, kLambda, tol(1e-10, e));
    REQUIRE(r.status == Status::left_region);
    CHECK((r.exit_dir - d).norm() <= 1e-15);
    CHECK((r.exit_frame - e).norm() <= 1e-15);
}

TEST_CASE("Rytov's law: on a meridional ray (zero torsion) the polarisation keeps its angle to the ray's plane",
          "[grin][rytov]") {
    Profile rod = SechRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, 1.0};
    Region box = Box{Vec3(-2, -2, 0), Vec3(2, 2, 7.5)};  // more than one pitch 2π
    validate(box, "r");
    validate(rod, box, 0.36, 0.83, "p");
    const double psi = 0.4, elev = 20 * kPi / 180;
    const Vec3 u(std::cos(psi), std::sin(psi), 0), m(-std::sin(psi), std::cos(psi), 0);  // m: the plane's normal
    const Vec3 x0 = 0.3 * u, d0 = std::sin(elev) * u + std::cos(elev) * Vec3::UnitZ();
    double worst = 0.0, bent = 0.0;
    for (double beta : {0.0, kPi / 2, 0.7, -2.2}) {  // from the normal m towards m × dir, in the plane
        const Vec3 e0 = std::cos(beta) * m + std::sin(beta) * m.cross(d0);
        const Result r = advance(rod, box, x0, d0, kLambda, tol(1e-13, e0));
        REQUIRE(r.status == Status::left_region);
        bent = std::max(bent, std::acos(std::clamp(r.exit_dir.dot(d0), -1.0, 1.0)));
        CHECK(std::abs(r.exit_dir.dot(m)) <= 1e-14);  // the ray stayed in its plane
        const double beta1 = std::atan2(r.exit_frame.dot(m.cross(r.exit_dir)), r.exit_frame.dot(m));
        worst = std::max(worst, std::abs(std::remainder(beta1 - beta, 2 * kPi)));
    }
    CHECK(bent > 0.3);  // the ray did turn
    CHECK(worst <= 1e-12);
}

TEST_CASE("A GRIN polarisation frame is taken across the start direction, and one along it is refused",
          "[grin][rytov]") {
    Profile p = Luneburg{};
    const Region sphere = Sphere{};
    const Vec3 x0(0.5, 0, -std::sqrt(0.75)), d = Vec3::UnitZ();
    const Result a = advance(p, sphere, x0, d, kLambda, tol(1e-12, Vec3(0, 2, 0)));
    const Result b = advance(p, sphere, x0, d, kLambda, tol(1e-12, Vec3(0, 1, 0.7)));  // a part along d
    CHECK((a.exit_frame - b.exit_frame).norm() <= 1e-15);
    // The Luneburg ray is planar (in the xz plane): ŷ stays ŷ.
    CHECK((a.exit_frame - Vec3::UnitY()).norm() <= 1e-13);
    CHECK(advance(p, sphere, x0, d, kLambda, tol(1e-12, Vec3::Zero())).exit_frame.isZero());
    CHECK_THROWS_AS(advance(p, sphere, x0, d, kLambda, tol(1e-12, Vec3(0, 0, 3))), std::invalid_argument);
    CHECK_THROWS_AS(advance(p, sphere, x0, d, kLambda, tol(1e-12, Vec3(NAN, 1, 0))), std::invalid_argument);
}
