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
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/image.h>
#include <refract/core/polarisation.h>
#include <refract/core/render.h>
#include <refract/experiments/experiment.h>

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
    double depth_natural = 0, depth_exact = 0;  // `depth` summed
    double seconds_natural = 0, seconds_exact = 0;        // light + eye pass
    double light_pass_natural = 0, light_pass_exact = 0;  // light pass alone (0: none)
    double seconds_depth = 0;
    Image difference_x10;  // |natural − exact| × 10, clipped at 1
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
    Image dolp_grey;  // the diamond's DoLP as grey levels (sRGB-encoded grey = DoLP, clamped to 0-1)
    double seconds = 0;
};

// ---- Everything ----------------------------------------------------------------------

// What the summary states beside its tables, each from the numbers (`judge`).
struct Findings {
    // A scene rendered without the spectral pass: the sums over depth equal the renders' ΣS0 (to 1e-9).
    bool diamond_depth_sums_match = false, glass_depth_sums_match = false;
    bool clipping_deviates = false;       // pixel channels break I(0) + I(90) = S0 (the cie-rgb clipping)
    bool outside_cone = false;            // DoLP above 1 or Stokes vectors outside the cone
};

struct Result {
    bool quick = false;
    int threads = 0;
    SphereStudy sphere;
    Comparison diamond, glass;
    AnalyserStudy analyser;
    double seconds_sphere = 0, seconds_total = 0;
    Findings findings;  // judge(*this), set by compute
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// The findings from a Result's numbers (pure; compute stores them in Result::findings) and
// the summary's sentences that state them, worded by r.findings.
Findings judge(const Result& r);
std::string depth_sums_text(const Result& r, const Comparison& c);  // a non-spectral scene: the walk is the render
std::string clipping_text(const Result& r);                         // the analyser's sums and the clipping
std::string cone_text(const Result& r);                             // DoLP above 1, Stokes vectors outside the cone

// Scenes (saved beside the results).
nlohmann::json sphere_dop_scene(double n);
nlohmann::json glass_sphere_scene(bool quick);

}  // namespace refract::experiments::polarisation

