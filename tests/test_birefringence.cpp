// Double refraction at uniaxial crystals (core/birefringence.h) against closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <refract/core/birefringence.h>
#include <refract/core/polarisation.h>
#include <refract/core/spectrum/dispersion.h>

using namespace refract;
using namespace refract::biref;
using Catch::Matchers::WithinAbs;

namespace {
double deg(double d) { return d * M_PI / 180.0; }

// Calcite at 589.3 nm (handbook values).
constexpr double kCalciteO = 1.6584, kCalciteE = 1.4864;

Vec3 random_unit(std::mt19937_64& g) {
    std::normal_distribution<double> n;
    return Vec3(n(g), n(g), n(g)).normalized();
}

// A ray from the air hitting a surface of normal (0, 0, 1) at θ, in the azimuth φ.
Vec3 incident(double theta, double phi) {
    return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
}

const Beam* find(const InterfaceSplit& s, Wave w, bool transmitted) {
    for (int i = 0; i < s.count; ++i)
        if (s.beam[static_cast<size_t>(i)].wave == w && s.beam[static_cast<size_t>(i)].transmitted == transmitted)
            return &s.beam[static_cast<size_t>(i)];
    return nullptr;
}

void check_close(const polar::Mueller& A, const polar::Mueller& B, double tol) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) CHECK_THAT(A(i, j), WithinAbs(B(i, j), tol));
}

// Power carried by all beams for a unit-power incident Jones vector e.
double outgoing_power(const InterfaceSplit& s, const Eigen::Vector2cd& e) {
    double p = 0;
    for (int i = 0; i < s.count; ++i) p += (s.beam[static_cast<size_t>(i)].J * e).squaredNorm();
    return p;
}
}  // namespace

TEST_CASE("Jones to Mueller of a general matrix equals the field transformation", "[birefringence]") {
    std::mt19937_64 g(7);
    std::normal_distribution<double> n;
    for (int trial = 0; trial < 20; ++trial) {
        Jones J;
        for (int i = 0; i < 4; ++i) J(i) = cplx(n(g), n(g));
        const Eigen::Vector2cd e(cplx(n(g), n(g)), cplx(n(g), n(g)));
        const auto stokes = [](const Eigen::Vector2cd& f) {
            const cplx c = 2.0 * std::conj(f[0]) * f[1];
            return polar::Stokes(std::norm(f[0]) + std::norm(f[1]), std::norm(f[0]) - std::norm(f[1]), c.real(),
                                 c.imag());
        };
        const polar::Stokes want = stokes(J * e), got = polar::jones_to_mueller(J) * stokes(e);
        for (int i = 0; i < 4; ++i) CHECK_THAT(got[i], WithinAbs(want[i], 1e-12 * want[0]));
    }
    check_close(polar::jones_to_mueller(Jones(Eigen::Vector2cd(cplx(0.3, 0.1), cplx(-0.5, 0.7)).asDiagonal())),
                polar::jones_diagonal_to_mueller(cplx(0.3, 0.1), cplx(-0.5, 0.7)), 1e-15);
}

TEST_CASE("Extraordinary index follows the index ellipsoid", "[birefringence]") {
    CHECK_THAT(extraordinary_index(kCalciteO, kCalciteE, 1.0), WithinAbs(kCalciteO, 1e-15));
    CHECK_THAT(extraordinary_index(kCalciteO, kCalciteE, 0.0), WithinAbs(kCalciteE, 1e-15));
    // The e wave refracted into calcite has |k| = n(θ), θ between k and the optic axis.
    std::mt19937_64 g(1);
    for (int trial = 0; trial < 50; ++trial) {
        const Medium m{kCalciteO, kCalciteE, random_unit(g)};
        const Vec3 N(0, 0, -1);
        const Vec3 t = 0.9 * Vec3(random_unit(g).x(), random_unit(g).y(), 0);
        const Vec3 s = Vec3(0, 0, 1).cross(t).normalized();
        const auto w = plane_waves(m, t, N, s);
        const Vec3 k = w[1].k.real();
        const double c = k.normalized().dot(m.axis);
        const double want = 1.0 / std::sqrt(c * c / (kCalciteO * kCalciteO) + (1 - c * c) / (kCalciteE * kCalciteE));
        CHECK_THAT(k.norm(), WithinAbs(want, 1e-12));
        CHECK_THAT(k.norm(), WithinAbs(extraordinary_index(kCalciteO, kCalciteE, c), 1e-12));
        // Tangential components match the incident ones (phase matching).
        CHECK_THAT((k - k.dot(N) * N - t).norm(), WithinAbs(0.0, 1e-12));
        // The ray direction is along ε k, and the e wave's ray recovers its wave vector.
        CHECK_THAT((wave_vector_of_ray(m, Wave::Extraordinary, w[1].ray) - k).norm(), WithinAbs(0.0, 1e-12));
    }
}

