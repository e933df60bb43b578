#pragma once
// Double refraction in uniaxial crystals (docs/birefringence.md, issue 14):
//  1. a calcite plate over a printed line, seen straight down: the double image, its
//     separation measured in the render against walk-off × thickness, and the two images
//     through a linear analyser at 0° and 90° (exact polarisation);
//  2. round brilliants of diamond, cubic zirconia and moissanite (optic axis along the
//     table normal and tilted) seen from above through the table: the share of table
//     pixels that change when moissanite's double refraction is replaced by its ordinary
//     index alone (doubled facet edges), and the walk-off of a traced ray against theory;
//  3. fire: the G–B angular spread of a ray leaving through a crown facet, diamond against
//     moissanite's o and e exits.
// `compute` measures into a Result; `write` writes CSV, images, figures and summary.md.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/image.h>
#include <refract/experiments/experiment.h>

namespace refract::experiments::birefringence {

// The calcite plate scene: thickness T, optic axis at `axis_deg` from the plate normal (in
// the plane across the printed line), an orthographic camera looking down, W × H pixels;
// `analyser_deg` < 0: none (natural light), else exact polarisation through a linear
// analyser at that angle (from the image's right). RGB rays at the sodium D line.
nlohmann::json plate_scene(double thickness, double axis_deg, int width, int height, double analyser_deg);

// The bright runs of a row profile (above half its maximum): their centroids (scene x)
// and mean intensities, the largest first.
struct Peak {
    double x = 0, intensity = 0;
    int pixels = 0;
};
std::vector<Peak> peaks(const std::vector<double>& profile, double x0, double dx);

struct Plate {
    double thickness = 0, axis_deg = 0, n_o = 0, n_e = 0;
    double rho_deg = 0;                 // walk-off, closed form (normal incidence)
    double separation_theory = 0;       // T tan ρ
    double separation_measured = 0;     // between the two images' centroids in the render
    int bright_runs = 0;                // bright runs in the natural-light profile (two: the line doubled)
    double pixel = 0;                   // scene units per pixel across the plate view
    std::array<double, 3> o_intensity{}, e_intensity{};  // no analyser, 0°, 90°
    std::vector<double> x;                               // profile abscissae
    std::array<std::vector<double>, 3> profile;          // the middle row, per analyser
    Image image;                                         // natural light
    nlohmann::json scene;
};

struct GemRow {
    std::string id, gem, axis;           // "moissanite-tilted", "moissanite", "tilted 30°"
    double changed_fraction = 0;         // table pixels changed by > 0.05 against the o-index twin
    double rho_theory_deg = 0, rho_traced_deg = 0;  // walk-off of the traced ray (0: isotropic)
    double offset_theory = 0, offset_traced = 0;    // lateral offset at the pavilion
    double seconds = 0;
    Image image;
    nlohmann::json scene;
};

// Fire: a ray inside the gem meeting a crown facet (34.5° from the table, optic axis along
// the table normal) at internal incidence θ leaves into the air; the angle between its exit
// directions at the Fraunhofer G (430.78 nm) and B (686.72 nm) lines. Moissanite has an o and
// an e exit per wavelength (a ray inside along the same direction travelling as o or as e):
// `moissanite_oe_deg` is the widest angle among the four. `diamond_closed_deg`: the
// closed form asin(n_G sin θ) − asin(n_B sin θ).
struct FireRow {
    double theta_deg = 0;
    double diamond_deg = 0, diamond_closed_deg = 0;
    double moissanite_o_deg = 0, moissanite_oe_deg = 0;
};

// What the summary states beside its tables, each from the numbers (`judge`).
struct Findings {
    bool line_doubled = false;      // the natural-light profile has two bright runs
    bool crossed_images = false;    // analyser 0°: o below a tenth of its brightness, e above half; 90°: the reverse
};

struct Result {
    bool quick = false;
    Plate plate;
    std::vector<GemRow> gems;
    std::vector<FireRow> fire;
    Findings findings;  // judge(*this), set by compute
};

// The findings from a Result's numbers (pure; compute stores them in Result::findings) and
// the summary's sentences that state them, worded by r.findings.
Findings judge(const Result& r);
std::string doubling_text(const Result& r);  // the line seen twice?
std::string analyser_text(const Result& r);  // the images polarised at right angles?

// The fire rows at internal incidence angles `thetas_deg` (below both gems' critical angles).
std::vector<FireRow> fire_spread(const std::vector<double>& thetas_deg);

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);

}  // namespace refract::experiments::birefringence

namespace refract {

template <>
struct Fields<experiments::birefringence::Plate> {
    static auto list() {
        using P = experiments::birefringence::Plate;
        return std::make_tuple(
            field("thickness", &P::thickness), field("axis_deg", &P::axis_deg), field("n_o", &P::n_o),
            field("n_e", &P::n_e), field("rho_deg", &P::rho_deg).csv("walk_off_deg"),
            field("separation_theory", &P::separation_theory), field("separation_measured", &P::separation_measured),
            derived<P>("relative_error", [](const P& p) { return p.separation_measured / p.separation_theory - 1; }),
            derived<P>("o_natural", [](const P& p) { return p.o_intensity[0]; }),
            derived<P>("e_natural", [](const P& p) { return p.e_intensity[0]; }),
            derived<P>("o_analyser_0", [](const P& p) { return p.o_intensity[1]; }),
            derived<P>("e_analyser_0", [](const P& p) { return p.e_intensity[1]; }),
            derived<P>("o_analyser_90", [](const P& p) { return p.o_intensity[2]; }),
            derived<P>("e_analyser_90", [](const P& p) { return p.e_intensity[2]; }));
    }
};
template <>
struct Fields<experiments::birefringence::GemRow> {
    static auto list() {
        using G = experiments::birefringence::GemRow;
        return std::make_tuple(field("id", &G::id), field("gem", &G::gem), field("axis", &G::axis).csv("optic_axis"),
                               field("changed_fraction", &G::changed_fraction),
                               field("rho_theory_deg", &G::rho_theory_deg).csv("walk_off_theory_deg"),
                               field("rho_traced_deg", &G::rho_traced_deg).csv("walk_off_traced_deg"),
                               field("offset_theory", &G::offset_theory), field("offset_traced", &G::offset_traced),
                               field("seconds", &G::seconds).digits(3));
    }
};
template <>
struct Fields<experiments::birefringence::FireRow> {
    static auto list() {
        using F = experiments::birefringence::FireRow;
        return std::make_tuple(field("theta_deg", &F::theta_deg).csv("theta_in_deg"), field("diamond_deg", &F::diamond_deg),
                               field("diamond_closed_deg", &F::diamond_closed_deg).csv("diamond_closed_form_deg"),
                               field("moissanite_o_deg", &F::moissanite_o_deg),
                               field("moissanite_oe_deg", &F::moissanite_oe_deg).csv("moissanite_o_and_e_deg"));
    }
};

}  // namespace refract