namespace refract {

template <>
struct Fields<experiments::polarisation::SpherePoint> {
    static auto list() {
        using P = experiments::polarisation::SpherePoint;
        namespace pol = experiments::polarisation;
        return std::make_tuple(
            field("n", &P::n), field("theta_deg", &P::theta_deg), field("class_id", &P::cls).csv_only(),
            derived<P>("path", [](const P& p) { return pol::path_classes()[static_cast<size_t>(p.cls)].name; }).csv("class"),
            field("stokes", &P::S).python_only(), derived<P>("S0", [](const P& p) { return p.S(0); }).csv_only(),
            derived<P>("S1", [](const P& p) { return p.S(1); }).csv_only(),
            derived<P>("S2", [](const P& p) { return p.S(2); }).csv_only(),
            derived<P>("S3", [](const P& p) { return p.S(3); }).csv_only(), field("dop", &P::dop),
            field("dop_closed", &P::dop_closed),
            derived<P>("dop_error", [](const P& p) { return p.dop - p.dop_closed; }).csv_only(),
            field("s1", &P::s1).csv("s1_over_s0"), field("s1_closed", &P::s1_closed));
    }
};
template <>
struct Fields<experiments::polarisation::SphereClassError> {
    static auto list() {
        using E = experiments::polarisation::SphereClassError;
        namespace pol = experiments::polarisation;
        return std::make_tuple(
            field("n", &E::n),
            derived<E>("path", [](const E& e) { return pol::path_classes()[static_cast<size_t>(e.cls)].name; }).csv("class"),
            derived<E>("reflections", [](const E& e) { return pol::path_classes()[static_cast<size_t>(e.cls)].reflections; })
                .csv_only(),
            derived<E>("transmissions",
                       [](const E& e) { return pol::path_classes()[static_cast<size_t>(e.cls)].transmissions; })
                .csv_only(),
            field("points", &E::points), field("max_dop_error", &E::max_dop_error).digits(3),
            field("max_signed_error", &E::max_signed_error).digits(3),
            field("max_s23", &E::max_s23).csv("max_off_plane").digits(3));
    }
};
template <>
struct Fields<experiments::polarisation::RainbowRay> {
    static auto list() {
        using R = experiments::polarisation::RainbowRay;
        return std::make_tuple(field("n", &R::n), field("theta_deg", &R::theta_deg).csv("theta_i_deg").digits(6),
                               field("deviation_deg", &R::deviation_deg).digits(6), field("dop", &R::dop),
                               field("dop_closed", &R::dop_closed));
    }
};
template <>
struct Fields<experiments::polarisation::SphereStudy> {
    static auto list() {
        using S = experiments::polarisation::SphereStudy;
        return std::make_tuple(field("points", &S::points), field("errors", &S::errors), field("rainbows", &S::rainbows),
                               field("max_dop_error", &S::max_dop_error));
    }
};
template <>
struct Fields<experiments::polarisation::DepthRow> {
    static auto list() {
        using D = experiments::polarisation::DepthRow;
        return std::make_tuple(
            field("depth", &D::depth), field("natural", &D::natural).digits(8), field("exact", &D::exact).digits(8),
            derived<D>("difference", [](const D& d) { return d.exact - d.natural; }).digits(4).csv_only(),
            derived<D>("relative_difference",
                       [](const D& d) {
                           return d.natural > 0 ? std::optional<double>((d.exact - d.natural) / d.natural) : std::nullopt;
                       })
                .digits(4)
                .csv_only());
    }
};
template <>
struct Fields<experiments::polarisation::Comparison> {
    static auto list() {
        using C = experiments::polarisation::Comparison;
        return std::make_tuple(
            field("id", &C::id).csv("scene").csv_only(), field("title", &C::title).python_only(),
            field("natural", &C::natural).python_only(), field("exact", &C::exact).python_only(),
            derived<C>("dolp", [](const C& c) { return ArrayRef{&c.exact_polarisation.dolp, {c.height, c.width}}; })
                .python_only(),
            field("width", &C::width), field("height", &C::height), field("rmse", &C::rmse).digits(4),
            field("max_abs", &C::max_abs).digits(4), field("delta_e_mean", &C::de_mean).csv("de2000_mean").digits(4),
            field("delta_e_p95", &C::de_p95).csv("de2000_p95").digits(4),
            field("delta_e_max", &C::de_max).csv("de2000_max").digits(4),
            field("light_natural", &C::light_natural).digits(6), field("light_exact", &C::light_exact).digits(6),
            derived<C>("light_ratio", [](const C& c) { return c.light_exact / c.light_natural; }).digits(6).csv_only(),
            field("object_pixels", &C::object_pixels), field("object_natural", &C::object_natural).digits(6),
            field("object_exact", &C::object_exact).digits(6),
            derived<C>("object_ratio", [](const C& c) { return c.object_exact / c.object_natural; }).digits(6).csv_only(),
            field("depth", &C::depth).python_only(), field("seconds_natural", &C::seconds_natural).digits(3),
            field("seconds_exact", &C::seconds_exact).digits(3));
    }
};
template <>
struct Fields<experiments::polarisation::AnalyserStudy> {
    static auto list() {
        using A = experiments::polarisation::AnalyserStudy;
        return std::make_tuple(field("angles", &A::angles), field("images", &A::images), field("light", &A::light),
                               field("max_dev_0_90", &A::max_dev_0_90), field("max_dev_45_135", &A::max_dev_45_135),
                               field("dolp_mean_object", &A::dolp_mean_object),
                               field("dolp_max_object", &A::dolp_max_object));
    }
};
template <>
struct Fields<experiments::polarisation::Findings> {
    static auto list() {
        using F = experiments::polarisation::Findings;
        return std::make_tuple(field("diamond_depth_sums_match", &F::diamond_depth_sums_match),
                               field("glass_depth_sums_match", &F::glass_depth_sums_match),
                               field("clipping_deviates", &F::clipping_deviates), field("outside_cone", &F::outside_cone));
    }
};
template <>
struct Fields<experiments::polarisation::Result> {
    static auto list() {
        using R = experiments::polarisation::Result;
        return std::make_tuple(field("quick", &R::quick), field("sphere", &R::sphere), field("diamond", &R::diamond),
                               field("glass", &R::glass), field("analyser", &R::analyser),
                               field("seconds", &R::seconds_total), field("findings", &R::findings));
    }
};

}  // namespace refract
