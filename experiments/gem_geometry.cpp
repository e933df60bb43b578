// The round brilliant's geometry: line drawings, proportions measured back, a rendered
// Fresnel diamond per preset, and the plane-set against triangle-mesh intersection cost.
#include <refract/experiments/gem_geometry.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <sstream>

#include <refract/core/provenance.h>
#include <refract/core/random.h>
#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::gem_geometry {
namespace fs = std::filesystem;
using nlohmann::json;

std::vector<ProportionRow> proportion_rows(const std::string& preset, const Gem& gem) {
    const BrilliantProportions want = closed_form_proportions(gem.cut), got = gem.measured;
    struct Q {
        const char* name;
        const char* unit;
        double BrilliantProportions::*field;
        bool derived;
    };
    static const Q qs[] = {
        {"table", "%", &BrilliantProportions::table, false},
        {"crown_angle", "deg", &BrilliantProportions::crown_angle, false},
        {"pavilion_angle", "deg", &BrilliantProportions::pavilion_angle, false},
        {"star", "%", &BrilliantProportions::star, false},
        {"lower_half", "%", &BrilliantProportions::lower_half, false},
        {"girdle", "%", &BrilliantProportions::girdle, false},
        {"culet", "%", &BrilliantProportions::culet, false},
        {"crown_height", "%", &BrilliantProportions::crown_height, true},
        {"pavilion_depth", "%", &BrilliantProportions::pavilion_depth, true},
        {"total_depth", "%", &BrilliantProportions::total_depth, true},
    };
    std::vector<ProportionRow> rows;
    for (const Q& q : qs)
        rows.push_back({preset, q.name, q.unit, q.derived ? "closed form" : "requested", want.*q.field, got.*q.field});
    return rows;
}

json render_scene(const std::string& preset, bool quick) {
    const json floor = {{"type", "diffuse"},
                        {"color", vec(0.9, 0.9, 0.85)},
                        {"checker", {{"color2", vec(0.15, 0.25, 0.55)}, {"size", 0.5}}}};
    return json{
        {"description", "Round brilliant, preset '" + preset +
                            "', as a Fresnel diamond (n = 2.417, no dispersion) on a checker floor, point light"},
        {"camera",
         {{"location", vec(1.0, 5.0, -5.6)}, {"look_at", vec(0, 0.6, 0)}, {"angle", 34},
          {"width", quick ? 80 : 480}, {"height", quick ? 60 : 360}}},
        {"background", vec(0.55, 0.7, 0.9)},
        {"materials", {{"floor", floor}, {"diamond", {{"type", "dielectric"}, {"ior", 2.417}}}}},
        {"objects",
         json::array({{{"type", "plane"}, {"name", "floor"}, {"normal", vec(0, 1, 0)}, {"offset", 0}, {"material", "floor"}},
                      {{"type", "brilliant"}, {"name", "diamond"}, {"preset", preset}, {"position", vec(0, 0.95, 0)},
                       {"diameter", 2}, {"material", "diamond"}}})},
        {"lights", json::array({{{"position", vec(-2, 8, -5)}, {"color", vec(1, 1, 1)}}})},
        {"render", {{"max_depth", 12}}},
    };
}

std::vector<Outline> outlines(const Gem& gem, const std::string& view) {
    std::vector<Outline> out;
    for (const GemFacet& f : gem.facets) {
        const Vec3& n = f.plane.normal;
        const double facing = view == "crown" ? n.z() : view == "pavilion" ? -n.z() : -n.y();
        if (facing <= 1e-12) continue;  // back facets and (for top/bottom) the vertical girdle
        Outline o{f.label, {}};
        for (size_t k = 0; k <= f.polygon.size(); ++k) {
            const Vec3& p = f.polygon[k % f.polygon.size()];
            if (view == "crown") o.points.emplace_back(p.x(), p.y());
            else if (view == "pavilion") o.points.emplace_back(-p.x(), p.y());  // seen from below: mirrored
            else o.points.emplace_back(p.x(), p.z());
        }
        out.push_back(std::move(o));
    }
    return out;
}

