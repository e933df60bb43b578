#pragma once
// Double refraction in uniaxial crystals (docs/birefringence.md, issue 14):
//  1. a calcite plate over a printed line, seen straight down: the double image, its
//     separation measured in the render against walk-off × thickness, and the two images
//     through a linear analyser at 0° and 90° (exact polarisation);
//  2. round brilliants of diamond, cubic zirconia and moissanite (optic axis along the
//     table normal and tilted) seen from above through the table: the share of table
//     pixels that change when moissanite's double refraction is replaced by its ordinary
//     index alone (doubled facet edges), and the walk-off of a traced ray against theory.
// `compute` measures into a Result; `write` writes CSV, images, figures and summary.md.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "experiments/experiment.h"

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

struct Result {
    bool quick = false;
    Plate plate;
    std::vector<GemRow> gems;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);

}  // namespace refract::experiments::birefringence
