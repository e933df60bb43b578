// optics-bench: the files (CSV, figures, scenes, summary.md) written from a Result
// (experiments/optics_bench.h).
#include <cmath>
#include <filesystem>
#include <sstream>

#include <refract/experiments/common.h>
#include <refract/experiments/far_field_output.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/optics_bench.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::optics_bench {

const char* class_name(int p) {
    static const char* names[] = {"external reflection", "direct transmission", "1 internal reflection (primary bow)",
                                  "2 internal reflections (secondary bow)"};
    return names[p];
}

namespace {

std::string g(double v, int digits = 6) { return fmt(v, digits); }

void figures(const std::string& dir) {
    if (!gnuplot_available()) return;
    std::ostringstream d;
    d << "set datafile separator ','\nset logscale y\nset format y '10^{%L}'\nset xrange [0:180]\nset yrange [1e-6:*]\n"
         "set xlabel 'scattering angle (degrees)'\nset ylabel 'fraction of the beam per degree'\n"
         "set key top left\nset title 'Water drop (n = 1.333) in a beam: measured (points) and closed form (lines)'\n"
         "plot ";
    for (int p = 0; p <= 3; ++p)
        d << (p ? ", " : "") << "'drop.csv' using (($1 == " << p << ") ? ($2 + $3) / 2 : NaN):4 skip 1 with points pt 7 ps 0.4 lc " << p + 1
          << " title '" << class_name(p) << "', 'drop.csv' using (($1 == " << p << ") ? ($2 + $3) / 2 : NaN):7 skip 1 with lines lc "
          << p + 1 << " notitle";
    d << "\n";
    gnuplot_figure(dir, "drop", d.str());
    gnuplot_figure(dir, "rainbow",
                   "set datafile separator ','\nset xlabel 'wavelength (nm)'\nset ylabel 'scattering angle (degrees)'\n"
                   "set key center right\nset title 'Rainbow angles of a water drop: measured (points), Descartes (lines)'\n"
                   "plot 'rainbow.csv' using 1:3 skip 1 with points pt 7 lc 1 title 'primary (first light of class 2)', "
                   "'rainbow.csv' using 1:4 skip 1 with lines lc 1 notitle, "
                   "'rainbow.csv' using 1:6 skip 1 with points pt 5 lc 2 title 'secondary (last light of class 3)', "
                   "'rainbow.csv' using 1:7 skip 1 with lines lc 2 notitle\n");
    gnuplot_figure(dir, "prism",
                   "set datafile separator ','\nset xlabel 'wavelength (nm)'\nset ylabel 'deviation (degrees)'\n"
                   "set title '60° N-BK7 prism at fixed incidence: measured (points), closed form (line)'\n"
                   "plot 'prism.csv' using 1:3 skip 1 with points pt 7 title 'far-field detector', "
                   "'prism.csv' using 1:4 skip 1 with lines title 'Snell at both faces'\n");
    gnuplot_figure(dir, "slab",
                   "set datafile separator ','\nset xlabel 'incidence angle (degrees)'\nset ylabel 'transmittance'\n"
                   "set yrange [0:1.05]\nset key bottom left\n"
                   "set title 'Glass slab (n = 1.5), all internal reflections: measured (points), closed form (lines)'\n"
                   "plot 'slab.csv' using 1:2 skip 1 with points pt 7 lc 1 title 'T_s', 'slab.csv' using 1:5 skip 1 with lines lc 1 notitle, "
                   "'slab.csv' using 1:3 skip 1 with points pt 5 lc 2 title 'T_p', 'slab.csv' using 1:6 skip 1 with lines lc 2 notitle, "
                   "'slab.csv' using 1:4 skip 1 with points pt 9 lc 3 title 'T (natural)', 'slab.csv' using 1:7 skip 1 with lines lc 3 notitle\n");
}

}  // namespace