TEST_CASE("Ordinary ray obeys Snell's law with n_o", "[birefringence]") {
    std::mt19937_64 g(2);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 50; ++trial) {
        const Medium air{1.0, 1.0, Vec3::Zero()};
        const Medium calcite{kCalciteO, kCalciteE, random_unit(g)};
        const double th = deg(85.0 * u(g)), phi = 2 * M_PI * u(g);
        const Vec3 d = incident(th, phi), n(0, 0, 1);
        const auto split = split_at_interface(air, Wave::Isotropic, calcite, d, n);
        const Beam* o = find(split, Wave::Ordinary, true);
        REQUIRE(o);
        const double sin_t = std::sqrt(1 - o->dir.z() * o->dir.z());
        CHECK_THAT(kCalciteO * sin_t, WithinAbs(std::sin(th), 1e-12));
        CHECK_THAT(o->dir.dot(n.cross(d).normalized()), WithinAbs(0.0, 1e-12));  // in the plane of incidence
        CHECK(o->dir.z() < 0);
    }
}

TEST_CASE("Walk-off of the extraordinary ray in a calcite plate cut at 45 degrees", "[birefringence]") {
    const Medium air{1.0, 1.0, Vec3::Zero()};
    const Medium calcite{kCalciteO, kCalciteE, Vec3(std::sin(deg(45)), 0, std::cos(deg(45)))};
    const auto split = split_at_interface(air, Wave::Isotropic, calcite, Vec3(0, 0, -1), Vec3(0, 0, 1));
    const Beam* o = find(split, Wave::Ordinary, true);
    const Beam* e = find(split, Wave::Extraordinary, true);
    REQUIRE(o);
    REQUIRE(e);
    CHECK_THAT(o->dir.z(), WithinAbs(-1.0, 1e-15));
    const double rho = std::acos(-e->dir.z());
    const double r = kCalciteO * kCalciteO / (kCalciteE * kCalciteE);
    CHECK_THAT(rho, WithinAbs(std::atan((r - 1) / (1 + r)), 1e-12));
    CHECK_THAT(rho, WithinAbs(walk_off_angle(kCalciteO, kCalciteE, deg(45)), 1e-12));
    CHECK_THAT(rho, WithinAbs(deg(6.22), deg(0.01)));
    // Negative crystal: the ray leans away from the optic axis's line ±â; k = −z is at 45°
    // to −â = (−1, 0, −1)/√2, so the ray turns towards +x.
    CHECK(e->dir.x() > 0);
    // Orthogonal polarisations: the o wave along k × â (y), the e wave in the x–z plane.
    CHECK_THAT(o->J.row(0).norm(), WithinAbs(0.0, 1e-15));  // x̂ = (1, 0, 0): the o field is along y
    CHECK_THAT(std::abs((e->J.row(0).norm() > e->J.row(1).norm() ? e->J.row(1) : e->J.row(0)).norm()),
               WithinAbs(0.0, 1e-12));
}

TEST_CASE("Optic axis along the surface normal at normal incidence gives one ray", "[birefringence]") {
    const Medium air{1.0, 1.0, Vec3::Zero()};
    const Medium calcite{kCalciteO, kCalciteE, Vec3(0, 0, 1)};
    const auto split = split_at_interface(air, Wave::Isotropic, calcite, Vec3(0, 0, -1), Vec3(0, 0, 1));
    const Beam* o = find(split, Wave::Ordinary, true);
    const Beam* e = find(split, Wave::Extraordinary, true);
    REQUIRE(o);
    REQUIRE(e);
    CHECK_THAT((o->dir - e->dir).norm(), WithinAbs(0.0, 1e-15));
    CHECK_THAT(o->dir.z(), WithinAbs(-1.0, 1e-15));
    // Both see n_o: the transmittance is the isotropic one, 1 − ((n_o − 1)/(n_o + 1))².
    const double R = std::pow((kCalciteO - 1) / (kCalciteO + 1), 2);
    CHECK_THAT(o->power + e->power, WithinAbs(1 - R, 1e-12));
    CHECK_THAT(o->power, WithinAbs(0.5 * (1 - R), 1e-12));
}

