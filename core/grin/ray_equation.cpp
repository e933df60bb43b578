// The ray equation by Dormand–Prince 5(4) (core/grin/ray_equation.h; docs/grin.md).
//
// An own integrator rather than Boost.Odeint's runge_kutta_dopri5: the walker needs the
// step's dense output to find the boundary crossing inside a step, a step budget, the
// evaluation count and, later, one ray per SIMD lane; each of those is a wrapper around
// Odeint's steppers, while the whole method is the ~150 lines below (docs/grin.md).
#include <refract/core/grin/ray_equation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <refract/core/grin/rytov.h>

namespace refract::grin {

namespace {

// y = (r, T, optical path, length); y′ = (T, n∇n, n², n) with ′ = d/dt, dt = ds/n. With a
// polarisation frame (N = 11) also e, y′ = … Ω × e (core/grin/rytov.h): the same stages and
// the same error test. N = 8 is the integrator without it, the same code as before it.
constexpr int kRay = 8, kRayAndFrame = 11;
template <int N>
using State = Eigen::Matrix<double, N, 1>;

template <int N>
struct Rhs {
    const Profile& profile;
    double lambda_um;
    long evaluations = 0;
    State<N> operator()(const State<N>& y) {
        ++evaluations;
        const IndexGradient g = index_and_gradient(profile, Vec3(y.template head<3>()), lambda_um);
        State<N> f;
        f.template head<3>() = y.template segment<3>(3);
        f.template segment<3>(3) = g.n * g.grad;
        f[6] = g.n * g.n;
        f[7] = g.n;
        if constexpr (N == kRayAndFrame)
            f.template tail<3>() = rytov_rate(y.template segment<3>(3), f.template segment<3>(3), y.template tail<3>());
        return f;
    }
};

// Dormand & Prince (1980), the tableau of RK5(4)7M; e = b − b̂ (the error estimate's weights).
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84;
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200, e6 = 22.0 / 525,
                 e7 = -1.0 / 40;
// The dense output of order 4 (Hairer's DOPRI5, CONTD5).
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                 d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                 d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;

// One step of size h from y0 with k1 = f(y0): the new state, its derivative k7 (FSAL: the
// next step's k1), the error estimate and the dense output's coefficients.
template <int N>
struct Step {
    State<N> y1, k7, err;
    std::array<State<N>, 5> cont;  // y(θ) = c0 + θ(c1 + (1−θ)(c2 + θ(c3 + (1−θ) c4)))

    State<N> at(double th) const {
        const double th1 = 1.0 - th;
        return cont[0] + th * (cont[1] + th1 * (cont[2] + th * (cont[3] + th1 * cont[4])));
    }
};

template <int N>
Step<N> dp_step(Rhs<N>& f, const State<N>& y0, const State<N>& k1, double h) {
    using State = State<N>;
    const State k2 = f(y0 + h * (a21 * k1));
    const State k3 = f(y0 + h * (a31 * k1 + a32 * k2));
    const State k4 = f(y0 + h * (a41 * k1 + a42 * k2 + a43 * k3));
    const State k5 = f(y0 + h * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4));
    const State k6 = f(y0 + h * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5));
    Step<N> s;
    s.y1 = y0 + h * (a71 * k1 + a73 * k3 + a74 * k4 + a75 * k5 + a76 * k6);
    s.k7 = f(s.y1);
    s.err = h * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * s.k7);
    const State dy = s.y1 - y0, bspl = h * k1 - dy;
    s.cont[0] = y0;
    s.cont[1] = dy;
    s.cont[2] = bspl;
    s.cont[3] = dy - h * s.k7 - bspl;
    s.cont[4] = h * (d1 * k1 + d3 * k3 + d4 * k4 + d5 * k5 + d6 * k6 + d7 * s.k7);
    (void)c2, (void)c3, (void)c4, (void)c5;  // the nodes, implied by the rows of a
    return s;
}

