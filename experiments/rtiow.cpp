// RTIOW dielectric chapter: the stages of the glass sphere, Schlick's error, and the
// convergence of the one-branch stochastic choice to the full Fresnel tree.
#include <refract/experiments/rtiow.h>

#include <cmath>
#include <deque>
#include <filesystem>
#include <sstream>

#include <refract/core/optics.h>
#include <refract/core/ray_tree.h>
#include <refract/core/tracer.h>
#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::rtiow {
namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<Stage>& stages() {
    static const std::vector<Stage> v{
        {"fig1_27_always_refract", "Fig. 1.27  always refract (listing 1.51)"},
        {"fig1_28_refract_tir", "Fig. 1.28  refract, or reflect on TIR (listing 1.54)"},
        {"listing1_57_schlick", "+ Schlick reflection (listing 1.57)"},
        {"fig1_29_hollow", "Fig. 1.29  hollow glass sphere (listing 1.58)"},
    };
    return v;
}

namespace {

// The book's max_depth 50 counts rays, the primary included; refract counts bounces.
constexpr int kMaxDepth = 49;

// The book's camera: origin 0, looking down −z, 16:9, vertical field of view 90°
// (viewport height 2 at focal length 1), x to the right. refract's camera follows
// POV-Ray (left-handed: right = sky × direction), which for a view down −z puts −x on
// the right. Mirroring the scene in z (every z negated, the camera looking down +z)
// gives right = +x: the image is the book's, not its mirror image.
json camera(bool quick) {
    return {{"location", vec(0, 0, 0)}, {"look_at", vec(0, 0, 1)}, {"sky", vec(0, 1, 0)}, {"vfov", 90},
            {"width", quick ? 80 : 400}, {"height", quick ? 45 : 225}};
}

json sky() { return {{"type", "gradient"}, {"bottom", vec(1, 1, 1)}, {"top", vec(0.5, 0.7, 1.0)}}; }

json sphere(const std::string& name, const std::string& material, double x, double y, double z, double r) {
    return {{"type", "sphere"}, {"name", name}, {"material", material}, {"center", vec(x, y, z == 0 ? 0.0 : -z)}, {"radius", r}};
}

}  // namespace

json stage_scene(const std::string& id, bool quick) {
    const Stage* stage = nullptr;
    for (const auto& s : stages())
        if (s.id == id) stage = &s;
    if (!stage) throw std::logic_error("rtiow: unknown stage " + id);
    const bool hollow = id == "fig1_29_hollow";
    json glass = {{"type", "dielectric"}, {"ior", 1.5}};
    if (id == "fig1_27_always_refract" || id == "fig1_28_refract_tir") {
        // Reflectance 0: every ray refracts, except where Snell's law has no solution,
        // where the tracer reflects (listing 1.54). Listing 1.51 differs only there, and a
        // solid sphere never gets there (see count_tir_nodes and the summary).
        glass["reflectance"] = "constant";
        glass["reflectivity"] = 0.0;
    } else {
        glass["reflectance"] = "schlick";
    }
    json objects = json::array({sphere("centre", "centre", 0, 0, -1, 0.5), sphere("ground", "ground", 0, -100.5, -1, 100),
                                sphere("right", "metal", 1, 0, -1, 0.5), sphere("left", "glass", -1, 0, -1, 0.5)});
    if (hollow) objects.push_back(sphere("left inside", "glass", -1, 0, -1, -0.45));
    return json{
        {"description", "Ray Tracing in One Weekend, dielectric chapter: " + stage->caption +
                            ". The book's scene mirrored in z (camera looking down +z) so that refract's "
                            "POV-Ray camera shows it as the book does."},
        {"camera", camera(quick)},
        {"background", sky()},
        {"materials",
         {{"ground", {{"type", "lambertian"}, {"color", vec(0.8, 0.8, 0.0)}}},
          {"centre", {{"type", "lambertian"}, {"color", vec(0.1, 0.2, 0.5)}}},
          {"metal", {{"type", "metal"}, {"color", vec(0.8, 0.6, 0.2)}, {"fuzz", hollow ? 0.3 : 0.0}}},
          {"glass", glass}}},
        {"objects", objects},
        {"render", {{"integrator", "stochastic"}, {"samples", quick ? 8 : 100}, {"max_depth", kMaxDepth}, {"jitter", true},
                    {"seed", 1u}, {"polarisation", "natural"}}},
    };
}

