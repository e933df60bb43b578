// grin: the files (CSV, figures, summary.md) written from a Result (experiments/grin.h).
// Every sentence that states a finding is chosen by Result::findings (judge()).
#include <cmath>
#include <sstream>

#include <refract/experiments/common.h>
#include <refract/experiments/grin.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::grin_media {

namespace {

std::string gfmt(double v, int digits = 4) { return std::isfinite(v) ? fmt(v, digits) : std::string("—"); }
std::string cell(double v, int digits = 10) { return std::isfinite(v) ? fmt(v, digits) : std::string(); }

Csv paths_csv(const std::vector<PathPoint>& p, const std::string& u, const std::string& v) {
    Csv t{{"ray", u, v}, {}};
    for (const PathPoint& q : p) t.add({std::to_string(q.ray), cell(q.u), cell(q.v)});
    return t;
}
int last_ray(const std::vector<PathPoint>& p) { return p.empty() ? 0 : p.back().ray; }

// `plot for` over the rays of a paths file: one line each.
std::string rays_plot(const std::string& file, int last, const std::string& style) {
    return "for [i=0:" + std::to_string(last) + "] '" + file + "' using ($1 == i ? $2 : NaN):3 skip 1 with lines " +
           style + " notitle";
}

// Per ray: with the layer and without, and the run of consecutive rays reaching the object
// it belongs to (a ray meeting the ground ends a run; the figure draws each run as one line).
Csv mirage_csv(const MirageStudy& m) {
    Csv t{{"elevation_deg", "hits_ground", "ground_distance_m", "height_at_object_m", "standard_hits_ground",
           "standard_height_at_object_m", "run", "standard_run"},
          {}};
    int run = 0, standard_run = 0;
    for (size_t i = 0; i < m.rays.size(); ++i) {
        const MirageRay &a = m.rays[i], &b = m.standard_rays[i];
        if (i > 0 && a.hits_ground && !m.rays[i - 1].hits_ground) ++run;
        if (i > 0 && b.hits_ground && !m.standard_rays[i - 1].hits_ground) ++standard_run;
        t.add({cell(a.elevation_deg), a.hits_ground ? "1" : "0", a.hits_ground ? cell(a.ground_distance) : "",
               cell(a.height_at_object), b.hits_ground ? "1" : "0", cell(b.height_at_object), std::to_string(run),
               std::to_string(standard_run)});
    }
    return t;
}
int last_run(const MirageStudy& m, bool standard) {
    int run = 0;
    const auto& rays = standard ? m.standard_rays : m.rays;
    for (size_t i = 1; i < rays.size(); ++i)
        if (rays[i].hits_ground && !rays[i - 1].hits_ground) ++run;
    return run;
}

void mirage_figure(const std::string& dir, const MirageStudy& m, const std::string& file, const std::string& title,
                   const std::string& layer) {
    std::ostringstream b;
    b << "set datafile separator ','\nset multiplot layout 2,1 title '" << title << "'\n"
      << "set xlabel 'distance along the ground (m)'\nset ylabel 'height (m)'\nset yrange [0:*]\n"
      << "set arrow from " << m.distance << ", graph 0 to " << m.distance << ", graph 1 nohead dt 2\n"
      << "plot " << rays_plot(file + "_paths.csv", last_ray(m.paths), "lc rgb '#1f77b4'") << "\n"
      << "unset arrow\nset yrange [*:*]\nset xlabel 'elevation at the eye (degrees)'\n"
      << "set ylabel 'height reached at " << fmt(m.distance, 6) << " m (m)'\nset key top left\n"
      << "plot for [i=0:" << last_run(m, false) << "] '" << file << ".csv' using 1:($7 == i ? $4 : NaN) skip 1 "
      << "with linespoints pt 7 ps 0.4 lc 1 title (i == 0 ? 'with " << layer << "' : ''), "
      << "for [i=0:" << last_run(m, true) << "] '" << file << ".csv' using 1:($8 == i ? $6 : NaN) skip 1 "
      << "with lines dt 2 lc 2 title (i == 0 ? 'without it' : '')\n"
      << "unset multiplot\n";
    gnuplot_figure(dir, file, b.str(), {800, 900, 6.0, 6.8});
}

void figures(const Result& r, const std::string& dir) {
    if (!gnuplot_available()) return;
    gnuplot_figure(dir, "luneburg",
                   "set datafile separator ','\nset size ratio -1\nset xlabel 'z / R'\nset ylabel 'y / R'\n"
                   "set title 'Luneburg lens: a parallel bundle meets at the far surface point'\nset xrange [-1.8:1.8]\n"
                   "set object 1 circle at 0,0 size 1 fc rgb '#dddddd' fs solid 0.4 noborder behind\n"
                   "plot " + rays_plot("luneburg_paths.csv", last_ray(r.luneburg.paths), "lc rgb '#1f77b4'") + "\n");
    gnuplot_figure(dir, "fisheye",
                   "set datafile separator ','\nset size ratio -1\nset xlabel 'z / a'\nset ylabel 'x / a'\n"
                   "set title \"Maxwell's fish-eye: rays from z = " + gfmt(r.fisheye.r0) + " a are circles through z = " +
                       gfmt(r.fisheye.image) + " a\"\nset xrange [-3:3]\nset yrange [-3:3]\n"
                       "set object 1 circle at 0,0 size 1 fc rgb '#dddddd' fs solid 0.4 noborder behind\n"
                       "set label 1 'object' at " + fmt(r.fisheye.r0) + ",0 point pt 7 ps 1.2 lc rgb 'red' offset 0.5,0.5\n"
                       "set label 2 'image' at " + fmt(r.fisheye.image) + ",0 point pt 7 ps 1.2 lc rgb 'red' offset 0.5,0.5\n"
                       "plot " + rays_plot("fisheye_paths.csv", last_ray(r.fisheye.paths), "lc rgb '#1f77b4'") + "\n");
    gnuplot_figure(dir, "rods",
                   "set datafile separator ','\nset multiplot layout 2,1 title 'A point on the axis after one pitch "
                   "2π/α: sech rod (top), parabolic rod (bottom)'\nset xlabel 'z'\nset ylabel 'x'\n"
                   "plot " + rays_plot("rod_sech_paths.csv", last_ray(r.rods.sech_paths), "lc rgb '#1f77b4'") +
                       "\nplot " + rays_plot("rod_parabolic_paths.csv", last_ray(r.rods.parabolic_paths), "lc rgb '#d62728'") +
                       "\nunset multiplot\n",
                   {800, 800, 6.0, 6.0});
    gnuplot_figure(dir, "grid",
                   "set datafile separator ','\nset multiplot layout 1,2 title 'A parabolic GRIN rod imaging a grid'\n"
                   "set size ratio -1\nset xlabel 'x'\nset ylabel 'y'\nset key bottom left\n"
                   "plot 'grid.csv' using 1:2 skip 1 with points pt 6 ps 1.2 title 'object', "
                   "'grid.csv' using 3:4 skip 1 with points pt 7 ps 0.8 title 'image (centroids)', "
                   "'grid.csv' using ($1 * " + fmt(r.grid.paraxial_magnification) + "):($2 * " +
                       fmt(r.grid.paraxial_magnification) + ") skip 1 with points pt 1 ps 1.5 title 'paraxial image'\n"
                       "set size noratio\nset xlabel 'z'\nset ylabel 'x'\n"
                       "set object 1 rect from 0," + fmt(-r.grid.rod_radius) + " to " + fmt(r.grid.length) + "," +
                       fmt(r.grid.rod_radius) + " fc rgb '#dddddd' fs solid 0.4 noborder behind\n"
                       "plot " + rays_plot("grid_paths.csv", last_ray(r.grid.paths), "lc rgb '#1f77b4'") +
                       "\nunset multiplot\n",
                   {1100, 560, 8.0, 4.2});
    mirage_figure(dir, r.road, "mirage_road", "Inferior mirage over a hot road: rays from an eye at " +
                                                  gfmt(r.road.eye_height) + " m", "the surface layer");
    mirage_figure(dir, r.sea, "mirage_sea", "Superior mirage over a cold sea: rays from an eye at " +
                                                gfmt(r.sea.eye_height) + " m", "the inversion");
    gnuplot_figure(dir, "sun",
                   "set datafile separator ','\nset multiplot layout 2,1 title 'The setting sun (standard atmosphere)'\n"
                   "set xlabel 'apparent altitude of the lower limb (degrees)'\nset ylabel 'vertical / horizontal diameter'\n"
                   "set key bottom right\n"
                   "plot 'sun.csv' using 1:6 skip 1 with linespoints pt 7 title 'traced', "
                   "'sun.csv' using 1:7 skip 1 with linespoints pt 6 dt 2 title 'Bennett 1982'\n"
                   "set xlabel 'apparent altitude (degrees)'\nset ylabel 'R(520 nm) − R(650 nm) (arcsec)'\n"
                   "plot 'sun_limbs.csv' using 1:2 skip 1 with linespoints pt 7 title 'traced', "
                   "'sun_limbs.csv' using 1:3 skip 1 with lines dt 2 title 'refraction integral'\nunset multiplot\n",
                   {800, 900, 6.0, 6.8});
    gnuplot_figure(dir, "refraction",
                   "set datafile separator ','\nset multiplot layout 2,1 title 'Astronomical refraction at 10 °C, "
                   "101.0 kPa, 550 nm'\nset xlabel 'apparent altitude (degrees)'\nset ylabel 'refraction (arcmin)'\n"
                   "set logscale y\nset xrange [0:90]\nset yrange [0.1:100]\n"
                   "plot 'refraction.csv' using 1:3 skip 1 with points pt 7 title 'traced', "
                   "'refraction.csv' using 1:4 skip 1 with lines title 'refraction integral', "
                   "'refraction.csv' using 1:5 skip 1 with lines dt 2 title 'Bennett', "
                   "'refraction.csv' using 1:7 skip 1 with lines dt 3 title 'Sæmundsson'\n"
                   "unset logscale y\nset ylabel 'minus the integral (arcmin)'\nset key top right\n"
                   "plot 'refraction.csv' using 1:($3 - $4) skip 1 with linespoints pt 7 title 'traced', "
                   "'refraction.csv' using 1:($5 - $4) skip 1 with linespoints pt 6 title 'Bennett', "
                   "'refraction.csv' using 1:($6 - $4) skip 1 with linespoints pt 4 title 'Bennett corrected', "
                   "'refraction.csv' using 1:($7 - $4) skip 1 with linespoints pt 8 title 'Sæmundsson'\n"
                   "unset multiplot\n",
                   {800, 900, 6.0, 6.8});
    std::ostringstream c;
    c << "set datafile separator ','\nset multiplot layout 1,2 title 'Dormand–Prince 5(4) on rays with known exits'\n"
      << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset key top left\n"
      << "set xlabel 'tolerance'\nset ylabel 'exit error'\nplot ";
    for (size_t k = 0; k < r.convergence.curves.size(); ++k)
        c << (k ? ", " : "") << "'convergence.csv' using ($1 == " << k << " && $2 == 0 ? $3 : NaN):4 skip 1 with linespoints pt 7 title '"
          << r.convergence.curves[k].ray << "'";
    c << "\nset xlabel 'exit error'\nset ylabel 'gradient evaluations'\nplot ";
    for (size_t k = 0; k < r.convergence.curves.size(); ++k)
        c << (k ? ", " : "") << "'convergence.csv' using ($1 == " << k << " && $2 == 0 ? $4 : NaN):5 skip 1 with linespoints pt 7 lc "
          << k + 1 << " title 'adaptive, " << r.convergence.curves[k].ray << "', 'convergence.csv' using ($1 == " << k
          << " && $2 == 1 ? $4 : NaN):5 skip 1 with linespoints pt 4 dt 2 lc " << k + 1 << " title 'fixed steps'";
    c << "\nunset multiplot\n";
    gnuplot_figure(dir, "convergence", c.str(), {1100, 560, 8.0, 4.2});
}

Csv branches_csv(const MirageStudy& m) {
    Csv t{{"elevation_from_deg", "elevation_to_deg", "height_from_m", "height_to_m", "image"}, {}};
    for (const MirageBranch& b : m.branches)
        t.add({cell(b.elevation_lo_deg), cell(b.elevation_hi_deg), cell(b.height_lo), cell(b.height_hi),
               b.inverted() ? "inverted" : "erect"});
    return t;
}

// The mirage's sentences: `inverted` and `looming` are the findings for this study.
std::string mirage_text(const MirageStudy& m, bool inverted, const std::string& ground) {
    std::ostringstream s;
    const std::string at = "at " + fmt(m.distance, 6) + " m";
    if (inverted) {
        s << "Seen " << at << ", the object appears more than once: ";
        for (size_t k = 0; k < m.branches.size(); ++k) {
            const MirageBranch& b = m.branches[k];
            s << (k ? (k + 1 == m.branches.size() ? " and " : ", ") : "") << (b.inverted() ? "inverted" : "erect")
              << " at elevations " << gfmt(b.elevation_lo_deg) << "° to " << gfmt(b.elevation_hi_deg) << "° (heights "
              << gfmt(b.height_lo) << " to " << gfmt(b.height_hi) << " m)";
        }
        s << ". ";
    } else {
        s << "Seen " << at << ", the heights rise with the elevation at the eye: no inverted image. ";
    }
    s << "Nothing of the object below " << gfmt(m.lowest_seen) << " m is seen (the vanishing line; "
      << gfmt(m.lowest_seen_standard) << " m without the layer"
      << (m.lowest_seen < m.lowest_seen_standard ? ": the layer lifts the hidden part into view)."
          : m.lowest_seen > m.lowest_seen_standard ? ": the layer hides it)." : ").");
    if (std::isfinite(m.ground_onset_deg))
        s << " Rays at elevations up to " << gfmt(m.ground_onset_deg) << "° meet the " << ground << ".";
    return s.str();
}

}  // namespace

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    const auto path = [&](const std::string& f) { return dir + "/" + f; };
    const Findings& f = r.findings;
    // 1. Lenses.
    write_csv(path("luneburg_paths.csv"), paths_csv(r.luneburg.paths, "z", "y"));
    Csv lenses{{"lens", "rays", "tolerance", "error", "second_error", "measured"}, {}};
    lenses.add({"Luneburg", std::to_string(r.luneburg.rays), cell(r.luneburg.tol), cell(r.luneburg.spot_radius),
                cell(r.luneburg.direction_error), "spot radius / R; exit direction error (rad)"});
    lenses.add({"Maxwell fish-eye", std::to_string(r.fisheye.rays), cell(r.fisheye.tol), cell(r.fisheye.image_error),
                cell(r.fisheye.circle_error), "image error / a; distance from the circle / a"});
    lenses.add({"sech rod", std::to_string(r.rods.rows.size()), cell(r.rods.tol), cell(r.rods.sech_spot), "",
                "largest height after one pitch"});
    lenses.add({"parabolic rod", std::to_string(r.rods.rows.size()), cell(r.rods.tol), cell(r.rods.parabolic_spot), "",
                "largest height after one paraxial pitch"});
    write_csv(path("lenses.csv"), lenses);
    write_csv(path("fisheye_paths.csv"), paths_csv(r.fisheye.paths, "z", "x"));
    Csv rods{{"angle_deg", "sech_height", "sech_slope_error", "parabolic_height"}, {}};
    for (const RodRow& w : r.rods.rows)
        rods.add({cell(w.angle_deg), cell(w.sech_height), cell(w.sech_slope_error), cell(w.parabolic_height)});
    write_csv(path("rods.csv"), rods);
    write_csv(path("rod_sech_paths.csv"), paths_csv(r.rods.sech_paths, "z", "x"));
    write_csv(path("rod_parabolic_paths.csv"), paths_csv(r.rods.parabolic_paths, "z", "x"));
    Csv grid{{"object_x", "object_y", "image_x", "image_y", "spot_rms", "magnification"}, {}};
    for (const GridPoint& p : r.grid.points)
        grid.add({cell(p.object_x), cell(p.object_y), cell(p.image_x), cell(p.image_y), cell(p.spot_rms),
                  cell(p.magnification)});
    write_csv(path("grid.csv"), grid);
    write_csv(path("grid_paths.csv"), paths_csv(r.grid.paths, "z", "x"));
    // 2. Mirages.
    write_csv(path("mirage_road.csv"), mirage_csv(r.road));
    const Csv road_branches = branches_csv(r.road), sea_branches = branches_csv(r.sea);
    write_csv(path("mirage_road_branches.csv"), road_branches);
    write_csv(path("mirage_sea_branches.csv"), sea_branches);
    write_csv(path("mirage_road_paths.csv"), paths_csv(r.road.paths, "distance_m", "height_m"));
    write_csv(path("mirage_sea.csv"), mirage_csv(r.sea));
    write_csv(path("mirage_sea_paths.csv"), paths_csv(r.sea.paths, "distance_m", "height_m"));
    // 3. The sun.
    Csv sun{{"lower_limb_deg", "upper_limb_deg", "vertical_arcmin", "horizontal_arcmin", "shortening_arcmin", "ratio",
             "ratio_bennett"},
            {}};
    for (const SunRow& w : r.sun.rows)
        sun.add({cell(w.lower_apparent_deg), cell(w.upper_apparent_deg), cell(w.vertical_arcmin), cell(w.horizontal_arcmin),
                 cell(w.horizontal_arcmin - w.vertical_arcmin), cell(w.ratio), cell(w.ratio_bennett)});
    write_csv(path("sun.csv"), sun);
    Csv limbs{{"apparent_deg", "traced_arcsec", "integral_arcsec"}, {}};
    for (const LimbRow& l : r.sun.limbs) limbs.add({cell(l.apparent_deg), cell(l.traced_arcsec), cell(l.integral_arcsec)});
    write_csv(path("sun_limbs.csv"), limbs);
    // 4. Refraction.
    Csv refr{{"apparent_deg", "true_deg", "traced_arcmin", "integral_arcmin", "bennett_arcmin", "bennett_corrected_arcmin",
              "saemundsson_arcmin"},
             {}};
    for (const RefractionRow& w : r.refraction.rows)
        refr.add({cell(w.apparent_deg), cell(w.true_deg), cell(w.traced_arcmin), cell(w.integral_arcmin),
                  cell(w.bennett_arcmin), cell(w.bennett_corrected_arcmin), cell(w.saemundsson_arcmin)});
    write_csv(path("refraction.csv"), refr);
    // 5. Convergence.
    Csv conv{{"ray", "fixed", "setting", "error", "evaluations", "steps"}, {}};
    Csv fits{{"ray", "error_vs_tolerance_slope", "error_vs_step_order", "fixed_over_adaptive_at_tol_1e-11"}, {}};
    for (size_t k = 0; k < r.convergence.curves.size(); ++k) {
        const ConvergenceCurve& c = r.convergence.curves[k];
        for (int fixed = 0; fixed < 2; ++fixed)
            for (const grin::StepPoint& p : fixed ? c.fixed : c.adaptive)
                conv.add({std::to_string(k), std::to_string(fixed), cell(p.setting), p.left ? cell(p.error) : "",
                          std::to_string(p.evaluations), std::to_string(p.steps)});
        fits.add({csv_quote(c.ray), cell(c.tol_slope, 4), cell(c.step_order, 4), cell(c.matched_ratio, 4)});
    }
    write_csv(path("convergence.csv"), conv);
    write_csv(path("convergence_fits.csv"), fits);
    figures(r, dir);

    const LuneburgStudy& L = r.luneburg;
    const FishEyeStudy& F = r.fisheye;
    const RodStudy& R = r.rods;
    const GridStudy& G = r.grid;
    std::ostringstream md;
    md << "# grin: gradient-index media traced by the ray equation\n\n"
       << "Every ray is integrated by `core/grin`'s `advance()` (Dormand–Prince 5(4), docs/grin.md); no renderer. "
       << "λ = " << gfmt(r.lambda_um * 1000, 3) << " nm unless stated. " << (r.quick ? "Quick run (fewer rays). " : "")
       << "Total time " << gfmt(r.seconds, 3) << " s (";
    for (size_t k = 0; k < r.study_seconds.size(); ++k)
        md << (k ? ", " : "") << r.study_seconds[k].first << " " << gfmt(r.study_seconds[k].second, 2) << " s";
    md << ").\n\n";
    md << "## 1. Lenses\n\n" << lenses.markdown(3) << "\n";
    md << "**Luneburg lens** (luneburg.png): " << L.rays << " parallel rays, impacts −0.95…0.95 R, tolerance "
       << gfmt(L.tol, 2) << ", " << gfmt(L.mean_evaluations, 4) << " evaluations a ray. "
       << (f.luneburg_focus ? "They meet at the antipodal surface point: spot radius " + gfmt(L.spot_radius, 2) + " R (≤ 1e-9 R)."
                            : "Spot radius " + gfmt(L.spot_radius, 2) + " R: above 1e-9 R, the bundle does not meet at one point.")
       << "\n\n";
    md << "**Maxwell's fish-eye** (fisheye.png): " << F.rays << " rays from a point at z = " << gfmt(F.r0) << " a. "
       << (f.fisheye_image ? "Every ray is a circle and meets at −a²/r₀ = " + gfmt(F.image) + " a: image error " +
                                 gfmt(F.image_error, 2) + " a, largest distance of a path point from its circle " +
                                 gfmt(F.circle_error, 2) + " a (both ≤ 1e-8 a)."
                           : "Image error " + gfmt(F.image_error, 2) + " a, distance from the circles " + gfmt(F.circle_error, 2) +
                                 " a: above 1e-8 a.")
       << "\n\n";
    md << "**GRIN rods** (rods.png, rods.csv): a point on the axis, meridional rays at " << gfmt(R.rows.front().angle_deg)
       << "°…" << gfmt(R.rows.back().angle_deg) << "°, after one pitch 2π/α = " << gfmt(R.pitch) << ". "
       << (f.sech_refocus ? "The hyperbolic-secant rod refocuses every ray on the point (largest height " + gfmt(R.sech_spot, 2) +
                                "), the parabolic rod of the same paraxial pitch does not (largest height " +
                                gfmt(R.parabolic_spot, 3) + ": its period depends on the launch angle)."
                          : "Largest heights after one pitch: sech rod " + gfmt(R.sech_spot, 2) + ", parabolic rod " +
                                gfmt(R.parabolic_spot, 3) + ": the sech rod's refocusing is not shown at 1e-9.")
       << "\n\n";
    md << "**A rod imaging a grid** (grid.png, grid.csv): a parabolic rod n₀ = " << gfmt(G.n0) << ", √A = " << gfmt(G.g)
       << ", length " << gfmt(G.length) << ", object " << gfmt(G.object_distance) << " in front; paraxial (ABCD) image "
       << gfmt(G.image_distance) << " behind, magnification " << gfmt(G.paraxial_magnification) << ". " << G.rays_per_point
       << " rays a point through a pupil of radius " << gfmt(G.pupil_radius) << " on the entrance face. "
       << (f.grid_inverted_as_paraxial ? "Near the axis the measured magnification is " + gfmt(G.axis_magnification) +
                                             ", within 1 % of the paraxial one"
                                       : "Near the axis the measured magnification is " + gfmt(G.axis_magnification) +
                                             ", more than 1 % from the paraxial one")
       << "; at the grid's corner " << gfmt(G.corner_magnification) << " (distortion "
       << gfmt(100 * (G.corner_magnification / G.axis_magnification - 1), 3) << " %); largest RMS spot " << gfmt(G.max_spot, 3)
       << ".\n\n";
    md << "## 2. Mirages\n\nRays from an eye over the spherical Earth to the radial plane at the object's distance "
          "or to the ground; the heights they reach there against their elevation at the eye (a run of heights falling "
          "as the elevation rises is an inverted image).\n\n";
    md << "**Inferior mirage over a hot road** (mirage_road.png): the standard atmosphere at "
       << gfmt(r.road.sea_level_temperature_K - 273.15, 3) << " °C with the surface layer ΔT = " << gfmt(r.road.delta_T)
       << " K, h_s = " << gfmt(r.road.surface_height) << " m (docs/grin.md); eye at " << gfmt(r.road.eye_height) << " m. "
       << mirage_text(r.road, f.road_inverted, "road") << "\n\n"
       << road_branches.markdown(4) << "\n";
    md << "**Superior mirage over a cold sea** (mirage_sea.png): " << gfmt(r.sea.sea_level_temperature_K - 273.15, 3)
       << " °C at the sea, 6.5 K/km lapse, an inversion of " << gfmt(r.sea.delta_T) << " K centred at "
       << gfmt(r.sea.surface_height) << " m (a logistic step 2 m wide), the index Ciddor's, tabulated; eye at "
       << gfmt(r.sea.eye_height) << " m, a ship at " << gfmt(r.sea.distance / 1000, 3) << " km. "
       << mirage_text(r.sea, f.sea_inverted, "sea") << "\n\n"
       << sea_branches.markdown(4) << "\n";
    md << "## 3. The setting sun\n\nStandard atmosphere (15 °C, 101.325 kPa, dry), 550 nm, the sun's semidiameter "
       << gfmt(r.sun.semidiameter_arcmin) << "′. " << (f.sun_flattened
              ? "With its lower limb on the horizon the sun is flattened to " + gfmt(r.sun.rows.front().ratio, 3) +
                    " of its width, and the flattening eases as it rises."
              : "With its lower limb on the horizon the ratio of its diameters is " + gfmt(r.sun.rows.front().ratio, 3) +
                    ", outside 0.75–0.9 or not rising with altitude.")
       << " Figure: sun.png.\n\n" << sun.markdown(5) << "\n"
       << (f.green_above_red ? "Green light (520 nm) is refracted more than red (650 nm) at every altitude, by " +
                                   gfmt(r.sun.limbs.front().traced_arcsec, 4) +
                                   "″ at the horizon (traced, within 0.01″ of the integral): the green limb stands above the red one."
                             : "The traced separation of the green and red limbs is not positive everywhere or differs from the "
                               "integral by more than 0.01″.")
       << "\n\n" << limbs.markdown(6) << "\n";
    md << "## 4. Astronomical refraction\n\nBennett's conditions (10 °C, 101.0 kPa, dry), 550 nm. "
       << (f.traced_is_integral ? "The traced refraction equals the refraction integral to " +
                                      gfmt(r.refraction.max_traced_integral_arcsec, 2) + "″ (≤ 0.01″) at every altitude. "
                                : "The traced refraction differs from the integral by up to " +
                                      gfmt(r.refraction.max_traced_integral_arcsec, 2) + "″. ")
       << (f.bennett_within ? "Bennett's corrected formula is within his stated 0.07′ of the integral from 5° up"
                            : "Bennett's corrected formula is not within 0.07′ of the integral everywhere from 5° up")
       << "; largest differences from the integral: Bennett " << gfmt(r.refraction.max_bennett_arcmin, 3) << "′, Sæmundsson "
       << gfmt(r.refraction.max_saemundsson_arcmin, 3) << "′ (near the horizon). Figure: refraction.png.\n\n"
       << refr.markdown(6) << "\n";
    md << "## 5. The integrator's convergence\n\n"
       << (f.tolerance_proportional ? "The exit error falls in proportion to the tolerance" :
                                      "The exit error does not fall in proportion to the tolerance")
       << " and, at fixed steps, "
       << (f.fifth_order ? "as the fifth power of the step (the method's order)." : "not as the fifth power of the step.")
       << " Figure: convergence.png.\n\n" << fits.markdown(4) << "\n";
    md << "## 6. Rendered views\n\nThe renderer's own walk through GRIN objects (docs/grin.md): "
       << (f.views_complete ? "every view rendered with finite pixels and no ray out of steps."
                            : "a view has non-finite pixels or rays that ran out of steps.")
       << " Each scene is beside its image (`refract render NAME.json -o NAME.png` renders it again).\n\n"
       << "| view | image | size | seconds | curved segments | index-gradient evaluations | out of steps |\n"
       << "|---|---|---|---|---|---|---|\n";
    for (const ViewStudy& v : r.views) {
        write_image(path(v.name + ".png"), v.image);
        write_text_atomic(path(v.name + ".json"), v.scene.dump(1) + "\n");
        md << "| " << v.title << " | " << v.name << ".png | " << v.image.width << "×" << v.image.height << " | "
           << gfmt(v.seconds, 3) << " | " << v.grin_segments << " | " << v.grin_evaluations << " | " << v.grin_exhausted
           << " |\n";
    }
    md << "\n"
       << (f.sea_view_inverted
                   ? "The ship 25 km away over the cold sea (sea_view.png) is seen upside down: down the image's centre column its white superstructure (rows " +
                             std::to_string(f.ship.white_top) + "–" + std::to_string(f.ship.white_bottom) +
                             ") lies under its red hull (rows " + std::to_string(f.ship.red_top) + "–" +
                             std::to_string(f.ship.red_bottom) + "): the superior mirage's inverted image, as the "
                             "traced rays above find it.\n"
                   : f.ship.seen ? "The ship over the cold sea (sea_view.png) is not seen upside down in its rendered view.\n"
                                 : "The ship over the cold sea is not seen in its rendered view (sea_view.png).\n")
       << "\n"
       << (f.limb_blue_on_top
                   ? "The setting sun's upper limb, rendered by the spectral eye pass through the standard air "
                     "(sunset_limb_view.png): its first lit pixel is blue (RGB " + gfmt(f.limb.top_rgb.x(), 3) + ", " +
                             gfmt(f.limb.top_rgb.y(), 3) + ", " + gfmt(f.limb.top_rgb.z(), 3) + ") and red reaches half "
                             "its strength " + gfmt(f.limb.rim_arcsec, 3) + "″ lower: the air refracts the short "
                             "wavelengths more, so the limb's image splits, violet and blue above green above red. "
                             "Seen by eye the blue and violet are scattered out along the long path (extinction is "
                             "not modelled here), which leaves the green rim of the green flash.\n"
                   : f.limb.found ? "The setting sun's rendered upper limb (sunset_limb_view.png) does not show blue above "
                                    "red down its centre column.\n"
                                  : "The setting sun's upper limb was not found in its rendered view.\n")
       << "\n" << write_shimmer(r.shimmer, f, dir);
    write_text_atomic(path("summary.md"), md.str());
}

}  // namespace refract::experiments::grin_media