IntersectionTiming time_intersections(const std::string& preset, const Gem& gem, long rays) {
    std::uint64_t stream = 0;
    for (const char c : preset) stream = stream * 131 + static_cast<unsigned char>(c);
    Rng rng(2024, stream);
    std::vector<Ray> rs(static_cast<size_t>(rays));
    for (Ray& r : rs) {
        r.origin = 3.0 * rng.unit_vector();
        const Vec3 target(2.2 * (rng.uniform() - 0.5), 2.2 * (rng.uniform() - 0.5), -1.0 + 1.3 * rng.uniform());
        r.dir = (target - r.origin).normalized();
    }
    IntersectionTiming t;
    t.preset = preset;
    t.planes = static_cast<int>(gem.solid.planes.size());
    t.triangles = static_cast<int>(gem.mesh.triangles.size());
    t.rays = rays;
    std::vector<std::optional<Hit>> hp(rs.size()), hm(rs.size());
    using clock = std::chrono::steady_clock;
    auto pass = [&](auto&& shape, std::vector<std::optional<Hit>>& hits) {
        const auto t0 = clock::now();
        for (size_t i = 0; i < rs.size(); ++i) hits[i] = intersect(shape, rs[i], 1e-9, 1e30);
        return std::chrono::duration<double, std::nano>(clock::now() - t0).count() / static_cast<double>(rs.size());
    };
    t.plane_ns = t.mesh_ns = INFINITY;
    for (int rep = 0; rep < 3; ++rep) {  // best of three passes, interleaved
        t.plane_ns = std::min(t.plane_ns, pass(gem.solid, hp));
        t.mesh_ns = std::min(t.mesh_ns, pass(gem.mesh, hm));
    }
    for (size_t i = 0; i < rs.size(); ++i) {
        if (hp[i]) ++t.hits;
        if (hp[i].has_value() != hm[i].has_value()) continue;
        if (!hp[i]) {
            ++t.agree;
            continue;
        }
        const std::string& lp = gem.solid.labels[static_cast<size_t>(hp[i]->facet)];
        const std::string& lm = gem.facets[static_cast<size_t>(gem.triangle_facet[static_cast<size_t>(hm[i]->facet)])].label;
        if (std::abs(hp[i]->t - hm[i]->t) <= 1e-9 && lp == lm) ++t.agree;
    }
    return t;
}

namespace {

std::string outline_text(const PresetResult& pr) {
    // gnuplot data: one index block per view (two blank lines), one polygon per block
    // of lines (one blank line).
    std::ostringstream o;
    o << "# facet outlines of the round brilliant (girdle radius 1): x,y\n"
      << "# index 0: crown from above; 1: pavilion from below (mirrored); 2: side, from -y (x, z)\n";
    bool first_view = true;
    for (const auto& [view, lines] : pr.outlines) {
        if (!first_view) o << "\n\n";
        first_view = false;
        o << "# " << view << "\n";
        bool first = true;
        for (const Outline& ol : lines) {
            if (!first) o << "\n";
            first = false;
            o << "# " << ol.label << "\n";
            for (const auto& [x, y] : ol.points) o << fmt(x) << "," << fmt(y) << "\n";
        }
    }
    return o.str();
}

std::string drawings_body(const std::vector<std::string>& presets) {
    std::ostringstream b;
    b << "set datafile separator comma\n"
      << "set multiplot layout " << presets.size() << ",3 title \"Round brilliant: facet outlines (crown from above, "
      << "pavilion from below, side profile)\" font \",13\"\n"
      << "unset border; unset tics; unset key; set size ratio -1\n"
      << "set xrange [-1.08:1.08]\n";
    for (const auto& p : presets) {
        const std::string f = "gem_outline_" + p + ".csv";
        b << "set yrange [-1.08:1.08]\n"
          << "set title \"" << p << ": crown (top view)\"\n"
          << "plot '" << f << "' index 0 using 1:2 with lines lc rgb 'black' lw 1\n"
          << "set title \"" << p << ": pavilion (bottom view)\"\n"
          << "plot '" << f << "' index 1 using 1:2 with lines lc rgb 'black' lw 1\n"
          << "set yrange [-1.0:0.45]\n"
          << "set title \"" << p << ": side profile\"\n"
          << "plot '" << f << "' index 2 using 1:2 with lines lc rgb 'black' lw 1\n";
    }
    b << "unset multiplot\n";
    return b.str();
}

std::string md_num(double v) { return fmt(v, 10); }

}  // namespace

