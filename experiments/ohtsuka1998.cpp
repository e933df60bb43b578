#include <refract/experiments/ohtsuka1998.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <thread>

#include <refract/core/illumination_map.h>
#include <refract/core/image.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/render.h>
#include <refract/core/spectrum/cie.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/ohtsuka1998_maps.h>
#include <refract/experiments/ohtsuka1998_result.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::ohtsuka1998 {

using nlohmann::json;

namespace {
constexpr int kMaxDepth = 17;  // 8 reflections + 8 transmissions + the primary ray
// The main image's light pass (the first version had 30 000 photons on box elements of
// 0.025; the map studies below chose these).
constexpr std::uint64_t kPhotons = 1000000, kFirstPhotons = 30000;
constexpr double kElement = 0.0125, kFirstElement = 0.025;
}

json scene_json(const SceneParams& p) {
    json spectral = {{"range", json::array({400, 700})},
                     {"step", p.step_nm},
                     {"pipeline", "cie-rgb"},
                     {"light", "equal"},
                     {"shortcut", p.shortcut},
                     {"shortcut_threshold", p.shortcut_threshold},
                     {"shortcut_wavelengths",
                      json::array({p.shortcut_wavelengths[0], p.shortcut_wavelengths[1], p.shortcut_wavelengths[2]})},
                     {"max_reflections", 8},
                     {"max_transmissions", 8}};
    // The paper's model, natural light at every interface, kept explicitly (the physical
    // mode's default is exact polarisation).
    json render = {{"max_depth", kMaxDepth}, {"threshold", 1.0 / 255.0}, {"spectral", spectral}, {"polarisation", "natural"}};
    if (p.light_pass)
        render["light_pass"] = {{"photons", p.photons}, {"element_size", p.element_size}, {"region", 3},
                                {"seed", p.seed}, {"filter", filter_name(p.filter)}};
    return json{
        {"description", "Ohtsuka & Kawai 1998: round-brilliant diamond (Sellmeier, Peter 1923) on a diffuse floor, "
                        "one point light, 400-700 nm, at most 8 reflections and 8 transmissions"},
        {"camera",
         {{"location", vec(0, 3.0, -3.6)}, {"look_at", vec(0, 0.35, 0)}, {"angle", 38}, {"width", p.width},
          {"height", p.height}}},
        {"background", vec(0.02, 0.02, 0.03)},
        {"materials",
         {{"floor", {{"type", "diffuse"}, {"color", vec(0.75, 0.75, 0.75)}}},
          {"diamond", {{"type", "dielectric"}, {"dispersion", "diamond"}}}}},
        {"objects",
         json::array({{{"type", "plane"}, {"name", "floor"}, {"normal", vec(0, 1, 0)}, {"offset", 0}, {"material", "floor"}},
                      {{"type", "brilliant"}, {"name", "diamond"}, {"diameter", 1.6}, {"position", vec(0, 0.75, 0)},
                       {"rotation", vec(25, 0, 0)}, {"material", "diamond"}}})},
        {"lights", json::array({{{"position", vec(2.5, 7, 1.5)}, {"color", vec(1, 1, 1)}}})},
        {"render", render},
    };
}

json povray_scene_json(const SceneParams& p, int samples) {
    SceneParams q = p;
    q.light_pass = false;
    json j = scene_json(q);
    const auto& d = spectrum::catalogue("diamond");
    j["materials"]["diamond"] = {{"type", "dielectric"},
                                 {"ior", d.n(555)},
                                 {"dispersion",
                                  {{"model", "povray"}, {"ior", d.n(555)}, {"dispersion", d.n(380) / d.n(730)},
                                   {"samples", samples}}}};
    j["render"]["compat"] = "povray";
    j["render"]["spectral"] = {{"max_reflections", kMaxDepth}, {"max_transmissions", kMaxDepth}};
    j["description"] = "Ohtsuka & Kawai 1998 set-up with POV-Ray's dispersion law (benchmark against POV-Ray)";
    return j;
}

