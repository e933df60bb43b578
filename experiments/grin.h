#pragma once
// grin: gradient-index media as paper-style figures (docs/grin.md, "Experiment"), every ray
// integrated by the ray equation of core/grin (advance()), nothing through the renderer:
//  1. lenses: a Luneburg lens focusing a parallel bundle (spot radius), Maxwell's fish-eye
//     imaging a point along circles (image and circle errors), a hyperbolic-secant rod
//     refocusing a point after one pitch against a parabolic rod's aberration, and a
//     parabolic GRIN rod imaging a grid (magnification against the paraxial one);
//  2. mirages: an inferior mirage over a hot road and a superior one over a cold sea,
//     rays from an eye through the atmosphere's surface layer over the spherical Earth;
//  3. the setting sun: its vertical flattening and the green and red limbs;
//  4. astronomical refraction against apparent altitude: traced, the refraction
//     integral, Bennett (1982) and Sæmundsson (1986);
//  5. the integrator's convergence: error against tolerance, evaluations against error,
//     adaptive against fixed steps (core/grin/step_study.h).
// `compute` measures into a Result; `write` (grin_report.cpp) turns it into CSV, figures
// and summary.md, every finding worded by a predicate on the numbers (`judge`).
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/grin/grid.h>
#include <refract/core/grin/step_study.h>
#include <refract/core/image.h>
#include <refract/experiments/experiment.h>
#include <refract/geometry/constants.h>

namespace refract {
struct Scene;
}

