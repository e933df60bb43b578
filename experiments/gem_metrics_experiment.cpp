// `refract experiment gem-metrics`: metric values with errors for two presets, the
// observation set-ups' images, convergence with the ray count, and the per-cut cost.
#include <refract/experiments/gem_metrics_experiment.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/gem_observation.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::gem_metrics_experiment {
using gem_metrics::GemMetrics;
using gem_metrics::Metric;
using gem_metrics::MetricOptions;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Named {
    const char* name;
    Metric GemMetrics::*field;
};
const Named kMetrics[] = {{"light_return", &GemMetrics::light_return},
                          {"fire", &GemMetrics::fire},
                          {"leakage", &GemMetrics::leakage},
                          {"scintillation", &GemMetrics::scintillation}};

std::string pm(const Metric& m) { return fmt(m.value, 4) + " ± " + fmt(m.error, 2); }

}  // namespace

nlohmann::json viewer_scene(const std::string& preset, const std::string& view, const std::string& map_file, int size) {
    const bool below = view == "hearts";
    return nlohmann::json{
        {"description", "Round brilliant '" + preset + "' in the " + view +
                            " viewer (docs/gem-metrics.md): the viewer as an environment map coloured by elevation, "
                            "diamond (Peter 1923) at 400-700 nm, exact polarisation"},
        {"camera",
         {{"location", vec(0, below ? -12.0 : 12.0, 0)}, {"look_at", vec(0, 0, 0)}, {"sky", vec(0, 0, 1)},
          {"angle", 11}, {"width", size}, {"height", size}}},
        {"background", {{"type", "environment"}, {"map", map_file}}},
        {"materials", {{"diamond", {{"type", "dielectric"}, {"dispersion", "diamond"}}}}},
        {"objects", nlohmann::json::array({{{"type", "brilliant"}, {"name", "diamond"}, {"preset", preset},
                                            {"position", vec(0, 0, 0)}, {"diameter", 2}, {"material", "diamond"}}})},
        {"render", {{"max_depth", 24}, {"polarisation", "exact"}}},
    };
}

std::vector<std::pair<std::string, std::string>> viewer_maps() {
    return {{"viewer-aset.exr", "aset"},
            {"viewer-ideal-scope.exr", "ideal-scope"},
            {"viewer-arrows.exr", "arrows"},
            {"viewer-hearts.exr", "hearts"}};
}

std::vector<std::pair<std::string, nlohmann::json>> viewer_scenes(int size) {
    std::vector<std::pair<std::string, nlohmann::json>> out;
    for (const auto& [map, view] : viewer_maps())
        out.emplace_back("tolkowsky-" + view + ".json", viewer_scene("tolkowsky", view, map, size));
    return out;
}