template <int N>
double error_norm(const State<N>& err, const State<N>& y0, const State<N>& y1, const Settings& s) {
    double m = 0.0;
    for (int i = 0; i < N; ++i) {
        const double sc = s.abs_tol + s.rel_tol * std::max(std::abs(y0[i]), std::abs(y1[i]));
        const double e = std::abs(err[i]) / sc;
        if (!(e <= m)) m = e;  // NaN too
    }
    return std::isfinite(m) ? m : std::numeric_limits<double>::infinity();
}

// The first step (Hairer, Nørsett & Wanner, §II.4, "starting step size").
template <int N>
double initial_step(Rhs<N>& f, const State<N>& y0, const State<N>& k1, const Settings& s) {
    using State = State<N>;
    auto norm = [&](const State& v) {
        double m = 0.0;
        for (int i = 0; i < N; ++i) m = std::max(m, std::abs(v[i]) / (s.abs_tol + s.rel_tol * std::abs(y0[i])));
        return m;
    };
    const double dn0 = norm(y0), dn1 = norm(k1);
    const double h0 = (dn0 < 1e-5 || dn1 < 1e-5) ? 1e-6 : 0.01 * dn0 / dn1;
    const State k2 = f(y0 + h0 * k1);
    const double dn2 = norm(k2 - k1) / h0, dm = std::max(dn1, dn2);
    const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 0.2);
    return std::min(100.0 * h0, h1);
}

// Brent's method (Brent 1973, "zero"): a root of g in [a, b] with g(a) ≤ 0 < g(b), to tol.
template <class G>
double brent(G&& g, double a, double b, double fa, double fb, double tol) {
    double c = a, fc = fa, d = b - a, e = d;
    for (int it = 0; it < 200; ++it) {
        if ((fb > 0) == (fc > 0)) {
            c = a, fc = fa, d = b - a, e = d;
        }
        if (std::abs(fc) < std::abs(fb)) {
            a = b, b = c, c = a;
            fa = fb, fb = fc, fc = fa;
        }
        const double t = 2 * std::numeric_limits<double>::epsilon() * std::abs(b) + 0.5 * tol, m = 0.5 * (c - b);
        if (std::abs(m) <= t || fb == 0) return b;
        if (std::abs(e) >= t && std::abs(fa) > std::abs(fb)) {
            double p, q, s = fb / fa;
            if (a == c) {
                p = 2 * m * s, q = 1 - s;
            } else {
                const double qq = fa / fc, r = fb / fc;
                p = s * (2 * m * qq * (qq - r) - (b - a) * (r - 1));
                q = (qq - 1) * (r - 1) * (s - 1);
            }
            if (p > 0) q = -q;
            else p = -p;
            if (2 * p < std::min(3 * m * q - std::abs(t * q), std::abs(e * q))) {
                e = d, d = p / q;
            } else {
                d = m, e = m;
            }
        } else {
            d = m, e = m;
        }
        a = b, fa = fb;
        b += std::abs(d) > t ? d : (m > 0 ? t : -t);
        fb = g(b);
    }
    return b;
}

// The transported frame vector of y, unit and ⟂ its direction (zero without one).
template <int N>
Vec3 frame_of(const State<N>& y, const Vec3& dir) {
    if constexpr (N == kRayAndFrame) return transverse_unit(y.template tail<3>(), dir);
    else return Vec3::Zero();
}

template <int N>
PathSample sample(const State<N>& y) {
    const Vec3 dir = y.template segment<3>(3).normalized();
    return {Vec3(y.template head<3>()), dir, frame_of<N>(y, dir)};
}

template <int N>
void finish(Result& r, const State<N>& y, const State<N>& f, Status status, long evaluations) {
    r.status = status;
    r.exit_point = y.template head<3>();
    r.exit_dir = y.template segment<3>(3).normalized();
    r.exit_index = f[7];
    r.optical_path = y[6];
    r.length = y[7];
    r.evaluations = evaluations;
    r.exit_frame = frame_of<N>(y, r.exit_dir);
}

