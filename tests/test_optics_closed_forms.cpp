// The closed-form references of the optics bench (experiments/optics_closed_forms.h)
// against published values and against independent evaluations (brute-force scans, a
// midpoint rule, Walsh's closed form, a paraxial ray through a ball lens).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <refract/core/optics.h>
#include <refract/experiments/optics_closed_forms.h>

using namespace refract;
namespace cf = refract::experiments::closed_form;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
constexpr double kPi = 3.14159265358979323846;
double deg(double d) { return d * kPi / 180.0; }
double to_deg(double r) { return r * 180.0 / kPi; }

std::vector<double> uniform_edges(double first_deg, double step_deg) {
    std::vector<double> e;
    for (double a = first_deg; a < 180.0 + 1e-9; a += step_deg) e.push_back(deg(std::max(a, 0.0)));
    if (e.back() < kPi) e.push_back(kPi);
    return e;
}

// Independent binning: midpoint rule over u = sin² i with `points` samples, each sample's
// weight put whole into the bin of its scattering angle.
cf::SphereBins midpoint_bins(double n, int p, const std::vector<double>& edges, int points) {
    cf::SphereBins b;
    b.s.assign(edges.size() - 1, 0.0);
    b.p.assign(edges.size() - 1, 0.0);
    const double du = 1.0 / points;
    for (int j = 0; j < points; ++j) {
        const double i = std::asin(std::sqrt((j + 0.5) * du));
        const double th = cf::scattering_angle(p, i, n);
        if (!std::isfinite(th)) continue;
        const auto it = std::upper_bound(edges.begin(), edges.end(), th);
        if (it == edges.begin() || it == edges.end()) continue;
        const auto e = cf::sphere_class_fraction(p, i, n);
        b.s[it - edges.begin() - 1] += e.s * du;
        b.p[it - edges.begin() - 1] += e.p * du;
    }
    return b;
}

// Walsh (1926), the first moment of the Fresnel reflectance of natural light,
// 2∫ R(i) cos i sin i di over the hemisphere, for relative index m > 1 (as quoted by Prahl,
// PhD thesis 1988, eq. B.41). Not derived from Fresnel's formulae here: a published closed form.
double walsh_first_moment(double m) {
    const double m2 = m * m, m4 = m2 * m2;
    return 0.5 + (m - 1) * (3 * m + 1) / (6 * (m + 1) * (m + 1)) +
           m2 * (m2 - 1) * (m2 - 1) / std::pow(m2 + 1, 3) * std::log((m - 1) / (m + 1)) -
           2 * m * m2 * (m2 + 2 * m - 1) / ((m2 + 1) * (m4 - 1)) +
           8 * m4 * (m4 + 1) / ((m2 + 1) * (m4 - 1) * (m4 - 1)) * std::log(m);
}
}  // namespace

// ---- Sphere ------------------------------------------------------------------------------

TEST_CASE("Descartes' rainbow: primary and secondary bows of water", "[optics-closed-form][rainbow]") {
    // n = 4/3: minimum deviation 137.97° (the bow 42.03° from the antisolar point); the
    // secondary 129.0°, i.e. 51.0° from it. n = 1.333: 137.92° and 129.11° (50.89°).
    CHECK_THAT(to_deg(cf::rainbow_deviation(2, 4.0 / 3.0)), WithinAbs(137.97, 0.01));
    CHECK_THAT(to_deg(cf::rainbow_deviation(3, 4.0 / 3.0)), WithinAbs(129.02, 0.01));
    const double primary = to_deg(cf::rainbow_deviation(2, 1.333));
    const double secondary = to_deg(cf::rainbow_deviation(3, 1.333));
    CHECK_THAT(primary, WithinAbs(137.97, 0.05));
    CHECK_THAT(primary, WithinAbs(137.922, 0.001));
    CHECK_THAT(180.0 - secondary, WithinAbs(50.9, 0.05));
    CHECK_THAT(secondary, WithinAbs(129.109, 0.001));
    // No rainbow without one: direct light, reflection, or n >= p.
    CHECK(std::isnan(cf::rainbow_deviation(1, 1.333)));
    CHECK(std::isnan(cf::rainbow_deviation(2, 2.417)));
    CHECK(std::isfinite(cf::rainbow_deviation(3, 2.417)));
}

