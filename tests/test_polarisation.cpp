// Stokes–Mueller polarisation (core/polarisation.h) and Beer–Lambert absorption
// (core/optics.h) against closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <vector>

#include <refract/core/optics.h>
#include <refract/core/polarisation.h>

using namespace refract;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using cplx = std::complex<double>;

namespace {
double deg(double d) { return d * M_PI / 180.0; }

// The Stokes definition of core/polarisation.h, straight from the field.
polar::Stokes stokes_of(cplx Ex, cplx Ey) {
    const cplx c = 2.0 * std::conj(Ex) * Ey;
    return polar::Stokes(std::norm(Ex) + std::norm(Ey), std::norm(Ex) - std::norm(Ey), c.real(), c.imag());
}

void check_close(const polar::Mueller& A, const polar::Mueller& B, double tol) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) CHECK_THAT(A(i, j), WithinAbs(B(i, j), tol));
}

// The phase difference δ = arg rs − arg rp read off a Mueller matrix's lower block.
double lower_block_angle(const polar::Mueller& M) { return std::atan2(M(2, 3), M(2, 2)); }
}  // namespace

TEST_CASE("Jones to Mueller: diag(a, b) on Stokes vectors equals diag(a, b) on fields", "[polarisation]") {
    const std::vector<cplx> amps{{0.3, 0.0}, {-0.7, 0.2}, {0.0, 1.0}, {0.5, -0.5}, std::polar(1.0, 2.0)};
    const std::vector<std::pair<cplx, cplx>> fields{
        {{1, 0}, {0, 0}}, {{0, 0}, {1, 0}}, {{1, 0}, {0, 1}}, {{0.3, -0.2}, {0.8, 0.5}}, {{-1, 2}, {0.4, 0.1}}};
    for (const cplx a : amps)
        for (const cplx b : amps)
            for (const auto& [Ex, Ey] : fields) {
                const polar::Stokes got = polar::jones_diagonal_to_mueller(a, b) * stokes_of(Ex, Ey);
                const polar::Stokes want = stokes_of(a * Ex, b * Ey);
                for (int i = 0; i < 4; ++i) CHECK_THAT(got[i], WithinAbs(want[i], 1e-14));
            }
    // The helicity convention: Ex = 1, Ey = i turns from x̂ to ŷ (e^{−iωt}) and has S3 > 0.
    CHECK(stokes_of(1.0, cplx(0, 1))[3] > 0);
    const polar::Stokes want = stokes_of(1.0 / std::sqrt(2.0), cplx(0, 1.0 / std::sqrt(2.0)));
    for (int i = 0; i < 4; ++i) CHECK_THAT(polar::circular(1.0, +1)[i], WithinAbs(want[i], 1e-15));
}

TEST_CASE("Fresnel amplitudes: rs², rp² are Fresnel's Rs, Rp — unit modulus on TIR", "[polarisation]") {
    for (double eta : {1.5, 2.417, 1 / 1.5, 1 / 2.417}) {
        for (double a = 0; a <= 90.0; a += 0.25) {
            const double ci = std::cos(deg(a));
            const auto amp = polar::fresnel_amplitudes(ci, eta);
            const auto f = optics::fresnel(ci, eta);
            REQUIRE(amp.tir == !f.has_value());
            if (f) {
                CHECK(std::norm(amp.rs) == f->Rs);
                CHECK(std::norm(amp.rp) == f->Rp);
                CHECK(amp.cos_t == f->cos_t);
                CHECK(amp.rs.imag() == 0.0);
                CHECK(amp.rp.imag() == 0.0);
            } else {
                CHECK_THAT(std::abs(amp.rs), WithinAbs(1.0, 1e-15));
                CHECK_THAT(std::abs(amp.rp), WithinAbs(1.0, 1e-15));
                CHECK(amp.ts == 0.0);
                CHECK(amp.tp == 0.0);
                CHECK_FALSE(polar::mueller_transmission(ci, eta).has_value());
                // cos θt = iγ with γ² = sin²θi/η² − 1: the evanescent wave decays (γ >= 0).
                CHECK(amp.cos_t >= 0.0);
                CHECK_THAT(amp.cos_t * amp.cos_t, WithinAbs((1 - ci * ci) / (eta * eta) - 1, 1e-14));
                // The complex closed forms of Hecht's rs, rp with cos θt = iγ.
                const cplx ct(0.0, amp.cos_t);
                CHECK_THAT(std::abs(amp.rs - (ci - eta * ct) / (ci + eta * ct)), WithinAbs(0.0, 1e-15));
                CHECK_THAT(std::abs(amp.rp - (eta * ci - ct) / (eta * ci + ct)), WithinAbs(0.0, 1e-15));
            }
        }
    }
}

