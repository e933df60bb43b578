// Gradient-index media (core/grin/): rays through the profiles with closed-form paths
// against those paths computed here, the ray invariants, the integrator's order and its
// evaluations against fixed steps, the step budget and the refused parameters.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/grin/region.h>
#include <refract/geometry/error.h>

using namespace refract;
using namespace refract::grin;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kLambda = 0.5876;  // µm

Settings tol(double t) {
    Settings s;
    s.abs_tol = s.rel_tol = t;
    return s;
}
Vec3 unit(double theta_from_z, double phi) {
    return {std::sin(theta_from_z) * std::cos(phi), std::sin(theta_from_z) * std::sin(phi), std::cos(theta_from_z)};
}

// Parallel rays along +z entering the Luneburg lens of radius 1 at impact ρ, azimuth φ;
// the largest distance of their exits from the antipode (0, 0, 1) and of their exit
// directions from −x0 (r(t) = x0 cos t + d sin t, so at t = π/2 the ray is at d going −x0).
struct Spot {
    double radius = 0, dir = 0;
    long evaluations = 0;
    int rays = 0;
};
Spot luneburg_spot(double t) {
    Profile p = Luneburg{};
    const Region sphere = Sphere{};
    Spot s;
    for (double rho : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99})
        for (double phi : {0.0, 1.0, 2.5, 4.0}) {
            const Vec3 x0(rho * std::cos(phi), rho * std::sin(phi), -std::sqrt(1 - rho * rho));
            const Result r = advance(p, sphere, x0, Vec3::UnitZ(), kLambda, tol(t));
            REQUIRE(r.status == Status::left_region);
            s.radius = std::max(s.radius, (r.exit_point - Vec3::UnitZ()).norm());
            s.dir = std::max(s.dir, (r.exit_dir + x0).norm());
            s.evaluations += r.evaluations;
            ++s.rays;
        }
    return s;
}
}  // namespace

TEST_CASE("Luneburg lens focuses a parallel bundle on the antipodal surface point", "[grin]") {
    const Spot s = luneburg_spot(1e-13);
    CHECK(s.radius <= 1e-9);
    CHECK(s.dir <= 1e-9);
}

TEST_CASE("Maxwell fish-eye images a point at -a^2 r0/|r0|^2 along circular rays", "[grin]") {
    const double a = 1.3;
    Profile p = MaxwellFishEye{Vec3::Zero(), {2.0, 0.0}, a};
    const Vec3 r0(0, 0, 0.5);
    const Vec3 image = -a * a * r0 / r0.squaredNorm();
    // Every ray from r0 stays in its meridional plane and returns to the axis at the image;
    // the half-space x ≥ 0 ends each ray (launched with x > 0) where it meets the axis again.
    const Region half = HalfSpace{-Vec3::UnitX(), 0.0};
    Settings s = tol(1e-14);
    s.record_path = true;
    double spot = 0, off_circle = 0;
    for (double theta_deg : {20.0, 45.0, 90.0, 135.0, 160.0})
        for (double phi : {0.0, 0.7, -1.2}) {
            const Vec3 d = unit(theta_deg * kPi / 180, phi);
            const Result r = advance(p, half, r0, d, kLambda, s);
            REQUIRE(r.status == Status::left_region);
            spot = std::max(spot, (r.exit_point - image).norm());
            // The circle through r0 tangent to d and through the image: centre c = r0 + s m,
            // m ⊥ d in the meridional plane, |c − r0| = |c − image|.
            const Vec3 m = Vec3::UnitZ().cross(d).cross(d).normalized();
            const double sc = -(r0 - image).squaredNorm() / (2 * m.dot(r0 - image));
            const Vec3 c = r0 + sc * m;
            for (const PathSample& q : r.path) off_circle = std::max(off_circle, std::abs((q.x - c).norm() - std::abs(sc)));
        }
    CHECK(spot <= 1e-9 * a);
    CHECK(off_circle <= 1e-9 * a);
}

TEST_CASE("Hyperbolic-secant rod refocuses every meridional ray after one pitch 2 pi/alpha", "[grin]") {
    const double alpha = 0.8;
    Profile p = SechRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, alpha};
    const Region slab = Slab{Vec3::UnitZ(), 0.0, 2 * kPi / alpha};
    double dx = 0, dd = 0;
    for (double x0 : {0.0, 0.3, 0.8})
        for (double theta_deg : {2.0, 10.0, 20.0, 30.0}) {
            const Vec3 start(x0, 0, 0), d = unit(theta_deg * kPi / 180, 0.0);
            const Result r = advance(p, slab, start, d, kLambda, tol(1e-13));
            REQUIRE(r.status == Status::left_region);
            dx = std::max(dx, (r.exit_point - (start + Vec3(0, 0, 2 * kPi / alpha))).norm());
            dd = std::max(dd, (r.exit_dir - d).norm());
        }
    CHECK(dx <= 1e-9);
    CHECK(dd <= 1e-9);
}