std::vector<int> convergence_spp(bool quick) {
    std::vector<int> v;
    for (int s = 1; s <= (quick ? 256 : 1024); s *= 4) v.push_back(s);
    return v;
}

json convergence_scene(int spp, bool quick) {
    json j = stage_scene("listing1_57_schlick", quick);
    j["description"] =
        "RTIOW chapter scene (+ Schlick) with the Lambertian surfaces made directly lit diffuse ones and no "
        "fuzz, so that the stochastic one-branch choice and the full Fresnel tree estimate the same image";
    j["camera"]["width"] = quick ? 48 : 200;
    j["camera"]["height"] = quick ? 27 : 112;
    j["materials"]["ground"] = {{"type", "diffuse"}, {"color", vec(0.8, 0.8, 0.0)}, {"ambient", 0.2}};
    j["materials"]["centre"] = {{"type", "diffuse"}, {"color", vec(0.1, 0.2, 0.5)}, {"ambient", 0.2}};
    j["lights"] = json::array({{{"position", vec(-3, 5, 2)}, {"color", vec(1, 1, 1)}}});
    if (spp == 0)
        j["render"] = {{"integrator", "fresnel-tree"}, {"threshold", 0}, {"max_depth", kMaxDepth}, {"polarisation", "natural"}};
    else
        j["render"] = {{"integrator", "stochastic"}, {"samples", spp}, {"max_depth", kMaxDepth}, {"jitter", false}, {"seed", 7u},
                       {"polarisation", "natural"}};
    return j;
}

// Counts the dielectric hits at total internal reflection in every pixel's ray tree
// (branches under 1e-4 dropped).
struct TirCounter {
    std::uint64_t tir = 0;
    void background(const TreeEntry&) {}
    void leaf(const TreeEntry&, const SurfaceHit&) {}
    double band_ior(const TreeEntry&, const SurfaceHit&) const { return 0.0; }
    double wavelength(const TreeEntry&) const { return 0.0; }
    bool intercept(RayTreeWalker&, const TreeEntry& e, const SurfaceHit& h, RayTreeWalker::List&) {
        if (const auto* d = h.material->dielectric()) {
            const double eta = h.entering ? d->ior : 1.0 / d->ior;
            if (!optics::refract(e.ray.dir, h.normal, eta)) ++tir;
        }
        return false;
    }
};

std::uint64_t count_tir_nodes(const Scene& scene) {
    SceneTracer tracer(scene);
    RenderStats st;
    TreeLimits limits = tree_limits(scene.settings);
    limits.threshold = 1e-4;
    RayTreeWalker walker(tracer, limits, st);
    TirCounter counter;
    for (int j = 0; j < scene.camera.height; ++j)
        for (int i = 0; i < scene.camera.width; ++i) {
            RayTreeWalker::List list{TreeEntry{tracer.camera_ray(i + 0.5, j + 0.5), Vec3(1, 1, 1)}};
            walker.walk(list, counter);
        }
    return counter.tir;
}

