#pragma once
// Yasuda, Yokoi, Toriwaki, Tsuruoka, Miyake (1984), "An Improved Ray Tracing Algorithm
// for Rendering Transparent Objects": Fig. 4, 7, 8, 9 and the cost claims of §5.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/core/render.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/op_count.h>
#include <refract/core/fields.h>

namespace refract::experiments::yasuda1984 {

void run(const ExperimentOptions& opt);  // compute, then write into opt.out_dir

// Fig. 7: the indices of refraction of panels (a) (n > 1) and (b) (n < 1).
const std::vector<double>& fig7_indices_a();
const std::vector<double>& fig7_indices_b();
// Fig. 8: the ten spheres (a) ... (j) and their names in the caption.
struct Fig8Sphere {
    char letter;
    double n;
    std::string label;  // "ice (0 °C)", "water", ...
};
const std::vector<Fig8Sphere>& fig8_spheres();
// Fig. 9: the constant reflectivities (a) ... (f).
const std::vector<double>& fig9_reflectivities();

// Transmissivity T(θ) = 1 − R(θ) for natural light at incidence angle θ (degrees).
double transmissivity(double angle_deg, double n);

// The largest T over 0–90° for index n, located to 1e-6°. `interior` is true when T
// rises above its normal-incidence value (a peak away from 0°).
struct TransmissivityPeak {
    double n = 0;
    double angle_deg = 0;
    double T = 0;
    double T0 = 0;  // at normal incidence
    bool interior = false;
};
TransmissivityPeak transmissivity_peak(double n);
// Smallest n (to 1e-6) for which T has an interior peak, and for which that peak lies
// at or beyond `angle_deg`.
double peak_onset_index();
double peak_beyond_index(double angle_deg);

// The scenes (built in code, saved as JSON under DIR/scenes/ and in the repository's
// scenes/yasuda1984/). `quick`: small images for tests.
nlohmann::json fig8_scene(double n, bool quick);
nlohmann::json fig9_scene(double reflectivity, bool quick);
nlohmann::json tree_growth_scene(int max_depth, double threshold, const std::string& integrator, bool quick);

// Cost of one branching node (§5): counted arithmetic per formulation and model.
struct NodeCost {
    std::string formulation;  // "yasuda1984" (eq. 2-5, 7) or "refract" (the dielectric node of core/interaction.h)
    std::string model;        // "constant", "fresnel", "schlick"
    OpCounts ops;
};
std::vector<NodeCost> count_node_costs();
OpCounts count_sphere_test();  // one ray-sphere intersection test (geometry/shapes.cpp)
OpCounts count_plane_test();   // one ray-plane intersection test

// §5 measured: counted arithmetic per node and per intersection test, time per node and per
// search, whole renders with constant and Fresnel reflectivity, and the peak memory of the
// stored tree against the list as the depth limit grows.
struct MemoryRow {
    int max_depth = 0;
    RenderStats whitted, list_threshold0, list_threshold_1_255;  // peak_list: nodes / entries per pixel
    std::uint64_t whitted_bytes = 0, list_bytes_threshold0 = 0, list_bytes_threshold_1_255 = 0;  // peak_list × size
};
struct CostResult {
    std::vector<NodeCost> node_costs;
    OpCounts sphere_test, plane_test;
    double ns_constant = 0, ns_fresnel = 0, ns_schlick = 0;  // SceneTracer::interact per node (fastest round)
    double ns_search = 0;                                    // one intersection search in the Fig. 8 scene
    int node_rounds = 0, render_rounds = 0;                  // timing rounds (fastest kept)
    int render_size = 0;                                     // the timed render's width = height
    double render_best[2] = {0, 0}, render_median[2] = {0, 0};  // [constant, fresnel], seconds, one thread
    RenderStats render_stats[2];
    std::vector<MemoryRow> memory;
    std::size_t whitted_node_bytes = 0, list_entry_bytes = 0;  // one stored node / one list entry
    nlohmann::json tree_growth_scene;                          // the memory study's scene, depth 16
};
CostResult compute_cost(const ExperimentOptions& opt);

// The cost numbers the summary compares (pure functions of the counts and times).
double muldiv_of(const CostResult& c, const std::string& formulation, const std::string& model);
double counted_increase(const CostResult& c, const std::string& formulation);  // Fresnel over constant − 1
double search_muldiv(const CostResult& c);              // the Fig. 8 scene's search: two spheres, two planes
double counted_segment_increase(const CostResult& c);   // (Fresnel − constant) / (constant node + search)
double measured_render_increase(const CostResult& c);   // fastest renders, Fresnel / constant − 1


// ---- The whole experiment: `compute` measures into a Result (numbers and images in
// memory), `write` turns it into CSV, figures, images, scenes and summary.md; `run` does both.

struct Fig4Row {
    double angle_deg = 0, Rs = 0, Rp = 0, R = 0;  // n = 1.5
};
struct Fig7Row {
    double n = 0, angle_deg = 0, T = 0;
};
struct RenderedPanel {
    std::string file;     // "fig8_a", "fig9_c", ...
    std::string caption;
    double value = 0;     // the sphere's index (Fig. 8) or the reflectivity (Fig. 9)
    nlohmann::json scene;
    Image image;
    RenderStats stats;
    // Fig. 8: the paraxial focus behind the sphere's centre (a ball lens of radius 1,
    // n / (2(n − 1)); negative: diverging) and, for n < 1, the share of the disc beyond the
    // critical angle (parallel light: 1 − n²).
    double focus = 0, tir_share = 0;
};
struct CriticalAngle {
    double n = 0, angle_deg = 0;
};

// What the summary states beside its tables, each from the numbers (`judge`); write() picks
// the wording each way (the *_text functions below).
struct Findings {
    bool rs_rp_close_below_40 = false;  // Rs − Rp < 0.1 up to 40°: one alone changes the picture little (the paper)
    bool R_one_at_grazing = false;      // Fig. 4's R is 1 at 90°
    bool paper_peak_holds = false;      // interior peak beyond 70° for n = 5 and 10 (the paper: n ≳ 5)
    bool onset_is_closed_form = false;  // the measured onset is 2 + √3 (to 1e-5)
    bool peak_moves_to_grazing = false; // the interior peaks' angles grow with n
    bool low_n_rise = false;            // n = 0.2 and 0.1: T rises above T(0°) before the critical angle
    bool zero_beyond_critical = false;  // n < 1: T = 0 beyond the critical angle (at it, rounding leaves ~1e-7)
    bool lenses_as_described = false;   // n > 1: focus in front of the wall (inverted); n < 1: diverging
    bool mirror_rim_and_whole = false;  // TIR share of the disc: n = 0.8 under half, n = 0.1 over 0.9
    bool high_n_mirror_like = false;    // R(0°) of n = 10 above n = 5's, both above 0.25
    bool fresnel_rim_brightens = false; // glass (1.52): R at 80° over twice R at 0°
    bool count_about_40 = false;        // the paper's formulation: Fresnel adds 30-50 % multiplications/divisions
    bool test_about_quarter = false;    // a sphere test is 20-30 % of the paper's constant node
    bool identical_trees = false;         // the timed renders (constant, Fresnel) trace the same segments and nodes
    bool measured_below_counted = false;  // the render's time increase below the counted per-segment one
    bool list_about_half_tree = false;  // threshold 0: deepest list 25-75 % of the stored tree
    bool threshold_list_flat = false;   // threshold 1/255: the list stops growing (same peak at half and full depth)
};

struct Result {
    bool quick = false;
    std::vector<Fig4Row> fig4;                // 0–90° in 0.5° steps
    std::vector<Fig7Row> fig7;                // panels (a) and (b), 0.1° steps plus the critical angle
    std::vector<TransmissivityPeak> peaks;    // Fig. 7's indices and a few more, ascending
    double peak_onset = 0, peak_beyond_70 = 0;
    // Numbers quoted beside the figures: Fig. 4 at 0°, at Brewster's angle and Rs − Rp at 40°;
    // Fig. 7's closed-form onset and the critical angles of panel (b); Fig. 8's R(0°) of
    // n = 5 and 10, the wall's distance behind the sphere's centre (radius 1); Fig. 9's
    // glass R at 0° and 80°.
    double R0 = 0, brewster_deg = 0, Rp_brewster = 0, R_brewster = 0, rs_rp_gap_40 = 0;
    double onset_closed_form = 0;  // 2 + √3
    std::vector<CriticalAngle> critical;
    double R0_n5 = 0, R0_n10 = 0, wall_distance = 0;
    double glass_R0 = 0, glass_R80 = 0;
    std::vector<RenderedPanel> fig8, fig9;
    CostResult cost;
    Findings findings;  // judge(*this), set by compute
};

Result compute(const ExperimentOptions& opt);
void write(const Result& r, const std::string& dir);
// Writes cost.csv, cost_render.csv, memory.csv, the memory figure and scenes/tree_growth.json
// (yasuda_cost.cpp); returns the summary's §5 sections.
std::string write_cost(const Result& r, const std::string& dir);

// The findings from a Result's numbers (pure; compute stores them in Result::findings).
Findings judge(const Result& r);
// The summary's sentences that state them, worded by r.findings.
std::string fig4_text(const Result& r);
std::string fig7_text(const Result& r);
std::string fig8_text(const Result& r);
std::string fig9_text(const Result& r);
std::string cost_text(const Result& r);    // the count against "about 40 %", the test against the node
std::string trees_text(const Result& r);   // the timed renders' trees: identical?
std::string time_text(const Result& r);    // measured against counted: the paper's conclusion
std::string memory_text(const Result& r);

}  // namespace refract::experiments::yasuda1984

