#pragma once
// The round brilliant's geometry (geometry/gem/brilliant.h, docs/gems.md): line drawings of
// each preset as the trade draws them (crown from above, pavilion from below, side
// profile), the proportions measured back from the exact polyhedron against the requested
// and closed-form values, a rendered Fresnel diamond (no dispersion) per preset, and the
// cost of a ray–gem intersection with the plane set against the triangle mesh.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/render.h>
#include <refract/experiments/experiment.h>
#include <refract/geometry/gem/brilliant.h>

namespace refract::experiments::gem_geometry {

void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// One proportion of one preset: requested (or closed form, for the derived heights)
// against measured on the exact polyhedron.
struct ProportionRow {
    std::string preset;
    std::string quantity;  // "table", "crown_angle", ..., "total_depth"
    std::string unit;      // "%" of the girdle diameter, or "deg"
    std::string source;    // "requested" or "closed form"
    double expected = 0;
    double measured = 0;
};
std::vector<ProportionRow> proportion_rows(const std::string& preset, const Gem& gem);

// The rendered diamond of a preset: a Fresnel diamond (n = 2.417) on a checker floor.
nlohmann::json render_scene(const std::string& preset, bool quick);

// Outlines of the facets seen in one view, projected to the drawing plane (x right, y up):
// "crown" from above (+z), "pavilion" from below, "side" from −y (x right, z up). A
// convex solid shows exactly the facets whose outward normals face the viewer.
struct Outline {
    std::string label;
    std::vector<std::pair<double, double>> points;  // closed loop (first point repeated)
};
std::vector<Outline> outlines(const Gem& gem, const std::string& view);

// The same random rays (from a sphere of radius 3 towards the gem's bounding box, in the
// gem's own frame) intersected with the plane set and with the triangle mesh.
struct IntersectionTiming {
    std::string preset;
    int planes = 0, triangles = 0;
    long rays = 0, hits = 0, agree = 0;  // agree: same hit or miss, t within 1e-9, same facet
    double plane_ns = 0, mesh_ns = 0;    // wall time per ray (best of a few passes)
};
IntersectionTiming time_intersections(const std::string& preset, const Gem& gem, long rays);

// ---- The whole experiment: `compute` measures into a Result (numbers and images in
// memory), `write` turns it into CSV, figures, scenes and summary.md; `run` does both.

struct PresetResult {
    std::string preset;
    Gem gem;
    std::vector<ProportionRow> proportions;
    std::vector<std::pair<std::string, int>> facet_counts;
    IntersectionTiming timing;
    nlohmann::json scene;  // the rendered Fresnel diamond's scene
    RenderResult render;
    std::vector<std::pair<std::string, std::vector<Outline>>> outlines;  // per view: "crown", "pavilion", "side"
};

struct Result {
    bool quick = false;
    std::vector<PresetResult> presets;  // brilliant_preset_names() order
    double worst = 0;                   // largest |measured − expected| over the proportions
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::gem_geometry

namespace refract {

template <>
struct Fields<experiments::gem_geometry::ProportionRow> {
    static auto list() {
        using P = experiments::gem_geometry::ProportionRow;
        return std::make_tuple(field("preset", &P::preset), field("quantity", &P::quantity), field("unit", &P::unit),
                               field("source", &P::source), field("expected", &P::expected), field("measured", &P::measured),
                               derived<P>("abs_diff", [](const P& p) { return std::abs(p.measured - p.expected); }).csv_only());
    }
};
template <>
struct Fields<experiments::gem_geometry::IntersectionTiming> {
    static auto list() {
        using T = experiments::gem_geometry::IntersectionTiming;
        return std::make_tuple(field("preset", &T::preset), field("planes", &T::planes), field("triangles", &T::triangles),
                               field("rays", &T::rays), field("hits", &T::hits), field("agree", &T::agree),
                               field("plane_ns", &T::plane_ns).csv("plane_ns_per_ray").digits(4),
                               field("mesh_ns", &T::mesh_ns).csv("mesh_ns_per_ray").digits(4),
                               derived<T>("mesh_over_plane", [](const T& t) { return t.mesh_ns / t.plane_ns; }).digits(3).csv_only());
    }
};
// The rendered diamond of gem_renders.csv, and the preset's dict in Python.
template <>
struct Fields<experiments::gem_geometry::PresetResult> {
    static auto list() {
        using P = experiments::gem_geometry::PresetResult;
        return std::make_tuple(field("preset", &P::preset), field("proportions", &P::proportions).python_only(),
                               field("facet_counts", &P::facet_counts).python_only(),
                               field("timing", &P::timing).python_only(), field("scene", &P::scene).python_only(),
                               derived<P>("rgb", [](const P& p) -> const Image& { return p.render.image; }).python_only(),
                               derived<P>("width", [](const P& p) { return p.render.image.width; }).csv_only(),
                               derived<P>("height", [](const P& p) { return p.render.image.height; }).csv_only(),
                               derived<P>("render_seconds", [](const P& p) { return p.render.stats.seconds; })
                                   .csv("seconds")
                                   .digits(3),
                               derived<P>("primary_rays", [](const P& p) { return p.render.stats.primary_rays; }).csv_only(),
                               derived<P>("segments", [](const P& p) { return p.render.stats.segments; }).csv_only(),
                               derived<P>("shadow_rays", [](const P& p) { return p.render.stats.shadow_rays; }).csv_only());
    }
};
template <>
struct Fields<experiments::gem_geometry::Result> {
    static auto list() {
        using R = experiments::gem_geometry::Result;
        return std::make_tuple(field("quick", &R::quick), field("worst", &R::worst), field("presets", &R::presets));
    }
};

}  // namespace refract