namespace {

struct Timed {
    RenderResult r;
    double light_s = 0, eye_s = 0;
};

Scene make(const SceneParams& p, const std::string& name) { return scene_from_json(scene_json(p), name); }

// Light pass (timed) then eye pass reusing its maps (timed).
Timed run_both(const Scene& s, int threads, std::shared_ptr<const IlluminationMaps>* keep = nullptr) {
    Timed t;
    const SpectralContext ctx = SpectralContext::build(s);
    std::shared_ptr<const IlluminationMaps> maps = light_pass(s, ctx, threads);
    t.light_s = maps->seconds;
    RenderOptions o;
    o.threads = threads;
    o.maps = maps;
    t.r = render(s, o);
    t.eye_s = t.r.stats.seconds;
    if (keep) *keep = maps;
    return t;
}

RenderResult eye_only(const Scene& s, int threads, const std::shared_ptr<const IlluminationMaps>& maps) {
    RenderOptions o;
    o.threads = threads;
    o.maps = maps;
    o.lost_energy = true;  // the lost-light study reads it
    return render(s, o);
}

// Linear-RGB RMSE and max, and CIEDE2000 treating the (clipped) values as linear sRGB.
Diff difference(const Image& a, const Image& b) {
    Diff d;
    d.rmse = rmse(a, b);
    const int n = a.width * a.height;
    for (int j = 0; j < a.height; ++j)
        for (int i = 0; i < a.width; ++i) {
            const Vec3 x = a.at(i, j).cwiseMax(0.0), y = b.at(i, j).cwiseMax(0.0);
            d.max = std::fmax(d.max, (a.at(i, j) - b.at(i, j)).cwiseAbs().maxCoeff());
            const double e = spectrum::delta_e2000(x, y);
            d.de_mean += e / n;
            d.de_max = std::fmax(d.de_max, e);
        }
    return d;
}

Image diff_image(const Image& a, const Image& b, double gain) {
    Image d(a.width, a.height);
    for (int j = 0; j < a.height; ++j)
        for (int i = 0; i < a.width; ++i) d.set(i, j, ((a.at(i, j) - b.at(i, j)).cwiseAbs() * gain).cwiseMin(1.0));
    return d;
}

std::string f3(double v) { return fmt(v, 3); }

}  // namespace