TEST_CASE("Brewster's law: natural light reflected at tan θB = n is fully s-polarised", "[polarisation]") {
    for (double eta : {1.5, 1 / 1.5, 2.417}) {
        const double thB = optics::brewster_angle(eta);
        const polar::Stokes S = polar::mueller_reflection(std::cos(thB), eta) * polar::unpolarised(1.0);
        CHECK(S[0] > 0.01);
        CHECK_THAT(polar::degree_of_polarisation(S), WithinAbs(1.0, 1e-12));
        CHECK_THAT(S[1] / S[0], WithinAbs(1.0, 1e-12));  // along x̂ = ŝ
        CHECK_THAT(polar::angle_of_linear_polarisation(S), WithinAbs(0.0, 1e-12));
    }
    // Away from θB the reflected light is only partially polarised.
    const polar::Stokes S = polar::mueller_reflection(std::cos(deg(30)), 1.5) * polar::unpolarised(1.0);
    CHECK(polar::degree_of_polarisation(S) < 0.9);
}

TEST_CASE("Malus's law: I = I0 cos²θ through an ideal linear polariser", "[polarisation]") {
    for (double a = -180; a <= 180; a += 7.5) {
        const double th = deg(a);
        const polar::Stokes S = polar::linear_polariser(0.0) * polar::linear(1.0, th);
        CHECK_THAT(S[0], WithinAbs(std::cos(th) * std::cos(th), 1e-12));
        // Same law with the polariser turned instead of the light.
        const polar::Stokes S2 = polar::linear_polariser(th) * polar::linear(2.0, 0.0);
        CHECK_THAT(S2[0], WithinAbs(2 * std::cos(th) * std::cos(th), 1e-12));
    }
    // Natural light through any polariser: half, fully linear along the axis.
    const polar::Stokes S = polar::linear_polariser(deg(30)) * polar::unpolarised(1.0);
    CHECK_THAT(S[0], WithinAbs(0.5, 1e-15));
    CHECK_THAT(polar::degree_of_linear_polarisation(S), WithinAbs(1.0, 1e-12));
    CHECK_THAT(polar::angle_of_linear_polarisation(S), WithinAbs(deg(30), 1e-12));
    // Circular polarisers pass their own handedness only.
    CHECK_THAT((polar::circular_polariser(+1) * polar::circular(1.0, +1))[0], WithinAbs(1.0, 1e-15));
    CHECK_THAT((polar::circular_polariser(+1) * polar::circular(1.0, -1))[0], WithinAbs(0.0, 1e-15));
    CHECK_THAT((polar::circular_polariser(-1) * polar::circular(1.0, -1))[3], WithinAbs(-1.0, 1e-15));
    CHECK_THAT((polar::circular_polariser(-1) * polar::unpolarised(1.0))[0], WithinAbs(0.5, 1e-15));
}

TEST_CASE("Energy conservation: R + T = 1 for s and for p (Mueller reflection + transmission)",
          "[polarisation]") {
    int checked = 0;
    for (double eta : {1.5, 1 / 1.5}) {
        for (double a = 0; a < 89.95; a += 0.1) {
            const double ci = std::cos(deg(a));
            const auto T = polar::mueller_transmission(ci, eta);
            const auto f = optics::fresnel(ci, eta);
            REQUIRE(T.has_value() == f.has_value());
            if (!T) continue;  // beyond the critical angle
            const polar::Mueller R = polar::mueller_reflection(ci, eta);
            CHECK_THAT(R(0, 0) + R(0, 1) + (*T)(0, 0) + (*T)(0, 1), WithinAbs(1.0, 1e-12));  // s
            CHECK_THAT(R(0, 0) - R(0, 1) + (*T)(0, 0) - (*T)(0, 1), WithinAbs(1.0, 1e-12));  // p
            CHECK_THAT(R(0, 0), WithinAbs(f->R(), 1e-15));
            CHECK_THAT((*T)(0, 0), WithinAbs(f->T(), 1e-12));
            ++checked;
        }
    }
    CHECK(checked > 1300);
}