TEST_CASE("Energy is conserved at uniaxial interfaces for every wave and polarisation", "[birefringence]") {
    std::mt19937_64 g(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> nd;
    const Medium air{1.0, 1.0, Vec3::Zero()};
    int tir = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Medium crystal{1.4 + 1.3 * u(g), 1.4 + 1.3 * u(g), random_unit(g)};
        const double th = deg(89.0 * u(g)), phi = 2 * M_PI * u(g);
        // Into the crystal, any polarisation.
        const auto in = split_at_interface(air, Wave::Isotropic, crystal, incident(th, phi), Vec3(0, 0, 1));
        Eigen::Vector2cd e(cplx(nd(g), nd(g)), cplx(nd(g), nd(g)));
        e.normalize();
        CHECK_THAT(outgoing_power(in, e), WithinAbs(1.0, 1e-12));
        double natural = 0;
        for (int i = 0; i < in.count; ++i) natural += polar::jones_to_mueller(in.beam[static_cast<size_t>(i)].J)(0, 0);
        CHECK_THAT(natural, WithinAbs(1.0, 1e-12));
        // Out of it, each wave: the rays inside heading for the surface.
        for (int i = 0; i < in.count; ++i) {
            const Beam& b = in.beam[static_cast<size_t>(i)];
            if (!b.transmitted) continue;
            // Turn the ray around a tilted exit face.
            const Vec3 exit_normal = (Vec3(0.3 * nd(g), 0.3 * nd(g), 1)).normalized();
            if (b.dir.dot(-exit_normal) <= 0.05) continue;
            const auto out = split_at_interface(crystal, b.wave, air, b.dir, exit_normal);
            double p = 0;
            bool transmitted = false;
            for (int j = 0; j < out.count; ++j) {
                p += out.beam[static_cast<size_t>(j)].power;
                transmitted |= out.beam[static_cast<size_t>(j)].transmitted;
            }
            CHECK_THAT(p, WithinAbs(1.0, 1e-12));
            if (!transmitted) ++tir;
        }
    }
    CHECK(tir > 10);  // total internal reflection of both waves was met and conserved energy
}

TEST_CASE("Total internal reflection inside calcite gives an ordinary and an extraordinary reflected ray",
          "[birefringence]") {
    const Medium air{1.0, 1.0, Vec3::Zero()};
    const Medium calcite{kCalciteO, kCalciteE, Vec3(1, 1, 1).normalized()};
    // An o ray inside at 50° to the normal: beyond both critical angles (asin(1/1.6584) = 37.1°).
    const Vec3 d = Vec3(std::sin(deg(50)), 0, std::cos(deg(50)));
    const auto out = split_at_interface(calcite, Wave::Ordinary, air, d, Vec3(0, 0, -1));
    REQUIRE(out.count == 2);
    const Beam* ro = find(out, Wave::Ordinary, false);
    const Beam* re = find(out, Wave::Extraordinary, false);
    REQUIRE(ro);
    REQUIRE(re);
    CHECK(re->power > 1e-3);  // the axis is oblique: some of the o wave turns into e
    CHECK_THAT(ro->power + re->power, WithinAbs(1.0, 1e-12));
    // The reflected o ray obeys the law of reflection.
    CHECK_THAT((ro->dir - Vec3(d.x(), d.y(), -d.z())).norm(), WithinAbs(0.0, 1e-12));
}

TEST_CASE("Isotropic limit n_e = n_o reproduces the Fresnel Mueller matrices", "[birefringence]") {
    std::mt19937_64 g(4);
    std::uniform_real_distribution<double> u(0, 1);
    const Medium air{1.0, 1.0, Vec3::Zero()};
    for (int trial = 0; trial < 30; ++trial) {
        const double n = 1.3 + 1.2 * u(g);
        const Medium crystal{n, n, random_unit(g)};
        const double th = deg(1 + 88.0 * u(g)), phi = 2 * M_PI * u(g);
        const Vec3 d = incident(th, phi), nrm(0, 0, 1);
        const double cos_i = std::cos(th);
        INFO("trial " << trial << " n " << n << " theta " << th);
        const auto in = split_at_interface(air, Wave::Isotropic, crystal, d, nrm);
        REQUIRE(in.count == 3);
        Jones Jt = Jones::Zero();
        for (int i = 0; i < in.count; ++i) {
            const Beam& b = in.beam[static_cast<size_t>(i)];
            if (!b.transmitted) check_close(polar::jones_to_mueller(b.J), polar::mueller_reflection(cos_i, n), 1e-12);
            if (b.transmitted) Jt += b.J;  // the o and e beams coincide: coherent sum
        }
        check_close(polar::jones_to_mueller(Jt), *polar::mueller_transmission(cos_i, n), 1e-12);

        // Out of the crystal: the o and e incident waves together span all states.
        const double th2 = deg(1 + 88.0 * u(g));
        const Vec3 d2(std::sin(th2) * std::cos(phi), std::sin(th2) * std::sin(phi), std::cos(th2));
        const auto from_o = split_at_interface(crystal, Wave::Ordinary, air, d2, Vec3(0, 0, -1));
        const auto from_e = split_at_interface(crystal, Wave::Extraordinary, air, d2, Vec3(0, 0, -1));
        Jones Jr = Jones::Zero(), Jout = Jones::Zero();
        bool tir = true;
        for (const auto* s : {&from_o, &from_e})
            for (int i = 0; i < s->count; ++i) {
                const Beam& b = s->beam[static_cast<size_t>(i)];
                (b.transmitted ? Jout : Jr) += b.J;
                tir &= !b.transmitted;
            }
        const double c2 = std::cos(th2);
        INFO("exit theta " << th2);
        check_close(polar::jones_to_mueller(Jr), polar::mueller_reflection(c2, 1.0 / n), 1e-12);
        const auto Mt = polar::mueller_transmission(c2, 1.0 / n);
        CHECK(tir == !Mt.has_value());
        if (Mt) check_close(polar::jones_to_mueller(Jout), *Mt, 1e-12);
    }
}

