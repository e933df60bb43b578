// A sampled 3D gradient-index field (core/grin/grid.h; docs/grin.md, "Sampled fields").
#include <refract/core/grin/grid.h>

#include <algorithm>
#include <cmath>

#include <refract/core/grin/air_index.h>
#include <refract/core/grin/check.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>

namespace refract::grin {

CubicWeights cubic_bspline_weights(double t) {
    const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    return {{s * s * s / 6.0, (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0, (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0, t3 / 6.0},
            {-0.5 * s * s, 0.5 * (3.0 * t2 - 4.0 * t), 0.5 * (-3.0 * t2 + 2.0 * t + 1.0), 0.5 * t2}};
}

namespace {

// One line of n samples f (stride `stride` in `a`) replaced by its spline coefficients:
// c_0 = f_0, c_{n−1} = f_{n−1}, c_{i−1} + 4c_i + c_{i+1} = 6f_i inside (Thomas algorithm;
// the system is diagonally dominant, so stable without pivoting).
void prefilter_line(double* a, int n, long stride, std::vector<double>& cp, std::vector<double>& dp) {
    if (n < 3) return;  // c = f
    const int m = n - 2;  // unknowns c_1 … c_{n−2}
    cp.assign(static_cast<size_t>(m), 0.0);
    dp.assign(static_cast<size_t>(m), 0.0);
    auto f = [&](int i) -> double& { return a[i * stride]; };
    for (int r = 0; r < m; ++r) {
        double rhs = 6.0 * f(r + 1);
        if (r == 0) rhs -= f(0);
        if (r == m - 1) rhs -= f(n - 1);
        const double diag = 4.0 - (r > 0 ? cp[r - 1] : 0.0);
        cp[r] = 1.0 / diag;
        dp[r] = (rhs - (r > 0 ? dp[r - 1] : 0.0)) / diag;
    }
    for (int r = m - 1; r >= 0; --r) f(r + 1) = dp[r] - (r + 1 < m ? cp[r] * f(r + 2) : 0.0);
}

}  // namespace

std::vector<double> bspline_coefficients(const std::vector<double>& values, const std::array<int, 3>& d) {
    const long nx = d[0], ny = d[1], nz = d[2];
    std::vector<double> c = values;
    std::vector<double> cp, dp;
    for (long k = 0; k < nz; ++k)
        for (long j = 0; j < ny; ++j) prefilter_line(&c[static_cast<size_t>(nx * (j + ny * k))], d[0], 1, cp, dp);
    for (long k = 0; k < nz; ++k)
        for (long i = 0; i < nx; ++i) prefilter_line(&c[static_cast<size_t>(i + nx * ny * k)], d[1], nx, cp, dp);
    for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i) prefilter_line(&c[static_cast<size_t>(i + nx * j)], d[2], nx * ny, cp, dp);
    // Padded by one on each side, the ghosts extrapolated linearly axis by axis
    // (c_{−1} = 2c_0 − c_1, the natural end condition).
    const long px = nx + 2, py = ny + 2, pz = nz + 2;
    std::vector<double> p(static_cast<size_t>(px * py * pz), 0.0);
    auto at = [&](long i, long j, long k) -> double& { return p[static_cast<size_t>(i + px * (j + py * k))]; };
    for (long k = 0; k < nz; ++k)
        for (long j = 0; j < ny; ++j)
            for (long i = 0; i < nx; ++i) at(i + 1, j + 1, k + 1) = c[static_cast<size_t>(i + nx * (j + ny * k))];
    for (long k = 1; k <= nz; ++k)
        for (long j = 1; j <= ny; ++j) {
            at(0, j, k) = 2 * at(1, j, k) - at(2, j, k);
            at(px - 1, j, k) = 2 * at(px - 2, j, k) - at(px - 3, j, k);
        }
    for (long k = 1; k <= nz; ++k)
        for (long i = 0; i < px; ++i) {
            at(i, 0, k) = 2 * at(i, 1, k) - at(i, 2, k);
            at(i, py - 1, k) = 2 * at(i, py - 2, k) - at(i, py - 3, k);
        }
    for (long j = 0; j < py; ++j)
        for (long i = 0; i < px; ++i) {
            at(i, j, 0) = 2 * at(i, j, 1) - at(i, j, 2);
            at(i, j, pz - 1) = 2 * at(i, j, pz - 2) - at(i, j, pz - 3);
        }
    return p;
}

SplineValue tricubic_bspline(const std::vector<double>& c, const std::array<int, 3>& d, const Vec3& u) {
    int cell[3];
    CubicWeights w[3];
    for (int a = 0; a < 3; ++a) {
        const double top = d[a] - 1;
        const double x = std::clamp(u[a], 0.0, top);
        const int i = std::min(static_cast<int>(x), d[a] - 2);
        cell[a] = i;  // coefficients i − 1 … i + 2 are padded indices i … i + 3
        w[a] = cubic_bspline_weights(x - i);
    }
    const long px = d[0] + 2, py = d[1] + 2;
    double v = 0, gx = 0, gy = 0, gz = 0;
    for (int k = 0; k < 4; ++k) {
        double v_k = 0, gx_k = 0, gy_k = 0;
        for (int j = 0; j < 4; ++j) {
            const double* row = &c[static_cast<size_t>(cell[0] + px * ((cell[1] + j) + py * (cell[2] + k)))];
            double s = 0, sd = 0;
            for (int i = 0; i < 4; ++i) {
                s += w[0].w[i] * row[i];
                sd += w[0].d[i] * row[i];
            }
            v_k += w[1].w[j] * s;
            gx_k += w[1].w[j] * sd;
            gy_k += w[1].d[j] * s;
        }
        v += w[2].w[k] * v_k;
        gx += w[2].w[k] * gx_k;
        gy += w[2].w[k] * gy_k;
        gz += w[2].d[k] * v_k;
    }
    return {v, Vec3(gx, gy, gz)};
}

void check_grid_size(long long nx, long long ny, long long nz, const std::string& where) {
    const double count = static_cast<double>(nx) * static_cast<double>(ny) * static_cast<double>(nz);
    if (!(count <= static_cast<double>(kMaxGridSamples)))
        throw InputError(where + ": the grid's active voxels span " + std::to_string(nx) + "×" + std::to_string(ny) +
                         "×" + std::to_string(nz) + " samples, more than " + std::to_string(kMaxGridSamples));
}

SampledGrid sampled_grid(GridSamples s, GridQuantity quantity, double T_ref, double pressure, const std::string& field,
                         const std::string& where) {
    const std::string base = where + "/" + field;
    for (int a = 0; a < 3; ++a)
        if (s.dims[a] < 2)
            throw InputError(base + ": " + std::to_string(s.dims[a]) + " samples along " + "xyz"[a] +
                             ", at least 2 are needed");
    const size_t count = static_cast<size_t>(s.dims[0]) * static_cast<size_t>(s.dims[1]) * static_cast<size_t>(s.dims[2]);
    if (s.values.size() != count)
        throw InputError(base + ": " + std::to_string(s.values.size()) + " samples for a grid of " +
                         std::to_string(s.dims[0]) + "×" + std::to_string(s.dims[1]) + "×" + std::to_string(s.dims[2]));
    detail::finite_vec(s.origin, where + "/origin");
    detail::finite_vec(s.spacing, where + "/spacing");
    if (!(s.spacing.minCoeff() > 0)) throw InputError(where + "/spacing: every spacing must be > 0");
    if (quantity == GridQuantity::temperature) {
        detail::finite(T_ref, where + "/reference_temperature");
        detail::finite(pressure, where + "/pressure");
        if (!(T_ref > 0)) throw InputError(where + "/reference_temperature: " + format_value(T_ref) + " K must be > 0");
        if (!(pressure > 0)) throw InputError(where + "/pressure: " + format_value(pressure) + " Pa must be > 0");
    }
    const char* what = quantity == GridQuantity::index ? "the index" : "the temperature";
    for (int k = 0; k < s.dims[2]; ++k)
        for (int j = 0; j < s.dims[1]; ++j)
            for (int i = 0; i < s.dims[0]; ++i) {
                const double v = s.values[static_cast<size_t>(i + s.dims[0] * (j + s.dims[1] * k))];
                if (std::isfinite(v) && v > 0) continue;
                const std::string ijk = std::to_string(i) + "/" + std::to_string(j) + "/" + std::to_string(k);
                throw InputError(field == "values"
                                         ? base + "/" + ijk + ": " + what + " " + format_value(v) + " must be finite and > 0"
                                         : base + ": voxel (" + std::to_string(i) + ", " + std::to_string(j) + ", " +
                                                   std::to_string(k) + ") of the grid has " + what + " " +
                                                   format_value(v) + "; it must be finite and > 0");
            }
    SampledGrid g;
    g.quantity = quantity;
    g.dims = s.dims;
    g.origin = s.origin;
    g.spacing = s.spacing;
    g.reference_temperature_K = T_ref;
    g.pressure_Pa = pressure;
    g.field = field;
    if (quantity == GridQuantity::temperature)
        for (double& v : s.values) v = T_ref / v;  // the density ratio q
    auto c = std::make_shared<std::vector<double>>(bspline_coefficients(s.values, s.dims));
    const auto [lo, hi] = std::minmax_element(c->begin(), c->end());
    g.coefficient_min = *lo;
    g.coefficient_max = *hi;
    g.coefficients = std::move(c);
    if (quantity == GridQuantity::index && !(g.coefficient_min > 0))
        throw InputError(base + ": the spline through the samples may fall to " + format_value(g.coefficient_min) +
                         " between them (a sample changes too abruptly); the index must stay > 0");
    return g;
}

double reference_refractivity(const SampledGrid& g, double lambda_um) {
    // One entry per thread: a spectral ray asks at one wavelength many times in a row.
    thread_local double last_l = -1, last_T = -1, last_p = -1, last_r = 0;
    if (lambda_um != last_l || g.reference_temperature_K != last_T || g.pressure_Pa != last_p) {
        AirState air;
        air.temperature_K = g.reference_temperature_K;
        air.pressure_Pa = g.pressure_Pa;
        air.relative_humidity = 0.0;
        last_r = ciddor_refractivity(ciddor_reference(lambda_um, air.co2_ppm), air.pressure_Pa, air.temperature_K, 0.0);
        last_l = lambda_um;
        last_T = g.reference_temperature_K;
        last_p = g.pressure_Pa;
    }
    return last_r;
}

Vec3 grid_lo(const SampledGrid& g) { return g.origin; }
Vec3 grid_hi(const SampledGrid& g) {
    return g.origin + Vec3(g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1).cwiseProduct(g.spacing);
}

}  // namespace refract::grin