namespace refract {

template <>
struct Fields<experiments::yasuda1984::Fig4Row> {
    static auto list() {
        using R = experiments::yasuda1984::Fig4Row;
        return std::make_tuple(field("angle_deg", &R::angle_deg), field("Rs", &R::Rs), field("Rp", &R::Rp),
                               field("R", &R::R));
    }
};
template <>
struct Fields<experiments::yasuda1984::Fig7Row> {
    static auto list() {
        using R = experiments::yasuda1984::Fig7Row;
        return std::make_tuple(field("n", &R::n), field("angle_deg", &R::angle_deg), field("T", &R::T));
    }
};
template <>
struct Fields<experiments::yasuda1984::TransmissivityPeak> {
    static auto list() {
        using P = experiments::yasuda1984::TransmissivityPeak;
        return std::make_tuple(field("n", &P::n), field("angle_deg", &P::angle_deg).csv("peak_angle_deg").digits(8),
                               field("T", &P::T).csv("T_peak").digits(8), field("T0", &P::T0).csv("T_0").digits(8),
                               field("interior", &P::interior).csv("interior_peak"));
    }
};
template <>
struct Fields<experiments::yasuda1984::RenderedPanel> {
    static auto list() {
        using P = experiments::yasuda1984::RenderedPanel;
        return std::make_tuple(
            field("file", &P::file).python_only(),
            derived<P>("panel", [](const P& p) { return p.file.substr(5); }).csv_only(),
            field("caption", &P::caption).python_only(), field("value", &P::value).csv("n"),
            field("scene", &P::scene).python_only(), field("rgb", &P::image).python_only(),
            derived<P>("seconds", [](const P& p) { return p.stats.seconds; }).digits(4),
            derived<P>("segments", [](const P& p) { return p.stats.segments; }),
            derived<P>("tree_nodes", [](const P& p) { return p.stats.tree_nodes; }),
            derived<P>("pruned", [](const P& p) { return p.stats.pruned; }),
            derived<P>("peak_list", [](const P& p) { return p.stats.peak_list; }),
            field("focus", &P::focus).python_only(), field("tir_share", &P::tir_share).python_only());
    }
};
template <>
struct Fields<experiments::yasuda1984::NodeCost> {
    static auto list() {
        using N = experiments::yasuda1984::NodeCost;
        return std::make_tuple(field("formulation", &N::formulation), field("model", &N::model),
                               derived<N>("mul", [](const N& n) { return n.ops.mul; }),
                               derived<N>("div", [](const N& n) { return n.ops.div; }),
                               derived<N>("add", [](const N& n) { return n.ops.add; }),
                               derived<N>("sqrt", [](const N& n) { return n.ops.sqrt; }),
                               derived<N>("cmp", [](const N& n) { return n.ops.cmp; }));
    }
};
template <>
struct Fields<experiments::yasuda1984::MemoryRow> {
    static auto list() {
        using M = experiments::yasuda1984::MemoryRow;
        return std::make_tuple(
            field("max_depth", &M::max_depth),
            derived<M>("whitted_peak_nodes", [](const M& m) { return m.whitted.peak_list; }),
            field("whitted_bytes", &M::whitted_bytes).csv_only(),
            derived<M>("list_peak_entries_threshold0", [](const M& m) { return m.list_threshold0.peak_list; }),
            field("list_bytes_threshold0", &M::list_bytes_threshold0).csv_only(),
            derived<M>("list_peak_entries_threshold_1_255", [](const M& m) { return m.list_threshold_1_255.peak_list; }),
            field("list_bytes_threshold_1_255", &M::list_bytes_threshold_1_255).csv_only(),
            derived<M>("segments_per_pixel",
                       [](const M& m) {
                           return static_cast<double>(m.list_threshold0.segments) / static_cast<double>(m.whitted.primary_rays);
                       })
                .digits(6)
                .csv_only());
    }
};
template <>
struct Fields<experiments::yasuda1984::CostResult> {
    static auto list() {
        using C = experiments::yasuda1984::CostResult;
        return std::make_tuple(field("node_costs", &C::node_costs),
                               derived<C>("sphere_test_muldiv", [](const C& c) { return c.sphere_test.muldiv(); }),
                               derived<C>("plane_test_muldiv", [](const C& c) { return c.plane_test.muldiv(); }),
                               field("ns_constant", &C::ns_constant), field("ns_fresnel", &C::ns_fresnel),
                               field("ns_schlick", &C::ns_schlick), field("ns_search", &C::ns_search),
                               derived<C>("render_constant", [](const C& c) { return c.render_best[0]; }),
                               derived<C>("render_fresnel", [](const C& c) { return c.render_best[1]; }),
                               field("memory", &C::memory));
    }
};
template <>
struct Fields<experiments::yasuda1984::Findings> {
    static auto list() {
        using F = experiments::yasuda1984::Findings;
        return std::make_tuple(
            field("rs_rp_close_below_40", &F::rs_rp_close_below_40), field("R_one_at_grazing", &F::R_one_at_grazing),
            field("paper_peak_holds", &F::paper_peak_holds), field("onset_is_closed_form", &F::onset_is_closed_form),
            field("peak_moves_to_grazing", &F::peak_moves_to_grazing), field("low_n_rise", &F::low_n_rise),
            field("zero_beyond_critical", &F::zero_beyond_critical), field("lenses_as_described", &F::lenses_as_described),
            field("mirror_rim_and_whole", &F::mirror_rim_and_whole), field("high_n_mirror_like", &F::high_n_mirror_like),
            field("fresnel_rim_brightens", &F::fresnel_rim_brightens), field("count_about_40", &F::count_about_40),
            field("test_about_quarter", &F::test_about_quarter), field("identical_trees", &F::identical_trees),
            field("measured_below_counted", &F::measured_below_counted),
            field("list_about_half_tree", &F::list_about_half_tree), field("threshold_list_flat", &F::threshold_list_flat));
    }
};
template <>
struct Fields<experiments::yasuda1984::Result> {
    static auto list() {
        using R = experiments::yasuda1984::Result;
        return std::make_tuple(field("quick", &R::quick), field("fig4", &R::fig4).table(), field("fig7", &R::fig7).table(),
                               field("peaks", &R::peaks), field("peak_onset", &R::peak_onset),
                               field("peak_beyond_70", &R::peak_beyond_70), field("fig8", &R::fig8), field("fig9", &R::fig9),
                               field("cost", &R::cost), field("findings", &R::findings));
    }
};

}  // namespace refract
