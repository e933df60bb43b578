// Exact polarisation against natural light: the files (CSV, figures, images, scenes,
// summary.md) written from a Result (experiments/polarisation.h).
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <refract/core/polarisation_output.h>
#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/plot.h>
#include <refract/experiments/polarisation.h>

namespace refract::experiments::polarisation {

namespace {
namespace fs = std::filesystem;

std::string f3(double v) { return fmt(v, 3); }
std::string f4(double v) { return fmt(v, 4); }
std::string angle_id(double a) {
    char b[8];
    std::snprintf(b, sizeof b, "%03d", static_cast<int>(std::lround(a)));
    return b;
}

// A map of per-pixel values as raw native float32, row 0 at the top (for gnuplot).
void write_f32(const std::string& path, const std::vector<double>& v) {
    std::string bytes(v.size() * sizeof(float), '\0');
    for (size_t k = 0; k < v.size(); ++k) {
        const float f = static_cast<float>(v[k]);
        std::memcpy(&bytes[k * sizeof(float)], &f, sizeof(float));
    }
    write_text_atomic(path, bytes);
}

void map_figure(const std::string& dir, const std::string& name, const std::string& data, int w, int h,
                const std::string& title, const std::string& cblabel, double cbmax, const std::string& palette) {
    std::ostringstream b;
    b << "set size ratio -1\nunset key\nunset xtics\nunset ytics\n"
      << "set xrange [-0.5:" << w - 0.5 << "]\nset yrange [-0.5:" << h - 0.5 << "]\n"
      << "set cbrange [0:" << cbmax << "]\nset cblabel '" << cblabel << "'\n" << palette << "\n"
      << "set title \"" << title << "\"\n"
      << "plot '" << data << "' binary array=(" << w << "," << h << ") format='%float32' flipy with image\n";
    FigureSize size;
    size.width_px = 820;
    size.height_px = static_cast<int>(std::lround(700.0 * h / w)) + 90;
    size.width_in = 6.5;
    size.height_in = 6.5 * size.height_px / size.width_px;
    gnuplot_figure(dir, name, b.str(), size);
}

}  // namespace

std::string depth_sums_text(const Result& r, const Comparison& c) {
    if (c.spectral) return "";
    const bool match = &c == &r.diamond ? r.findings.diamond_depth_sums_match : r.findings.glass_depth_sums_match;
    std::ostringstream s;
    if (match) s << "The " << c.title << " is rendered by this same walk: the sums over depth against the renders' ΣS0: ";
    else
        s << "The " << c.title << " is rendered by the same walk, yet the sums over depth differ from the renders' "
          << "ΣS0 (beyond 1e-9): ";
    s << "natural " << fmt(c.depth_natural, 10) << " / " << fmt(c.light_natural, 10) << ", exact "
      << fmt(c.depth_exact, 10) << " / " << fmt(c.light_exact, 10) << ".\n\n";
    return s.str();
}

std::string clipping_text(const Result& r) {
    const AnalyserStudy& an = r.analyser;
    std::ostringstream s;
    if (r.findings.clipping_deviates)
        s << "The cie-rgb pipeline (the 1998 paper's) clips negative channel sums to 0 at the end, which breaks "
             "the sums where it acts: "
          << an.deviating_channels << " pixel channels deviate by more than 1e-9, "
          << (an.deviations_at_zeros ? "every one of them" : "not all of them") << " 0 in one of the five images (";
    else
        s << "The cie-rgb pipeline (the 1998 paper's) clips negative channel sums to 0 at the end, which could break "
             "the sums where it acts; no pixel channel deviates by more than 1e-9 (";
    s << an.zero_channels << " channels are 0 somewhere, clipped or dark).";
    return s.str();
}

std::string cone_text(const Result& r) {
    const AnalyserStudy& an = r.analyser;
    std::ostringstream s;
    if (r.findings.outside_cone)
        s << "The same cause: a cie-rgb channel is a sum over wavelengths with weights of both signs (r̄'s negative "
             "lobe) and its S0 is clipped at 0 at the end, so its (S0, S1, S2, S3) need not be a physical Stokes "
             "vector; "
          << an.channels_outside_cone << " pixel channels of the image have √(S1² + S2² + S3²) > S0.";
    else
        s << "Although a cie-rgb channel is a sum over wavelengths with weights of both signs (r̄'s negative lobe), "
             "clipped at 0 at the end, every pixel channel's (S0, S1, S2, S3) lies in the cone √(S1² + S2² + S3²) "
             "<= S0 here.";
    return s.str();
}

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    auto path = [&](const std::string& f) { return (fs::path(dir) / f).string(); };
    const std::string scenes = path("scenes");
    const bool plots = gnuplot_available();
    const auto& classes = path_classes();
    std::ostringstream md;
    md << "# Exact polarisation against natural light\n\n"
       << "Measured by `refract experiment polarisation`" << (r.quick ? " (quick mode: small images, few photons)" : "")
       << ". Natural light (Yasuda 1984 eq. 7 at every interface, the papers' model) against exact "
          "polarisation (Stokes vectors through Mueller matrices; conventions in docs/polarisation.md). "
          "Scenes in `scenes/`.\n\n";