TEST_CASE("Sellmeier indices of the uniaxial crystals match the handbook at 589.3 nm", "[birefringence]") {
    struct Row {
        const char* name;
        double n_o, n_e, tol;
    };
    // Handbook values at the sodium D line; moissanite's extraordinary fit (Wang 2013) gives
    // 2.6890 against the handbook's 2.691.
    for (const Row r : {Row{"calcite", 1.6584, 1.4864, 1e-3}, Row{"quartz", 1.5443, 1.5534, 1e-3},
                        Row{"sapphire", 1.768, 1.760, 1e-3}, Row{"moissanite", 2.648, 2.691, 2.5e-3}}) {
        INFO(r.name);
        const auto c = spectrum::uniaxial_crystal(r.name);
        REQUIRE(c);
        CHECK_THAT(c->ordinary.n(589.3), WithinAbs(r.n_o, r.tol));
        CHECK_THAT(c->extraordinary.n(589.3), WithinAbs(r.n_e, r.tol));
    }
    // The catalogue's moissanite is the ordinary ray of the crystal.
    CHECK(spectrum::uniaxial_crystal("moissanite")->ordinary.n(550) == spectrum::catalogue("moissanite").n(550));
    CHECK_FALSE(spectrum::uniaxial_crystal("diamond"));
}

TEST_CASE("Reciprocity: the reversed path's Jones matrix is D J-transpose D", "[birefringence]") {
    // Light reversed along each outgoing beam, traced explicitly, leaves along the reversed
    // incident ray with the Jones matrix `reversed` gives (frames: the same x̂ on each ray).
    std::mt19937_64 g(5);
    std::uniform_real_distribution<double> u(0, 1);
    const Medium air{1.0, 1.0, Vec3::Zero()};
    int checked = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const Medium crystal{1.4 + 1.3 * u(g), 1.4 + 1.3 * u(g), random_unit(g)};
        const bool entering = trial % 2 == 0;
        const Vec3 n(0, 0, 1);
        const double th = deg((entering ? 85.0 : 30.0) * u(g)), phi = 2 * M_PI * u(g);
        const Vec3 d = incident(th, phi);
        const Medium& from = entering ? air : crystal;
        const Medium& to = entering ? crystal : air;
        const Wave w_in = entering ? Wave::Isotropic : (trial % 4 == 1 ? Wave::Ordinary : Wave::Extraordinary);
        const auto fwd = split_at_interface(from, w_in, to, d, n);
        for (int i = 0; i < fwd.count; ++i) {
            const Beam& b = fwd.beam[static_cast<size_t>(i)];
            const Medium& side = b.transmitted ? to : from;
            const Medium& other = b.transmitted ? from : to;
            const auto rev = split_at_interface(side, b.wave, other, -b.dir, b.transmitted ? Vec3(-n) : n);
            const Beam* rb = nullptr;
            for (int k = 0; k < rev.count; ++k) {
                const Beam& c = rev.beam[static_cast<size_t>(k)];
                if (c.transmitted == b.transmitted && c.wave == w_in && c.dir.dot(-d) > 1 - 1e-9) rb = &c;
            }
            REQUIRE(rb);
            // Express both in the frames x̂ = b.x (child) and x̂ = fwd.x_in (parent).
            const auto rot = [](const Vec3& from_x, const Vec3& to_x, const Vec3& k) {
                return polar::rotator(polar::frame_angle(from_x, to_x, k));
            };
            const polar::Mueller explicit_M = rot(rb->x, fwd.x_in, -d) * polar::jones_to_mueller(rb->J) *
                                              rot(b.x, rev.x_in, -b.dir);
            check_close(explicit_M, polar::jones_to_mueller(reversed(b.J)), 1e-11);
            ++checked;
        }
    }
    CHECK(checked > 100);
}
