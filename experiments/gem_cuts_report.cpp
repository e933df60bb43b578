// gem-cuts: the write step (experiments/gem_cuts.h) — CSVs, contour maps, summary.md.
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include <refract/core/provenance.h>
#include <refract/experiments/common.h>
#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_sweep_file.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::gem_cuts {

namespace sw = gem_sweep;

namespace {

std::string csv_of(const std::vector<sw::Row>& rows) {
    sw::Lines lines;
    for (const auto& r : rows) lines[r.index] = sw::csv_line(r);
    return sw::csv_text(lines);
}

// crown pavilion value... per cut, a blank line after each crown angle (gnuplot grid blocks).
std::string map_text(const Result& r) {
    std::ostringstream t;
    t << "# crown_angle pavilion_angle";
    for (const auto& m : metrics()) t << " " << m.key;
    t << "\n";
    double last_crown = std::nan("");
    for (const auto& row : r.main_rows) {
        if (!std::isnan(last_crown) && row.cut.crown_angle != last_crown) t << "\n";
        last_crown = row.cut.crown_angle;
        t << sw::number(row.cut.crown_angle) << " " << sw::number(row.cut.pavilion_angle);
        for (const auto& m : metrics())
            t << " " << (row.possible ? sw::number(metric_of(row.metrics, m.key).value) : std::string("NaN"));
        t << "\n";
    }
    return t.str();
}

std::string contour_body(const Result& r, size_t k) {
    const MetricInfo& m = metrics()[k];
    std::ostringstream b;
    b << "set datafile missing 'NaN'\n"
      << "set view map\nset pm3d at b\nset contour base\nset cntrparam levels auto 8\nunset clabel\n"
      << "set palette rgbformulae 33,13,10\nunset key\n"
      << "set xlabel 'crown angle (deg)'\nset ylabel 'pavilion angle (deg)'\n"
      << "set title \"" << m.title << (m.maximise ? "" : " (smaller is better)")
      << "\\n{/=9 circle: Tolkowsky 1919, square: GIA default, star: best in the grid}\"\n"
      << "set xrange [" << r.main.grid.axes[1].value(0) << ":" << r.main.grid.axes[1].value(r.main.grid.axes[1].count - 1)
      << "]\nset yrange [" << r.main.grid.axes[2].value(0) << ":"
      << r.main.grid.axes[2].value(r.main.grid.axes[2].count - 1) << "]\n"
      << "splot 'gem_cuts_map.dat' using 1:2:" << 3 + k << " with pm3d nocontours notitle, \\\n"
      << "      '' using 1:2:" << 3 + k << " with lines nosurface lc rgb 'black' lw 0.8 notitle, \\\n"
      << "      'gem_cuts_marks.dat' index 0 using 1:2:(0) with points nocontours pt 6 ps 2.2 lw 2 lc rgb 'black' title 'Tolkowsky 1919', \\\n"
      << "      'gem_cuts_marks.dat' index 1 using 1:2:(0) with points nocontours pt 5 ps 0.9 lc rgb 'black' title 'GIA default', \\\n"
      << "      'gem_cuts_best_marks.dat' index " << k
      << " using 1:2:(0) with points nocontours pt 3 ps 2 lw 2 lc rgb 'blue' title 'best in the grid'\n";
    return b.str();
}

std::string num(double v) { return fmt(v, 4); }

}  // namespace

