#pragma once
// A sampled 3D gradient-index field (docs/grin.md, "Sampled fields"): a regular grid of
// samples of the index n or of the air's temperature T, interpolated by a tricubic uniform
// B-spline whose coefficients are prefiltered so that it passes through the samples (the
// interpolating cubic spline, natural ends). The interpolant is C² (n, ∇n and the Hessian
// continuous), so the adaptive ray integrator keeps its order; it reproduces fields linear
// in x exactly and converges as h⁴ on smooth ones (tests/test_grin_grid.cpp).
//
// A temperature grid holds the air's density ratio q = T_ref/T (ideal gas at constant
// pressure); its index is n(x, λ) − 1 = (n_ref(λ) − 1)·q(x) by Gladstone & Dale (1863),
// n_ref the index of dry air at T_ref and the grid's pressure by Ciddor (1996,
// core/grin/air_index.h), so the field disperses. Interpolating q, not T, keeps n linear
// in the interpolated quantity, so ∇n is exactly (n_ref − 1)∇q.
//
// Samples come from a scene file's inline "values" (nested lists, also what a NumPy array
// becomes in Python) or from an OpenVDB file (core/grin/grid_vdb.cpp, the one file that
// includes OpenVDB).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace refract::grin {

using Vec3 = Eigen::Vector3d;

// Samples on a regular grid: value (i, j, k) at origin + (i·s_x, j·s_y, k·s_z), stored
// with i fastest: values[i + n_x·(j + n_y·k)].
struct GridSamples {
    std::array<int, 3> dims{0, 0, 0};
    Vec3 origin = Vec3::Zero();
    Vec3 spacing = Vec3::Ones();
    std::vector<double> values;
};

// The most samples a grid may have (2^26: 512 MiB of samples and as much of spline
// coefficients). An OpenVDB file's active voxels are made dense over their bounding box, so
// two voxels far apart would otherwise ask for any amount of memory.
inline constexpr std::size_t kMaxGridSamples = std::size_t{1} << 26;
// InputError "WHERE: the grid's active voxels span NX×NY×NZ samples, more than …" when
// nx·ny·nz exceeds kMaxGridSamples (checked before the dense samples are allocated).
void check_grid_size(long long nx, long long ny, long long nz, const std::string& where);

enum class GridQuantity { index, temperature };

struct SampledGrid {
    GridQuantity quantity = GridQuantity::index;
    std::array<int, 3> dims{0, 0, 0};  // samples per axis, each ≥ 2
    Vec3 origin = Vec3::Zero();
    Vec3 spacing = Vec3::Ones();
    // The B-spline coefficients of n (index) or of q = T_ref/T (temperature), padded by one
    // on each side: (n_x + 2)(n_y + 2)(n_z + 2), i fastest. Shared: copies are cheap.
    std::shared_ptr<const std::vector<double>> coefficients;
    double coefficient_min = 0, coefficient_max = 0;  // bound the interpolant (convex hull)
    // Temperature grids: the reference air (dry, 450 ppm CO₂).
    double reference_temperature_K = 288.15;
    double pressure_Pa = 101325.0;
    // Temperature grids: the index relative to the reference air, n = 1 + (n_ref − 1)(q − 1),
    // for a field in a scene whose outside (n = 1) stands for that air (a hot plume in air
    // at T_ref: no interface at the box's faces where T = T_ref). The ray curvature ∇n/n
    // differs from the absolute field's by the factor n_ref (3e-4).
    bool relative = false;
    // The field that gave the samples ("values" or "file"), for messages about the grid.
    std::string field = "values";
};

// ---------------------------------------------------------------------------------------
// The interpolant, as small pure functions.

// The uniform cubic B-spline's four weights at t ∈ [0, 1] (coefficients i−1 … i+2 for a
// point in cell [i, i+1]) and their derivatives in t.
struct CubicWeights {
    double w[4];
    double d[4];
};
CubicWeights cubic_bspline_weights(double t);

// The coefficients (padded as SampledGrid::coefficients) of the tricubic B-spline that
// interpolates `values` (dims ≥ 2 per axis, i fastest): along each axis the tridiagonal
// system (c_{i−1} + 4c_i + c_{i+1})/6 = f_i with natural ends (c_{−1} = 2c_0 − c_1, so
// c_0 = f_0), solved by the Thomas algorithm; the padding extrapolates linearly.
std::vector<double> bspline_coefficients(const std::vector<double>& values, const std::array<int, 3>& dims);

// The tricubic B-spline's value and gradient (per unit of the grid coordinate) at grid
// coordinate u (sample (i, j, k) at u = (i, j, k)), u clamped into [0, n − 1] per axis.
struct SplineValue {
    double value;
    Vec3 gradient;
};
SplineValue tricubic_bspline(const std::vector<double>& coefficients, const std::array<int, 3>& dims, const Vec3& u);

// ---------------------------------------------------------------------------------------
// Building and evaluating a grid.

// A grid from samples: checks dims (≥ 2 per axis), origin and spacing (finite, > 0), each
// sample finite and > 0 (an index, or a temperature in K), and for an index grid that the
// interpolant stays > 0; InputError "PATH/FIELD…" naming the sample ("PATH/values/i/j/k"
// for inline values, "PATH/file: voxel (i, j, k)…" otherwise). `where` is "FILE: PATH".
SampledGrid sampled_grid(GridSamples samples, GridQuantity quantity, double reference_temperature_K, double pressure_Pa,
                         const std::string& field, const std::string& where);

// The refractivity n_ref − 1 of the grid's reference air at λ (µm), Ciddor (1996).
double reference_refractivity(const SampledGrid& g, double lambda_um);

// The grid's box: its first and last samples' positions.
Vec3 grid_lo(const SampledGrid& g);
Vec3 grid_hi(const SampledGrid& g);

// ---------------------------------------------------------------------------------------
// OpenVDB (core/grin/grid_vdb.cpp).

// The samples of the float (or double) grid `grid_name` (empty: the file's first scalar
// grid) of an OpenVDB file, dense over its active voxels' bounding box (inactive voxels
// take the grid's background value), at the world positions of its voxel transform (a
// uniform or axis-aligned scale and a translation; a rotated transform is refused).
// InputError "WHERE/file: …" or "WHERE/grid: …" for a missing or unreadable file, no such
// grid, a grid of another type, an empty grid.
GridSamples read_vdb_grid(const std::string& path, const std::string& grid_name, const std::string& where);
// Writes `s` as a grid named `grid_name` (a FloatGrid, what other tools read; `precision`
// double: a DoubleGrid, for index samples whose refractivity n − 1 a float would round to
// 1e-7/3e-4 ≈ 3e-4 of itself) with a uniform voxel size (s.spacing's x) and the
// translation placing voxel (0, 0, 0) at s.origin, every voxel active. The file appears
// whole or not at all (geometry/atomic_file.h). InputError naming `path` for a spacing that
// is not uniform, a grid name that is empty, samples that are not finite, dims below 1 or
// a value count that does not match them, and when the file cannot be written.
enum class VdbPrecision { single, double_ };
void write_vdb_grid(const std::string& path, const std::string& grid_name, const GridSamples& s,
                    VdbPrecision precision = VdbPrecision::single);

}  // namespace refract::grin