Result compute(const ExperimentOptions& opt) {
    Result r;
    r.quick = opt.quick;
    for (const auto& p : brilliant_preset_names()) {
        PresetResult pr;
        pr.preset = p;
        pr.gem = build_brilliant(brilliant_preset(p));
        pr.proportions = proportion_rows(p, pr.gem);
        for (const auto& row : pr.proportions) r.worst = std::max(r.worst, std::abs(row.measured - row.expected));
        pr.facet_counts = facet_counts(pr.gem);
        for (const char* view : {"crown", "pavilion", "side"}) pr.outlines.emplace_back(view, outlines(pr.gem, view));
        r.presets.push_back(std::move(pr));
    }
    for (auto& pr : r.presets) pr.timing = time_intersections(pr.preset, pr.gem, opt.quick ? 4000 : 200000);
    for (auto& pr : r.presets) {
        pr.scene = render_scene(pr.preset, opt.quick);
        RenderOptions ro;
        ro.threads = opt.threads;
        pr.render = render(scene_from_json(pr.scene, "gem_render_" + pr.preset + ".json"), ro);
    }
    return r;
}

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    std::vector<std::string> presets;
    for (const auto& pr : r.presets) presets.push_back(pr.preset);
    std::ostringstream summary;
    summary << "# gem-geometry: the round brilliant, exactly\n\n"
            << "Presets built with CGAL's exact kernel (geometry/gem/brilliant.h, docs/gems.md); every figure "
            << "below is measured on the built polyhedron.\n\n";

    // Proportions.
    Csv prop{csv_header<ProportionRow>(), {}};
    std::ostringstream md;
    md << "| preset | quantity | unit | source | expected | measured | abs diff |\n|---|---|---|---|---:|---:|---:|\n";
    Csv facets;
    facets.header = {"preset", "kind", "count"};
    for (const auto& pr : r.presets) {
        for (const auto& row : pr.proportions) {
            const double d = std::abs(row.measured - row.expected);
            prop.add(csv_cells(row));
            md << "| " << row.preset << " | " << row.quantity << " | " << row.unit << " | " << row.source << " | "
               << md_num(row.expected) << " | " << md_num(row.measured) << " | " << fmt(d, 2) << " |\n";
        }
        for (const auto& [kind, count] : pr.facet_counts) facets.add({pr.preset, kind, std::to_string(count)});
    }
    write_csv(dir + "/gem_proportions.csv", prop);
    write_text_atomic(dir + "/gem_proportions.md", md.str());
    write_csv(dir + "/gem_facets.csv", facets);
    summary << "## Proportions: requested / closed form against measured\n\n"
            << "Percent of the girdle diameter, degrees from the girdle plane (`gem_proportions.csv`, "
            << "`gem_proportions.md`). Largest difference: " << fmt(r.worst, 3) << ".\n\n"
            << md.str() << "\n";

    // Line drawings.
    for (const auto& pr : r.presets)
    {
        write_text_atomic(dir + "/gem_outline_" + pr.preset + ".csv", outline_text(pr));
        write_csv_sidecar(dir + "/gem_outline_" + pr.preset + ".csv");  // core/provenance.h
    }
    const FigureSize size{1200, 420 * static_cast<int>(presets.size()) + 40, 9.0,
                          3.1 * static_cast<double>(presets.size()) + 0.3};
    gnuplot_figure(dir, "gem_drawings", drawings_body(presets), size);
    summary << "## Line drawings\n\n`gem_drawings.png` / `.pdf`: per preset the crown from above, the pavilion "
            << "from below (mirrored, as seen) and the side profile; facet outlines in `gem_outline_PRESET.csv` "
            << "(gnuplot index blocks 0, 1, 2). Facet counts in `gem_facets.csv`.\n\n";

    // Intersection cost.
    Csv timing{csv_header<IntersectionTiming>(), {}};
    summary << "## Ray–gem intersection: plane set against triangle mesh\n\n"
            << "The same random rays (from a sphere of radius 3 towards the bounding box), best of three passes, "
            << "one thread (`gem_intersection.csv`). Timings are of this machine and run.\n\n"
            << "| preset | planes | triangles | rays | hits | agree | plane set ns/ray | mesh ns/ray | mesh / plane |\n"
            << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& pr : r.presets) {
        const IntersectionTiming& t = pr.timing;
        timing.add(csv_cells(t));
        summary << "| " << t.preset << " | " << t.planes << " | " << t.triangles << " | " << t.rays << " | " << t.hits
                << " | " << t.agree << " | " << fmt(t.plane_ns, 3) << " | " << fmt(t.mesh_ns, 3) << " | "
                << fmt(t.mesh_ns / t.plane_ns, 3) << " |\n";
    }
    write_csv(dir + "/gem_intersection.csv", timing);

    // Renders.
    std::vector<Panel> panels;
    summary << "\n## Rendered diamonds (n = 2.417, Fresnel, no dispersion)\n\n"
            << "| preset | image | scene | seconds | segments |\n|---|---|---|---:|---:|\n";
    for (const auto& pr : r.presets) {
        const std::string stem = "gem_render_" + pr.preset;
        save_json(dir, stem + ".json", pr.scene);
        write_image(dir + "/" + stem + ".png", pr.render.image);
        const RenderStats& st = pr.render.stats;
        panels.push_back({stem + ".png", pr.preset});
        summary << "| " << pr.preset << " | `" << stem << ".png` | `" << stem << ".json` | " << fmt(st.seconds, 3)
                << " | " << st.segments << " |\n";
    }
    write_csv(dir + "/gem_renders.csv", csv_table(r.presets));
    image_grid_figure(dir, "gem_renders", 1, static_cast<int>(panels.size()), panels,
                      "Round brilliant presets, Fresnel diamond n = 2.417", 0.75, r.quick ? 200 : 420);
    summary << "\n`gem_renders.png` / `.pdf` shows them side by side; `refract render gem_render_PRESET.json -o x.png` "
            << "re-renders one.\n";
    write_text_atomic(dir + "/summary.md", summary.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::gem_geometry
