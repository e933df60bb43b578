// The laws of core/optics.h against analytic and published values.
#include <catch2/catch.hpp>

#include <cmath>

#include <refract/core/optics.h>

using namespace refract;
using Catch::Matchers::WithinAbs;

namespace {
double deg(double d) { return d * M_PI / 180.0; }
}  // namespace

TEST_CASE("Fresnel: energy conservation Rs + Ts = 1 and Rp + Tp = 1", "[optics][fresnel]") {
    // Transmittances from the amplitude coefficients (Born & Wolf): T = (η cos t / cos i)·t².
    for (double eta : {1.2, 1.5, 2.417, 1 / 1.5, 0.5}) {
        for (double a = 0; a < 89.9; a += 0.7) {
            const double ci = std::cos(deg(a));
            const auto f = optics::fresnel(ci, eta);
            if (!f) continue;
            const double ts = 2 * ci / (ci + eta * f->cos_t);
            const double tp = 2 * ci / (eta * ci + f->cos_t);
            const double k = eta * f->cos_t / ci;
            CHECK_THAT(f->Rs + k * ts * ts, WithinAbs(1.0, 1e-12));
            CHECK_THAT(f->Rp + k * tp * tp, WithinAbs(1.0, 1e-12));
        }
    }
}

TEST_CASE("Fresnel: normal incidence gives ((n-1)/(n+1))^2", "[optics][fresnel]") {
    CHECK_THAT(optics::fresnel_reflectance(1.0, 1.5), WithinAbs(0.04, 1e-15));
    CHECK_THAT(optics::fresnel_reflectance(1.0, 2.417), WithinAbs(std::pow(1.417 / 3.417, 2), 1e-15));
    CHECK_THAT(optics::fresnel_reflectance(1.0, 1.333), WithinAbs(std::pow(0.333 / 2.333, 2), 1e-15));
    // Same from inside: the interface reflects equally both ways at normal incidence.
    CHECK_THAT(optics::fresnel_reflectance(1.0, 1 / 1.5), WithinAbs(0.04, 1e-15));
}

TEST_CASE("Fresnel: Rp vanishes at Brewster's angle, Rs does not", "[optics][fresnel]") {
    for (double eta : {1.5, 2.417, 1 / 1.5}) {
        const double b = optics::brewster_angle(eta);
        const auto f = optics::fresnel(std::cos(b), eta);
        REQUIRE(f);
        CHECK_THAT(f->Rp, WithinAbs(0.0, 1e-15));
        CHECK(f->Rs > 0.01);
    }
    CHECK_THAT(optics::brewster_angle(1.5) * 180 / M_PI, WithinAbs(56.3099, 1e-4));
}

TEST_CASE("Fresnel: total internal reflection beyond the critical angle", "[optics][fresnel][tir]") {
    const double eta = 1 / 1.5;
    const double c = *optics::critical_angle(eta);
    CHECK_THAT(c * 180 / M_PI, WithinAbs(41.8103, 1e-4));
    CHECK_FALSE(optics::critical_angle(1.5).has_value());
    CHECK(optics::fresnel(std::cos(c - 1e-6), eta).has_value());
    CHECK_FALSE(optics::fresnel(std::cos(c + 1e-6), eta).has_value());
    CHECK(optics::fresnel_reflectance(std::cos(c + 1e-6), eta) == 1.0);
    CHECK_FALSE(optics::refract(Vec3(std::sin(c + 1e-3), -std::cos(c + 1e-3), 0), Vec3(0, 1, 0), eta));
    // Approaching the critical angle from below, R tends to 1.
    CHECK(optics::fresnel_reflectance(std::cos(c - 1e-9), eta) > 0.999);
}