namespace {
// The largest relative change of an invariant along a recorded ray.
template <class F>
double drift(const Result& r, F&& invariant) {
    const double i0 = invariant(r.path.front());
    double m = 0;
    for (const PathSample& q : r.path) m = std::max(m, std::abs(invariant(q) / i0 - 1));
    return m;
}
}  // namespace

TEST_CASE("Snell's invariant n cos(elevation) is conserved along rays in stratified media", "[grin]") {
    Settings s = tol(1e-12);
    s.record_path = true;
    const Region slab = Slab{Vec3::UnitZ(), 0.0, 2.0};
    double worst = 0;
    for (Profile p : {Profile(LinearHeight{{1.5, 0.0}, -0.2, 0.0, Vec3::UnitZ()}),
                      Profile(ExponentialHeight{{1.6, 0.0}, 0.5, 0.0, Vec3::UnitZ()})})
        for (double elev_deg : {5.0, 20.0, 40.0}) {
            const double e = elev_deg * kPi / 180;
            const Result r = advance(p, slab, Vec3(0, 0, 0.1), Vec3(std::cos(e), 0, std::sin(e)), kLambda, s);
            REQUIRE(r.status == Status::left_region);
            REQUIRE(r.path.size() > 10);
            worst = std::max(worst, drift(r, [&](const PathSample& q) {
                                 return index(p, q.x, kLambda) * q.dir.head<2>().norm();
                             }));
        }
    CHECK(worst <= 1e-10);
}

TEST_CASE("Bouguer's invariant n r sin(psi) is conserved along rays in spherically symmetric media", "[grin]") {
    Settings s = tol(1e-14);
    s.record_path = true;
    std::vector<double> radii, values;
    for (int i = 0; i <= 120; ++i) {
        radii.push_back(3.0 * i / 120);
        values.push_back(1.0 + 0.5 * std::exp(-radii.back() * radii.back()));
    }
    const Region ball = Sphere{Vec3::Zero(), 2.5};
    double worst = 0;
    for (Profile p : {Profile(Luneburg{Vec3::Zero(), 2.5}), Profile(MaxwellFishEye{Vec3::Zero(), {2.0, 0.0}, 1.0}),
                      Profile(tabulated_radial(Vec3::Zero(), radii, values, "table"))})
        for (double b : {0.2, 1.0, 2.0}) {
            const Vec3 x0(b, 0, -std::sqrt(2.5 * 2.5 - b * b));
            const Result r = advance(p, ball, x0, Vec3::UnitZ(), kLambda, s);
            REQUIRE(r.status == Status::left_region);
            const double dr = drift(r, [&](const PathSample& q) {
                                 return index(p, q.x, kLambda) * q.x.cross(q.dir).norm();
                             });
            worst = std::max(worst, dr);
        }
    CHECK(worst <= 1e-10);
}

namespace {
// Least-squares slope of log y against log x.
double log_slope(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0, my = 0;
    for (size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]) / double(x.size()), my += std::log(y[i]) / double(y.size());
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
        sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
    }
    return sxy / sxx;
}
// One Luneburg ray (impact 0.7) and its distance from the antipode.
double luneburg_error(const Settings& s, long* evaluations = nullptr) {
    const double rho = 0.7;
    const Result r = advance(Luneburg{}, Sphere{}, Vec3(rho, 0, -std::sqrt(1 - rho * rho)), Vec3::UnitZ(), kLambda, s);
    REQUIRE(r.status == Status::left_region);
    if (evaluations) *evaluations = r.evaluations;
    return (r.exit_point - Vec3::UnitZ()).norm();
}
}  // namespace

TEST_CASE("Dormand-Prince error falls as the fifth power of the step and in proportion to the tolerance", "[grin]") {
    std::vector<double> h, err_h;
    for (double step = 0.4; step >= 0.02; step /= 2) {
        Settings s;
        s.fixed_step = step;
        h.push_back(step);
        err_h.push_back(luneburg_error(s));
    }
    std::vector<double> t, err_t;
    for (double tl = 1e-5; tl >= 0.9e-12; tl /= 10) {
        t.push_back(tl);
        err_t.push_back(luneburg_error(tol(tl)));
    }
    const double order = log_slope(h, err_h), proportional = log_slope(t, err_t);
    CHECK(order == Approx(5.0).margin(0.3));
    CHECK(proportional == Approx(1.0).margin(0.1));
}