Result compute(const ExperimentOptions& opt) {
    const auto t_all = std::chrono::steady_clock::now();
    const int T = opt.threads;
    Result r;
    r.quick = opt.quick;
    r.threads_used = T > 0 ? T : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

    // ---- The main image, with and without the shortcut ----------------------------------
    SceneParams& base = r.base;
    base.photons = kPhotons;
    base.element_size = kElement;
    if (opt.quick) {
        base.width = 120;
        base.height = 90;
        base.photons = 3000;
        base.element_size = 0.05;
    }
    const Scene full_scene = make(base, "scene.json");
    std::shared_ptr<const IlluminationMaps> maps;
    Timed full = run_both(full_scene, T, &maps);
    r.light_s = full.light_s;
    r.eye_s = full.eye_s;
    r.full = std::move(full.r);
    r.map_elements = static_cast<std::uint64_t>(maps->elements());
    r.map_photons = maps->photons;
    r.map_deposits = maps->deposits;
    r.gem_planes = std::get<ConvexPolyhedron>(full_scene.objects[1].shape).planes.size();
    r.shortcut = base;
    r.shortcut.shortcut = true;
    r.fast = eye_only(make(r.shortcut, "scene-shortcut.json"), T, maps);
    // The floor as the first version rendered it (30 000 photons, box elements), and the
    // same photons as the main image read box-wise: what the photon count and the filter do.
    r.box = base;
    r.box.filter = MapFilter::Box;
    r.box_image = eye_only(make(r.box, "scene-box.json"), T, maps).image;
    r.first = r.box;
    r.first.photons = opt.quick ? 300 : kFirstPhotons;
    r.first.element_size = opt.quick ? 0.1 : kFirstElement;
    r.first_image = run_both(make(r.first, "scene-first.json"), T).r.image;
    r.shortcut_diff = difference(r.full.image, r.fast.image);
    r.difference_x10 = diff_image(r.full.image, r.fast.image, 10.0);
    r.base_scene = scene_json(base);
    r.shortcut_scene = scene_json(r.shortcut);
    r.box_scene = scene_json(r.box);
    r.first_scene = scene_json(r.first);

    // ---- Study: wavelength step ------------------------------------------------------------
    SceneParams& st = r.study;
    st = base;
    st.width = opt.quick ? 32 : 160;
    st.height = opt.quick ? 24 : 120;
    st.photons = opt.quick ? 300 : 10000;
    Image ref;
    for (double step : {1.0, 5.0, 10.0, 20.0, 50.0}) {
        SceneParams q = st;
        q.step_nm = step;
        const Timed t = run_both(make(q, "step"), T);
        if (step == 1.0) ref = t.r.image;
        r.steps.push_back({step, difference(t.r.image, ref), t.light_s, t.eye_s});
    }

    // ---- Studies: the floor map against photon count and element size ------------------------
    // The reference: the main image's light pass and one more of another seed.
    MapStudyPlan& plan = r.plan;
    plan.reference_element = base.element_size;
    plan.reference_photons = base.photons;
    plan.reference_seeds[0] = base.seed;
    plan.reference_seeds[1] = base.seed + 1;
    if (opt.quick) {
        plan.photon_element = 0.1;
        plan.photons = {500, 2000};
        plan.elements = {0.4, 0.2, 0.1};
        plan.density_element = 0.1;
        plan.density_photons = 2000;
    }
    r.maps = run_map_studies(base, plan, T, maps);

    // ---- Study: shortcut threshold, and 610 nm against the measured r̄ peak -------------------
    {
        std::shared_ptr<const IlluminationMaps> m;
        const Timed t0 = run_both(make(st, "threshold"), T, &m);
        auto row = [&](const std::string& label, const SceneParams& q, const RenderResult& x) {
            ShortcutRow sr;
            sr.label = label;
            sr.threshold = q.shortcut_threshold;
            for (int k = 0; k < 3; ++k) sr.wavelengths[k] = q.shortcut_wavelengths[k];
            sr.taken_fraction = static_cast<double>(x.stats.shortcut_taken) / std::max<double>(1, x.stats.shortcut_tests);
            sr.speedup_time = t0.eye_s / x.stats.seconds;
            sr.speedup_segments = static_cast<double>(t0.r.stats.segments) / x.stats.segments;
            sr.against_full = difference(x.image, t0.r.image);
            return sr;
        };
        for (double th : {0.001, 0.003, 0.01, 0.03, 0.1, 0.3}) {
            SceneParams q = st;
            q.shortcut = true;
            q.shortcut_threshold = th;
            r.thresholds.push_back(row(fmt(th), q, eye_only(make(q, "threshold"), T, m)));
        }
        const auto pk = spectrum::cie_rgb_peaks();
        for (int k = 0; k < 2; ++k) {
            SceneParams q = st;
            q.shortcut = true;
            if (k == 1) {
                q.shortcut_wavelengths[0] = pk.r;
                q.shortcut_wavelengths[1] = pk.g;
                q.shortcut_wavelengths[2] = pk.b;
            }
            r.peaks.push_back(row(k == 0 ? "paper" : "measured", q, eye_only(make(q, "peaks"), T, m)));
        }
    }

    // ---- Study: the light the limits drop (eye pass over the same maps) ------------------
    // Per setting the weight the dropped branches would have carried (RenderStats::lost_*)
    // as a fraction of the primary rays', the worst pixel's, and the image's difference
    // from the deepest setting.
    {
        std::shared_ptr<const IlluminationMaps> m;
        run_both(make(st, "lost"), T, &m);
        struct Setting {
            bool paper_limits;
            int depth;
            double threshold;
        };
        const Setting settings[] = {{true, kMaxDepth, 1.0 / 255.0}, {true, kMaxDepth, 0.0}, {false, kMaxDepth, 1.0 / 255.0},
                                    {false, 30, 1e-5}, {false, 60, 1e-5}};
        std::vector<RenderResult> runs;
        for (const Setting& s : settings) {
            json j = scene_json(st);
            j["render"]["max_depth"] = s.depth;
            j["render"]["threshold"] = s.threshold;
            if (!s.paper_limits) j["render"]["spectral"].erase("max_reflections"), j["render"]["spectral"].erase("max_transmissions");
            runs.push_back(eye_only(scene_from_json(j, "lost"), T, m));
        }
        for (size_t k = 0; k < runs.size(); ++k) {
            LostRow row;
            row.paper_limits = settings[k].paper_limits;
            row.max_depth = settings[k].depth;
            row.threshold = settings[k].threshold;
            row.stats = runs[k].stats;
            for (size_t p = 0; p + 2 < runs[k].lost.size(); p += 3)
                row.worst_pixel = std::fmax(row.worst_pixel, runs[k].lost[p] + runs[k].lost[p + 1] + runs[k].lost[p + 2]);
            row.rmse_vs_deepest = difference(runs[k].image, runs.back().image).rmse;
            r.lost.push_back(row);
        }
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_all).count();
    return r;
}