std::string marks_text(const Result& r) {
    const BrilliantCut &tolk = r.presets.at(0).second.cut, &gia = r.presets.at(1).second.cut;
    if (r.findings.presets_share_angles)
        return "(the same angles, table " + num(gia.table) + " % against " + num(tolk.table) + " %)";
    return "(crown " + num(gia.crown_angle) + "°, pavilion " + num(gia.pavilion_angle) + "°, table " + num(gia.table) +
           " %, against Tolkowsky's " + num(tolk.crown_angle) + "°, " + num(tolk.pavilion_angle) + "°, " +
           num(tolk.table) + " %)";
}

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    write_text_atomic(dir + "/gem_cuts_sweep.csv", csv_of(r.main_rows));
    write_csv_sidecar(dir + "/gem_cuts_sweep.csv", gem_sweep::settings_json(r.main));  // core/provenance.h
    write_text_atomic(dir + "/gem_cuts_star_lower_half.csv", csv_of(r.detail_rows));
    write_csv_sidecar(dir + "/gem_cuts_star_lower_half.csv", gem_sweep::settings_json(r.detail));
    write_text_atomic(dir + "/gem_cuts_map.dat", map_text(r));
    std::ostringstream marks;
    for (const auto& [name, row] : r.presets)
        marks << "# " << name << "\n" << sw::number(row.cut.crown_angle) << " " << sw::number(row.cut.pavilion_angle) << "\n\n\n";
    write_text_atomic(dir + "/gem_cuts_marks.dat", marks.str());
    std::ostringstream best_marks;  // index k: the best cut for metrics()[k]
    for (const auto& o : r.optima)
        best_marks << "# " << o.metric << "\n" << sw::number(o.best.cut.crown_angle) << " "
                   << sw::number(o.best.cut.pavilion_angle) << "\n\n\n";
    write_text_atomic(dir + "/gem_cuts_best_marks.dat", best_marks.str());

    Csv best;
    best.header = {"metric", "rank", "crown_angle", "pavilion_angle", "value", "error"};
    for (const auto& o : r.optima)
        for (size_t i = 0; i < o.top.size(); ++i) {
            const auto& v = metric_of(o.top[i].metrics, o.metric);
            best.add({o.metric, std::to_string(i + 1), fmt(o.top[i].cut.crown_angle), fmt(o.top[i].cut.pavilion_angle),
                      fmt(v.value), fmt(v.error)});
        }
    write_csv(dir + "/gem_cuts_best.csv", best);
    for (size_t k = 0; k < metrics().size(); ++k) gnuplot_figure(dir, "gem_cuts_" + metrics()[k].key, contour_body(r, k));

    const sw::Row& tolk = r.presets[0].second;
    const sw::Row& gia = r.presets[1].second;
    std::ostringstream s;
    s << "# gem-cuts: where the round brilliant is brightest and most fiery\n\n"
      << "Every cut built exactly (CGAL) and measured by the gem metrics (docs/gem-metrics.md) with "
      << r.main.metric.rays << " rays per metric, " << r.main.metric.wavelengths << " wavelengths, "
      << (r.main.metric.exact_polarisation ? "exact" : "natural") << " polarisation, material "
      << r.main.metric.material << "; each cut's seed derives from its parameters only"
      << (r.quick ? " (quick mode: a few cuts, few rays: mechanics only, not results)" : "") << ". "
      << fmt(r.seconds, 3) << " s.\n\n"
      << "## Grids\n\n"
      << "- Crown × pavilion map, " << r.main.grid.size() << " cuts (" << r.impossible
      << " impossible), the other parameters GIA's default: `" << command_of(r.main, "gem_cuts_sweep.csv") << "`\n"
      << "- Star × lower half at the GIA default crown and pavilion, " << r.detail.grid.size() << " cuts: `"
      << command_of(r.detail, "gem_cuts_star_lower_half.csv") << "`\n"
      << "- The full grid (" << full_sweep().grid.size() << " cuts; `refract bench --sweep` times it): `"
      << command_of(full_sweep(), "sweep.csv") << "`\n\n"
      << "Reference cuts, evaluated alike: Tolkowsky 1919 (crown " << num(tolk.cut.crown_angle) << "°, pavilion "
      << num(tolk.cut.pavilion_angle) << "°, table " << num(tolk.cut.table) << " %) and the GIA default (crown "
      << num(gia.cut.crown_angle) << "°, pavilion " << num(gia.cut.pavilion_angle) << "°, table " << num(gia.cut.table)
      << " %).\n\n"
      << "## Where each metric is best, and Tolkowsky's distance from it\n\n"
      << "Contour maps `gem_cuts_METRIC.png` / `.pdf` (crown angle × pavilion angle, the other parameters the GIA default; open circle Tolkowsky, "
      << "black square GIA default " << marks_text(r) << ", blue star the grid's best). The grid's best value is the largest of many "
      << "noisy cells and so biased towards better; the difference is given in combined standard errors.\n\n"
      << "| metric | best crown | best pavilion | best value ± error | Tolkowsky ± error | Δcrown | Δpavilion | "
         "difference / σ |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& o : r.optima) {
        const auto& b = metric_of(o.best.metrics, o.metric);
        s << "| " << o.metric << " | " << num(o.best.cut.crown_angle) << " | " << num(o.best.cut.pavilion_angle) << " | "
          << num(b.value) << " ± " << fmt(b.error, 2) << " | " << num(o.tolkowsky.value) << " ± "
          << fmt(o.tolkowsky.error, 2) << " | " << num(o.d_crown) << " | " << num(o.d_pavilion) << " | "
          << fmt(o.sigmas, 3) << " |\n";
    }
    s << "\nThe five best cuts per metric: `gem_cuts_best.csv`.\n\n";
    for (const auto& o : r.optima) {
        s << "- " << o.metric << ":";
        for (const auto& row : o.top)
            s << " (" << num(row.cut.crown_angle) << "°, " << num(row.cut.pavilion_angle) << "°) "
              << num(metric_of(row.metrics, o.metric).value) << ";";
        s << "\n";
    }
    s << "\n## How much the star and lower-half lengths matter\n\n"
      << "Range of each metric over the star × lower-half grid (`gem_cuts_star_lower_half.csv`), against one "
         "cut's standard error and the range over the crown × pavilion map.\n\n"
      << "| metric | min | max | range | mean error of a cut | range over crown × pavilion |\n"
         "|---|---:|---:|---:|---:|---:|\n";
    for (const auto& x : r.sensitivity)
        s << "| " << x.metric << " | " << num(x.min) << " | " << num(x.max) << " | " << num(x.max - x.min) << " | "
          << fmt(x.mean_error, 2) << " | " << num(x.crown_pavilion_spread) << " |\n";
    s << "\nCSV columns: docs/gem-metrics.md, \"Sweep\". `gnuplot gem_cuts_METRIC.gp` redraws a map from "
         "`gem_cuts_map.dat`.\n";
    write_text_atomic(dir + "/summary.md", s.str());
}

}  // namespace refract::experiments::gem_cuts
