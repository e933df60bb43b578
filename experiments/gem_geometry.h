#pragma once
// The round brilliant's geometry (geometry/gem/brilliant.h, docs/gems.md): line drawings of
// each preset as the trade draws them (crown from above, pavilion from below, side
// profile), the proportions measured back from the exact polyhedron against the requested
// and closed-form values, a rendered Fresnel diamond (no dispersion) per preset, and the
// cost of a ray–gem intersection with the plane set against the triangle mesh.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/render.h"
#include "experiments/experiment.h"
#include "geometry/gem/brilliant.h"

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
};

struct Result {
    bool quick = false;
    std::vector<PresetResult> presets;  // brilliant_preset_names() order
    double worst = 0;                   // largest |measured − expected| over the proportions
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);

}  // namespace refract::experiments::gem_geometry
