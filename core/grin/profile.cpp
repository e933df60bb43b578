// Gradient-index profiles (core/grin/profile.h; sources in docs/grin.md).
#include <refract/core/grin/profile.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <refract/core/grin/air_index.h>
#include <refract/core/grin/check.h>
#include <refract/core/spectrum/dispersion.h>

namespace refract::grin {

using detail::finite;
using detail::finite_vec;
using detail::unit_in_place;

double value(const CauchyIndex& c, double lambda_um) {
    return c.B == 0.0 ? c.A : spectrum::cauchy_index(lambda_um, c.A, c.B, 0.0);
}

// ---------------------------------------------------------------------------------------
// Stratified.

IndexGradient index_and_gradient(const LinearHeight& p, const Vec3& x, double l) {
    return {value(p.n0, l) + p.slope * (p.up.dot(x) - p.h0), p.slope * p.up};
}
IndexGradient index_and_gradient(const ExponentialHeight& p, const Vec3& x, double l) {
    const double e = (value(p.n0, l) - 1.0) * std::exp(-(p.up.dot(x) - p.h0) / p.scale_height);
    return {1.0 + e, (-e / p.scale_height) * p.up};
}

// ---------------------------------------------------------------------------------------
// Spherically symmetric.

IndexGradient index_and_gradient(const Luneburg& p, const Vec3& x, double) {
    const Vec3 v = x - p.centre;
    const double u = v.squaredNorm() / (p.radius * p.radius);
    // Up to 1e-12 past the surface the inside's law still holds (n = 1 − 5e-13 there): a ray
    // started on the surface, |x − centre| = R to rounding, sees the lens's gradient.
    if (u > 1.0 + 1e-12) return {1.0, Vec3::Zero()};
    const double n = std::sqrt(2.0 - u);
    return {n, v * (-1.0 / (p.radius * p.radius * n))};
}
IndexGradient index_and_gradient(const MaxwellFishEye& p, const Vec3& x, double l) {
    const Vec3 v = x - p.centre;
    const double a2 = p.a * p.a, q = 1.0 / (1.0 + v.squaredNorm() / a2), n = value(p.n0, l) * q;
    return {n, v * (-2.0 * n * q / a2)};
}

namespace {
// The spline on interval i at r: value and derivative.
std::pair<double, double> spline_at(const TabulatedRadial& p, size_t i, double r) {
    const double h = p.r[i + 1] - p.r[i], b = (r - p.r[i]) / h, a = 1.0 - b;
    const double M0 = p.n2[i], M1 = p.n2[i + 1], y0 = p.n[i], y1 = p.n[i + 1];
    const double v = a * y0 + b * y1 + ((a * a * a - a) * M0 + (b * b * b - b) * M1) * (h * h / 6.0);
    const double d = (y1 - y0) / h + ((1.0 - 3.0 * a * a) * M0 + (3.0 * b * b - 1.0) * M1) * (h / 6.0);
    return {v, d};
}
}  // namespace

IndexGradient index_and_gradient(const TabulatedRadial& p, const Vec3& x, double) {
    const Vec3 v = x - p.centre;
    const double r = v.norm();
    if (!(r > p.r.front())) return {p.n.front(), Vec3::Zero()};
    if (!(r < p.r.back())) return {p.n.back(), Vec3::Zero()};
    const size_t i = static_cast<size_t>(std::upper_bound(p.r.begin(), p.r.end(), r) - p.r.begin()) - 1;
    const auto [n, dn] = spline_at(p, i, r);
    return {n, v * (dn / r)};
}

IndexGradient index_and_gradient(const EarthAtmosphere& p, const Vec3& x, double l) {
    const Vec3 v = x - p.centre;
    const double r = v.norm(), h = r - kEarthRadius_m;
    if (!(h > 0)) return {p.air.index(0.0, l).n, Vec3::Zero()};
    const Atmosphere::Index a = p.air.index(h, l);
    return {a.n, v * (a.dn_dh / r)};
}

// ---------------------------------------------------------------------------------------
// A sampled field (core/grin/grid.h): the spline in grid coordinates u = (x − origin)/spacing.

IndexGradient index_and_gradient(const SampledGrid& p, const Vec3& x, double l) {
    const SplineValue s = tricubic_bspline(*p.coefficients, p.dims, (x - p.origin).cwiseQuotient(p.spacing));
    const Vec3 grad = s.gradient.cwiseQuotient(p.spacing);
    if (p.quantity == GridQuantity::index) return {s.value, grad};
    // Gladstone–Dale on the density ratio q (relative: the excess q − 1 over the reference
    // air's); the law is linear in q, so the gradient is (n_ref − 1)∇q.
    const double r = reference_refractivity(p, l);
    return {1.0 + gladstone_dale_refractivity(r, p.relative ? s.value - 1.0 : s.value), r * grad};
}

// ---------------------------------------------------------------------------------------
// Rods: r the distance from the axis, v the vector from the axis to x.

namespace {
Vec3 from_axis(const Vec3& x, const Vec3& point, const Vec3& axis) {
    const Vec3 w = x - point;
    return w - w.dot(axis) * axis;
}
// tanh(s)/s, smooth through s = 0.
double tanh_over(double s) {
    if (std::abs(s) < 1e-4) return 1.0 - s * s / 3.0;
    return std::tanh(s) / s;
}
}  // namespace

IndexGradient index_and_gradient(const SechRod& p, const Vec3& x, double l) {
    const Vec3 v = from_axis(x, p.point, p.axis);
    const double s = p.alpha * v.norm(), n = value(p.n0, l) / std::cosh(s);
    // ∇n = −n₀ α sech(αr) tanh(αr) r̂ = −n α² (tanh(s)/s) v
    return {n, v * (-n * p.alpha * p.alpha * tanh_over(s))};
}
IndexGradient index_and_gradient(const ParabolicRod& p, const Vec3& x, double l) {
    const Vec3 v = from_axis(x, p.point, p.axis);
    const double n0 = value(p.n0, l);
    return {n0 * (1.0 - 0.5 * p.A * v.squaredNorm()), v * (-n0 * p.A)};
}

// ---------------------------------------------------------------------------------------
// index and gradient of each kind from index_and_gradient; the variant over the kinds.

#define REFRACT_GRIN_FROM_BOTH(Kind)                                                                         \
    double index(const Kind& p, const Vec3& x, double l) { return index_and_gradient(p, x, l).n; }          \
    Vec3 gradient(const Kind& p, const Vec3& x, double l) { return index_and_gradient(p, x, l).grad; }
REFRACT_GRIN_FROM_BOTH(LinearHeight)
REFRACT_GRIN_FROM_BOTH(ExponentialHeight)
REFRACT_GRIN_FROM_BOTH(Luneburg)
REFRACT_GRIN_FROM_BOTH(MaxwellFishEye)
REFRACT_GRIN_FROM_BOTH(SechRod)
REFRACT_GRIN_FROM_BOTH(ParabolicRod)
REFRACT_GRIN_FROM_BOTH(TabulatedRadial)
REFRACT_GRIN_FROM_BOTH(EarthAtmosphere)
REFRACT_GRIN_FROM_BOTH(SampledGrid)
#undef REFRACT_GRIN_FROM_BOTH

bool dispersive(const LinearHeight& p) { return p.n0.B != 0; }
bool dispersive(const ExponentialHeight& p) { return p.n0.B != 0; }
bool dispersive(const Luneburg&) { return false; }
bool dispersive(const MaxwellFishEye& p) { return p.n0.B != 0; }
bool dispersive(const SechRod& p) { return p.n0.B != 0; }
bool dispersive(const ParabolicRod& p) { return p.n0.B != 0; }
bool dispersive(const TabulatedRadial&) { return false; }
bool dispersive(const EarthAtmosphere&) { return true; }
bool dispersive(const SampledGrid& p) { return p.quantity == GridQuantity::temperature; }
bool dispersive(const Profile& p) {
    return std::visit([](const auto& k) { return dispersive(k); }, p);
}

double index(const Profile& p, const Vec3& x, double l) {
    return std::visit([&](const auto& k) { return index(k, x, l); }, p);
}
Vec3 gradient(const Profile& p, const Vec3& x, double l) {
    return std::visit([&](const auto& k) { return gradient(k, x, l); }, p);
}
IndexGradient index_and_gradient(const Profile& p, const Vec3& x, double l) {
    return std::visit([&](const auto& k) { return index_and_gradient(k, x, l); }, p);
}

// ---------------------------------------------------------------------------------------
// The tabulated profile's spline.

namespace {
void check_table(const TabulatedRadial& t, const std::string& path) {
    finite_vec(t.centre, path + "/centre");
    if (t.r.size() != t.n.size())
        throw InputError(path + "/n: " + std::to_string(t.n.size()) + " values for " + std::to_string(t.r.size()) +
                         " radii");
    if (t.r.size() < 3) throw InputError(path + "/r: " + std::to_string(t.r.size()) + " radii, at least 3 are needed");
    for (size_t i = 0; i < t.r.size(); ++i) {
        const std::string k = "/" + std::to_string(i);
        finite(t.r[i], path + "/r" + k);
        finite(t.n[i], path + "/n" + k);
        if (!(t.r[i] >= 0)) throw InputError(path + "/r" + k + ": " + format_value(t.r[i]) + " must be >= 0");
        if (!(t.n[i] > 0)) throw InputError(path + "/n" + k + ": " + format_value(t.n[i]) + " must be > 0");
        if (i > 0 && !(t.r[i] > t.r[i - 1]))
            throw InputError(path + "/r" + k + ": " + format_value(t.r[i]) + " must be > the radius before it (" +
                             format_value(t.r[i - 1]) + ")");
    }
}
// The smallest value of the spline on interval i (at its ends or where n′ = 0): with
// b = (r − r_i)/h, dn/db = q0 + q1 b + q2 b².
double interval_min(const TabulatedRadial& t, size_t i) {
    const double h = t.r[i + 1] - t.r[i], M0 = t.n2[i], M1 = t.n2[i + 1];
    const double q2 = 0.5 * h * h * (M1 - M0), q1 = h * h * M0, q0 = t.n[i + 1] - t.n[i] - h * h * (2 * M0 + M1) / 6;
    double m = std::min(t.n[i], t.n[i + 1]);
    auto at = [&](double b) {
        if (b > 0 && b < 1) m = std::min(m, spline_at(t, i, t.r[i] + b * h).first);
    };
    if (q2 == 0) {
        if (q1 != 0) at(-q0 / q1);
    } else {
        const double disc = q1 * q1 - 4 * q2 * q0;
        if (disc >= 0) {
            const double s = std::sqrt(disc);
            at((-q1 + s) / (2 * q2));
            at((-q1 - s) / (2 * q2));
        }
    }
    return m;
}
void check_spline_positive(const TabulatedRadial& t, const std::string& path) {
    for (size_t i = 0; i + 1 < t.r.size(); ++i) {
        const double m = interval_min(t, i);
        if (!(m > 0))
            throw InputError(path + "/n: the spline between radii " + format_value(t.r[i]) + " and " +
                             format_value(t.r[i + 1]) + " falls to " + format_value(m) + "; it must stay > 0");
    }
}
}  // namespace

TabulatedRadial tabulated_radial(const Vec3& centre, std::vector<double> r, std::vector<double> n,
                                 const std::string& path) {
    TabulatedRadial t{centre, std::move(r), std::move(n), {}};
    check_table(t, path);
    // The natural spline: n″ = 0 at both ends, the tridiagonal system solved by the
    // Thomas algorithm (diagonally dominant, so stable without pivoting).
    const size_t N = t.r.size();
    t.n2.assign(N, 0.0);
    std::vector<double> c(N, 0.0), d(N, 0.0);
    for (size_t i = 1; i + 1 < N; ++i) {
        const double h0 = t.r[i] - t.r[i - 1], h1 = t.r[i + 1] - t.r[i];
        const double rhs = 6.0 * ((t.n[i + 1] - t.n[i]) / h1 - (t.n[i] - t.n[i - 1]) / h0);
        const double diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
        c[i] = h1 / diag;
        d[i] = (rhs - h0 * d[i - 1]) / diag;
    }
    for (size_t i = N - 2; i >= 1; --i) t.n2[i] = d[i] - c[i] * t.n2[i + 1];
    check_spline_positive(t, path);
    return t;
}

// ---------------------------------------------------------------------------------------
// Validation.

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();

struct Check {
    const Region& where;
    double l0, l1;  // µm
    const std::string& path;