TEST_CASE("Descartes' rainbow is the stationary (minimum) deviation of its class", "[optics-closed-form][rainbow]") {
    // A brute-force scan of D_p(i), independent of cos² i = (n² − 1)/(p² − 1).
    for (double n : {1.333, 1.5, 1.76}) {
        for (int p = 2; p <= 6; ++p) {
            if (!(n < p)) continue;
            double best = 1e300, best_i = 0;
            const int steps = 20000;
            for (int j = 0; j <= steps; ++j) {
                const double i = 0.5 * kPi * j / steps;
                const double D = cf::deviation(p, i, n);
                if (D < best) { best = D; best_i = i; }
            }
            const double i_rb = cf::rainbow_incidence(p, n);
            CHECK_THAT(best_i, WithinAbs(i_rb, 2e-4));
            CHECK_THAT(cf::deviation(p, i_rb, n), WithinAbs(best, 1e-8));
            CHECK(cf::deviation(p, i_rb, n) <= best + 1e-15);
            // θ is D folded into [0, π].
            CHECK_THAT(std::cos(cf::rainbow_deviation(p, n)), WithinAbs(std::cos(best), 1e-8));
        }
    }
}

TEST_CASE("Sphere deviation laws: reflection pi - 2i, transmission 2(i - r), folded into [0, pi]",
          "[optics-closed-form][sphere]") {
    const double n = 1.5;
    for (double a = 0; a <= 90; a += 7.5) {
        const double i = deg(a), r = std::asin(std::sin(i) / n);
        CHECK_THAT(cf::scattering_angle(0, i, n), WithinAbs(kPi - 2 * i, 1e-14));
        CHECK_THAT(cf::scattering_angle(1, i, n), WithinAbs(2 * (i - r), 1e-14));
        for (int p = 0; p <= 7; ++p) {
            const double th = cf::scattering_angle(p, i, n);
            CHECK(th >= 0.0);
            CHECK(th <= kPi);
            CHECK_THAT(std::cos(th), WithinAbs(std::cos(cf::deviation(p, i, n)), 1e-13));
        }
    }
    // Head-on: the reflection goes straight back, the transmission straight through.
    CHECK(cf::scattering_angle(0, 0.0, n) == kPi);
    CHECK(cf::scattering_angle(1, 0.0, n) == 0.0);
    // An air bubble (n < 1): beyond the critical angle only the reflection exists.
    CHECK(std::isnan(cf::scattering_angle(1, deg(60), 0.75)));
    CHECK(cf::sphere_class_fraction(0, deg(60), 0.75).natural == 1.0);
    CHECK(cf::sphere_class_fraction(2, deg(60), 0.75).natural == 0.0);
}

TEST_CASE("Sphere energy conservation: the classes of each polarisation sum to the beam",
          "[optics-closed-form][sphere]") {
    for (double n : {1.333, 1.5, 0.75}) {
        double sum_s = 0, sum_p = 0;
        for (int p = 0; p <= 40; ++p) {
            const auto b = cf::sphere_scattering(n, p, {});
            sum_s += b.total_s;
            sum_p += b.total_p;
            CHECK_THAT(b.total_natural, WithinAbs(0.5 * (b.total_s + b.total_p), 1e-16));
        }
        // Σ_{p<=40} ε_p = 1 − (1 − R) R^40 ray by ray: rays near grazing incidence keep
        // bouncing, and the beam fraction beyond p = 40 is a few 1e-6 (s). That remainder,
        // by an independent midpoint rule in sin² i:
        double rest_s = 0, rest_p = 0;
        const int m = 400000;
        for (int j = 0; j < m; ++j) {
            const double i = std::asin(std::sqrt((j + 0.5) / m));
            const auto f = optics::fresnel(std::cos(i), n);
            const double Rs = f ? f->Rs : 1.0, Rp = f ? f->Rp : 1.0;
            rest_s += (1 - Rs) * std::pow(Rs, 40) / m;
            rest_p += (1 - Rp) * std::pow(Rp, 40) / m;
        }
        CHECK(rest_s < 1e-5);
        CHECK_THAT(sum_s + rest_s, WithinAbs(1.0, 1e-6));
        CHECK_THAT(sum_p + rest_p, WithinAbs(1.0, 1e-6));
        // And with enough classes the sum reaches 1 on its own.
        for (int p = 41; p <= 400; ++p) {
            const auto b = cf::sphere_scattering(n, p, {});
            sum_s += b.total_s;
            sum_p += b.total_p;
        }
        CHECK_THAT(sum_s, WithinAbs(1.0, 1e-8));
        CHECK_THAT(sum_p, WithinAbs(1.0, 1e-8));
    }
}