void write(const Result& r, const std::string& dir) {
    namespace fs = std::filesystem;
    ensure_dir(dir);
    const auto path = [&](const std::string& f) { return dir + "/" + f; };
    // 1. Drop.
    write_csv(path("drop.csv"), csv_table(r.drop.bins));
    const Csv drop_classes = csv_table(r.drop.classes);
    write_csv(path("drop_classes.csv"), drop_classes);
    write_far_field(dir + "/drop_far_field", r.drop.far_field_tables, "water drop in a beam, 550 nm");
    write_text_atomic(path("drop.json"), r.drop.scene.dump(2) + "\n");
    // 2. Rainbow.
    const Csv bow = csv_table(r.rainbow.rows);
    write_csv(path("rainbow.csv"), bow);
    write_text_atomic(path("rainbow.json"), r.rainbow.scene.dump(2) + "\n");
    // 3. Prism.
    const Csv prism = csv_table(r.prism.rows);
    write_csv(path("prism.csv"), prism);
    write_text_atomic(path("prism.json"), r.prism.scene.dump(2) + "\n");
    // 4. Slab.
    const Csv slab = csv_table(r.slab.rows);
    write_csv(path("slab.csv"), slab);
    figures(dir);

    std::ostringstream md;
    md << "# optics-bench: classic optics measured with the far-field detector\n\n"
       << "Each measurement is made by `refract`'s far-field detector (photons from a collimated beam, walked by the "
          "ray-tree walker, binned by direction) and set beside its closed form, computed independently "
          "(experiments/optics_closed_forms.h). "
       << (r.quick ? "Quick run (fewer photons). " : "") << "Total time " << g(r.seconds, 3) << " s.\n\n";
    md << "## 1. A water drop in a beam (n = 1.333, exact polarisation)\n\n"
       << r.drop.photons << " photons, 1° bins of scattering angle, depth 40, threshold 1e-9 (dropped: "
       << g(r.drop.dropped, 3) << " of the beam); " << g(r.drop.seconds, 3)
       << " s. Closed form: van de Hulst's geometric optics, ε₀ = R, ε_p = (1 − R)² R^(p−1) per polarisation. "
          "A z-score is a bin's difference over σ = √(closed / N), an upper bound of its statistical error. "
          "Figure: drop.png; the detector's own files in drop_far_field/.\n\n"
       << drop_classes.markdown() << "\n";
    md << "## 2. Rainbow angles against wavelength (dispersive water)\n\n"
       << r.rainbow.photons << " photons per wavelength, bins of " << g(r.rainbow.bin_deg, 3)
       << "°; the measured angle is the centre of the first bin with class-2 light (primary) and the last with "
          "class-3 light (secondary); closed form: Descartes' minimum deviation, cos² i = (n² − 1)/(p² − 1). "
          "Largest difference "
       << g(r.rainbow.max_error, 3) << "° (half a bin is " << g(r.rainbow.bin_deg / 2, 3) << "°); " << g(r.rainbow.seconds, 3)
       << " s. Figure: rainbow.png.\n\n"
       << bow.markdown(6) << "\n";
    md << "## 3. A 60° N-BK7 prism at fixed incidence\n\n"
       << "Incidence " << g(r.prism.incidence_deg, 6) << "° (minimum deviation at 550 nm); bins of " << g(r.prism.bin_deg, 3)
       << "°, the deviation is the power-weighted mean of class 1 (through both faces). Largest difference "
       << g(r.prism.max_error, 3) << "°; " << g(r.prism.seconds, 3) << " s. Figure: prism.png.\n\n"
       << prism.markdown(7) << "\n";
    md << "## 4. A glass slab (n = 1.5): transmittance against incidence\n\n"
       << "All light leaving the far side (every internal reflection; depth 80, threshold 1e-12), s and p from the "
          "detector's Stokes vectors; closed form (1 − R)/(1 + R) per polarisation. Largest difference "
       << g(r.slab.max_error, 3) << "; " << g(r.slab.seconds, 3) << " s. Figure: slab.png.\n\n"
       << slab.markdown(8) << "\n";
    write_text_atomic(path("summary.md"), md.str());
}

}  // namespace refract::experiments::optics_bench