TEST_CASE("Total internal reflection: phase difference δs − δp (Born & Wolf §1.5.4)", "[polarisation]") {
    for (double n : {1.5, 1.51, 1.333, 2.417}) {
        const double eta = 1 / n;
        const double thc = *optics::critical_angle(eta);
        const double delta_max = 2 * std::atan((1 - eta * eta) / (2 * eta));  // eq. 61
        const auto delta_mueller = [&](double th) {
            return lower_block_angle(polar::mueller_reflection(std::cos(th), eta));
        };
        const int N = 20000;
        double grid_max = 0;
        for (int j = 0; j <= N; ++j) {
            const double th = thc + (M_PI / 2 - thc) * j / N;
            const polar::Mueller M = polar::mueller_reflection(std::cos(th), eta);
            CHECK_THAT(M(0, 0), WithinAbs(1.0, 1e-15));  // total reflection
            CHECK_THAT(M(0, 1), WithinAbs(0.0, 1e-15));
            const double d = lower_block_angle(M);
            CHECK_THAT(d, WithinAbs(polar::tir_phase_difference(std::cos(th), eta), 1e-12));
            grid_max = std::max(grid_max, d);
        }
        CHECK(grid_max <= delta_max + 1e-12);
        // The maximum, by golden-section search on the Mueller matrix's phase.
        double lo = thc, hi = M_PI / 2;
        const double g = (std::sqrt(5.0) - 1) / 2;
        for (int it = 0; it < 200; ++it) {
            const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
            if (delta_mueller(x1) < delta_mueller(x2))
                lo = x1;
            else
                hi = x2;
        }
        CHECK_THAT(delta_mueller(0.5 * (lo + hi)), WithinAbs(delta_max, 1e-9));
        // …at sin²θm = 2η²/(1 + η²).
        const double thm = std::asin(std::sqrt(2 * eta * eta / (1 + eta * eta)));
        CHECK_THAT(0.5 * (lo + hi), WithinAbs(thm, 1e-6));
        CHECK_THAT(polar::tir_phase_difference(std::cos(thm), eta), WithinAbs(delta_max, 1e-12));
    }
    // Glass n = 1.5: δmax = 45.24° (Born & Wolf); no TIR, no phase difference.
    CHECK_THAT(2 * std::atan((1 - 1 / 2.25) / (2 / 1.5)) * 180 / M_PI, WithinAbs(45.2397, 1e-4));
    CHECK(polar::tir_phase_difference(std::cos(deg(30)), 1 / 1.5) == 0.0);
    CHECK(polar::tir_phase_difference(std::cos(deg(60)), 1.5) == 0.0);
}

TEST_CASE("Fresnel rhomb: two total internal reflections at 54.6° in n = 1.51 make circular light",
          "[polarisation]") {
    const double eta = 1 / 1.51, th = deg(54.6);
    // Per reflection δ ≈ 45° (Born & Wolf §1.5.4: 54°37′ for n = 1.51).
    CHECK_THAT(polar::tir_phase_difference(std::cos(th), eta) * 180 / M_PI, WithinAbs(45.0, 0.1));
    // Trace the frames: the beam zig-zags between two parallel faces whose inner normals
    // are opposite; light enters linearly polarised at 45° to the plane of incidence.
    Vec3 k(std::sin(th), 0, -std::cos(th));
    const Vec3 faces[2] = {Vec3(0, 0, 1), Vec3(0, 0, -1)};
    Vec3 x = polar::s_axis(faces[0], k, Vec3(0, 1, 0));
    polar::Stokes S = polar::linear(1.0, deg(45));
    for (const Vec3& n : faces) {
        const Vec3 s = polar::s_axis(n, k, x);
        S = polar::rotator(polar::frame_angle(x, s, k)) * S;
        S = polar::mueller_reflection(-k.dot(n), eta) * S;
        x = s;
        k = optics::reflect(k, n);
    }
    CHECK_THAT(S[0], WithinAbs(1.0, 1e-14));
    CHECK(std::abs(S[3]) / S[0] >= 0.999);
    CHECK_THAT(polar::degree_of_polarisation(S), WithinAbs(1.0, 1e-12));
}