TEST_CASE("Sphere external reflection: Walsh's closed form of the mean Fresnel reflectance",
          "[optics-closed-form][sphere]") {
    // The beam's measure d(sin² i) = 2 sin i cos i di is the hemispherical first moment.
    const auto w = cf::sphere_scattering(1.333, 0, {});
    CHECK_THAT(w.total_natural, WithinAbs(0.066405764783, 1e-11));
    CHECK_THAT(w.total_natural, WithinAbs(walsh_first_moment(1.333), 1e-12));
    CHECK_THAT(cf::sphere_scattering(1.5, 0, {}).total_natural, WithinAbs(walsh_first_moment(1.5), 1e-12));
    CHECK_THAT(cf::sphere_scattering(2.417, 0, {}).total_natural, WithinAbs(walsh_first_moment(2.417), 1e-12));
    // And an independent quadrature over the disk of impact points: rings of radius b
    // (b = sin i, unit sphere), area 2b db, by a 10⁶-point midpoint rule in b.
    double sum = 0;
    const int m = 1000000;
    for (int j = 0; j < m; ++j) {
        const double b = (j + 0.5) / m;
        sum += optics::fresnel_reflectance(std::sqrt(1 - b * b), 1.333) * 2 * b / m;
    }
    CHECK_THAT(sum, WithinAbs(w.total_natural, 1e-8));
}

TEST_CASE("Sphere bins: the primary bow peaks in the bin holding Descartes' angle, dark below it",
          "[optics-closed-form][sphere][rainbow]") {
    const double n = 1.333;
    const double rb = to_deg(cf::rainbow_deviation(2, n));
    // Bins of 1° with the bow 0.25° above a bin's lower edge. (The density diverges as
    // (θ − θ_rb)^(−1/2) just above the bow, so with edges on whole degrees, where the bow at
    // 137.92° is 0.08° below an edge, the brightest bin is [138°, 139°).)
    const auto edges = uniform_edges(rb - 0.25 - std::floor(rb - 0.25), 1.0);
    const auto b = cf::sphere_scattering(n, 2, edges);
    const auto peak = std::max_element(b.natural.begin(), b.natural.end()) - b.natural.begin();
    CHECK(edges[peak] <= deg(rb));
    CHECK(deg(rb) < edges[peak + 1]);
    // Class 2 sends nothing below the bow, class 3 nothing above its own (Alexander's band).
    const double rb3 = to_deg(cf::rainbow_deviation(3, n));
    const auto b3 = cf::sphere_scattering(n, 3, edges);
    for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
        if (edges[k + 1] <= deg(rb)) CHECK(b.natural[k] == 0.0);
        if (edges[k] >= deg(rb3)) CHECK(b3.natural[k] == 0.0);
    }
    // Whole-degree edges: the peak is the next bin up.
    const auto whole = cf::sphere_scattering(n, 2, uniform_edges(0, 1.0));
    CHECK(std::max_element(whole.natural.begin(), whole.natural.end()) - whole.natural.begin() == 138);
}