Result compute(const ExperimentOptions& opt) {
    Result res;
    res.quick = opt.quick;
    RenderOptions ro;
    ro.threads = opt.threads;

    // ---- The stages.
    for (const auto& st : stages()) {
        StageResult sr;
        sr.stage = st;
        sr.scene = stage_scene(st.id, opt.quick);
        const Scene s = scene_from_json(sr.scene, st.id + ".json");
        if (st.id == "fig1_28_refract_tir") sr.image = res.stages.front().image;  // the same scene as Fig. 1.27 (see write)
        else sr.image = render(s, ro).image;
        sr.tir_nodes = count_tir_nodes(s);
        res.stages.push_back(std::move(sr));
    }

    // ---- Schlick against exact Fresnel.
    const std::vector<SchlickCase> cases{{"n=1.5", 1.5, false, {}, 0, 0, 0},
                                         {"n=2.417", 2.417, false, {}, 0, 0, 0},
                                         {"inside eta=1/1.5 (RTIOW: cos_i)", 1 / 1.5, false, {}, 0, 0, 0},
                                         {"inside eta=1/1.5 (cos_t)", 1 / 1.5, true, {}, 0, 0, 0}};
    for (SchlickCase c : cases) {
        double sum = 0;
        int count = 0;
        for (int k = 0; k <= 360; ++k) {
            const double a = 0.25 * k;
            const double ci = std::fmax(std::cos(a * M_PI / 180.0), 0.0);
            const double R = optics::fresnel_reflectance(ci, c.eta);
            const auto ct = optics::cos_transmitted(ci, c.eta);
            const double S = !ct ? 1.0 : optics::schlick(c.use_cos_t ? *ct : ci, c.eta);
            c.rows.push_back({a, R, S});
            if (std::abs(S - R) > c.max_error) c.max_error = std::abs(S - R), c.max_error_at = a;
            sum += std::abs(S - R);
            ++count;
        }
        c.mean_error = sum / count;
        res.schlick.push_back(std::move(c));
    }

    // ---- Convergence of the stochastic choice to the tree.
    Convergence& cv = res.convergence;
    cv.reference_scene = convergence_scene(0, opt.quick);
    cv.stochastic_scene = convergence_scene(convergence_spp(opt.quick).back(), opt.quick);
    cv.reference = render(scene_from_json(cv.reference_scene, "convergence_reference.json"), ro).image;
    for (int spp : convergence_spp(opt.quick)) {
        const auto r = render(scene_from_json(convergence_scene(spp, opt.quick), "convergence"), ro);
        cv.rows.push_back({spp, rmse(r.image, cv.reference), r.stats.seconds});
        if (spp == convergence_spp(opt.quick).back()) cv.stochastic = r.image;
    }
    std::vector<double> xs, ys;
    for (const auto& row : cv.rows) xs.push_back(row.spp), ys.push_back(row.rmse);
    cv.fit = loglog_fit(xs, ys);
    res.findings = judge(res);
    return res;
}

Findings judge(const Result& r) {
    Findings f;
    bool solid = false;  // a stage with the solid sphere was run
    f.solid_without_tir = true;
    for (const auto& s : r.stages) {
        if (s.stage.id == "fig1_29_hollow") f.hollow_with_tir = s.tir_nodes > 0;
        else solid = true, f.solid_without_tir = f.solid_without_tir && s.tir_nodes == 0;
    }
    f.solid_without_tir = f.solid_without_tir && solid;
    f.schlick_one_at_tir = !r.schlick.empty();
    for (const auto& c : r.schlick)
        for (const auto& row : c.rows)
            if (row.fresnel == 1 && row.schlick != 1) f.schlick_one_at_tir = false;
    f.slope_one_half = !r.convergence.rows.empty() && std::abs(r.convergence.fit.slope + 0.5) <= 0.1;
    return f;
}