TEST_CASE("Pile of plates: DoP = (Tp^2k − Ts^2k)/(Tp^2k + Ts^2k) after k plates", "[polarisation]") {
    const double n = 1.5;
    for (double th : {optics::brewster_angle(n), deg(45)}) {
        const double ci = std::cos(th);
        const auto f = optics::fresnel(ci, n);
        REQUIRE(f);
        const double Ts = 1 - f->Rs, Tp = 1 - f->Rp;
        // One plate: into the glass, then out of it at the refraction angle (same ŝ).
        const polar::Mueller plate =
            *polar::mueller_transmission(f->cos_t, 1 / n) * *polar::mueller_transmission(ci, n);
        polar::Stokes S = polar::unpolarised(1.0);
        for (int k = 1; k <= 10; ++k) {
            S = plate * S;
            const double ts = std::pow(Ts, 2 * k), tp = std::pow(Tp, 2 * k);
            CHECK_THAT(polar::degree_of_polarisation(S), WithinAbs((tp - ts) / (tp + ts), 1e-12));
            CHECK_THAT(S[0], WithinAbs(0.5 * (tp + ts), 1e-12));
            CHECK(S[1] < 0);  // the transmitted light is p-polarised
        }
    }
}

TEST_CASE("Frame rotation: rotators compose, keep S0 and S3, and follow the field", "[polarisation]") {
    const polar::Stokes S(1.0, 0.3, -0.4, 0.5);
    for (double a = -200; a <= 200; a += 13.7) {
        const polar::Mueller R = polar::rotator(deg(a));
        check_close(polar::rotator(-deg(a)) * R, polar::Mueller::Identity(), 1e-15);
        const polar::Stokes Sr = R * S;
        CHECK(Sr[0] == S[0]);
        CHECK(Sr[3] == S[3]);
        CHECK_THAT(Sr.norm(), WithinAbs(S.norm(), 1e-15));
        const polar::Stokes L = polar::rotator(deg(a)) * polar::linear(1.0, deg(a));
        CHECK_THAT(polar::angle_of_linear_polarisation(L), WithinAbs(0.0, 1e-12));
        CHECK_THAT(L[1], WithinAbs(1.0, 1e-12));
    }
    // frame_angle against a linear field direction described in two frames about k.
    const Vec3 k = Vec3(1, 2, 2).normalized();
    const Vec3 xa = k.unitOrthogonal(), ya = k.cross(xa);
    for (double a = -170; a <= 170; a += 17) {
        const Vec3 xb = std::cos(deg(a)) * xa + std::sin(deg(a)) * ya, yb = k.cross(xb);
        CHECK_THAT(polar::frame_angle(xa, xb, k), WithinAbs(deg(a), 1e-12));
        const Vec3 E = std::cos(0.3) * xa + std::sin(0.3) * ya;  // linear field at 0.3 rad in frame a
        const polar::Stokes Sa = stokes_of(E.dot(xa), E.dot(ya)), Sb = stokes_of(E.dot(xb), E.dot(yb));
        const polar::Stokes got = polar::rotator(polar::frame_angle(xa, xb, k)) * Sa;
        for (int i = 0; i < 4; ++i) CHECK_THAT(got[i], WithinAbs(Sb[i], 1e-12));
    }
    // s_axis: n × k normalised, or the fallback made ⟂ k at normal incidence.
    const Vec3 n(0, 0, 1);
    const Vec3 k_oblique(std::sin(0.5), 0, -std::cos(0.5));
    CHECK((polar::s_axis(n, k_oblique, Vec3(1, 0, 0)) - Vec3(0, 1, 0)).norm() < 1e-15);
    CHECK((polar::s_axis(n, Vec3(0, 0, -1), Vec3(1, 0, 0.3)) - Vec3(1, 0, 0)).norm() < 1e-15);
}

