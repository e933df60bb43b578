#include <refract/experiments/optics_closed_forms.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <refract/core/optics.h>

namespace refract::experiments::closed_form {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The sphere's surface as met from outside at incidence i: Fresnel reflectances and the
// refraction angle r, all from core/optics.h (fresnel gives cos r; sin r = sin i / n is the
// same Snell law). No r on total reflection at entry (n < 1 beyond the critical angle),
// where Rs = Rp = 1.
struct Entry {
    double Rs = 1.0, Rp = 1.0;
    std::optional<double> r;
};
Entry entry(double i, double n) {
    const auto f = optics::fresnel(std::cos(i), n);
    if (!f) return {};
    return {f->Rs, f->Rp, std::atan2(std::sin(i) / n, f->cos_t)};
}

// D folded into [0, π]: arccos(cos D), computed without arccos's loss of precision near 0, π.
double fold(double D) {
    double d = std::fmod(D, 2.0 * kPi);
    if (d < 0.0) d += 2.0 * kPi;
    return d <= kPi ? d : 2.0 * kPi - d;
}

// The x in [a, b] where the monotone f reaches target (f(a), f(b) on either side), by bisection
// down to adjacent doubles.
template <class F>
double bisect(const F& f, double a, double b, double target) {
    const bool a_below = f(a) < target;
    for (int it = 0; it < 200; ++it) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        if ((f(m) < target) == a_below)
            a = m;
        else
            b = m;
    }
    return 0.5 * (a + b);
}

struct SP {
    double s = 0.0, p = 0.0;
};

// Tanh–sinh (double-exponential) quadrature of the s and p parts of f over [a, b]
// (Takahasi & Mori 1974): x = mid + half·tanh(π/2 sinh t), step h in t. Robust to the
// square-root endpoint behaviour of Fresnel at a critical angle.
template <class F>
SP tanh_sinh(const F& f, double a, double b) {
    SP sum;
    if (!(b > a)) return sum;
    constexpr double h = 1.0 / 32.0;
    const double half = 0.5 * (b - a);
    const auto add = [&sum](SP v, double w) {
        sum.s += w * v.s;
        sum.p += w * v.p;
    };
    add(f(a + half), 0.5 * kPi);
    for (int k = 1; k * h <= 4.0; ++k) {
        const double t = k * h;
        const double u = 0.5 * kPi * std::sinh(t);
        const double w = 0.5 * kPi * std::cosh(t) / (std::cosh(u) * std::cosh(u));
        if (w < 1e-300) break;
        const double d = (b - a) / (1.0 + std::exp(2.0 * u));  // distance to the nearer end
        if (a + d <= a || b - d >= b) break;
        add(f(a + d), w);
        add(f(b - d), w);
    }
    return {sum.s * half * h, sum.p * half * h};
}

// ε_p(i) d(sin² i)/di = ε_p(i) sin 2i, per polarisation.
SP class_density(int p, double i, double n) {
    const Polarised e = sphere_class_fraction(p, i, n);
    const double j = std::sin(2.0 * i);
    return {e.s * j, e.p * j};
}

}  // namespace

// ---- 1. Sphere ------------------------------------------------------------------------

double deviation(int p, double i, double n) {
    if (p < 0) return kNaN;
    if (p == 0) return kPi - 2.0 * i;  // D_0 = π − 2i
    const auto r = entry(i, n).r;
    if (!r) return kNaN;
    return 2.0 * (i - *r) + (p - 1) * (kPi - 2.0 * *r);  // D_p = 2(i − r) + (p − 1)(π − 2r)
}

double scattering_angle(int p, double i, double n) {
    const double D = deviation(p, i, n);
    return std::isfinite(D) ? fold(D) : kNaN;
}

Polarised sphere_class_fraction(int p, double i, double n) {
    if (p < 0) return {};
    const Entry e = entry(i, n);
    const auto eps = [&](double R) { return p == 0 ? R : (e.r ? (1.0 - R) * (1.0 - R) * std::pow(R, p - 1) : 0.0); };
    const double s = eps(e.Rs), pp = eps(e.Rp);
    return {s, pp, 0.5 * (s + pp)};
}