TEST_CASE("Sphere bins: they sum to the class totals and agree with a midpoint rule in sin^2 i",
          "[optics-closed-form][sphere]") {
    const auto edges = uniform_edges(0, 2.0);
    const std::pair<double, int> cases[] = {{1.333, 0}, {1.333, 2}, {1.5, 3}, {1.5, 5}};
    for (const auto& [n, p] : cases) {
        const auto b = cf::sphere_scattering(n, p, edges);
        double s = 0, pp = 0;
        for (std::size_t k = 0; k < b.s.size(); ++k) {
            s += b.s[k];
            pp += b.p[k];
            CHECK(b.natural[k] == 0.5 * (b.s[k] + b.p[k]));
        }
        CHECK_THAT(s, WithinAbs(b.total_s, 1e-12));
        CHECK_THAT(pp, WithinAbs(b.total_p, 1e-12));
        // Bins of 1°, merged in pairs, give the bins of 2°.
        const auto fine = cf::sphere_scattering(n, p, uniform_edges(0, 1.0));
        for (std::size_t k = 0; k < b.s.size(); ++k) {
            CHECK_THAT(fine.s[2 * k] + fine.s[2 * k + 1], WithinAbs(b.s[k], 1e-13));
            CHECK_THAT(fine.p[2 * k] + fine.p[2 * k + 1], WithinAbs(b.p[k], 1e-13));
        }
        // The midpoint rule converges (doubling its points moves no bin by 1e-5) to the exact
        // bins, and lands within 1e-5 of them.
        const auto m1 = midpoint_bins(n, p, edges, 200000);
        const auto m2 = midpoint_bins(n, p, edges, 400000);
        double doubling = 0, exact = 0;
        for (std::size_t k = 0; k < b.s.size(); ++k) {
            doubling = std::max({doubling, std::abs(m2.s[k] - m1.s[k]), std::abs(m2.p[k] - m1.p[k])});
            exact = std::max({exact, std::abs(b.s[k] - m2.s[k]), std::abs(b.p[k] - m2.p[k])});
        }
        INFO("n = " << n << ", p = " << p << ": doubling " << doubling << ", exact − midpoint " << exact);
        CHECK(doubling < 1e-5);
        CHECK(exact < 1e-5);
    }
}

// ---- Prism -------------------------------------------------------------------------------

TEST_CASE("Prism minimum deviation: 2 asin(n sin(A/2)) - A, at symmetric passage", "[optics-closed-form][prism]") {
    const double A = deg(60), n = 1.5;
    CHECK_THAT(to_deg(cf::prism_minimum_deviation(A, n)), WithinAbs(37.18, 0.005));
    // Symmetric passage: sin i1 = n sin(A/2).
    const double i_sym = std::asin(n * std::sin(A / 2));
    const auto d = cf::prism_deviation(A, i_sym, n);
    REQUIRE(d);
    CHECK_THAT(*d, WithinAbs(cf::prism_minimum_deviation(A, n), 1e-12));
    // Every other incidence deviates more; near normal incidence the ray is totally
    // reflected at the second face (r2 = 60° beyond the critical 41.8°).
    for (double a = 0; a < 90; a += 0.5) {
        const auto da = cf::prism_deviation(A, deg(a), n);
        if (da) CHECK(*da >= cf::prism_minimum_deviation(A, n) - 1e-12);
    }
    CHECK_FALSE(cf::prism_deviation(A, 0.0, n).has_value());
    CHECK(cf::prism_deviation(A, deg(30), n).has_value());
    // The ray is reversible: entering at the exit angle gives the same deviation.
    const double i1 = deg(50);
    const double i2 = *cf::prism_deviation(A, i1, n) + A - i1;
    CHECK_THAT(*cf::prism_deviation(A, i2, n), WithinAbs(*cf::prism_deviation(A, i1, n), 1e-12));
}

// ---- Slab --------------------------------------------------------------------------------