TEST_CASE("Adaptive steps need over 10x fewer gradient evaluations than fixed steps for the same error", "[grin]") {
    // A fish-eye ray launched 20° off the axis away from the image: a circle of radius 3.7a
    // reaching r = 7.2a, through n from 1.6 down to 0.04, where the best step varies widely.
    const Profile p = MaxwellFishEye{Vec3::Zero(), {2.0, 0.0}, 1.0};
    const Region half = HalfSpace{-Vec3::UnitX(), 0.0};
    const Vec3 r0(0, 0, 0.5), image = -r0 / r0.squaredNorm(), d = unit(20 * kPi / 180, 0.0);
    const Result a = advance(p, half, r0, d, kLambda, tol(1e-11));
    REQUIRE(a.status == Status::left_region);
    const double target = (a.exit_point - image).norm();
    long fixed_evaluations = 0;
    double err = 1;
    for (double step = 0.1; err > target && step > 1e-4; step /= 2) {
        Settings s;
        s.fixed_step = step;
        s.max_steps = 1000000;
        const Result f = advance(p, half, r0, d, kLambda, s);
        err = f.status == Status::left_region ? (f.exit_point - image).norm() : 1.0;
        fixed_evaluations = f.evaluations;
    }
    REQUIRE(err <= target);
    CHECK(fixed_evaluations >= 10 * a.evaluations);
}

TEST_CASE("A ray out of step budget ends as budget exhausted at once, not in a loop", "[grin]") {
    Settings s = tol(1e-13);
    s.max_steps = 5;
    s.record_path = true;
    const Result r = advance(Luneburg{}, Sphere{}, Vec3(0, 0, -1), Vec3::UnitZ(), kLambda, s);
    CHECK(r.status == Status::budget_exhausted);
    CHECK(r.steps + r.rejected == 5);
    CHECK(r.evaluations <= 2 + 6 * 5);
    CHECK(r.exit_point.allFinite());
    CHECK(std::abs(r.exit_dir.norm() - 1) < 1e-15);
    CHECK(r.exit_point.z() < 0);  // still inside, short of the antipode
    // A profile the tolerance cannot follow (tol 1e-300) never hangs either.
    Settings tight = tol(1e-300);
    tight.max_steps = 1000;
    CHECK(advance(Luneburg{}, Sphere{}, Vec3(0, 0, -1), Vec3::UnitZ(), kLambda, tight).status == Status::budget_exhausted);
}