namespace refract::experiments::grin_media {

constexpr double kDeg = kPi / 180.0;

// A ray diagram: points of ray `ray` in the figure's plane (u across, v up), in order.
struct PathPoint {
    int ray = 0;
    double u = 0, v = 0;
};

// 1a. Luneburg lens, radius 1: a bundle along +z meets at (0, 0, 1).
struct LuneburgStudy {
    double tol = 0;            // of the rays measured
    int rays = 0;              // impacts in [−0.95, 0.95] R
    double spot_radius = 0;    // max |exit − (0, 0, R)| / R
    double direction_error = 0;  // max |exit direction − the reference|, rad
    double mean_evaluations = 0;
    std::vector<PathPoint> paths;  // (z, y)
};

// 1b. Maxwell's fish-eye n₀/(1 + (r/a)²), a point at r₀ on the axis imaged at −a²/r₀.
struct FishEyeStudy {
    double a = 1, n0 = 2, r0 = 0.5, image = -2;  // along z
    double tol = 0;
    int rays = 0;
    double image_error = 0;   // max |exit − image| / a
    double circle_error = 0;  // max distance of a path point from its circle / a
    std::vector<PathPoint> paths;  // (z, x)
};

// 1c. A point on the axis of a sech rod and of a parabolic rod with the same paraxial
// pitch 2π/α, meridional rays at launch angles: the height and slope after one pitch.
struct RodRow {
    double angle_deg = 0;
    double sech_height = 0, sech_slope_error = 0;  // height at z = pitch; |direction − the start's|
    double parabolic_height = 0;
};
struct RodStudy {
    double n0 = 1.5, alpha = 1, pitch = 0;
    double tol = 0;
    std::vector<RodRow> rows;
    double sech_spot = 0, parabolic_spot = 0;  // max |height| at one pitch
    std::vector<PathPoint> sech_paths, parabolic_paths;  // (z, x)
};

// 1d. A parabolic rod of length L between an object grid at distance s in front and the
// paraxial image plane at s′ behind (ABCD matrices); each object point's bundle through
// the rod, its centroid and RMS spot on that plane.
struct GridPoint {
    double object_x = 0, object_y = 0, image_x = 0, image_y = 0, spot_rms = 0;
    double magnification = 0;  // image radius / object radius (signed), NaN on the axis
};
struct GridStudy {
    double n0 = 1.6, g = 0.5, length = 0, rod_radius = 1;
    double object_distance = 0, image_distance = 0, paraxial_magnification = 0;  // ABCD
    double pupil_radius = 0;  // rays from each object point fill this disc on the entrance face
    int rays_per_point = 0;
    std::vector<GridPoint> points;
    double axis_magnification = 0;   // of the grid points nearest the axis
    double corner_magnification = 0;  // of the farthest
    double max_spot = 0;
    std::vector<PathPoint> paths;  // meridional rays (z, x)
};

// 2. A mirage: the atmosphere with a surface layer ΔT·exp(−h/h_s), rays from an eye at
// elevation angles, each to the object's distance D (the radial plane there) or the ground.
struct MirageRay {
    double elevation_deg = 0;
    bool hits_ground = false;
    double ground_distance = 0;  // m along the ground, when it does
    double height_at_object = 0; // m at D, when it does not
};
struct MirageBranch {
    double elevation_lo_deg = 0, elevation_hi_deg = 0;
    double height_lo = 0, height_hi = 0;  // at D, of the rays at the two elevations
    bool inverted() const { return height_hi < height_lo; }
};
struct MirageStudy {
    std::string name;  // "inferior" / "superior"
    // The road: the atmosphere's surface layer ΔT·exp(−h/h_s); the sea: an inversion of ΔT
    // centred at height h_s (grin_sky.cpp).
    double sea_level_temperature_K = 0, delta_T = 0, surface_height = 0, eye_height = 0, distance = 0;
    std::vector<MirageRay> rays;            // with the layer
    std::vector<MirageRay> standard_rays;   // the same atmosphere without it
    std::vector<PathPoint> paths;           // (distance along the ground, height), m
    // Measured on `rays`: the monotonic runs of height at D against elevation over
    // consecutive rays that reach D (a run falling as the elevation rises is an inverted
    // image), the elevation where rays start hitting the ground, and the lowest height at D
    // seen with and without the layer (below it the object is not seen: the vanishing line).
    std::vector<MirageBranch> branches;
    double ground_onset_deg = 0;            // the largest elevation of a ray that hits the ground (NaN: none)
    double lowest_seen = 0, lowest_seen_standard = 0;
};

// 3. The setting sun: its lower limb at apparent altitude a, the upper limb's image, the
// vertical and horizontal diameters; the green (520 nm) and red (650 nm) limbs' separation.
struct SunRow {
    double lower_apparent_deg = 0, upper_apparent_deg = 0;
    double vertical_arcmin = 0, horizontal_arcmin = 0, ratio = 0;
    double ratio_bennett = 0;  // the same from Bennett's formula for the refraction
};
struct LimbRow {
    double apparent_deg = 0;
    double traced_arcsec = 0, integral_arcsec = 0;  // R(520 nm) − R(650 nm)
};
struct SunStudy {
    double semidiameter_arcmin = 0;
    std::vector<SunRow> rows;
    std::vector<LimbRow> limbs;
};

// 4. Refraction against apparent altitude at Bennett's conditions (10 °C, 101.0 kPa, dry, 550 nm).
struct RefractionRow {
    double apparent_deg = 0, true_deg = 0;
    double traced_arcmin = 0, integral_arcmin = 0, bennett_arcmin = 0, bennett_corrected_arcmin = 0, saemundsson_arcmin = 0;
};
struct RefractionStudy {
    std::vector<RefractionRow> rows;
    double max_traced_integral_arcsec = 0;
    double max_bennett_arcmin = 0, max_saemundsson_arcmin = 0;  // |formula − integral|
};

// 5. Convergence on two rays with known exits.
struct ConvergenceCurve {
    std::string ray;
    std::vector<grin::StepPoint> adaptive, fixed;
    double tol_slope = 0;    // log error against log tol (adaptive)
    double step_order = 0;   // log error against log step (fixed), the method's order
    double matched_ratio = 0;  // fixed evaluations / adaptive at the adaptive error of tol 1e-11
};
struct ConvergenceStudy {
    std::vector<ConvergenceCurve> curves;
};

// 6. Rendered views through GRIN objects (experiments/grin_views.cpp): each scene, its
// image and the render's counters.
struct ViewStudy {
    std::string name, title;
    nlohmann::json scene;
    Image image;
    double seconds = 0;
    std::uint64_t grin_segments = 0, grin_evaluations = 0, grin_exhausted = 0;
    bool finite = false;
};

// The rendered upper limb of the setting sun (view "sunset_limb_view"), down its centre
// column: the first lit pixel's colour, and the angle from it to the first pixel whose red
// is at least half its largest channel (the coloured rim above the white disc).
struct SunsetLimb {
    bool found = false;
    Vec3 top_rgb = Vec3::Zero();
    double rim_arcsec = 0;
    bool blue_on_top = false;  // the top pixel bluer than it is red or green
};
SunsetLimb sunset_limb(const ViewStudy& v);
// The ship of the superior mirage's view ("sea_view") down its centre column (rows from
// the top): the rows of its red hull and of its white superstructure; inverted when every
// white row lies below every red one (the superstructure, on top of the hull, seen under it).
struct ShipImage {
    int red_top = -1, red_bottom = -1, white_top = -1, white_bottom = -1;
    bool seen = false, inverted = false;
};
ShipImage ship_image(const ViewStudy& v);

// 7. Heat shimmer (experiments/grin_shimmer.cpp): a warm turbulent plume over a road as a
// sampled temperature grid; the target points' apparent displacement against the plume's
// amplitude, and a view through the field written as OpenVDB and read by the scene.
struct ShimmerRow {
    double amplitude_K = 0;
    double rms_displacement = 0, max_displacement = 0;  // m on the target plane, against no plume
    double rms_angle_urad = 0;                          // rms displacement / distance, µrad
};
struct ShimmerStudy {
    double air_temperature_K = 0, plume_height = 0, length = 0, spacing = 0, eye_to_target = 0;
    std::array<int, 3> grid_dims{0, 0, 0};
    int target_points = 0;
    std::vector<ShimmerRow> rows;
    long evaluations = 0;
    double exponent = 0;  // rms displacement ∝ amplitude^exponent, fitted over amplitudes ≤ 4 K
    double view_amplitude_K = 0;
    grin::GridSamples field;  // the view's temperature field (written as shimmer.vdb)
    bool vdb_dims_match = false;
    double vdb_max_index_difference = 0;  // the grid read back against the one sampled, at probes
    ViewStudy view;
};

// What the summary states, each from the numbers (`judge`).
struct Findings {
    bool luneburg_focus = false;      // spot ≤ 1e-9 R
    bool fisheye_image = false;       // image and circle errors ≤ 1e-8 a
    bool sech_refocus = false;        // sech spot ≤ 1e-9 and ≥ 1000× below the parabolic one
    bool grid_inverted_as_paraxial = false;  // axis magnification within 1 % of the paraxial one
    bool road_inverted = false;       // the hot road shows an inverted branch beside an erect one
    bool sea_inverted = false;        // the cold sea shows an inverted branch
    bool sea_looming = false;         // the cold sea shows lower at D than the standard atmosphere
    bool sun_flattened = false;       // the ratio at the horizon in [0.75, 0.9] and rising with altitude
    bool green_above_red = false;     // R(520) − R(650) > 0 at every altitude, traced within 0.01″ of the integral
    bool traced_is_integral = false;  // ≤ 0.01″ at every altitude
    bool bennett_within = false;      // corrected Bennett within 0.07′ of the integral from 5° to 90°
    bool tolerance_proportional = false;  // every tol slope in [0.8, 1.2]
    bool fifth_order = false;             // every fixed-step order in [4.5, 5.5]
    bool views_complete = false;          // every view finite, no ray out of steps
    bool limb_blue_on_top = false;        // the rendered upper limb: blue first, red only lower down
    SunsetLimb limb;                      // what the limb view shows (sunset_limb)
    bool sea_view_inverted = false;       // the rendered ship over the cold sea is seen upside down
    ShipImage ship;                       // what the sea view shows (ship_image)
    bool shimmer_linear = false;          // the displacement's exponent within 0.05 of 1
    bool shimmer_vdb_same = false;        // the .vdb read back: same grid, index within 1e-9
};

struct Result {
    bool quick = false;
    double lambda_um = 0.55;
    LuneburgStudy luneburg;
    FishEyeStudy fisheye;
    RodStudy rods;
    GridStudy grid;
    MirageStudy road, sea;
    SunStudy sun;
    RefractionStudy refraction;
    ConvergenceStudy convergence;
    std::vector<ViewStudy> views;
    ShimmerStudy shimmer;
    double seconds = 0;
    std::vector<std::pair<std::string, double>> study_seconds;  // each study's time
    Findings findings;  // judge(*this), set by compute
};

Findings judge(const Result& r);

// The studies (grin.cpp: lenses; grin_sky.cpp: mirages, sun, refraction, convergence).
LuneburgStudy luneburg_study(bool quick);
FishEyeStudy fisheye_study(bool quick);
RodStudy rod_study(bool quick);
GridStudy grid_study(bool quick);
MirageStudy mirage_study(bool inferior, bool quick);
SunStudy sun_study(bool quick);
RefractionStudy refraction_study(bool quick);
ConvergenceStudy convergence_study(bool quick);
std::vector<ViewStudy> view_study(bool quick, int threads);
// The superior mirage study's air over the cold sea (grin_sky.cpp): n at the radii r from
// the Earth's centre (a tabulated radial profile, 0–500 m above the sea), the eye's height,
// the ship's distance, the inversion's ΔT and height, for its rendered view.
struct SeaAir {
    Vec3 centre;
    std::vector<double> r, n;
    double eye_height = 0, distance = 0, delta_T = 0, inversion_height = 0;
};
SeaAir sea_air(double lambda_um);
// Its last two: the setting sun whole and its upper limb (sunset_view, sunset_limb_view).
std::vector<ViewStudy> sunset_views(bool quick, int threads);
// One rendered view: `scene` (kept in the result) as `parsed` (read from it, with the file
// name its relative paths resolve against), its image, time and GRIN counters.
ViewStudy render_view(const std::string& name, const std::string& title, const nlohmann::json& scene,
                      const Scene& parsed, int threads);
ShimmerStudy shimmer_study(bool quick, int threads);
// The shimmer study's files (CSV, figure, shimmer.vdb, the view) and its summary section.
std::string write_shimmer(const ShimmerStudy& s, const Findings& f, const std::string& dir);

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);

}  // namespace refract::experiments::grin_media