// The first crossing of a step's dense output (θ from 0, the step's start, to 1) with the
// surfaces inside (Settings::obstacles): the polyline of kObstacleChords chords in order,
// then, in the first chord that meets one, bisection on θ, each time the chord from the
// last point known before the crossing to the middle. The crossing reported is the last
// chord that met a surface (θ and the point there, on the surface): near the surface its
// own test can no longer tell a start just before it from one just past it (a sphere of
// the Earth's size resolves heights of about 1e-9 m), so a chord said to miss may have
// crossed, and the last hit, not the bisection's end, is what is known.
struct Crossing {
    double theta;
    Vec3 point;
    int id;
};
template <int N>
std::optional<Crossing> obstacle_crossing(const Obstacles& obs, const Step<N>& st) {
    const auto pos = [&](double th) { return Vec3(st.at(th).template head<3>()); };
    double lo = 0.0;
    Vec3 a = pos(0.0);
    for (int k = 1; k <= kObstacleChords; ++k) {
        const double end = static_cast<double>(k) / kObstacleChords;
        const Vec3 b = k == kObstacleChords ? Vec3(st.y1.template head<3>()) : pos(end);
        const std::optional<ObstacleHit> h = obs.first(a, b);
        if (!h) {
            lo = end;
            a = b;
            continue;
        }
        Crossing best{lo + h->fraction * (end - lo), a + h->fraction * (b - a), h->id};
        double hi = end;
        for (int it = 0; it < 40; ++it) {
            const double mid = 0.5 * (lo + hi);
            const Vec3 m = pos(mid);
            if (const auto hm = obs.first(a, m)) {
                best = Crossing{lo + hm->fraction * (mid - lo), a + hm->fraction * (m - a), hm->id};
                hi = mid;
            } else {
                lo = mid;
                a = m;
            }
        }
        return best;
    }
    return std::nullopt;
}

// The ray ended on a surface inside: the state at the crossing from the step's dense
// output (its direction, lengths and frame), the point the surface's own test gave.
template <int N>
Result met_obstacle(Result& res, Rhs<N>& f, const Step<N>& st, const Crossing& c, const Settings& s) {
    const State<N> yc = st.at(c.theta);
    const State<N> fc = f(yc);
    ++res.steps;
    finish<N>(res, yc, fc, Status::met_obstacle, f.evaluations);
    res.exit_point = c.point;
    res.obstacle = c.id;
    if (s.record_path) res.path.push_back({c.point, res.exit_dir, res.exit_frame});
    return res;
}