    // ---- 1. Sphere ------------------------------------------------------------------------
    const SphereStudy& sp = r.sphere;
    for (const auto& [n, j] : sp.scenes) save_json(scenes, "sphere-dop-n" + fmt(n) + ".json", j);
    Csv pts{csv_header<SpherePoint>(), {}};
    // Grouped by index and class (gnuplot draws each group as one line), by angle within.
    for (double n : sp.indices)
        for (size_t c = 0; c < classes.size(); ++c)
            for (const auto& p : sp.points) {
                if (p.n != n || p.cls != static_cast<int>(c)) continue;
                pts.add(csv_cells(p));
            }
    write_csv(path("sphere_dop.csv"), pts);
    const Csv errs = csv_table(sp.errors);
    write_csv(path("sphere_dop_errors.csv"), errs);
    write_csv(path("sphere_rainbow.csv"), csv_table(sp.rainbows));
    md << "## 1. A sphere's paths: degree of polarisation against the closed forms\n\n"
       << "Parallel rays along +z hit a unit sphere at impact parameters b = sin θi, θi = "
       << fmt(sp.angles_deg.front()) << "…" << fmt(sp.angles_deg.back()) << "° (" << sp.angles_deg.size()
       << " values), exact polarisation, threshold 0. Each background leaf of the ray tree is classified by its "
          "path (reflections, transmissions) and brings C·(1, 0, 0, 0), white unpolarised light, to the camera; "
          "the Stokes vectors are summed per class. No other path falls into a class, so each has a closed form "
          "(Rs, Rp at the entry angle, T = 1 − R): reflection (Rs − Rp)/(Rs + Rp); k internal reflections "
          "(Ts²Rs^k − Tp²Rp^k)/(Ts²Rs^k + Tp²Rp^k) (k = 0: direct transmission). The camera frame's x̂ is ŝ of "
          "every interface on these paths, so S1/S0 is the signed (Is − Ip)/(Is + Ip).\n\n"
       << errs.markdown() << "\n`max_dop_error`: max |DoP − |closed form||; `max_signed_error`: max |S1/S0 − closed "
          "form|; `max_off_plane`: max √(S2² + S3²)/S0. Largest DoP error over both spheres and all classes: **"
       << fmt(sp.max_dop_error, 3) << "**.\n\n";
    for (const auto& b : sp.rainbows)
        md << "Primary rainbow ray of n = " << fmt(b.n) << " (one internal reflection at minimum deviation, θi = "
           << fmt(b.theta_deg, 5) << "°, deviation " << fmt(b.deviation_deg, 5) << "°): DoP " << fmt(b.dop, 6)
           << " (closed form " << fmt(b.dop_closed, 6) << ").\n";
    md << "\n";
    if (plots) {
        std::ostringstream g;
        g << "set datafile separator ','\nset multiplot layout 1,2\nset grid\nset xrange [0:90]\nset yrange [0:1.02]\n"
          << "set xtics 15\nset xlabel 'angle of incidence θi (degrees)'\nset ylabel 'degree of polarisation'\n"
          << "set key top left box opaque font ',9'\n";
        for (size_t k = 0; k < sp.indices.size(); ++k) {
            const double n = sp.indices[k];
            g << "set title 'Sphere n = " << fmt(n) << ": refract (points), closed form (lines)'\n";
            for (const auto& b : sp.rainbows)
                if (b.n == n)
                    g << "set arrow 1 from " << b.theta_deg << ",0 to " << b.theta_deg
                      << ",1 nohead dt 2 lc rgb 'gray40'\nset label 1 'rainbow' at " << b.theta_deg + 1 << ",0.05\n";
            g << "plot ";
            for (size_t c = 0; c < classes.size(); ++c) {
                const std::string sel = "(($1 == " + fmt(n) + " && $3 == " + std::to_string(c) + ") ? ";
                g << (c ? ", \\\n     " : "") << "'sphere_dop.csv' every ::1 using 2:" << sel
                  << "$10 : NaN) with lines lw 2 lc " << c + 1 << " notitle, \\\n"
                  << "     '' every ::1 using 2:" << sel << "$9 : NaN) with points pt 7 ps 0.6 lc " << c + 1
                  << " title '" << classes[c].name << "'";
            }
            g << "\nunset arrow 1\nunset label 1\n";
        }
        g << "unset multiplot\n";
        const FigureSize size{1200, 520, 10.0, 4.3};
        gnuplot_figure(dir, "sphere_dop", g.str(), size);
        md << "![sphere DoP](sphere_dop.png)\n\n";
    }

