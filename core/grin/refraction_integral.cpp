// The refraction integral and the formulas of Bennett and Sæmundsson (refraction_integral.h).
#include <refract/core/grin/refraction_integral.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <refract/core/grin/check_range.h>
#include <refract/geometry/error.h>

namespace refract::grin {

namespace {
constexpr double kDeg = M_PI / 180.0;

}  // namespace

double refraction_integral(const Atmosphere& atm, double lambda_um, double apparent_altitude_rad,
                           const RefractionIntegralOptions& o) {
    constexpr const char* where = "refraction_integral";
    check_range(apparent_altitude_rad, 0.0, M_PI / 2, where, "apparent_altitude", " rad");
    check_range(o.observer_height_m, 0.0, 1e5, where, "observer_height", " m");
    check_range(o.top_height_m, o.observer_height_m + 1.0, 1e6, where, "top_height", " m");
    check_range(o.relative_tolerance, 1e-14, 1e-3, where, "relative_tolerance", "");
    const CiddorReference ref = ciddor_reference(lambda_um, atm.spec().co2_ppm, where);

    const double r0 = kEarthRadius_m + o.observer_height_m, rt = kEarthRadius_m + o.top_height_m;
    const double n0 = atm.index(o.observer_height_m, ref).n;
    const double z0 = M_PI / 2 - apparent_altitude_rad;
    if (z0 < 1e-12) return 0.0;  // the zenith
    const double c = n0 * r0 * std::sin(z0);  // Bouguer's invariant n r sin z

    auto index_at = [&](double r) {
        const Atmosphere::Index x = atm.index(r - kEarthRadius_m, ref);
        if (!(x.n + r * x.dn_dh > 0.0))
            throw InputError(std::string(where) + ": the atmosphere ducts at height " + format_value(r - kEarthRadius_m) +
                             " m (d(n r)/dr <= 0 there): no single ray path");
        return x;
    };
    auto zenith_at = [&](double r) { return std::asin(std::min(1.0, c / (index_at(r).n * r))); };
    // r(z): n(r) r = c / sin z by Newton's method, kept inside its bracket [r0, rt].
    double guess = r0;
    auto radius_at = [&](double z) {
        const double target = c / std::sin(z);
        double lo = r0, hi = rt, r = std::clamp(guess, lo, hi);
        for (int i = 0; i < 100; ++i) {
            const Atmosphere::Index x = index_at(r);
            const double F = x.n * r - target;
            (F < 0 ? lo : hi) = r;
            double next = r - F / (x.n + r * x.dn_dh);
            if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
            const bool done = std::abs(next - r) < 1e-8;
            r = next;
            if (done || hi - lo < 1e-8) break;
        }
        return guess = r;
    };
    auto integrand = [&](double z) {
        const double r = radius_at(z);
        const Atmosphere::Index x = index_at(r);
        return -r * x.dn_dh / (x.n + r * x.dn_dh);
    };

    // Pieces between the heights where the lapse rate changes (the integrand's kinks).
    std::vector<double> z_breaks{z0};
    for (double h : atm.kink_heights()) {
        if (h > o.observer_height_m && h < o.top_height_m) z_breaks.push_back(zenith_at(kEarthRadius_m + h));
    }
    z_breaks.push_back(zenith_at(rt));
    // Each piece over u in [−1, 1] (Boost's error estimate of a subinterval is in the units
    // of [−1, 1], so a short interval in z would look far less accurate than it is), to an
    // absolute tolerance: relative_tolerance of the whole (a piece high up holds a tiny part
    // of R; its own relative tolerance would only chase rounding noise).
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    auto piece = [&](size_t i, unsigned depth, double tol) {
        const double mid = 0.5 * (z_breaks[i] + z_breaks[i + 1]), half = 0.5 * (z_breaks[i] - z_breaks[i + 1]);
        guess = r0;
        return GK::integrate([&](double u) { return integrand(mid + half * u) * half; }, -1.0, 1.0, depth, tol);
    };
    std::vector<double> rough;
    double total = 0.0;
    for (size_t i = 0; i + 1 < z_breaks.size(); ++i) {
        rough.push_back(piece(i, 0, 1.0));
        total += std::abs(rough.back());
    }
    double R = 0.0;
    for (size_t i = 0; i + 1 < z_breaks.size(); ++i) {
        const double tol = o.relative_tolerance * total / (std::abs(rough[i]) + 1e-300);
        R += tol >= 1e-3 ? rough[i] : piece(i, 12, std::max(tol, o.relative_tolerance));
    }
    return R;
}

double bennett_corrected_refraction_arcmin(double h, double p, double T) {
    const double R = bennett_refraction_arcmin(h, 101000.0, 283.0);
    return (R - 0.06 * std::sin((14.7 * R + 13.0) * kDeg)) * (p / 101000.0) * (283.0 / T);
}

double bennett_refraction_arcmin(double h, double p, double T) {
    check_range(h, 0.0, 90.0, "bennett_refraction", "apparent_altitude", "°");
    check_range(p, 0.0, 120000.0, "bennett_refraction", "pressure", " Pa");
    check_range(T, 180.0, 373.15, "bennett_refraction", "temperature", " K");
    return 1.0 / std::tan((h + 7.31 / (h + 4.4)) * kDeg) * (p / 101000.0) * (283.0 / T);
}

double saemundsson_refraction_arcmin(double h, double p, double T) {
    check_range(h, -1.0, 90.0, "saemundsson_refraction", "true_altitude", "°");
    check_range(p, 0.0, 120000.0, "saemundsson_refraction", "pressure", " Pa");
    check_range(T, 180.0, 373.15, "saemundsson_refraction", "temperature", " K");
    return 1.02 / std::tan((h + 10.3 / (h + 5.11)) * kDeg) * (p / 101000.0) * (283.0 / T);
}

}  // namespace refract::grin