void write(const Result& r, const std::string& dir) {
    const auto t_write = std::chrono::steady_clock::now();
    ensure_dir(dir);
    auto path = [&](const std::string& f) { return (std::filesystem::path(dir) / f).string(); };
    const SceneParams &base = r.base, &first = r.first, &st = r.study;
    const MapStudyPlan& plan = r.plan;
    const MapStudies& ms = r.maps;
    const int threads_used = r.threads_used;
    const json& scene = r.base_scene;  // the "here" column of the conditions, from the scene file
    const json& spectral = scene["render"]["spectral"];
    std::ostringstream md;
    md << "# Ohtsuka & Kawai 1998: dispersion in a diamond with bidirectional ray tracing\n\n";

    save_json(dir, "scene.json", r.base_scene);
    save_json(dir, "scene-shortcut.json", r.shortcut_scene);
    write_image(path("diamond.png"), r.full.image);
    write_image(path("diamond-shortcut.png"), r.fast.image);
    write_image(path("difference-x10.png"), r.difference_x10);
    save_json(dir, "scene-box.json", r.box_scene);
    write_image(path("diamond-box.png"), r.box_image);
    save_json(dir, "scene-first.json", r.first_scene);
    write_image(path("diamond-first.png"), r.first_image);
    const Diff& d = r.shortcut_diff;
    const double eye_full = r.eye_s, eye_fast = r.fast.stats.seconds;
    const RenderStats& full_stats = r.full.stats;
    const RenderStats& fast_stats = r.fast.stats;

    md << "![diamond](diamond.png) ![shortcut](diamond-shortcut.png) ![difference ×10](difference-x10.png)\n\n"
       << "Left: full spectral split; middle: with the three-wavelength shortcut (threshold "
       << base.shortcut_threshold << "); right: |difference| × 10.\n\n"
       << "![first](diamond-first.png) ![box](diamond-box.png) ![bilinear](diamond.png)\n\n"
       << "The floor's caustic: " << first.photons << " photons on elements of " << first.element_size
       << " read box-wise (the first version); " << base.photons << " photons on elements of " << base.element_size
       << " read box-wise, and the same maps read bilinearly (the main image).\n\n"
       << "## Conditions (the paper's Fig. 1)\n\n"
       << "| | paper | here |\n|---|---|---|\n"
       << "| patches | 244 | " << r.gem_planes << " facet planes + 1 floor plane |\n"
       << "| elements | 74 536 | " << r.map_elements << " (floor square, edge " << base.element_size << ") |\n"
       << "| image size | 640×480 | " << base.width << "×" << base.height << " |\n"
       << "| lights | 1 | " << scene["lights"].size() << " |\n| max reflections | 8 | "
       << spectral["max_reflections"].dump() << " |\n| max transmissions | 8 | " << spectral["max_transmissions"].dump()
       << " |\n| visible range | 400–700 nm | " << spectral["range"][0].dump() << "–" << spectral["range"][1].dump()
       << " nm |\n| sampling interval | 10 nm | " << base.step_nm << " nm |\n"
       << "| photons | — | " << r.map_photons << " (" << r.map_deposits << " deposits, "
       << fmt(static_cast<double>(r.map_photons) / r.light_s, 3) << " photons/s) |\n"
       << "| map reconstruction | — | " << filter_name(base.filter) << " |\n\n"
       << "## Times (" << threads_used << " threads)\n\n"
       << "| | paper (SGI O2, R10000 175 MHz) | here (s) |\n|---|---|---|\n"
       << "| light pass | 5.4 h | " << f3(r.light_s) << " |\n"
       << "| eye pass, no shortcut | 70.1 h | " << f3(eye_full) << " |\n"
       << "| eye pass, shortcut | 26.3 h | " << f3(eye_fast) << " |\n"
       << "| total, no shortcut | 75.5 h | " << f3(r.light_s + eye_full) << " |\n"
       << "| total, shortcut | 31.7 h | " << f3(r.light_s + eye_fast) << " |\n"
       << "| eye-pass speed-up | 2.67× | " << f3(eye_full / eye_fast) << "× (segments: "
       << f3(static_cast<double>(full_stats.segments) / static_cast<double>(fast_stats.segments)) << "×) |\n\n"
       << "Shortcut: " << fast_stats.shortcut_taken << " of " << fast_stats.shortcut_tests << " split rays ("
       << f3(100.0 * fast_stats.shortcut_taken / std::max<double>(1, fast_stats.shortcut_tests)) << " %) skipped the full split.\n\n"
       << "## Difference shortcut vs full\n\n"
       << "RMSE " << f3(d.rmse) << ", max " << f3(d.max) << " (linear RGB); CIEDE2000 mean " << f3(d.de_mean)
       << ", max " << f3(d.de_max) << " (values read as linear sRGB).\n\n"
       << "Throughput inside the gem: " << full_stats.wavelength_segments << " single-wavelength segments, "
       << f3(static_cast<double>(full_stats.segments) / eye_full / threads_used) << " segments/s per core (eye pass).\n\n";
    Csv times{{"pass", "paper_hours", "seconds"}, {}};
    times.add({"light", "5.4", fmt(r.light_s)});
    times.add({"eye_no_shortcut", "70.1", fmt(eye_full)});
    times.add({"eye_shortcut", "26.3", fmt(eye_fast)});
    write_csv(path("times.csv"), times);

    const Csv steps = csv_table(r.steps);
    write_csv(path("wavelength_step.csv"), steps);

    const Csv photon_count = csv_table(ms.by_photons), elems = csv_table(ms.by_element);
    write_csv(path("photon_count.csv"), photon_count);
    write_csv(path("element_size.csv"), elems);

    const Csv thr = csv_table(r.thresholds, {"threshold", "taken_fraction", "speedup_time", "speedup_segments", "rmse", "de_mean"});
    const Csv peak = csv_table(
        r.peaks, {"wavelengths", "r_nm", "g_nm", "b_nm", "taken_fraction", "speedup_segments", "rmse", "de_mean"});
    write_csv(path("shortcut_threshold.csv"), thr);
    write_csv(path("shortcut_peaks.csv"), peak);

    const Csv lost = csv_table(r.lost);
    write_csv(path("lost_light.csv"), lost);

    auto table = [](const Csv& c) { return c.markdown(4); };
    md << "## Study: wavelength sampling interval (" << st.width << "×" << st.height << ", error against 1 nm)\n\n"
       << table(steps) << "\n## Studies: the floor's illumination map\n\n"
       << "The floor map's irradiance (RGB) at the points of a grid (2×2 per reference element, the whole map), "
          "against a reference of "
       << ms.reference_photons << " photons on elements of " << ms.reference_element
       << " read bilinearly (its own noise σ_ref = " << fmt(ms.reference_noise, 3)
       << "; the main image's light pass and one of another seed), as a relative RMS: `error` of one run, `noise` "
          "from two runs of different seeds, `bias` what remains of the pair's mean against the reference "
          "(experiments/ohtsuka1998_maps.h). The studies traced "
       << ms.photons_traced << " photons besides the main image's, in " << fmt(ms.seconds, 3) << " s.\n\n"
       << "### Photon count (elements of " << plan.photon_element << ")\n\n" << table(photon_count)
       << "\n### Element size at a fixed photon density (" << plan.density_photons << " photons on elements of "
       << plan.density_element << ", × (" << plan.density_element << "/h)² on elements of edge h)\n\n"
       << table(elems) << "\n## Study: shortcut threshold (speed-up against error, eye pass)\n\n" << table(thr)
       << "\n## The paper's 610/545/445 nm against the measured peaks of r̄, ḡ, b̄ (threshold "
       << st.shortcut_threshold << ")\n\n" << table(peak)
       << "\n## Study: the light the limits drop (" << st.width << "×" << st.height
       << ", eye pass over the same maps)\n\n"
       << "Per setting, the weight of the branches dropped by the depth limit, the paper's 8/8 "
          "reflection/transmission limits and the threshold, as a fraction of the primary rays' "
          "(1 each); `worst_pixel`: the largest such fraction in one pixel; `rmse_vs_deepest`: the "
          "image against the last row. The floor and sky are dark, so dropped weight is an upper "
          "bound on the light missing (docs/scene-format.md, \"Light the limits drop\").\n\n"
       << table(lost) << "\n";

    if (gnuplot_available()) {
        const std::string common = "set datafile separator ','\nset grid\nset key top left box opaque\n";
        gnuplot_figure(dir, "wavelength_step",
                       common + "set logscale x\nset xlabel 'wavelength step (nm)'\nset ylabel 'RMSE against 1 nm'\n"
                                "set y2label 'time (s)'\nset y2tics\nset ytics nomirror\n"
                                "set title 'Wavelength sampling interval: error and time'\n"
                                "plot 'wavelength_step.csv' every ::2 using 1:3 with linespoints lw 2 title 'RMSE', \\\n"
                                "     '' every ::1 using 1:($6+$7) axes x1y2 with linespoints lw 2 title 'light + eye time'\n");
        // Rows alternate box, bilinear: every 2nd row from row 1 (box) or 2 (bilinear).
        const std::string curves = " using {x}:6 with linespoints lw 2 pt 7 lc 1 title 'box, error', \\\n"
                                   "     '' every 2::2 using {x}:6 with linespoints lw 2 pt 7 lc 2 title 'bilinear, error', \\\n"
                                   "     '' every 2::1 using {x}:7 with linespoints dt 2 lc 1 title 'box, noise', \\\n"
                                   "     '' every 2::2 using {x}:7 with linespoints dt 2 lc 2 title 'bilinear, noise', \\\n"
                                   "     '' every 2::1 using {x}:8 with linespoints dt 3 lc 1 title 'box, bias', \\\n"
                                   "     '' every 2::2 using {x}:8 with linespoints dt 3 lc 2 title 'bilinear, bias'\n";
        auto with_x = [&](const std::string& x) {
            std::string c = curves;
            for (size_t k; (k = c.find("{x}")) != std::string::npos;) c.replace(k, 3, x);
            return c;
        };
        gnuplot_figure(dir, "photon_count",
                       common + "set logscale xy\nset key top right box opaque\nset xlabel 'photons'\n"
                                "set ylabel 'relative RMS against the reference'\n"
                                "set title 'Floor map: error against photon count'\n"
                                "plot 'photon_count.csv' every 2::1" + with_x("3"));
        gnuplot_figure(dir, "element_size",
                       common + "set logscale xy\nset key top left box opaque\nset xlabel 'element edge (scene units)'\n"
                                "set ylabel 'relative RMS against the reference'\n"
                                "set title 'Floor map: error against element size (fixed photons per element)'\n"
                                "plot 'element_size.csv' every 2::1" + with_x("1"));
        gnuplot_figure(dir, "shortcut_threshold",
                       common + "set logscale y\nset xlabel 'eye-pass speed-up (segments)'\nset ylabel 'RMSE against full split'\n"
                                "set title 'Shortcut threshold: speed-up against error'\n"
                                "plot 'shortcut_threshold.csv' every ::1 using 4:5 with linespoints lw 2 title 'threshold 0.001 ... 0.3', \\\n"
                                "     '' every ::1 using 4:5:(sprintf('%g', $1)) with labels offset 1,1 notitle\n");
        md << "Figures: `wavelength_step.png`, `photon_count.png`, `element_size.png`, `shortcut_threshold.png` (and "
              "PDF).\n";
    }
    const double total = r.seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - t_write).count();
    md << "\nRun time of the whole experiment: " << f3(total) << " s (" << threads_used << " threads).\n";
    write_text_atomic(path("summary.md"), md.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::ohtsuka1998