    // ---- 2. Natural against exact -------------------------------------------------------------
    Csv cmp{csv_header<Comparison>(), {}};
    Csv depth{csv_join({"scene"}, csv_header<DepthRow>()), {}};
    for (const Comparison* c : {&r.diamond, &r.glass}) {
        save_json(scenes, c->id + "-natural.json", c->natural_scene);
        save_json(scenes, c->id + "-exact.json", c->exact_scene);
        write_image(path(c->id + "-natural.png"), c->natural);
        write_image(path(c->id + "-exact.png"), c->exact);
        write_image(path(c->id + "-difference-x10.png"), c->difference_x10);
        write_f32(path("de2000_" + c->id + ".f32"), c->delta_e);
        cmp.add(csv_cells(*c));
        for (const auto& d : c->depth) depth.add(csv_join({c->id}, csv_cells(d)));
        if (plots)
            map_figure(dir, "de2000_" + c->id, "de2000_" + c->id + ".f32", c->width, c->height,
                       "CIEDE2000, natural light against exact polarisation: " + c->title +
                           "\\n(colour scale up to the 99th percentile, " + f3(c->de_p99) + "; max " +
                           f3(c->de_max) + ")",
                       "ΔE00", std::fmax(c->de_p99, 1e-3), "set palette rgb 21,22,23");
    }
    write_csv(path("natural_vs_exact.csv"), cmp);
    write_csv(path("depth_split.csv"), depth);
    md << "## 2. Natural light against exact polarisation\n\n"
       << "Both models walk the same ray tree (the pruning threshold uses the natural-light weights), so the "
          "differences below are the physics only. The 1998 diamond: the scene of `refract experiment "
          "ohtsuka1998` (" << r.diamond.width << "×" << r.diamond.height << ", light pass with "
       << r.diamond.natural_scene["render"]["light_pass"]["photons"].get<std::uint64_t>()
       << " photons, then the spectral eye pass, 31 wavelengths, cie-rgb), each model with its own light pass. "
          "The glass sphere: scenes/examples/glass-sphere.json (n = 1.5, fresnel-tree, "
       << r.glass.width << "×" << r.glass.height << ").\n\n"
       << "| scene | RMSE | max abs | ΔE00 mean | ΔE00 95th pct | ΔE00 max | ΣS0 natural | ΣS0 exact | exact/natural "
          "| object pixels | ΣS0 object natural | ΣS0 object exact | exact/natural |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Comparison* c : {&r.diamond, &r.glass})
        md << "| " << c->title << " | " << f4(c->rmse) << " | " << f4(c->max_abs) << " | " << f4(c->de_mean) << " | "
           << f4(c->de_p95) << " | " << f4(c->de_max) << " | " << fmt(c->light_natural, 6) << " | "
           << fmt(c->light_exact, 6) << " | " << fmt(c->light_exact / c->light_natural, 6) << " | " << c->object_pixels
           << " | " << fmt(c->object_natural, 6) << " | " << fmt(c->object_exact, 6) << " | "
           << fmt(c->object_exact / c->object_natural, 6) << " |\n";
    md << "\nRMSE and max abs over every pixel and channel (linear RGB); ΔE00 per pixel with the values (negatives "
          "clipped) read as linear sRGB; ΣS0 summed over pixels and channels, over the whole image and over the "
          "pixels whose primary ray first meets the object (the gem, the glass sphere).\n\n"
       << "![diamond natural](diamond-natural.png) ![diamond exact](diamond-exact.png) "
          "![difference ×10](diamond-difference-x10.png)\n\n"
       << "![sphere natural](sphere-natural.png) ![sphere exact](sphere-exact.png) "
          "![difference ×10](sphere-difference-x10.png)\n\n";
    if (plots) md << "![ΔE diamond](de2000_diamond.png) ![ΔE sphere](de2000_sphere.png)\n\n";