Result compute(const ExperimentOptions& opt) {
    Result r;
    r.quick = opt.quick;
    r.options.rays = opt.quick ? 496 : MetricOptions{}.rays;
    r.image_size = opt.quick ? 40 : 200;
    r.image_samples = opt.quick ? 1 : 2;
    for (const std::string preset : {"tolkowsky", "gia-default"}) {
        PresetResult p;
        p.preset = preset;
        auto t0 = std::chrono::steady_clock::now();
        p.gem = build_brilliant(brilliant_preset(preset));
        p.build_seconds = seconds_since(t0);
        MetricOptions nat = r.options;
        nat.exact_polarisation = false;
        // Wall time of measure() on one thread, best of `reps` runs (the machine is shared).
        const int reps = opt.quick ? 1 : 3;
        p.exact_seconds = p.natural_seconds = 1e30;
        for (int k = 0; k < reps; ++k) {
            t0 = std::chrono::steady_clock::now();
            p.exact = gem_metrics::measure(p.gem, r.options);
            p.exact_seconds = std::min(p.exact_seconds, seconds_since(t0));
            t0 = std::chrono::steady_clock::now();
            p.natural = gem_metrics::measure(p.gem, nat);
            p.natural_seconds = std::min(p.natural_seconds, seconds_since(t0));
        }
        for (const auto& v : gem_metrics::view_names())
            p.views.emplace_back(v, gem_metrics::render_view(p.gem, v, r.image_size, r.image_samples, r.options));
        r.presets.push_back(std::move(p));
    }
    const std::vector<int> counts = opt.quick ? std::vector<int>{124, 496}
                                              : std::vector<int>{256, 1024, 4096, 16384};
    for (const int n : counts) {
        MetricOptions o = r.options;
        o.rays = n;
        r.convergence.push_back({"tolkowsky", n, gem_metrics::measure(r.presets[0].gem, o)});
    }
    // The pavilion angle from too shallow to too deep, the rest GIA's default.
    const std::vector<double> angles = opt.quick ? std::vector<double>{38.0, 40.75, 43.0}
                                                 : std::vector<double>{37.5, 38.0, 38.5, 39.0, 39.5, 40.0, 40.5, 40.75,
                                                                       41.0, 41.5, 42.0, 42.5, 43.0, 43.5};
    for (const double a : angles) {
        BrilliantCut cut = brilliant_preset("gia-default");
        cut.pavilion_angle = a;
        r.pavilion_scan.push_back({a, gem_metrics::measure(build_brilliant(cut), r.options)});
    }
    std::vector<double> n;
    for (const auto& c : r.convergence) n.push_back(c.rays);
    for (const auto& k : kMetrics) {
        std::vector<double> err;
        for (const auto& c : r.convergence) err.push_back((c.metrics.*(k.field)).error);
        r.convergence_slopes.emplace_back(k.name, loglog_fit(n, err).slope);
    }
    for (const auto& [file, view] : viewer_maps())
        r.viewer_map_images.emplace_back(file, gem_metrics::viewer_environment(view, kViewerMapWidth));
    r.viewer_scene_files = viewer_scenes(320);
    return r;
}

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    std::ostringstream s;
    s << "# gem-metrics: light return, fire, leakage and scintillation of the round brilliant\n\n"
      << "Definitions, set-ups and sources: docs/gem-metrics.md. Eye rays from a distant viewer above the table, "
      << "traced through the exact cut (diamond, Peter 1923), " << r.options.wavelengths
      << " wavelengths 400–700 nm, pruning threshold " << fmt(r.options.threshold) << ", depth " << r.options.max_depth
      << ". Light return and leakage from " << r.options.rays << " eye rays, fire from "
      << r.presets[0].exact.fire_pixels << " pixels × " << r.options.wavelengths << " wavelengths, scintillation from "
      << r.presets[0].exact.scintillation_pixels << " pixels × 3 tilts of " << fmt(r.options.tilt_deg) << "°"
      << (r.quick ? " (quick mode: fewer rays than the documented counts)" : "") << ". Errors are one standard error.\n\n";

    // Metric values, both polarisation models.
    Csv table;
    table.header = {"preset", "polarisation", "metric", "value", "error", "rays"};
    s << "## Metrics (value ± standard error)\n\n"
      << "| preset | polarisation | light return | fire | leakage | scintillation |\n|---|---|---|---|---|---|\n";
    for (const auto& p : r.presets)
        for (const auto& [model, m] : {std::pair{"exact", &p.exact}, std::pair{"natural", &p.natural}}) {
            s << "| " << p.preset << " | " << model;
            for (const auto& k : kMetrics) {
                table.add({p.preset, model, k.name, fmt(((*m).*(k.field)).value), fmt(((*m).*(k.field)).error),
                           std::to_string(m->light_return_rays)});
                s << " | " << pm((*m).*(k.field));
            }
            s << " |\n";
        }
    write_csv(dir + "/gem_metrics.csv", table);

    // Exact − natural.
    s << "\n## Exact polarisation against natural light\n\nThe same eye rays under both models (common random "
      << "numbers), so the difference is the model's; in units of the combined standard error in brackets.\n\n"
      << "| preset | metric | exact − natural | relative | (σ) |\n|---|---|---:|---:|---:|\n";
    for (const auto& p : r.presets)
        for (const auto& k : kMetrics) {
            const Metric a = p.exact.*(k.field), b = p.natural.*(k.field);
            const double d = a.value - b.value, sig = std::hypot(a.error, b.error);
            s << "| " << p.preset << " | " << k.name << " | " << fmt(d, 3) << " | "
              << fmt(b.value != 0 ? d / b.value : 0.0, 3) << " | " << fmt(sig > 0 ? d / sig : 0.0, 3) << " |\n";
        }

    // Energy balance and leakage by facet kind.
    Csv kinds;
    kinds.header = {"preset", "polarisation", "kind", "share"};
    s << "\n## Where the light of an eye ray leaves (exact polarisation)\n\nShares of the eye rays' light "
      << "(means over the eye rays, their bands drawn by luminance); the pavilion column (the leakage) sums lower "
      << "half, pavilion main and culet; the girdle is listed apart.\n\n"
      << "| preset | crown | girdle | pavilion | pruned | sum |";
    for (const auto& [kind, v] : r.presets[0].exact.leakage_by_kind) s << " " << kind << " |";
    s << "\n|---|---:|---:|---:|---:|---:|";
    for (size_t i = 0; i < r.presets[0].exact.leakage_by_kind.size(); ++i) s << "---:|";
    s << "\n";
    for (const auto& p : r.presets) {
        const auto& b = p.exact.balance;
        s << "| " << p.preset << " | " << fmt(b.crown, 4) << " | " << fmt(b.girdle, 3) << " | " << fmt(b.pavilion, 4)
          << " | " << fmt(b.lost, 2) << " | " << fmt(b.crown + b.girdle + b.pavilion + b.lost + b.missed, 12) << " |";
        for (const auto& [kind, v] : p.exact.leakage_by_kind) s << " " << fmt(v, 3) << " |";
        s << "\n";
        for (const auto& [model, m] : {std::pair{"exact", &p.exact}, std::pair{"natural", &p.natural}})
            for (const auto& [kind, v] : m->leakage_by_kind) kinds.add({p.preset, model, kind, fmt(v)});
    }
    write_csv(dir + "/gem_leakage_by_kind.csv", kinds);
    Csv aset{csv_join({"preset", "polarisation"}, csv_header<GemMetrics::Aset>()), {}};
    s << "\nBy ASET zone (the same rays; zones about the direction to the eye):\n\n"
      << "| preset | red 45–75° | green 0–45° | blue 75–90° (viewer) | white (below the horizon) |\n"
      << "|---|---:|---:|---:|---:|\n";
    for (const auto& p : r.presets) {
        const auto& a = p.exact.aset;
        s << "| " << p.preset << " | " << fmt(a.red, 4) << " | " << fmt(a.green, 4) << " | " << fmt(a.blue, 4) << " | "
          << fmt(a.white, 4) << " |\n";
        for (const auto& [model, m] : {std::pair{"exact", &p.exact}, std::pair{"natural", &p.natural}})
            aset.add(csv_join({p.preset, model}, csv_cells(m->aset)));
    }
    write_csv(dir + "/gem_aset.csv", aset);

    // Cost of one cut.
    Csv cost;
    cost.header = {"preset", "rays", "build_s", "measure_exact_s", "measure_natural_s"};
    s << "\n## Cost of one cut (one thread, best of " << (r.quick ? 1 : 3) << " runs, this machine and run)\n\n"
      << "| preset | rays | construction (CGAL) s | metrics, exact s | metrics, natural s |\n|---|---:|---:|---:|---:|\n";
    for (const auto& p : r.presets) {
        cost.add({p.preset, std::to_string(r.options.rays), fmt(p.build_seconds, 4), fmt(p.exact_seconds, 4),
                  fmt(p.natural_seconds, 4)});
        s << "| " << p.preset << " | " << r.options.rays << " | " << fmt(p.build_seconds, 3) << " | "
          << fmt(p.exact_seconds, 3) << " | " << fmt(p.natural_seconds, 3) << " |\n";
    }
    write_csv(dir + "/gem_cost.csv", cost);

    // Convergence.
    write_csv(dir + "/gem_convergence.csv", csv_table(r.convergence));
    s << "\n## Convergence (Tolkowsky, exact)\n\nStandard error against the light-return ray count (fire and "
      << "scintillation pixels scale with it), `gem_convergence.csv`, `gem_convergence.png`; least-squares slope "
      << "on log–log axes (−0.5 expected):\n\n| metric | slope |\n|---|---:|\n";
    for (const auto& [name, slope] : r.convergence_slopes) s << "| " << name << " | " << fmt(slope, 3) << " |\n";
    std::ostringstream gp;
    gp << "set datafile separator comma\nset logscale xy\nset key top right\nset grid\n"
       << "set xlabel 'eye rays (light return, leakage)'\nset ylabel 'standard error'\n"
       << "set title 'Gem metrics: statistical error against ray count (Tolkowsky, exact polarisation)'\n"
       << "ref = "
       << fmt(r.convergence[0].metrics.light_return.error * std::sqrt(static_cast<double>(r.convergence[0].rays))) << "\n"
       << "plot 'gem_convergence.csv' skip 1 using 1:2 with linespoints title 'light return', "
       << "'' skip 1 using 1:3 with linespoints title 'fire', '' skip 1 using 1:4 with linespoints title 'leakage', "
       << "'' skip 1 using 1:5 with linespoints title 'scintillation', "
       << "ref/sqrt(x) with lines dt 2 lc rgb 'black' title 'N^{-1/2} through the first light-return point'\n";
    gnuplot_figure(dir, "gem_convergence", gp.str());

    // Pavilion-angle scan.
    write_csv(dir + "/gem_pavilion_scan.csv", csv_table(r.pavilion_scan));
    std::ostringstream ps;
    ps << "set datafile separator comma\nset grid\nunset key\nset xlabel 'pavilion angle (deg)'\n"
       << "set multiplot layout 2,2 title 'GIA default proportions, pavilion angle varied (exact, ±1 standard error)'\n";
    for (size_t k = 0; k < 4; ++k)
        ps << "set title '" << kMetrics[k].name << "' noenhanced\nplot 'gem_pavilion_scan.csv' skip 1 using 1:" << 2 + 2 * k << ":"
           << 3 + 2 * k << " with yerrorlines lc rgb 'black' pt 7 ps 0.5\n";
    ps << "unset multiplot\n";
    const FigureSize big{1000, 760, 8.0, 6.0};
    gnuplot_figure(dir, "gem_pavilion_scan", ps.str(), big);
    s << "\n## Pavilion angle\n\nGIA's default proportions with the pavilion angle varied (`gem_pavilion_scan.csv`, "
      << "`gem_pavilion_scan.png`; exact polarisation, " << r.options.rays << " rays):\n\n"
      << "| pavilion angle | light return | fire | leakage | scintillation |\n|---:|---|---|---|---|\n";
    for (const auto& row : r.pavilion_scan) {
        s << "| " << fmt(row.pavilion_angle) << "°";
        for (const auto& k : kMetrics) s << " | " << pm(row.metrics.*(k.field));
        s << " |\n";
    }

    // Fire by wavelength.
    Csv spec;
    spec.header = {"wavelength_nm"};
    for (const auto& p : r.presets) spec.header.push_back(p.preset);
    for (size_t b = 0; b < r.presets[0].exact.fire_spectrum.size(); ++b) {
        std::vector<std::string> row{fmt(r.presets[0].exact.fire_spectrum[b].first)};
        for (const auto& p : r.presets) row.push_back(fmt(p.exact.fire_spectrum[b].second));
        spec.add(row);
    }
    write_csv(dir + "/gem_fire_spectrum.csv", spec);
    std::ostringstream fs;
    fs << "set datafile separator comma\nset grid\nset key top left\nset xlabel 'wavelength (nm)'\n"
       << "set ylabel 'coloured light above the white part'\nset xrange [400:700]\n"
       << "set title 'Fire resolved by wavelength (spot lighting, exact polarisation)'\nplot ";
    for (size_t k = 0; k < r.presets.size(); ++k)
        fs << (k ? ", " : "") << "'gem_fire_spectrum.csv' skip 1 using 1:" << k + 2 << " with linespoints title '"
           << r.presets[k].preset << "'";
    fs << "\n";
    gnuplot_figure(dir, "gem_fire_spectrum", fs.str());
    s << "\n## Fire by wavelength\n\n`gem_fire_spectrum.csv`, `gem_fire_spectrum.png`: per band the mean coloured "
      << "part r_b − min r of the pixels' returned spectra under spot lighting (no luminance weight): where in the "
      << "spectrum the coloured flashes lie.\n";

    // Images.
    std::vector<Panel> panels;
    for (const auto& p : r.presets)
        for (const auto& [view, img] : p.views) {
            const std::string f = "gem_view_" + p.preset + "_" + view + ".png";
            write_image(dir + "/" + f, img);
            panels.push_back({f, p.preset + " " + view});
        }
    image_grid_figure(dir, "gem_views", static_cast<int>(r.presets.size()),
                      static_cast<int>(r.presets[0].views.size()), panels,
                      "Observation set-ups: ASET, ideal-scope, arrows (face up), hearts (table down), brilliance", 1.0,
                      r.quick ? 120 : 240);
    s << "\n## Images of the set-ups\n\n`gem_views.png` / `.pdf` (one row per preset; " << r.image_size << "² pixels, "
      << r.image_samples * r.image_samples << " eye rays each, at " << "the band nearest 560 nm, exact polarisation): "
      << "ASET (red 45–75°, green 0–45°, blue: the viewer, white: leakage), ideal-scope (red reflector, black "
      << "viewing hole, white leakage), arrows (face up) and hearts (table down, seen from below) through the "
      << "reflector viewer, and the brilliance set-up's radiance. Single images: `gem_view_PRESET_VIEW.png`.\n";
    // The viewers as scene files (the same as scenes/gems/).
    for (const auto& [file, image] : r.viewer_map_images) write_image(dir + "/" + file, image);
    for (const auto& [file, scene] : r.viewer_scene_files) save_json(dir, file, scene);
    s << "\nThe viewers as scene files (`tolkowsky-VIEW.json` with the environment maps `viewer-VIEW.exr`, the "
      << "same as `scenes/gems/`): `refract render tolkowsky-aset.json -o aset.png` renders the stone in the ASET "
      << "viewer with the spectral eye pass (dispersion) and exact polarisation.\n";
    write_text_atomic(dir + "/summary.md", s.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::gem_metrics_experiment