TEST_CASE("Slab energy conservation: T + R = 1 per polarisation", "[optics-closed-form][slab]") {
    for (double n : {1.333, 1.5, 2.417}) {
        for (double a = 0; a < 90; a += 2.5) {
            const auto t = cf::slab(deg(a), n);
            CHECK_THAT(t.T.s + t.R.s, WithinAbs(1.0, 1e-15));
            CHECK_THAT(t.T.p + t.R.p, WithinAbs(1.0, 1e-15));
            CHECK_THAT(t.T.natural + t.R.natural, WithinAbs(1.0, 1e-15));
        }
    }
    // Normal incidence, glass: R = 0.04, T = 0.96/1.04.
    CHECK_THAT(cf::slab(0.0, 1.5).T.natural, WithinAbs(0.96 / 1.04, 1e-15));
    // Natural light is the mean of the s and p results, not the formula at the mean R.
    const auto t = cf::slab(deg(70), 1.5);
    const double Rmean = optics::fresnel_reflectance(std::cos(deg(70)), 1.5);
    CHECK_THAT(t.T.natural, WithinAbs(0.5 * (t.T.s + t.T.p), 1e-16));
    CHECK(std::abs(t.T.natural - (1 - Rmean) / (1 + Rmean)) > 1e-3);
}

TEST_CASE("Slab at Brewster's angle transmits all p light", "[optics-closed-form][slab]") {
    for (double n : {1.333, 1.5, 2.417}) {
        const auto t = cf::slab(optics::brewster_angle(n), n);
        CHECK_THAT(t.T.p, WithinAbs(1.0, 1e-15));
        CHECK(t.T.s < 0.95);
    }
}

TEST_CASE("Slab reflection classes: the series sum to the totals", "[optics-closed-form][slab]") {
    for (double a : {0.0, 30.0, 56.0, 75.0, 85.0}) {
        const auto f = optics::fresnel(std::cos(deg(a)), 1.5);
        const auto t = cf::slab(deg(a), 1.5);
        for (int pol = 0; pol < 2; ++pol) {
            const double R = pol == 0 ? f->Rs : f->Rp;
            double T = 0, Rsum = 0;
            for (int k = 0; k < 400; ++k) {
                T += cf::slab_transmitted_class(k, R);
                Rsum += cf::slab_reflected_class(k, R);
            }
            CHECK_THAT(T, WithinAbs(pol == 0 ? t.T.s : t.T.p, 1e-12));
            CHECK_THAT(Rsum, WithinAbs(pol == 0 ? t.R.s : t.R.p, 1e-12));
        }
    }
    CHECK(cf::slab_reflected_class(0, 0.04) == 0.04);
    CHECK_THAT(cf::slab_reflected_class(1, 0.04), WithinAbs(0.96 * 0.96 * 0.04, 1e-17));
    CHECK_THAT(cf::slab_transmitted_class(1, 0.04), WithinAbs(0.96 * 0.96 * 0.04 * 0.04, 1e-17));
}

// ---- Ball lens ---------------------------------------------------------------------------

TEST_CASE("Ball lens paraxial focus: f = n a / (2(n - 1)) from the centre", "[optics-closed-form][lens]") {
    // A ray 1e-4 radii off axis, refracted at both surfaces, crosses the axis at the focus.
    for (double n : {1.5, 1.8, 2.0}) {
        const double h = 1e-4;
        const Vec3 d(0, 0, 1);
        const Vec3 P(h, 0, -std::sqrt(1 - h * h));  // on the unit sphere; its outward normal is P
        const auto t1 = optics::refract(d, P, n);
        REQUIRE(t1);
        const Vec3 Q = P - 2 * P.dot(*t1) * *t1;  // the second intersection with |x| = 1
        const auto t2 = optics::refract(*t1, -Q, 1 / n);
        REQUIRE(t2);
        const double z_focus = Q.z() - Q.x() * t2->z() / t2->x();
        CHECK_THAT(z_focus, WithinRel(cf::ball_lens_focus_from_centre(n, 1.0), 1e-6));
    }
    CHECK_THAT(cf::ball_lens_focus_from_centre(1.5, 2.0), WithinAbs(3.0, 1e-15));
    CHECK_THAT(cf::ball_lens_back_focal_distance(2.0, 1.0), WithinAbs(0.0, 1e-15));  // n = 2 focuses on the surface
}
