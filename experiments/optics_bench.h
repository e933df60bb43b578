#pragma once
// optics-bench: classic optics measured with the far-field detector (core/far_field.h),
// each next to its closed form computed independently (experiments/optics_closed_forms.h),
// with the difference printed:
//  1. a water drop (n = 1.333) in a collimated beam: the power scattered into each angle
//     per van de Hulst class (external reflection, direct transmission, one and two
//     internal reflections), for s, p and natural light (exact polarisation);
//  2. the rainbow against wavelength: the primary bow's (class 2) smallest and the
//     secondary bow's (class 3) largest scattering angle of a dispersive water drop
//     (Descartes' minimum deviation);
//  3. a 60° N-BK7 prism: deviation against wavelength at a fixed incidence angle;
//  4. a plane-parallel glass slab (n = 1.5): transmittance against incidence angle, s and
//     p, all internal reflections summed (incoherent).
// `compute` measures into a Result; `write` turns it into CSV, figures and summary.md.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/far_field.h"
#include "experiments/experiment.h"

namespace refract::experiments::optics_bench {

// 1. Drop: per class and angle bin, measured fractions of the beam's power and the closed form.
struct DropBin {
    int cls = 0;  // van de Hulst p
    double theta0_deg = 0, theta1_deg = 0;
    double measured = 0, measured_s = 0, measured_p = 0;  // natural incident light: s + p = measured
    double closed = 0, closed_s = 0, closed_p = 0;         // the same from the closed form
};
struct DropClass {
    int cls = 0;
    double total = 0, total_closed = 0;  // fraction of the beam
    double max_bin_error = 0;            // max |measured − closed| over the bins
    // The largest |measured − closed| / σ over the bins, σ = √(closed / N) (an upper bound of
    // a bin's statistical error: each photon brings it at most its whole power).
    double max_z = 0;
};
struct DropStudy {
    double n = 1.333;
    std::uint64_t photons = 0;
    std::vector<DropBin> bins;
    std::vector<DropClass> classes;
    double dropped = 0;  // by the limits
    FarFieldResult far_field;
    nlohmann::json scene;
    double seconds = 0;
};

// 2. Rainbow angles per wavelength.
struct RainbowRow {
    double wavelength_nm = 0, n = 0;
    double primary = 0, primary_closed = 0;      // degrees: class 2's smallest scattering angle
    double secondary = 0, secondary_closed = 0;  // class 3's largest
};
struct RainbowStudy {
    double bin_deg = 0;
    std::uint64_t photons = 0;
    std::vector<RainbowRow> rows;
    double max_error = 0;
    nlohmann::json scene;
    double seconds = 0;
};

// 3. Prism deviation per wavelength.
struct PrismRow {
    double wavelength_nm = 0, n = 0, deviation = 0, deviation_closed = 0;  // degrees
};
struct PrismStudy {
    double apex_deg = 60, incidence_deg = 0, bin_deg = 0;
    std::vector<PrismRow> rows;
    double max_error = 0;
    nlohmann::json scene;
    double seconds = 0;
};

// 4. Slab transmittance per incidence angle.
struct SlabRow {
    double incidence_deg = 0;
    double T_s = 0, T_p = 0, T = 0;                       // measured (forward hemisphere)
    double T_s_closed = 0, T_p_closed = 0, T_closed = 0;
};
struct SlabStudy {
    double n = 1.5;
    std::vector<SlabRow> rows;
    double max_error = 0;
    double seconds = 0;
};

struct Result {
    bool quick = false;
    DropStudy drop;
    RainbowStudy rainbow;
    PrismStudy prism;
    SlabStudy slab;
    double seconds = 0;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
void run(const ExperimentOptions& opt);

}  // namespace refract::experiments::optics_bench