std::string tir_text(const Result& r) {
    std::string s =
        "**Always refract.** refract's dielectric always handles total internal reflection, so listing 1.51 "
        "(refract even when Snell's law has no solution; it yields NaN directions there) cannot be written "
        "as a material. ";
    if (r.findings.solid_without_tir)
        s += "It does not need to be: a ray that enters a solid sphere meets the far side at its "
             "own refraction angle, below the critical angle, so TIR never occurs and listings 1.51 and 1.54 give "
             "the same image. Both stages use a dielectric with constant reflectance 0 (refract whenever "
             "possible), and Fig. 1.28 is Fig. 1.27. ";
    else
        s += "A ray that enters a solid sphere meets the far side at its own refraction angle, below the critical "
             "angle, yet the pixel-centre trees of the solid sphere's stages below meet TIR, where listings 1.51 and "
             "1.54 differ: Fig. 1.28 (here the render of Fig. 1.27's scene, a dielectric with constant reflectance 0) "
             "is not what listing 1.51 would show there. ";
    return s + "Dielectric nodes with TIR met by the pixel-centre ray trees:";
}

std::string hollow_text(const Result& r) {
    if (r.findings.hollow_with_tir)
        return "The hollow sphere is where TIR occurs: rays inside the thin shell meet its surfaces beyond the "
               "critical angle and run along it, which lightens the rim; through the middle the world is seen "
               "upright and barely shifted, like a soap bubble, as in the book's Fig. 1.29.";
    return "The hollow sphere's pixel-centre trees meet no TIR either (the thin shell's rim would be where rays "
           "meet its surfaces beyond the critical angle).";
}

std::string schlick_text(const Result& r) {
    return r.findings.schlick_one_at_tir
               ? "Beyond the critical angle both are 1 (the tracer folds TIR in). "
               : "Beyond the critical angle the exact Fresnel is 1, but Schlick is not 1 in every row there. ";
}

std::string convergence_text(const Result& r) {
    std::string s = "Least-squares slope of log RMSE against log spp: **" + fmt(r.convergence.fit.slope, 4) + "** (1/√spp is −0.5)";
    if (r.findings.slope_one_half)
        return s + ": the one-branch choice is an unbiased estimator of the tree, its error falls like 1/√spp.";
    return s + ": the error does not fall like 1/√spp here (more than 0.1 from −0.5), so this run does not show the "
               "one-branch choice converging to the tree as an unbiased estimator would.";
}