SphereBins sphere_scattering(double n, int p, const std::vector<double>& edges) {
    SphereBins out;
    const std::size_t bins = edges.size() >= 2 ? edges.size() - 1 : 0;
    out.s.assign(bins, 0.0);
    out.p.assign(bins, 0.0);
    out.natural.assign(bins, 0.0);
    if (p < 0) return out;

    // Where θ(i) may turn: 0, the critical angle (n < 1: the end of classes p >= 1, a kink of
    // class 0), the rainbow incidence, π/2. D_p is monotone between these.
    std::vector<double> breaks{0.0};
    const auto crit = optics::critical_angle(n);
    double i_end = 0.5 * kPi;
    if (crit && p >= 1) {
        i_end = *crit;  // the last incidence that still enters (rounding may put crit just past it)
        while (i_end > 0.0 && !std::isfinite(deviation(p, i_end, n))) i_end = std::nextafter(i_end, 0.0);
    } else if (crit) {
        breaks.push_back(*crit);
    }
    const double i_rb = rainbow_incidence(p, n);
    if (std::isfinite(i_rb) && i_rb > 0.0 && i_rb < i_end) breaks.push_back(i_rb);
    breaks.push_back(i_end);
    std::sort(breaks.begin(), breaks.end());

    const auto D = [&](double i) { return deviation(p, i, n); };
    const auto theta = [&](double i) { return scattering_angle(p, i, n); };
    const auto density = [&](double i) { return class_density(p, i, n); };

    for (std::size_t m = 0; m + 1 < breaks.size(); ++m) {
        const double a = breaks[m], b = breaks[m + 1];
        if (!(b > a)) continue;
        const SP total = tanh_sinh(density, a, b);
        out.total_s += total.s;
        out.total_p += total.p;
        if (bins == 0) continue;

        // Split the monotone piece of D where it crosses a multiple of π (θ folds there),
        // then where θ crosses a bin edge; each resulting segment lies in one bin.
        std::vector<double> cuts{a, b};
        const double Da = D(a), Db = D(b);
        const double Dlo = std::min(Da, Db), Dhi = std::max(Da, Db);
        for (double k = std::ceil(Dlo / kPi); k * kPi < Dhi; k += 1.0)
            if (k * kPi > Dlo) cuts.push_back(bisect(D, a, b, k * kPi));
        std::sort(cuts.begin(), cuts.end());
        std::vector<double> splits = cuts;
        for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
            const double ta = theta(cuts[c]), tb = theta(cuts[c + 1]);
            const double lo = std::min(ta, tb), hi = std::max(ta, tb);
            for (double e : edges)
                if (e > lo && e < hi) splits.push_back(bisect(theta, cuts[c], cuts[c + 1], e));
        }
        std::sort(splits.begin(), splits.end());
        for (std::size_t c = 0; c + 1 < splits.size(); ++c) {
            const double x0 = splits[c], x1 = splits[c + 1];
            if (!(x1 > x0)) continue;
            const double tm = theta(0.5 * (x0 + x1));
            const auto it = std::upper_bound(edges.begin(), edges.end(), tm);
            if (it == edges.begin() || it == edges.end()) continue;  // outside [edges.front(), edges.back())
            const std::size_t k = static_cast<std::size_t>(it - edges.begin()) - 1;
            const SP v = tanh_sinh(density, x0, x1);
            out.s[k] += v.s;
            out.p[k] += v.p;
        }
    }
    for (std::size_t k = 0; k < bins; ++k) out.natural[k] = 0.5 * (out.s[k] + out.p[k]);
    out.total_natural = 0.5 * (out.total_s + out.total_p);
    return out;
}

double rainbow_incidence(int p, double n) {
    if (p < 2 || !(n > 1.0) || !(n < p)) return kNaN;
    // cos² i = (n² − 1)/(p² − 1)
    return std::acos(std::sqrt((n * n - 1.0) / (double(p) * p - 1.0)));
}

double rainbow_deviation(int p, double n) {
    const double i = rainbow_incidence(p, n);
    return std::isfinite(i) ? scattering_angle(p, i, n) : kNaN;
}

// ---- 2. Prism ---------------------------------------------------------------------------

std::optional<double> prism_deviation(double apex, double incidence, double n) {
    // First face: sin r1 = sin i1 / n (cos r1 from core/optics.h, signs kept by atan2).
    const auto c1 = optics::cos_transmitted(std::cos(incidence), n);
    if (!c1) return std::nullopt;
    const double r1 = std::atan2(std::sin(incidence) / n, *c1);
    // Second face, from inside at r2 = A − r1: sin i2 = n sin r2, empty on total reflection.
    const double r2 = apex - r1;
    if (!(std::abs(r2) < 0.5 * kPi)) return std::nullopt;  // does not reach the second face
    const auto c2 = optics::cos_transmitted(std::cos(r2), 1.0 / n);
    if (!c2) return std::nullopt;
    const double i2 = std::atan2(n * std::sin(r2), *c2);
    return incidence + i2 - apex;  // δ = i1 + i2 − A
}

double prism_minimum_deviation(double apex, double n) {
    // Symmetric passage r1 = r2 = A/2, leaving at i with sin i = n sin(A/2): δ = 2i − A.
    const double half = 0.5 * apex;
    const auto c = optics::cos_transmitted(std::cos(half), 1.0 / n);
    if (!c) return kNaN;
    return 2.0 * std::atan2(n * std::sin(half), *c) - apex;
}

// ---- 3. Slab ----------------------------------------------------------------------------

SlabTerms slab(double theta, double n) {
    const auto f = optics::fresnel(std::cos(theta), n);
    const double Rs = f ? f->Rs : 1.0, Rp = f ? f->Rp : 1.0;
    const auto T = [](double R) { return (1.0 - R) / (1.0 + R); };       // (1 − R)/(1 + R)
    const auto Rsl = [](double R) { return 2.0 * R / (1.0 + R); };       // 2R/(1 + R)
    SlabTerms out;
    out.T = {T(Rs), T(Rp), 0.5 * (T(Rs) + T(Rp))};
    out.R = {Rsl(Rs), Rsl(Rp), 0.5 * (Rsl(Rs) + Rsl(Rp))};
    return out;
}

double slab_transmitted_class(int k, double R) {
    if (k < 0) return 0.0;
    return (1.0 - R) * (1.0 - R) * std::pow(R, 2 * k);  // (1 − R)² R^(2k)
}

double slab_reflected_class(int k, double R) {
    if (k < 0) return 0.0;
    if (k == 0) return R;
    return (1.0 - R) * (1.0 - R) * std::pow(R, 2 * k - 1);  // (1 − R)² R^(2k−1)
}

// ---- 4. Ball lens -------------------------------------------------------------------------

double ball_lens_focus_from_centre(double n, double radius) { return n * radius / (2.0 * (n - 1.0)); }

double ball_lens_back_focal_distance(double n, double radius) {
    return ball_lens_focus_from_centre(n, radius) - radius;
}

}  // namespace refract::experiments::closed_form
