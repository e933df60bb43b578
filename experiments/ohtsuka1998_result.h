#pragma once
// ohtsuka1998 as data: `compute` measures the main image (full split and shortcut), the
// floor-map and shortcut studies and the light the limits drop into a Result (numbers and
// images in memory); `write` turns it into images, CSV, figures, scenes and summary.md.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/image.h>
#include <refract/core/render.h>
#include <refract/experiments/ohtsuka1998.h>
#include <refract/experiments/ohtsuka1998_maps.h>

namespace refract::experiments::ohtsuka1998 {

// Two images compared: linear-RGB RMSE and max, CIEDE2000 of the values read as linear sRGB.
struct Diff {
    double rmse = 0, max = 0, de_mean = 0, de_max = 0;
};

struct StepRow {
    double step_nm = 0;
    Diff against_1nm;
    double light_s = 0, eye_s = 0;
};
struct ShortcutRow {
    std::string label;    // the threshold, or "paper" / "measured" for the wavelength choice
    double threshold = 0;
    double wavelengths[3] = {0, 0, 0};
    double taken_fraction = 0, speedup_time = 0, speedup_segments = 0;
    Diff against_full;
};
struct LostRow {
    bool paper_limits = false;
    int max_depth = 0;
    double threshold = 0;
    RenderStats stats;
    double worst_pixel = 0;       // the largest dropped fraction in one pixel
    double rmse_vs_deepest = 0;
};

struct Result {
    bool quick = false;
    int threads_used = 0;
    SceneParams base, shortcut, box, first, study;  // the main image's, its variants', the studies'
    // Their scene files: scene.json, scene-shortcut.json, scene-box.json, scene-first.json.
    nlohmann::json base_scene, shortcut_scene, box_scene, first_scene;
    // The main image: light pass + full split, the shortcut over the same maps, the box-read
    // floor, and the first version's floor (fewer photons, box elements).
    RenderResult full, fast;
    Image box_image, first_image;
    Image difference_x10;  // |full − shortcut| × 10, clipped at 1
    double light_s = 0, eye_s = 0;
    std::uint64_t map_elements = 0, map_photons = 0, map_deposits = 0;
    std::size_t gem_planes = 0;
    Diff shortcut_diff;
    std::vector<StepRow> steps;
    MapStudyPlan plan;
    MapStudies maps;
    std::vector<ShortcutRow> thresholds, peaks;
    std::vector<LostRow> lost;
    double seconds = 0;
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::ohtsuka1998

namespace refract {

template <>
struct Fields<experiments::ohtsuka1998::Diff> {
    static auto list() {
        using D = experiments::ohtsuka1998::Diff;
        return std::make_tuple(field("rmse", &D::rmse), field("max", &D::max), field("delta_e_mean", &D::de_mean),
                               field("delta_e_max", &D::de_max));
    }
};
template <>
struct Fields<experiments::ohtsuka1998::StepRow> {
    static auto list() {
        using S = experiments::ohtsuka1998::StepRow;
        return std::make_tuple(
            field("step_nm", &S::step_nm),
            derived<S>("bands", [](const S& s) { return static_cast<int>(std::lround(300 / s.step_nm)) + 1; }).csv_only(),
            derived<S>("rmse", [](const S& s) { return s.against_1nm.rmse; }).csv_only(),
            derived<S>("max", [](const S& s) { return s.against_1nm.max; }).csv_only(),
            derived<S>("de_mean", [](const S& s) { return s.against_1nm.de_mean; }).csv_only(),
            field("against_1nm", &S::against_1nm).python_only(), field("light_s", &S::light_s), field("eye_s", &S::eye_s));
    }
};
template <>
struct Fields<experiments::ohtsuka1998::MapStudyRow> {
    static auto list() {
        using M = experiments::ohtsuka1998::MapStudyRow;
        return std::make_tuple(field("element_size", &M::element_size), field("elements", &M::elements),
                               field("photons", &M::photons),
                               derived<M>("filter", [](const M& m) { return filter_name(m.filter); }),
                               field("deposits_per_element", &M::deposits_per_element).digits(4),
                               derived<M>("error", [](const M& m) { return m.e.error; }).digits(4),
                               derived<M>("noise", [](const M& m) { return m.e.noise; }).digits(4),
                               derived<M>("bias", [](const M& m) { return m.e.bias; }).digits(4),
                               field("light_s", &M::light_s).digits(3));
    }
};
// Two tables: shortcut_threshold.csv and shortcut_peaks.csv (ohtsuka1998.cpp chooses the columns).
template <>
struct Fields<experiments::ohtsuka1998::ShortcutRow> {
    static auto list() {
        using S = experiments::ohtsuka1998::ShortcutRow;
        return std::make_tuple(
            field("label", &S::label).python_only(), field("threshold", &S::threshold).python_only(),
            field("wavelengths", &S::wavelengths).python_only(),
            derived<S>("threshold_label", [](const S& s) { return s.label; }).csv("threshold").csv_only(),
            derived<S>("wavelengths_label", [](const S& s) { return s.label; }).csv("wavelengths").csv_only(),
            derived<S>("r_nm", [](const S& s) { return s.wavelengths[0]; }).digits(5).csv_only(),
            derived<S>("g_nm", [](const S& s) { return s.wavelengths[1]; }).digits(5).csv_only(),
            derived<S>("b_nm", [](const S& s) { return s.wavelengths[2]; }).digits(5).csv_only(),
            field("taken_fraction", &S::taken_fraction), field("speedup_time", &S::speedup_time),
            field("speedup_segments", &S::speedup_segments),
            derived<S>("rmse", [](const S& s) { return s.against_full.rmse; }).csv_only(),
            derived<S>("de_mean", [](const S& s) { return s.against_full.de_mean; }).csv_only(),
            field("against_full", &S::against_full).python_only());
    }
};
template <>
struct Fields<experiments::ohtsuka1998::LostRow> {
    static auto list() {
        using L = experiments::ohtsuka1998::LostRow;
        // The dropped weights per primary ray.
        auto per_ray = [](double v, const L& l) { return v / static_cast<double>(l.stats.primary_rays); };
        return std::make_tuple(
            field("paper_limits", &L::paper_limits).python_only(),
            derived<L>("limits", [](const L& l) { return std::string(l.paper_limits ? "8/8" : "none"); }).csv_only(),
            field("max_depth", &L::max_depth), field("threshold", &L::threshold),
            derived<L>("lost_depth", [=](const L& l) { return per_ray(l.stats.lost_depth, l); }),
            derived<L>("lost_limits", [=](const L& l) { return per_ray(l.stats.lost_limits, l); }),
            derived<L>("lost_threshold", [=](const L& l) { return per_ray(l.stats.lost_threshold, l); }),
            derived<L>("lost_total",
                       [=](const L& l) {
                           return per_ray(l.stats.lost_depth + l.stats.lost_limits + l.stats.lost_threshold, l);
                       })
                .csv_only(),
            field("worst_pixel", &L::worst_pixel), field("rmse_vs_deepest", &L::rmse_vs_deepest),
            derived<L>("eye_s", [](const L& l) { return l.stats.seconds; }).csv_only());
    }
};
template <>
struct Fields<experiments::ohtsuka1998::Result> {
    static auto list() {
        using R = experiments::ohtsuka1998::Result;
        return std::make_tuple(
            field("quick", &R::quick), derived<R>("full", [](const R& r) -> const Image& { return r.full.image; }),
            derived<R>("shortcut", [](const R& r) -> const Image& { return r.fast.image; }),
            field("box", &R::box_image), field("first", &R::first_image), field("light_s", &R::light_s),
            field("eye_s", &R::eye_s), derived<R>("eye_shortcut_s", [](const R& r) { return r.fast.stats.seconds; }),
            derived<R>("shortcut_taken", [](const R& r) { return r.fast.stats.shortcut_taken; }),
            derived<R>("shortcut_tests", [](const R& r) { return r.fast.stats.shortcut_tests; }),
            field("map_elements", &R::map_elements), field("map_photons", &R::map_photons),
            field("map_deposits", &R::map_deposits), field("shortcut_diff", &R::shortcut_diff), field("steps", &R::steps),
            field("thresholds", &R::thresholds), field("peaks", &R::peaks), field("lost", &R::lost),
            derived<R>("map_by_photons", [](const R& r) { return r.maps.by_photons; }),
            derived<R>("map_by_element", [](const R& r) { return r.maps.by_element; }), field("seconds", &R::seconds));
    }
};

}  // namespace refract