TEST_CASE("GRIN parameters that make the index non-positive or non-finite are refused naming the field", "[grin]") {
    const std::string f = "s.json: /objects/0/grin";
    auto refused = [&](Profile p, const Region& where, const std::string& field) {
        CHECK_THROWS_WITH(validate(p, where, 0.36, 0.83, f), Catch::StartsWith(f + field + ":"));
    };
    const Region ball = Sphere{}, half = HalfSpace{Vec3::UnitZ(), 0.0};
    refused(Luneburg{Vec3::Zero(), -1.0}, ball, "/radius");
    refused(Luneburg{Vec3(NAN, 0, 0), 1.0}, ball, "/centre");
    refused(SechRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, 0.0}, ball, "/alpha");
    refused(SechRod{Vec3::Zero(), Vec3::Zero(), {1.5, 0.0}, 1.0}, ball, "/axis");
    refused(MaxwellFishEye{Vec3::Zero(), {NAN, 0.0}, 1.0}, ball, "/n0/A");
    refused(MaxwellFishEye{Vec3::Zero(), {2.0, 0.0}, -2.0}, ball, "/a");
    // n0(λ) = 0.1 + 0.2/λ² is 0.39 at 830 nm but a Cauchy B < 0 takes it below 0.
    refused(MaxwellFishEye{Vec3::Zero(), {0.1, -0.2}, 1.0}, ball, "/n0");
    // 1.5 − 2·(height): 0 at height 0.75, inside the unit ball but not inside a small one.
    refused(LinearHeight{{1.5, 0.0}, -2.0, 0.0, Vec3::UnitZ()}, ball, "/slope");
    Profile fine = LinearHeight{{1.5, 0.0}, -2.0, 0.0, Vec3::UnitZ()};
    CHECK_NOTHROW(validate(fine, Sphere{Vec3::Zero(), 0.7}, 0.36, 0.83, f));
    // Growing downwards without bound in the half-space below z = 0.
    refused(LinearHeight{{1.5, 0.0}, 0.1, 0.0, Vec3::UnitZ()}, half, "/slope");
    refused(ExponentialHeight{{0.5, 0.0}, 1.0, 0.0, Vec3::UnitZ()}, half, "/n0");
    refused(ExponentialHeight{{1.0003, 0.0}, 0.0, 0.0, Vec3::UnitZ()}, half, "/scale_height");
    refused(ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, 3.0}, ball, "/A");  // 0 at r = 0.82
    refused(ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, 0.5}, half, "/A");
    CHECK_THROWS_WITH(tabulated_radial(Vec3::Zero(), {0, 1, 2}, {1.2, 0.0, 1.1}, f), Catch::StartsWith(f + "/n/1:"));
    CHECK_THROWS_WITH(tabulated_radial(Vec3::Zero(), {0, 2, 1}, {1.2, 1.1, 1.1}, f), Catch::StartsWith(f + "/r/2:"));
    CHECK_THROWS_WITH(tabulated_radial(Vec3::Zero(), {0, 1}, {1.2, 1.1}, f), Catch::StartsWith(f + "/r:"));
    // Positive samples whose spline dips below 0 between them.
    CHECK_THROWS_WITH(tabulated_radial(Vec3::Zero(), {0, 1, 1.01, 2}, {2.0, 0.01, 2.0, 2.0}, f),
                      Catch::StartsWith(f + "/n:"));
    Region bad = Sphere{Vec3::Zero(), 0.0};
    CHECK_THROWS_WITH(validate(bad, f + "/region"), Catch::StartsWith(f + "/region/radius:"));
}

TEST_CASE("A GRIN base index disperses by Cauchy's law while a fish-eye's rays do not depend on it", "[grin]") {
    const LinearHeight lin{{1.5, 0.004}, 0.1, 0.0, Vec3::UnitZ()};
    for (double l : {0.4, 0.55, 0.7})
        CHECK(index(lin, Vec3(0, 0, 0.5), l) == Approx(1.5 + 0.004 / (l * l) + 0.05).epsilon(1e-15));
    // n → k·n leaves d²r/ds² unchanged: the fish-eye images every wavelength at one point.
    const Profile p = MaxwellFishEye{Vec3::Zero(), {1.9, 0.02}, 1.0};
    const Vec3 r0(0, 0, 0.5);
    const Result blue = advance(p, HalfSpace{-Vec3::UnitX(), 0.0}, r0, unit(1.0, 0.0), 0.4, tol(1e-13));
    const Result red = advance(p, HalfSpace{-Vec3::UnitX(), 0.0}, r0, unit(1.0, 0.0), 0.7, tol(1e-13));
    CHECK((blue.exit_point - red.exit_point).norm() < 1e-10);
    CHECK(blue.optical_path / red.optical_path == Approx((1.9 + 0.02 / 0.16) / (1.9 + 0.02 / 0.49)).epsilon(1e-10));
}

TEST_CASE("A GRIN ray ends exactly on the region's boundary, and one started on it heading out leaves at once", "[grin]") {
    const Profile rod = ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, 0.5};
    const Region box = Box{Vec3(-1, -1, 0), Vec3(1, 1, 3)};
    for (double theta : {0.1, 0.4, 0.8})
        for (double phi : {0.3, 2.0}) {
            const Result r = advance(rod, box, Vec3(0.2, -0.1, 0), unit(theta, phi), kLambda, tol(1e-10));
            REQUIRE(r.status == Status::left_region);
            CHECK(std::abs(signed_distance(box, r.exit_point)) <= 1e-13);
            CHECK(std::abs(r.exit_dir.norm() - 1) <= 1e-15);
            CHECK(r.exit_index == Approx(index(rod, r.exit_point, kLambda)).epsilon(1e-15));
            CHECK(r.optical_path > r.length);  // n > 1 throughout
        }
    // On the sphere's surface heading outwards: the exit is the start, after no length.
    const Result out = advance(Luneburg{}, Sphere{}, Vec3(0, 0, 1), Vec3(0.3, 0, 1).normalized(), kLambda);
    CHECK(out.status == Status::left_region);
    CHECK((out.exit_point - Vec3(0, 0, 1)).norm() <= 1e-13);
    CHECK(out.length <= 1e-13);
}
