// Astronomical refraction traced: a ray from an observer on the ground at apparent altitude
// a, integrated by the ray equation (core/grin/ray_equation.h) through the U.S. Standard
// Atmosphere 1976 over a spherical Earth (the profile EarthAtmosphere) to the top of the
// air, turns by the refraction the refraction integral gives for the same atmosphere
// (core/grin/refraction_integral.h, Auer & Standish's independent quadrature).
#include <catch2/catch.hpp>

#include <cmath>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/grin/refraction_integral.h>
#include <refract/core/grin/region.h>

using namespace refract;
using namespace refract::grin;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kArcsec = kPi / (180.0 * 3600.0);
constexpr double kTop = 150e3;  // m, the integral's default top

// The angle (radians) the traced ray turns by between the ground and the top of the air.
double traced_refraction(const Profile& air, double altitude_rad, double lambda_um, Result* out = nullptr) {
    const Region top = grin::Sphere{Vec3::Zero(), kEarthRadius_m + kTop};
    const Vec3 x0(0.0, kEarthRadius_m, 0.0);                                    // the observer
    const Vec3 d0(std::cos(altitude_rad), std::sin(altitude_rad), 0.0);          // +y is up there
    Settings s;
    s.abs_tol = s.rel_tol = 1e-13;
    const Result r = advance(air, top, x0, d0, lambda_um, s);
    REQUIRE(r.status == Status::left_region);
    if (out) *out = r;
    return std::atan2(d0.cross(r.exit_dir).norm(), d0.dot(r.exit_dir));
}
}  // namespace

TEST_CASE("Astronomical refraction traced through the standard atmosphere equals the refraction integral to 0.01 arcsec",
          "[grin]") {
    Profile air = EarthAtmosphere{};
    validate(air, grin::Sphere{Vec3::Zero(), kEarthRadius_m + kTop}, 0.55, 0.55, "air");
    const Atmosphere& atm = std::get<EarthAtmosphere>(air).air;
    const double lambda = 0.55;
    for (double deg : {0.0, 1.0, 5.0, 10.0, 45.0}) {
        Result r;
        const double traced = traced_refraction(air, deg * kPi / 180.0, lambda, &r);
        const double integral = refraction_integral(atm, lambda, deg * kPi / 180.0);
        INFO(deg << " deg: traced " << traced / kArcsec << "\" against " << integral / kArcsec << "\", difference " << (traced - integral) / kArcsec << "\" ("
                 << r.steps << " steps, " << r.evaluations << " evaluations)");
        CHECK(std::abs(traced - integral) < 0.01 * kArcsec);
        // Bouguer's invariant n r sin z (here n r cos(altitude)) from the ground to the exit.
        const double start = index(air, Vec3(0.0, kEarthRadius_m, 0.0), lambda) * kEarthRadius_m * std::cos(deg * kPi / 180.0);
        const double end = r.exit_index * r.exit_point.norm() * r.exit_point.normalized().cross(r.exit_dir).norm();
        CHECK(std::abs(end - start) < 1e-10 * start);
    }
}

TEST_CASE("Green flash: the traced horizon refraction at 520 nm exceeds 650 nm's by the integral's difference",
          "[grin]") {
    Profile air = EarthAtmosphere{};
    const Atmosphere& atm = std::get<EarthAtmosphere>(air).air;
    const double traced = traced_refraction(air, 0.0, 0.52) - traced_refraction(air, 0.0, 0.65);
    const double integral = refraction_integral(atm, 0.52, 0.0) - refraction_integral(atm, 0.65, 0.0);
    INFO("traced " << traced / kArcsec << "\" against " << integral / kArcsec << "\", difference " << (traced - integral) / kArcsec << "\"");
    CHECK(traced > 10 * kArcsec);
    CHECK(std::abs(traced - integral) < 0.01 * kArcsec);
}