TEST_CASE("Fresnel: reflectance from inside equals that from outside at conjugate angles (ku = ks)",
          "[optics][fresnel]") {
    // Yasuda 1984 §3.1.1: light arriving from P inside at the refraction angle reflects as
    // much as light from outside at the incidence angle.
    for (double n : {1.2, 1.5, 2.417, 10.0}) {
        for (double a = 0; a < 89.5; a += 1.3) {
            const double ci = std::cos(deg(a));
            const auto out = optics::fresnel(ci, n);
            const auto in = optics::fresnel(out->cos_t, 1 / n);
            REQUIRE(in);
            CHECK_THAT(in->R(), WithinAbs(out->R(), 1e-11));
            CHECK_THAT(in->Rs, WithinAbs(out->Rs, 1e-11));
            CHECK_THAT(in->Rp, WithinAbs(out->Rp, 1e-11));
            CHECK_THAT(in->cos_t, WithinAbs(ci, 1e-12));
        }
    }
}

TEST_CASE("Snell's law: n1 sin(i) = n2 sin(t) for the refracted direction", "[optics][snell]") {
    const Vec3 n(0, 0, 1);
    for (double eta : {1.5, 2.417, 1 / 1.33}) {
        for (double a = 0; a < 85; a += 5) {
            const Vec3 d(std::sin(deg(a)), 0.3 * std::sin(deg(a)), -std::cos(deg(a)));
            const Vec3 dn = d.normalized();
            const auto t = optics::refract(dn, n, eta);
            if (!t) continue;
            CHECK_THAT(t->norm(), WithinAbs(1.0, 1e-14));
            const double sin_i = dn.cross(n).norm(), sin_t = t->cross(n).norm();
            CHECK_THAT(sin_i - eta * sin_t, WithinAbs(0.0, 1e-14));
            // Coplanar with d and n, and on the far side.
            CHECK_THAT(t->dot(dn.cross(n)), WithinAbs(0.0, 1e-14));
            CHECK(t->dot(n) < 0);
        }
    }
}

TEST_CASE("Yasuda eq. 2-5 and Heckbert's form give the same directions", "[optics][snell][yasuda1984]") {
    const Vec3 N = Vec3(0.2, 1, -0.1).normalized();
    for (double eta : {1.5, 2.2, 10.0, 0.8}) {
        for (double a = 1; a < 89; a += 4) {
            const Vec3 tangent = N.cross(Vec3(1, 0, 0)).normalized();
            const Vec3 V = (std::sin(deg(a)) * tangent - std::cos(deg(a)) * N).normalized();
            const auto w = optics::whitted_directions(V, N, eta);
            CHECK((w.reflected.normalized() - optics::reflect(V, N)).norm() < 1e-13);
            const auto h = optics::refract(V, N, eta);
            REQUIRE(w.transmitted.has_value() == h.has_value());
            if (h) CHECK((w.transmitted->normalized() - *h).norm() < 1e-13);
        }
    }
}

TEST_CASE("Schlick's approximation stays within its known error of exact Fresnel", "[optics][schlick]") {
    // Exact at normal incidence and at grazing incidence; for glass (n = 1.5) from outside
    // the largest absolute error is about 0.036, near grazing incidence (80–89°).
    CHECK_THAT(optics::schlick(1.0, 1.5), WithinAbs(0.04, 1e-15));
    CHECK_THAT(optics::schlick(0.0, 1.5), WithinAbs(1.0, 1e-15));
    double worst = 0, worst_angle = 0;
    for (double a = 0; a <= 90; a += 0.1) {
        const double c = std::cos(deg(a));
        const double e = std::abs(optics::schlick(c, 1.5) - optics::fresnel_reflectance(c, 1.5));
        if (e > worst) { worst = e; worst_angle = a; }
    }
    CHECK(worst < 0.04);
    CHECK(worst > 0.03);  // it is an approximation, not the law
    CHECK(worst_angle > 80);
    CHECK(worst_angle < 89);
    // Below 30° it is within 0.0015 (Schlick underestimates there).
    for (double a = 0; a <= 30; a += 0.5) {
        const double c = std::cos(deg(a));
        CHECK(std::abs(optics::schlick(c, 1.5) - optics::fresnel_reflectance(c, 1.5)) < 0.0015);
    }
}
