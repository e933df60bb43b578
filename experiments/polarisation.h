#pragma once
// Exact polarisation against per-bounce natural light (docs/polarisation.md):
//  1. a glass (and a water) sphere hit by parallel rays at impact parameters b = r sin θi:
//     the degree of polarisation of each path class (external reflection, direct
//     transmission, one and two internal reflections) against its closed form;
//  2. the 1998 diamond (light pass + 31-wavelength spectral eye pass) and a glass sphere
//     rendered with natural light and with exact polarisation: RMSE, CIEDE2000, the light
//     returned, and the difference split by path depth;
//  3. the diamond through a linear analyser at 0°, 45°, 90°, 135°, and its DoLP image.
// `compute` measures everything into a Result (numbers and images in memory); `write`
// turns a Result into CSV, figures, images, scenes and summary.md. Part 1 is in
// polarisation_sphere.cpp, parts 2 and 3 in polarisation.cpp, the files in
// polarisation_report.cpp.
#include <array>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/polarisation.h"
#include "core/render.h"
#include "experiments/experiment.h"

namespace refract::experiments::polarisation {

// ---- 1. Sphere: degree of polarisation per path class ---------------------------------

// A path class: the background leaves of the exact walk with these counts.
struct PathClass {
    const char* name;  // "reflection", "transmission", "1 internal", "2 internal"
    int reflections, transmissions;
    int internal;  // internal reflections k (−1: the external reflection)
};
const std::array<PathClass, 4>& path_classes();

// Closed form of the signed degree of polarisation (Is − Ip)/(Is + Ip) of natural light
// after the class's path through a sphere of index n entered at θi: reflection
// (Rs − Rp)/(Rs + Rp); k internal reflections (Ts²Rs^k − Tp²Rp^k)/(Ts²Rs^k + Tp²Rp^k),
// T = 1 − R at the entry angle.
double closed_form_signed(const PathClass& c, double n, double theta_i_deg);

struct SpherePoint {
    double n = 0, theta_deg = 0;
    int cls = 0;           // index into path_classes()
    polar::Stokes S;       // summed over the class's background leaves (white, unpolarised light)
    double dop = 0;        // sqrt(S1² + S2² + S3²)/S0
    double dop_closed = 0; // |closed_form_signed|
    double s1 = 0;         // S1/S0 in the frame x̂ = ŝ (+: s-polarised)
    double s1_closed = 0;  // closed_form_signed
};

struct SphereClassError {
    double n = 0;
    int cls = 0;
    int points = 0;
    double max_dop_error = 0;     // max |dop − dop_closed|
    double max_signed_error = 0;  // max |s1 − s1_closed|
    double max_s23 = 0;           // max sqrt(S2² + S3²)/S0 (0 in the plane of incidence)
};

// The primary rainbow ray of a sphere (one internal reflection at minimum deviation,
// cos²θi = (n² − 1)/3).
struct RainbowRay {
    double n = 0, theta_deg = 0, deviation_deg = 0, dop = 0, dop_closed = 0;
};

struct SphereStudy {
    std::vector<double> indices;  // 1.5 (glass), 1.333 (water)
    std::vector<double> angles_deg;
    std::vector<SpherePoint> points;
    std::vector<SphereClassError> errors;  // per index and class
    std::vector<RainbowRay> rainbows;      // per index
    double max_dop_error = 0;              // over all
    std::map<double, nlohmann::json> scenes;  // per index: the sphere the rays are traced against
};

// Traces the parallel rays at `angles_deg` through a unit sphere of index n and
// returns one point per angle and class.
std::vector<SpherePoint> sphere_points(double n, const std::vector<double>& angles_deg);
// The whole study: n = 1.5 and 1.333, θi = 0…89° every degree, the errors, the rainbows.
SphereStudy sphere_study();

// ---- 2. Natural against exact --------------------------------------------------------

struct DepthRow {
    int depth = 0;
    double natural = 0, exact = 0;  // S0 summed over pixels and channels
};

struct Comparison {
    std::string id;     // file stem: "diamond", "sphere"
    std::string title;  // "1998 diamond", "glass sphere"
    bool spectral = false;
    int width = 0, height = 0;
    nlohmann::json natural_scene, exact_scene;
    Image natural, exact;
    PolarisationImages exact_polarisation;  // Stokes, DoLP, AoLP of the exact render
    std::vector<double> delta_e;  // CIEDE2000 per pixel, row-major
    double rmse = 0, max_abs = 0, de_mean = 0, de_p95 = 0, de_p99 = 0, de_max = 0;
    double light_natural = 0, light_exact = 0;  // S0 summed over pixels and channels
    int object_pixels = 0;                      // pixels whose primary ray first hits the object
    double object_natural = 0, object_exact = 0;
    std::vector<DepthRow> depth;                // the non-spectral walk, every pixel centre
    double seconds_natural = 0, seconds_exact = 0;        // light + eye pass
    double light_pass_natural = 0, light_pass_exact = 0;  // light pass alone (0: none)
    double seconds_depth = 0;
};

// Sums, over every pixel centre of `scene`, the light reaching the camera per depth of
// the leaf or background entry (RGB walk with the nominal index; the spectral split and
// the light pass's caustics are not part of it), under the scene's polarisation model.
std::vector<double> light_by_depth(const Scene& scene, int threads);

// ---- 3. The diamond through an analyser ------------------------------------------------

struct AnalyserStudy {
    std::array<double, 4> angles{0, 45, 90, 135};
    std::array<Image, 4> images;
    std::array<nlohmann::json, 4> scenes;
    std::array<double, 4> light{};    // S0 summed over pixels and channels
    int width = 0, height = 0;
    // max over pixels and channels of |I(0) + I(90) − S0| and |I(45) + I(135) − S0|
    double max_dev_0_90 = 0, max_dev_45_135 = 0;
    // The cie-rgb pipeline clips a negative channel to 0 at the end, which breaks the sums
    // where it acts. Channels that are 0 in one of the five images (clipped, or truly
    // dark) are counted, and the deviations measured without them; deviating channels are
    // those beyond 1e-9, and whether every one of them is 0 in one of the images.
    double max_dev_0_90_nonzero = 0, max_dev_45_135_nonzero = 0;
    int zero_channels = 0, deviating_channels = 0;
    bool deviations_at_zeros = true;
    double dolp_mean_object = 0, dolp_max_object = 0;  // over the diamond's pixels
    // Diamond pixels with DoLP > 1, and pixel channels (all pixels) whose Stokes vector lies
    // outside the cone S1² + S2² + S3² <= S0²: cie-rgb channels are sums over wavelengths
    // with weights of both signs (r̄'s negative lobe), and S0 is clipped at 0 at the end.
    int dolp_above_one = 0, channels_outside_cone = 0;
    double seconds = 0;
};

// ---- Everything ----------------------------------------------------------------------

struct Result {
    bool quick = false;
    int threads = 0;
    SphereStudy sphere;
    Comparison diamond, glass;
    AnalyserStudy analyser;
    double seconds_sphere = 0, seconds_total = 0;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// Scenes (saved beside the results).
nlohmann::json sphere_dop_scene(double n);
nlohmann::json glass_sphere_scene(bool quick);

}  // namespace refract::experiments::polarisation
