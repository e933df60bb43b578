// gem-cuts: the write step (experiments/gem_cuts.h) — CSVs, contour maps, summary.md.
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include <refract/core/provenance.h>
#include <refract/experiments/common.h>
#include <refract/experiments/contour_labels.h>
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

// Half a grid step: the plotted range reaches that far beyond the first and last values, so
// that each cut is a whole cell and a marker on the outermost row or column is not clipped.
double axis_half_step(const sw::Axis& a) { return a.count > 1 ? 0.5 * (a.value(1) - a.value(0)) : 0.5; }

// One metric's map: viridis over the range the possible cuts span; contour lines at round
// levels with a white rim (they read on the dark and the light end alike), each labelled
// once where the label covers no marker, other label or other line; the reference cuts and
// the grid's best as outlined markers, explained in the subtitle (outside the map). The two
// reference cuts share one marker when they share their angles (they differ in the table).
std::string contour_body(const Result& r, size_t k) {
    const MetricInfo& m = metrics()[k];
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& row : r.main_rows)
        if (row.possible) {
            const double v = metric_of(row.metrics, m.key).value;
            lo = std::fmin(lo, v);
            hi = std::fmax(hi, v);
        }
    if (!(lo < hi)) {  // one cut or a flat map: a range around it
        const double c = std::isfinite(lo) ? lo : 0.5, d = std::fmax(std::fabs(c) * 0.01, 1e-3);
        lo = c - d;
        hi = c + d;
    }
    const ContourLevels lv = round_contour_levels(lo, hi, 5);
    const bool shared = r.findings.presets_share_angles;
    // The contour labels, placed clear of the markers, of each other and of the other lines
    // (experiments/contour_labels.h) in the plot area the margins below fix.
    const sw::Axis &ax = r.main.grid.axes[1], &ay = r.main.grid.axes[2];
    GridMap grid;
    for (int i = 0; i < ax.count; ++i) grid.x.push_back(ax.value(i));
    for (int j = 0; j < ay.count; ++j) grid.y.push_back(ay.value(j));
    grid.values.assign(grid.x.size() * grid.y.size(), std::nan(""));
    auto index_of = [](const std::vector<double>& axis, double v) {
        size_t best = 0;
        for (size_t i = 1; i < axis.size(); ++i)
            if (std::fabs(axis[i] - v) < std::fabs(axis[best] - v)) best = i;
        return best;
    };
    for (const auto& row : r.main_rows)
        if (row.possible)
            grid.values[index_of(grid.x, row.cut.crown_angle) * grid.y.size() + index_of(grid.y, row.cut.pavilion_angle)] =
                metric_of(row.metrics, m.key).value;
    PlotFrame frame;
    frame.x0 = grid.x.front() - axis_half_step(ax);
    frame.x1 = grid.x.back() + axis_half_step(ax);
    frame.y0 = grid.y.front() - axis_half_step(ay);
    frame.y1 = grid.y.back() + axis_half_step(ay);
    std::vector<std::pair<double, double>> markers;
    for (const auto& p : r.presets) markers.emplace_back(p.second.cut.crown_angle, p.second.cut.pavilion_angle);
    markers.emplace_back(r.optima[k].best.cut.crown_angle, r.optima[k].best.cut.pavilion_angle);
    std::vector<double> levels;
    for (int i = 0; i < lv.count; ++i) levels.push_back(lv.start + i * lv.step);
    const std::string col = std::to_string(3 + k), next = ", \\\n     ";
    std::ostringstream b;
    // The contour lines into a data block (a 3-D pass), then a 2-D plot: each cut a cell
    // (impossible cuts, NaN, left blank), the lines, the labels and the markers.
    b << "set lmargin at screen 0.11\nset rmargin at screen 0.8\nset bmargin at screen 0.15\nset tmargin at screen 0.84\n";
    if (lv.count > 0)
        b << "set contour base\nunset surface\nset cntrparam levels incremental " << sw::number(lv.start) << ","
          << sw::number(lv.step) << "," << sw::number(lv.end) << "\nset table $contours\nsplot 'gem_cuts_map.dat' using 1:2:"
          << col << "\nunset table\nunset contour\n";
    b << "unset key\nset style textbox opaque noborder margins 1,1\nlabel_font = (fmt eq 'png') ? ',9' : ',7'\n";
    for (const auto& l : place_contour_labels(grid, levels, lv.format, frame, markers))
        b << "set label '" << l.text << "' at " << sw::number(l.x) << "," << sw::number(l.y)
          << " center front boxed font label_font\n";
    b << viridis_palette() << "\nset cbrange [" << sw::number(lo) << ":" << sw::number(hi) << "]\n"
      << "set cblabel '" << m.title << "'\n"
      << "set xlabel 'crown angle (deg)'\nset ylabel 'pavilion angle (deg)'\n"
      << "set title \"" << m.title << (m.maximise ? "" : " (smaller is better)") << "\\n{/=9 "
      << (shared ? "circle: Tolkowsky 1919 and GIA default (the same crown and pavilion)"
                 : "circle: Tolkowsky 1919, square: GIA default")
      << ", star: best in the grid" << (r.impossible > 0 ? ", blank: impossible cut" : "") << "}\"\n"
      << "set xrange [" << sw::number(frame.x0) << ":" << sw::number(frame.x1) << "]\nset yrange ["
      << sw::number(frame.y0) << ":" << sw::number(frame.y1) << "]\n"
      // Cells 2 % wider than the grid step: no seams between them.
      << "plot 'gem_cuts_map.dat' using 1:2:(" << sw::number(1.02 * axis_half_step(ax)) << "):("
      << sw::number(1.02 * axis_half_step(ay)) << "):" << col << " with boxxyerror fs solid 1.0 noborder fc palette";
    if (lv.count > 0)
        b << next << "$contours using 1:2 with lines lc rgb 'white' lw 2.2" << next
          << "$contours using 1:2 with lines lc rgb 'black' lw 0.8";
    b << next << "'gem_cuts_marks.dat' index 0 using 1:2 with points pt 7 ps 2.2 lc rgb 'white'" << next
      << "'gem_cuts_marks.dat' index 0 using 1:2 with points pt 6 ps 2.2 lw 2 lc rgb 'black'";
    if (!shared)
        b << next << "'gem_cuts_marks.dat' index 1 using 1:2 with points pt 5 ps 1.4 lc rgb 'white'" << next
          << "'gem_cuts_marks.dat' index 1 using 1:2 with points pt 5 ps 0.9 lc rgb 'black'";
    b << next << "'gem_cuts_best_marks.dat' index " << k << " using 1:2 with points pt 3 ps 2.2 lw 5 lc rgb 'white'"
      << next << "'gem_cuts_best_marks.dat' index " << k << " using 1:2 with points pt 3 ps 2 lw 2 lc rgb 'black'\n";
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
      << fmt(r.seconds, 3) << " s (" << fmt(r.observer_seconds, 3)
      << " s of them for the observer maps, the detector grids and the renders).\n\n"
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
      << "Contour maps `gem_cuts_METRIC.png` / `.pdf` (crown angle × pavilion angle, the other parameters the GIA default; circle Tolkowsky, "
      << "square GIA default " << marks_text(r) << (r.findings.presets_share_angles ? ", drawn as one circle" : "") << ", star the grid's best; viridis colour scale over the range the cuts span, contours at round levels, labelled). The grid's best value is the largest of many "
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
    s << "\n";
    for (const auto& o : r.optima) s << "- " << optimum_sentence(o, r.main.grid) << "\n";
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
    write_observers(r, dir, s);
    s << "\nCSV columns: docs/gem-metrics.md, \"Sweep\". `gnuplot gem_cuts_METRIC.gp` redraws a map from "
         "`gem_cuts_map.dat`.\n";
    write_text_atomic(dir + "/summary.md", s.str());
}

}  // namespace refract::experiments::gem_cuts