void write(const Result& res, const std::string& dir) {
    ensure_dir(dir);
    auto path = [&](const std::string& f) { return (fs::path(dir) / f).string(); };
    const std::string scenes = path("scenes");
    std::ostringstream md;
    md << "# Ray Tracing in One Weekend: the dielectric chapter\n\n"
       << "Reproduced by `refract experiment rtiow-dielectric`" << (res.quick ? " (quick mode: small images, few samples)" : "")
       << ". Every number below is measured by this run.\n\n";

    // ---- The stages.
    {
        std::vector<Panel> panels;
        std::ostringstream tirs;
        for (const auto& sr : res.stages) {
            const Stage& st = sr.stage;
            save_json(scenes, st.id + ".json", sr.scene);
            write_image(path(st.id + ".png"), sr.image);
            panels.push_back({st.id + ".png", st.caption});
            tirs << "| " << st.caption << " | " << sr.tir_nodes << " |\n";
        }
        std::ostringstream title;
        title << "Ray Tracing in One Weekend, dielectric chapter (stochastic, " << (res.quick ? 8 : 100)
              << " samples per pixel)";
        image_grid_figure(dir, "stages", 2, 2, panels, title.str(), 225.0 / 400.0, 420);
        md << "## The stages of the glass sphere\n\n"
           << "`fig1_27_always_refract.png`, `fig1_28_refract_tir.png`, `listing1_57_schlick.png`, "
           << "`fig1_29_hollow.png` (assembled in `stages.png`/`.pdf`), scenes in `scenes/*.json` (re-render "
           << "with `refract render scenes/fig1_29_hollow.json -o hollow.png`). Listing 1.55's scene: ground sphere "
           << "r = 100 at (0, −100.5, −1) and centre sphere Lambertian, metal (0.8, 0.6, 0.2) on the right, glass "
           << "n = 1.5 on the left; listing 1.58 adds the inner sphere of radius −0.45 (normals flipped: a hollow "
           << "shell) and metal fuzz 0.3. `stochastic` integrator as in the book: one scattered ray per hit, "
           << (res.quick ? 8 : 100) << " jittered samples per pixel, depth 49 (the book's max_depth 50), sky gradient white → (0.5, 0.7, 1). "
           << "The PNGs are sRGB-encoded; the book encodes with a square root (gamma 2), so its images are a "
              "little darker in the mid tones (linear 0.5: 0.707 against sRGB's 0.735).\n\n"
           << "**Camera.** The book's camera looks down −z with x to the right (right-handed). refract's camera "
              "follows POV-Ray (right = sky × direction), which for that view puts −x on the right and would show "
              "the scene mirrored. The scene files therefore negate every z coordinate and look down +z: a "
              "reflection of both world and camera, so the image is exactly the book's, glass sphere on the left.\n\n"
           << tir_text(res) << "\n\n"
           << "| stage | TIR nodes |\n|---|---|\n"
           << tirs.str() << "\n" << hollow_text(res) << "\n\n![stages](stages.png)\n\n";
    }

    // ---- Schlick against exact Fresnel.
    {
        Csv t{csv_join(csv_header<SchlickCase>(), csv_header<SchlickRow>()), {}};
        md << "## Schlick against exact Fresnel\n\n"
           << "`schlick_error.csv` (`case,eta,angle_deg,fresnel,schlick,error`, 0-90° in 0.25° steps), "
           << "`schlick_error.png`. " << schlick_text(res)
           << "Inside, RTIOW evaluates Schlick with the incident cosine; the last case uses the transmitted cosine "
              "instead.\n\n| case | max abs error | at | mean abs error |\n|---|---|---|---|\n";
        for (const auto& c : res.schlick) {
            for (const auto& row : c.rows) t.add(csv_join(csv_cells(c), csv_cells(row)));
            md << "| " << c.name << " | " << fmt(c.max_error, 3) << " | " << fmt(c.max_error_at) << "° | "
               << fmt(c.mean_error, 3) << " |\n";
        }
        write_csv(path("schlick_error.csv"), t);
        std::ostringstream b;
        b << "set datafile separator ','\nset multiplot layout 2,1\n"
          << "set grid\nset xrange [0:90]\nset xtics 10\nset key left center box opaque\n"
          << "set title 'Reflectance: exact Fresnel (solid) and Schlick (dashed)'\nset ylabel 'R'\nset yrange [0:1]\n"
          << "sel(n) = (stringcolumn(1) eq n)\n"
          << "plot 'schlick_error.csv' using 3:(sel('n=1.5') ? $4 : NaN) every ::1 with lines lw 2 lc 1 title 'n = 1.5', \\\n"
          << "     '' using 3:(sel('n=1.5') ? $5 : NaN) every ::1 with lines lw 2 lc 1 dt 2 notitle, \\\n"
          << "     '' using 3:(sel('n=2.417') ? $4 : NaN) every ::1 with lines lw 2 lc 2 title 'n = 2.417', \\\n"
          << "     '' using 3:(sel('n=2.417') ? $5 : NaN) every ::1 with lines lw 2 lc 2 dt 2 notitle, \\\n"
          << "     '' using 3:(sel('inside eta=1/1.5 (RTIOW: cos_i)') ? $4 : NaN) every ::1 with lines lw 2 lc 7 title 'inside, eta = 1/1.5', \\\n"
          << "     '' using 3:(sel('inside eta=1/1.5 (RTIOW: cos_i)') ? $5 : NaN) every ::1 with lines lw 2 lc 7 dt 2 notitle, \\\n"
          << "     '' using 3:(sel('inside eta=1/1.5 (cos_t)') ? $5 : NaN) every ::1 with lines lw 2 lc 4 dt 3 title 'inside, Schlick with cos θ_t'\n"
          << "set title 'Schlick − Fresnel'\nset ylabel 'error'\nset yrange [*:*]\nset xlabel 'angle of incidence (degrees)'\n"
          << "set key right bottom box opaque\n"
          << "plot 'schlick_error.csv' using 3:(sel('n=1.5') ? $6 : NaN) every ::1 with lines lw 2 lc 1 title 'n = 1.5', \\\n"
          << "     '' using 3:(sel('n=2.417') ? $6 : NaN) every ::1 with lines lw 2 lc 2 title 'n = 2.417', \\\n"
          << "     '' using 3:(sel('inside eta=1/1.5 (RTIOW: cos_i)') ? $6 : NaN) every ::1 with lines lw 2 lc 7 title 'inside (cos θ_i, RTIOW)', \\\n"
          << "     '' using 3:(sel('inside eta=1/1.5 (cos_t)') ? $6 : NaN) every ::1 with lines lw 2 lc 4 dt 3 title 'inside (cos θ_t)'\n"
          << "unset multiplot\n";
        FigureSize size;
        size.height_px = 900;
        size.height_in = 6.5;
        gnuplot_figure(dir, "schlick_error", b.str(), size);
        md << "\n![Schlick](schlick_error.png)\n\n";
    }

    // ---- Convergence of the stochastic choice to the tree.
    {
        const Convergence& cv = res.convergence;
        save_json(scenes, "convergence_reference.json", cv.reference_scene);
        save_json(scenes, "convergence_stochastic.json", cv.stochastic_scene);
        write_image(path("convergence_reference.png"), cv.reference);
        std::vector<double> xs, ys;
        for (const auto& row : cv.rows) {
            xs.push_back(row.spp);
            ys.push_back(row.rmse);
        }
        write_image(path("convergence_stochastic.png"), cv.stochastic);
        write_csv(path("convergence.csv"), csv_table(cv.rows));
        const LineFit& fit = cv.fit;
        std::ostringstream b;
        b << "set datafile separator ','\nset logscale x 4\nset logscale y 10\nset format y '%g'\n"
          << "set ytics (0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5)\nset grid\nset key top right box opaque\n"
          << "set xlabel 'samples per pixel'\nset ylabel 'RMSE against fresnel-tree (threshold 0)'\n"
          << "set title 'Convergence of the stochastic one-branch choice'\n"
          << "f(x) = exp(" << fit.intercept << ") * x**(" << fit.slope << ")\n"
          << "g(x) = " << ys.front() << " * x**(-0.5)\n"
          << "plot 'convergence.csv' using 1:2 every ::1 with points pt 7 ps 1.5 title 'measured', \\\n"
          << "     f(x) with lines lw 2 title sprintf('fit: slope %.3f', " << fit.slope << "), \\\n"
          << "     g(x) with lines dt 2 lc rgb 'gray40' title 'slope −1/2'\n";
        gnuplot_figure(dir, "convergence", b.str());
        md << "## Convergence: the stochastic choice against the full Fresnel tree\n\n"
           << "`convergence.csv` (`spp,rmse,seconds`), `convergence.png`. Scene `scenes/convergence_*.json`: the "
              "chapter's scene with Schlick glass, the Lambertian surfaces replaced by directly lit diffuse ones and "
              "fuzz 0, so that both integrators estimate the same value per pixel (the stochastic integrator picks "
              "one branch with probability R; the tree takes both with weights R and 1 − R). Reference: "
              "`fresnel-tree`, threshold 0, depth 49; stochastic: pixel centres (no jitter), depth 49 (the book's 50), seed 7.\n\n"
           << "| spp | RMSE |\n|---|---|\n";
        for (size_t k = 0; k < xs.size(); ++k) md << "| " << xs[k] << " | " << fmt(ys[k], 4) << " |\n";
        md << "\n" << convergence_text(res) << "\n\n![convergence](convergence.png)\n";
    }
    write_text_atomic(path("summary.md"), md.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::rtiow