TEST_CASE("Normal incidence reflection: Mueller = R diag(1, 1, −1, −1), the handedness flips",
          "[polarisation]") {
    for (double eta : {1.5, 1 / 1.5, 2.417, 1.333}) {
        const double R = optics::fresnel(1.0, eta)->R();
        polar::Mueller want = polar::Mueller::Zero();
        want.diagonal() << R, R, -R, -R;
        check_close(polar::mueller_reflection(1.0, eta), want, 1e-15);
        CHECK((polar::mueller_reflection(1.0, eta) * polar::circular(1.0, +1))[3] < 0);
    }
    CHECK_THAT(optics::fresnel(1.0, 1.5)->R(), WithinAbs(0.04, 1e-15));
}

TEST_CASE("Beer–Lambert slab: the bounce series sums to (1−R)² τ / (1 − R² τ²)", "[absorption]") {
    // An absorbing glass slab (n = 1.5) in air, all internal reflections summed
    // incoherently; τ = exp(−α d / cos θt) per pass.
    const double n = 1.5;
    struct Case {
        double angle_deg;
        int pol;  // +1: s (S = (1, 1, 0, 0)), −1: p (S = (1, −1, 0, 0))
    };
    for (const Case c : {Case{0, 1}, Case{30, 1}, Case{30, -1}, Case{80, 1}, Case{80, -1}}) {
        const double ci = std::cos(deg(c.angle_deg));
        const auto f = optics::fresnel(ci, n);
        REQUIRE(f);
        const double R = c.pol > 0 ? f->Rs : f->Rp;
        const auto power = [&](const polar::Mueller& M) { return M(0, 0) + c.pol * M(0, 1); };
        const double T_in = power(*polar::mueller_transmission(ci, n));
        const double T_out = power(*polar::mueller_transmission(f->cos_t, 1 / n));
        const double R_inside = power(polar::mueller_reflection(f->cos_t, 1 / n));
        for (double alpha_d : {0.0, 0.1, 1.0, 3.0}) {
            const double tau = optics::beer_lambert(alpha_d, 1 / f->cos_t);
            double inside = T_in, total = 0;
            for (int trip = 0; trip < 200; ++trip) {
                inside *= tau;               // down through the slab
                total += inside * T_out;     // out through the back face
                inside *= R_inside * tau * R_inside;  // back, up, and down again
            }
            const double closed = (1 - R) * (1 - R) * tau / (1 - R * R * tau * tau);
            CHECK_THAT(total, WithinAbs(closed, 1e-12));
        }
    }
    // No absorption, normal incidence: the lossless plate's 2n/(n² + 1).
    const double R = optics::fresnel(1.0, n)->R();
    CHECK_THAT((1 - R) * (1 - R) / (1 - R * R), WithinAbs(2 * n / (n * n + 1), 1e-15));
}

TEST_CASE("Beer–Lambert law: exp(−α d) and its inverse, the absorption coefficient", "[absorption]") {
    CHECK(optics::beer_lambert(0.7, 0.0) == 1.0);
    CHECK_THAT(optics::beer_lambert(0.5, 2.0), WithinAbs(std::exp(-1.0), 1e-16));
    CHECK_THAT(optics::beer_lambert(0.3, 1.0 + 2.5),
               WithinRel(optics::beer_lambert(0.3, 1.0) * optics::beer_lambert(0.3, 2.5), 1e-15));
    CHECK_THAT(*optics::absorption_coefficient(std::exp(-1.0), 2.0), WithinAbs(0.5, 1e-15));
    CHECK(*optics::absorption_coefficient(1.0, 3.0) == 0.0);
    for (double T : {1.0, 0.9, 0.5, 0.01, 1e-6, 1e-100})
        for (double d : {0.01, 1.0, 25.0}) {
            const auto alpha = optics::absorption_coefficient(T, d);
            REQUIRE(alpha);
            CHECK(*alpha >= 0.0);
            CHECK_THAT(optics::beer_lambert(*alpha, d), WithinRel(T, 1e-12));
            // The colour at another thickness: T^(d'/d).
            CHECK_THAT(optics::beer_lambert(*alpha, 2 * d), WithinRel(T * T, 1e-12));
        }
    const double nan = std::nan(""), inf = INFINITY;
    for (double T : {0.0, -0.1, 1.0 + 1e-12, 2.0, nan, inf, -inf})
        CHECK_FALSE(optics::absorption_coefficient(T, 1.0).has_value());
    for (double d : {0.0, -0.0, -1.0, nan, inf, -inf})
        CHECK_FALSE(optics::absorption_coefficient(0.5, d).has_value());
}