    md << "### The difference by path depth\n\n"
       << "Light reaching the camera summed over every pixel centre (S0, all channels) per depth of the entry "
          "that ends at the background or at a diffuse surface (depth = surface interactions before it), with "
          "each model's own walker (RayTreeWalkerT<NaturalLight>, RayTreeWalkerT<EyeStokes>). The split is made "
          "on the non-spectral RGB walk with the nominal index (the diamond's n_d "
          "and its 8/8 limits) and direct lighting of the floor, without the light pass's caustics: it "
          "apportions the difference, while the totals of section 2 come from the renders.\n\n";
    for (const Comparison* c : {&r.diamond, &r.glass}) {
        const double tn = c->depth_natural, te = c->depth_exact;
        md << "**" << c->title << "**\n\n| depth | natural | exact | difference | relative difference |\n"
           << "|---|---|---|---|---|\n";
        for (const auto& d : c->depth) {
            if (d.natural == 0 && d.exact == 0) continue;
            md << "| " << d.depth << " | " << fmt(d.natural, 6) << " | " << fmt(d.exact, 6) << " | "
               << fmt(d.exact - d.natural, 4) << " | "
               << (d.natural > 0 ? fmt((d.exact - d.natural) / d.natural, 4) : std::string("—")) << " |\n";
        }
        md << "| all | " << fmt(tn, 6) << " | " << fmt(te, 6) << " | " << fmt(te - tn, 4) << " | "
           << fmt((te - tn) / tn, 4) << " |\n\n";
        md << depth_sums_text(r, *c);
    }
    if (plots) {
        std::ostringstream g;
        g << "set datafile separator ','\nset multiplot layout 2,1\nset grid\nset key top right box opaque\n"
          << "sel(s) = (stringcolumn(1) eq s)\n"
          << "set title 'Light reaching the camera per path depth (ΣS0 over pixels and channels)'\n"
          << "set logscale y\nset format y '%g'\nset ylabel 'ΣS0'\nset xlabel 'depth'\n"
          << "plot 'depth_split.csv' every ::1 using 2:(sel('diamond') && $3 > 0 ? $3 : NaN) with lines lw 2 lc 1 "
             "title 'diamond, natural', \\\n"
          << "     '' every ::1 using 2:(sel('diamond') && $4 > 0 ? $4 : NaN) with points pt 7 lc 1 title "
             "'diamond, exact', \\\n"
          << "     '' every ::1 using 2:(sel('sphere') && $3 > 0 ? $3 : NaN) with lines lw 2 lc 2 title "
             "'glass sphere, natural', \\\n"
          << "     '' every ::1 using 2:(sel('sphere') && $4 > 0 ? $4 : NaN) with points pt 7 lc 2 title "
             "'glass sphere, exact'\n"
          << "unset logscale y\nset format y '%g'\nset title '(exact − natural) / natural per path depth'\n"
          << "set ylabel 'relative difference'\n"
          << "plot 'depth_split.csv' every ::1 using 2:(sel('diamond') && $3 > 0 ? $6 : NaN) with linespoints lw 2 "
             "pt 7 lc 1 title 'diamond', \\\n"
          << "     '' every ::1 using 2:(sel('sphere') && $3 > 0 ? $6 : NaN) with linespoints lw 2 pt 7 lc 2 title "
             "'glass sphere'\n"
          << "unset multiplot\n";
        FigureSize size;
        size.height_px = 900;
        size.height_in = 6.5;
        gnuplot_figure(dir, "depth_split", g.str(), size);
        md << "![depth split](depth_split.png)\n\n";
    }