    // The base index finite and > 0 over [l0, l1] (a Cauchy law is monotone in λ, so its
    // ends suffice); returns its smallest value.
    double base(const CauchyIndex& c, const std::string& field) const {
        finite(c.A, path + field + "/A");
        finite(c.B, path + field + "/B");
        const double a = value(c, l0), b = value(c, l1), m = std::min(a, b);
        if (!(m > 0) || !std::isfinite(m))
            throw InputError(path + field + ": the index " + format_value(m) + " at " +
                             format_value((a < b ? l0 : l1) * 1000) + " nm must be finite and > 0");
        return m;
    }
    void positive(double v, const std::string& field) const {
        finite(v, path + field);
        if (!(v > 0)) throw InputError(path + field + ": " + format_value(v) + " must be > 0");
    }
    void refuse_low(double n, double at, const std::string& field, const char* what) const {
        if (!(n > 0) || !std::isfinite(n))
            throw InputError(path + field + ": the index falls to " + format_value(n) + " at " + what + " " +
                             format_value(at) + " inside the region; it must stay finite and > 0");
    }

    void operator()(LinearHeight& p) const {
        unit_in_place(p.up, path + "/up");
        finite(p.slope, path + "/slope");
        finite(p.h0, path + "/h0");
        base(p.n0, "/n0");
        if (p.slope == 0) return;
        const auto [lo, hi] = extent(where, p.up);
        const double h = p.slope > 0 ? lo : hi;  // where the index is smallest
        if (!std::isfinite(h))
            throw InputError(path + "/slope: " + format_value(p.slope) +
                             " makes the index fall to 0 in the unbounded region; it must stay > 0");
        refuse_low(std::min(value(p.n0, l0), value(p.n0, l1)) + p.slope * (h - p.h0), h, "/slope", "height");
    }
    void operator()(ExponentialHeight& p) const {
        unit_in_place(p.up, path + "/up");
        positive(p.scale_height, "/scale_height");
        finite(p.h0, path + "/h0");
        base(p.n0, "/n0");
        const auto [lo, hi] = extent(where, p.up);
        for (double l : {l0, l1}) {
            const double e = value(p.n0, l) - 1.0;
            if (e >= 0) continue;  // n ≥ 1
            const double n = std::isfinite(lo) ? 1.0 + e * std::exp(-(lo - p.h0) / p.scale_height) : -inf;
            refuse_low(n, lo, "/n0", "height");
        }
        (void)hi;
    }
    void operator()(Luneburg& p) const {
        finite_vec(p.centre, path + "/centre");
        positive(p.radius, "/radius");
    }
    void operator()(MaxwellFishEye& p) const {
        finite_vec(p.centre, path + "/centre");
        positive(p.a, "/a");
        base(p.n0, "/n0");
    }
    void operator()(SechRod& p) const {
        finite_vec(p.point, path + "/point");
        unit_in_place(p.axis, path + "/axis");
        positive(p.alpha, "/alpha");
        base(p.n0, "/n0");
    }
    void operator()(ParabolicRod& p) const {
        finite_vec(p.point, path + "/point");
        unit_in_place(p.axis, path + "/axis");
        positive(p.A, "/A");
        const double n0 = base(p.n0, "/n0");
        const double r = max_distance_from_line(where, p.point, p.axis);
        if (!std::isfinite(r))
            throw InputError(path + "/A: " + format_value(p.A) +
                             " makes the index fall to 0 in the unbounded region; it must stay > 0");
        refuse_low(n0 * (1.0 - 0.5 * p.A * r * r), r, "/A", "distance from the axis");
    }
    void operator()(TabulatedRadial& p) const {
        check_table(p, path);
        if (p.n2.size() != p.r.size()) p = tabulated_radial(p.centre, p.r, p.n, path);
        check_spline_positive(p, path);
    }
    void operator()(EarthAtmosphere& p) const {
        finite_vec(p.centre, path + "/centre");  // the air's state is checked when it is built
    }
    void operator()(SampledGrid& p) const {
        // The grid's box must hold the region (the field outside it would be made up).
        const Vec3 lo = grid_lo(p), hi = grid_hi(p);
        const double margin = 1e-9 * (hi - lo).norm();
        for (int a = 0; a < 3; ++a) {
            const auto [rlo, rhi] = extent(where, Vec3::Unit(a));
            if (rlo < lo[a] - margin || rhi > hi[a] + margin) {
                std::string box, region;
                for (int b = 0; b < 3; ++b) {
                    const auto [u0, u1] = extent(where, Vec3::Unit(b));
                    box += (b ? " × [" : "[") + format_value(lo[b]) + ", " + format_value(hi[b]) + "]";
                    region += (b ? " × [" : "[") + format_value(u0) + ", " + format_value(u1) + "]";
                }
                throw InputError(path + "/" + p.field + ": the grid's box " + box +
                                 " does not cover the medium's region " + region);
            }
        }
        if (p.quantity == GridQuantity::index) {
            refuse_low(p.coefficient_min, p.coefficient_min, "/" + p.field, "a spline coefficient of");
            return;
        }
        for (double l : {l0, l1}) {  // n − 1 = (n_ref − 1)·q ≥ (n_ref − 1)·min q
            const double n = 1.0 + reference_refractivity(p, l) * (p.coefficient_min - (p.relative ? 1.0 : 0.0));
            refuse_low(n, l * 1000, "/" + p.field, "the wavelength (nm)");
        }
    }
};
}  // namespace

void validate(Profile& p, const Region& where, double lambda_min_um, double lambda_max_um, const std::string& path) {
    std::visit(Check{where, lambda_min_um, lambda_max_um, path}, p);
}

}  // namespace refract::grin