template <int N>
Result advance_with(const Profile& profile, const Region& region, const Vec3& x0, const Vec3& dir0, double lambda_um,
                    const Settings& s) {
    using State = State<N>;
    using Step = Step<N>;
    Rhs<N> f{profile, lambda_um};
    Result res;
    State y;
    if constexpr (N == kRayAndFrame) {
        const Vec3 d = dir0.normalized(), e0 = transverse_unit(s.frame, d);
        if (e0.isZero())
            throw std::invalid_argument(
                "grin::advance: Settings::frame must be finite and not parallel to the direction");
        y << x0, index(profile, x0, lambda_um) * d, 0.0, 0.0, e0;
    } else {
        y << x0, index(profile, x0, lambda_um) * dir0.normalized(), 0.0, 0.0;
    }
    State k1 = f(y);
    const bool fixed = s.fixed_step > 0;
    double h = fixed ? s.fixed_step : initial_step<N>(f, y, k1, s);
    // On the boundary: within 1e-14 of the region's size (or of the coordinates, past it).
    const double scale = length_scale(region);
    auto boundary_tol = [scale](const State& ys) {
        return 1e-14 * (scale + ys.template head<3>().cwiseAbs().maxCoeff());
    };
    if (s.record_path) res.path.push_back(sample<N>(y));
    bool just_rejected = false;
    double err_old = 1e-4;
    for (int tries = 0;; ++tries) {
        if (tries >= s.max_steps) {
            finish<N>(res, y, k1, Status::budget_exhausted, f.evaluations);
            return res;
        }
        const Step st = dp_step<N>(f, y, k1, h);
        const double g1 = signed_distance(region, Vec3(st.y1.template head<3>()));
        if (g1 > 0 && std::isfinite(g1)) {
            // The trial step leaves the region: the crossing is the root of the signed
            // distance along its dense output (Brent, to 1e-12 of the step), then Newton on
            // the true step of size τ (d(distance)/dτ = normal·T) until it ends on the
            // boundary to 1e-14 of the region's size. That step, whose stages stay inside
            // (the profile need not be smooth across the boundary), is the one the error
            // test accepts or rejects.
            auto g = [&](double th) { return signed_distance(region, Vec3(st.at(th).template head<3>())); };
            // A start on the boundary (|distance| within rounding) counts as just inside.
            double tau = h * brent(g, 0.0, 1.0, std::min(g(0.0), -boundary_tol(y)), g1, 1e-12);
            Step end = dp_step<N>(f, y, k1, tau);
            bool on_boundary = false;
            for (int it = 0; it < 8; ++it) {
                const Vec3 xe = end.y1.template head<3>();
                const double ge = signed_distance(region, xe);
                if ((on_boundary = std::abs(ge) <= boundary_tol(end.y1))) break;
                const double slope = outward_normal(region, xe).dot(end.y1.template segment<3>(3));
                if (!(slope > 0)) break;
                tau = std::clamp(tau - ge / slope, 0.0, 2.0 * h);
                end = dp_step<N>(f, y, k1, tau);
            }
            const double err = fixed ? 0.0 : error_norm<N>(end.err, y, end.y1, s);
            if (fixed || (on_boundary && err <= 1.0)) {
                if (s.obstacles)
                    if (const auto c = obstacle_crossing<N>(*s.obstacles, end))
                        return met_obstacle<N>(res, f, end, *c, s);
                ++res.steps;
                if (s.record_path) res.path.push_back(sample<N>(end.y1));
                finish<N>(res, end.y1, end.k7, Status::left_region, f.evaluations);
                return res;
            }
            ++res.rejected;
            h = on_boundary ? tau * std::max(0.2, std::isfinite(err) ? 0.9 * std::pow(err, -0.2) : 0.2)
                            : 0.5 * (tau > 0 ? std::min(tau, h) : h);
            just_rejected = true;
            continue;
        }
        double err = 0.0;
        if (!fixed) {
            err = error_norm<N>(st.err, y, st.y1, s);
            if (!(err <= 1.0)) {
                ++res.rejected;
                h *= std::max(0.2, std::isfinite(err) ? 0.9 * std::pow(err, -0.2) : 0.2);
                just_rejected = true;
                continue;
            }
        }
        if (s.obstacles)
            if (const auto c = obstacle_crossing<N>(*s.obstacles, st)) return met_obstacle<N>(res, f, st, *c, s);
        ++res.steps;
        y = st.y1;
        k1 = st.k7;
        if (s.record_path) res.path.push_back(sample<N>(y));
        if (!fixed) {
            // Gustafsson's PI control as in Hairer's DOPRI5 (β = 0.04): the new step from
            // this error and the last accepted one, growth at most 10×, none after a rejection.
            const double e = std::max(err, 1e-10);
            const double grow = 0.9 * std::pow(e, -0.2 + 0.75 * 0.04) * std::pow(err_old, 0.04);
            h *= std::clamp(grow, 0.2, just_rejected ? 1.0 : 10.0);
            err_old = std::max(err, 1e-4);
        }
        just_rejected = false;
    }
}

}  // namespace

Result advance(const Profile& profile, const Region& region, const Vec3& x0, const Vec3& dir0, double lambda_um,
               const Settings& s) {
    return s.frame.isZero() ? advance_with<kRay>(profile, region, x0, dir0, lambda_um, s)
                            : advance_with<kRayAndFrame>(profile, region, x0, dir0, lambda_um, s);
}

}  // namespace refract::grin