    // ---- 3. The analyser --------------------------------------------------------------------
    const AnalyserStudy& an = r.analyser;
    const PolarisationImages& pol = r.diamond.exact_polarisation;
    write_polarisation(path("diamond-exact.png"), an.width, an.height, pol);
    write_image(path("diamond-dolp.png"), an.dolp_grey);
    write_f32(path("dolp_diamond.f32"), pol.dolp);
    Csv ana{{"analyser_deg", "light", "light_over_unanalysed"}, {}};
    std::vector<Panel> panels{{"diamond-exact.png", "exact, no analyser (S0)"},
                              {"diamond-dolp.png", "degree of linear polarisation (grey 0-1, clamped)"}};
    for (size_t k = 0; k < an.angles.size(); ++k) {
        const std::string id = "diamond-analyser-" + angle_id(an.angles[k]);
        save_json(scenes, id + ".json", an.scenes[k]);
        write_image(path(id + ".png"), an.images[k]);
        ana.add({fmt(an.angles[k]), fmt(an.light[k], 8), fmt(an.light[k] / r.diamond.light_exact, 6)});
        panels.push_back({id + ".png", "linear analyser at " + fmt(an.angles[k]) + " degrees"});
    }
    write_csv(path("analyser.csv"), ana);
    md << "## 3. The diamond through a linear analyser\n\n"
       << "The exact render of section 2 seen through an ideal linear polariser at 0°, 45°, 90° and 135° "
          "(measured on the image from its right towards its top), the same light pass reused.\n\n"
       << "| analyser | ΣS0 | / unanalysed |\n|---|---|---|\n";
    for (size_t k = 0; k < an.angles.size(); ++k)
        md << "| " << fmt(an.angles[k]) << "° | " << fmt(an.light[k], 8) << " | "
           << fmt(an.light[k] / r.diamond.light_exact, 6) << " |\n";
    md << "| none | " << fmt(r.diamond.light_exact, 8) << " | 1 |\n\n"
       << "Check, per pixel and channel: max |I(0) + I(90) − S0| = **" << fmt(an.max_dev_0_90, 3)
       << "**, max |I(45) + I(135) − S0| = **" << fmt(an.max_dev_45_135, 3) << "**";
    md << ". Over the " << 3 * an.width * an.height - an.zero_channels << " pixel channels that are not 0 in any "
       << "of the five images: " << fmt(an.max_dev_0_90_nonzero, 3) << " and " << fmt(an.max_dev_45_135_nonzero, 3)
       << ". " << clipping_text(r) << "\n\nDegree of linear polarisation over the gem's " << r.diamond.object_pixels
       << " pixels: mean " << f3(an.dolp_mean_object) << ", max " << f3(an.dolp_max_object) << "; " << an.dolp_above_one
       << " of them above 1. " << cone_text(r)
       << " `diamond-dolp.png`: grey level = DoLP; `diamond-exact.stokes.exr`, `.dolp.exr`, `.aolp.exr`: the "
          "Stokes vectors per channel, DoLP and AoLP (docs/polarisation.md).\n\n";
    if (plots) {
        image_grid_figure(dir, "analyser", 2, 3, panels, "1998 diamond, exact polarisation, through a linear analyser",
                          static_cast<double>(an.height) / an.width, 320);
        map_figure(dir, "dolp_diamond", "dolp_diamond.f32", an.width, an.height,
                   "1998 diamond: degree of linear polarisation (exact)", "DoLP", 1.0,
                   "set palette defined (0 'black', 0.25 'dark-blue', 0.5 'red', 0.75 'orange', 1 '#ffffc0')");
        md << "![analyser](analyser.png)\n\n![DoLP](dolp_diamond.png)\n\n";
    } else {
        md << "gnuplot was not found: the figures were not drawn (the CSV files are written).\n\n";
    }

    // ---- Times -----------------------------------------------------------------------------
    Csv times{{"part", "seconds"}, {}};
    times.add({"sphere_dop", fmt(r.seconds_sphere, 4)});
    for (const Comparison* c : {&r.diamond, &r.glass}) {
        times.add({c->id + "_natural", fmt(c->seconds_natural, 4)});
        times.add({c->id + "_exact", fmt(c->seconds_exact, 4)});
        if (c->light_pass_natural > 0) times.add({c->id + "_light_pass_natural", fmt(c->light_pass_natural, 4)});
        if (c->light_pass_exact > 0) times.add({c->id + "_light_pass_exact", fmt(c->light_pass_exact, 4)});
        times.add({c->id + "_depth_split", fmt(c->seconds_depth, 4)});
    }
    times.add({"analyser_renders", fmt(an.seconds, 4)});
    times.add({"total_compute", fmt(r.seconds_total, 4)});
    write_csv(path("times.csv"), times);
    md << "## Times\n\n" << times.markdown() << "\n"
       << "Diamond, exact against natural (light + eye pass): " << fmt(r.diamond.seconds_exact / r.diamond.seconds_natural, 3)
       << "×. Threads: " << r.threads << ".\n";
    write_text_atomic(path("summary.md"), md.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::polarisation
