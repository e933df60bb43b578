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

#include <refract/core/far_field.h>
#include <refract/core/fields.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/far_field_output.h>

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
    FarFieldTables far_field_tables;  // far_field's files (drop_far_field/)
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

// The names of the drop's path classes (van de Hulst p = 0 … 3).
const char* class_name(int p);

}  // namespace refract::experiments::optics_bench

namespace refract {

template <>
struct Fields<experiments::optics_bench::DropBin> {
    static auto list() {
        using B = experiments::optics_bench::DropBin;
        return std::make_tuple(field("cls", &B::cls).csv("class"), field("theta0_deg", &B::theta0_deg).digits(6),
                               field("theta1_deg", &B::theta1_deg).digits(6), field("measured", &B::measured).digits(10),
                               field("measured_s", &B::measured_s).digits(10), field("measured_p", &B::measured_p).digits(10),
                               field("closed", &B::closed).digits(10), field("closed_s", &B::closed_s).digits(10),
                               field("closed_p", &B::closed_p).digits(10));
    }
};
template <>
struct Fields<experiments::optics_bench::DropClass> {
    static auto list() {
        using C = experiments::optics_bench::DropClass;
        return std::make_tuple(
            field("cls", &C::cls).csv("class"),
            derived<C>("path", [](const C& c) { return experiments::optics_bench::class_name(c.cls); }).csv_only(),
            field("total", &C::total).csv("measured").digits(7), field("total_closed", &C::total_closed).csv("closed form").digits(7),
            derived<C>("difference", [](const C& c) { return c.total - c.total_closed; }).digits(3).csv_only(),
            field("max_bin_error", &C::max_bin_error).csv("max bin difference").digits(3),
            field("max_z", &C::max_z).csv("max bin z-score").digits(3));
    }
};
template <>
struct Fields<experiments::optics_bench::DropStudy> {
    static auto list() {
        using D = experiments::optics_bench::DropStudy;
        return std::make_tuple(field("n", &D::n), field("photons", &D::photons), field("bins", &D::bins),
                               field("classes", &D::classes), field("dropped", &D::dropped), field("seconds", &D::seconds));
    }
};
template <>
struct Fields<experiments::optics_bench::RainbowRow> {
    static auto list() {
        using R = experiments::optics_bench::RainbowRow;
        return std::make_tuple(
            field("wavelength_nm", &R::wavelength_nm).digits(6), field("n", &R::n).digits(8),
            field("primary", &R::primary).csv("primary_deg").digits(8),
            field("primary_closed", &R::primary_closed).csv("primary_closed_deg").digits(8),
            derived<R>("primary_difference", [](const R& r) { return r.primary - r.primary_closed; }).digits(3).csv_only(),
            field("secondary", &R::secondary).csv("secondary_deg").digits(8),
            field("secondary_closed", &R::secondary_closed).csv("secondary_closed_deg").digits(8),
            derived<R>("secondary_difference", [](const R& r) { return r.secondary - r.secondary_closed; }).digits(3).csv_only());
    }
};
template <>
struct Fields<experiments::optics_bench::RainbowStudy> {
    static auto list() {
        using S = experiments::optics_bench::RainbowStudy;
        return std::make_tuple(field("bin_deg", &S::bin_deg), field("photons", &S::photons), field("rows", &S::rows),
                               field("max_error", &S::max_error), field("seconds", &S::seconds));
    }
};
template <>
struct Fields<experiments::optics_bench::PrismRow> {
    static auto list() {
        using R = experiments::optics_bench::PrismRow;
        return std::make_tuple(
            field("wavelength_nm", &R::wavelength_nm).digits(6), field("n", &R::n).digits(8),
            field("deviation", &R::deviation).csv("deviation_deg").digits(8),
            field("deviation_closed", &R::deviation_closed).csv("closed_deg").digits(8),
            derived<R>("difference_deg", [](const R& r) { return r.deviation - r.deviation_closed; }).digits(3).csv_only());
    }
};
template <>
struct Fields<experiments::optics_bench::PrismStudy> {
    static auto list() {
        using S = experiments::optics_bench::PrismStudy;
        return std::make_tuple(field("apex_deg", &S::apex_deg), field("incidence_deg", &S::incidence_deg),
                               field("bin_deg", &S::bin_deg), field("rows", &S::rows), field("max_error", &S::max_error),
                               field("seconds", &S::seconds));
    }
};
template <>
struct Fields<experiments::optics_bench::SlabRow> {
    static auto list() {
        using R = experiments::optics_bench::SlabRow;
        return std::make_tuple(field("incidence_deg", &R::incidence_deg).digits(6), field("T_s", &R::T_s).digits(12),
                               field("T_p", &R::T_p).digits(12), field("T", &R::T).digits(12),
                               field("T_s_closed", &R::T_s_closed).digits(12), field("T_p_closed", &R::T_p_closed).digits(12),
                               field("T_closed", &R::T_closed).digits(12));
    }
};
template <>
struct Fields<experiments::optics_bench::SlabStudy> {
    static auto list() {
        using S = experiments::optics_bench::SlabStudy;
        return std::make_tuple(field("n", &S::n), field("rows", &S::rows), field("max_error", &S::max_error),
                               field("seconds", &S::seconds));
    }
};
template <>
struct Fields<experiments::optics_bench::Result> {
    static auto list() {
        using R = experiments::optics_bench::Result;
        return std::make_tuple(field("quick", &R::quick), field("seconds", &R::seconds), field("drop", &R::drop),
                               field("rainbow", &R::rainbow), field("prism", &R::prism), field("slab", &R::slab));
    }
};

}  // namespace refract
