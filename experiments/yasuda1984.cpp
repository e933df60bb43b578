// Yasuda et al. 1984: Fig. 4 (reflectance vs angle, n = 1.5), Fig. 7 (transmissivity vs
// angle and index), Fig. 8 (ten transparent spheres, fresnel-tree), Fig. 9 (constant
// reflectivity). The cost study of §5 is in yasuda_cost.cpp.
#include <refract/experiments/yasuda1984.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include <refract/core/optics.h>
#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::yasuda1984 {
namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<double>& fig7_indices_a() {
    static const std::vector<double> v{1.2, 1.5, 2, 3, 5, 10};
    return v;
}
const std::vector<double>& fig7_indices_b() {
    static const std::vector<double> v{0.9, 0.8, 0.6, 0.4, 0.2, 0.1};
    return v;
}
const std::vector<Fig8Sphere>& fig8_spheres() {
    static const std::vector<Fig8Sphere> v{
        {'a', 0.1, ""},           {'b', 0.4, ""},     {'c', 0.8, ""},
        {'d', 1.309, "ice"},      {'e', 1.333, "water"}, {'f', 1.501, "benzene"},
        {'g', 1.52, "glass"},     {'h', 2.2, "diamond as quoted"}, {'i', 5.0, ""},
        {'j', 10.0, ""}};
    return v;
}
const std::vector<double>& fig9_reflectivities() {
    static const std::vector<double> v{0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
    return v;
}

double transmissivity(double angle_deg, double n) {
    const double c = std::cos(angle_deg * M_PI / 180.0);
    return 1.0 - optics::fresnel_reflectance(std::fmax(c, 0.0), n);  // eq. 8
}

TransmissivityPeak transmissivity_peak(double n) {
    TransmissivityPeak p;
    p.n = n;
    p.T0 = transmissivity(0, n);
    // Dense scan, then golden-section refinement around the best sample.
    double best = 0, best_T = p.T0;
    const int steps = 9000;
    for (int k = 1; k < steps; ++k) {
        const double a = 90.0 * k / steps;
        const double T = transmissivity(a, n);
        if (T > best_T) best_T = T, best = a;
    }
    double lo = std::fmax(0.0, best - 0.01), hi = std::fmin(90.0, best + 0.01);
    const double g = (std::sqrt(5.0) - 1) / 2;
    while (hi - lo > 1e-7) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        if (transmissivity(a, n) > transmissivity(b, n)) hi = b;
        else lo = a;
    }
    p.angle_deg = 0.5 * (lo + hi);
    p.T = transmissivity(p.angle_deg, n);
    if (p.T <= p.T0) p.angle_deg = 0, p.T = p.T0;
    p.interior = p.angle_deg > 0 && p.T > p.T0 + 1e-12;
    return p;
}

namespace {

template <class Pred>
double bisect_index(double lo, double hi, Pred pred) {  // pred(lo) false, pred(hi) true
    while (hi - lo > 1e-7) {
        const double mid = 0.5 * (lo + hi);
        (pred(mid) ? hi : lo) = mid;
    }
    return hi;
}

}  // namespace

double peak_onset_index() {
    return bisect_index(1.5, 10.0, [](double n) { return transmissivity_peak(n).interior; });
}
double peak_beyond_index(double angle_deg) {
    return bisect_index(peak_onset_index(), 10.0, [&](double n) {
        const auto p = transmissivity_peak(n);
        return p.interior && p.angle_deg >= angle_deg;
    });
}

// ---------------------------------------------------------------------------------------
// Scenes of Fig. 8 and 9: a sphere of radius 1 on a checker floor in front of a checker
// wall (refraction turns them upside down, so the index can be read off the image), lit
// by a point light inside the paper's highlight sphere: an emissive sphere thirty times
// brighter than the white surfaces, seen as the spot in the reflections.

namespace {

constexpr double kWallDistance = 4;  // the wall (offset −4 below) behind the sphere's centre

json sphere_scene(const json& glass, const std::string& description, bool quick) {
    const int size = quick ? 32 : 256;
    return json{
        {"description", description},
        {"camera", {{"location", vec(0, 1.6, -5.5)}, {"look_at", vec(0, 0.95, 0)}, {"angle", 36},
                    {"width", size}, {"height", size}}},
        {"background", vec(0.55, 0.65, 0.85)},
        {"materials",
         {{"glass", glass},
          {"floor", {{"type", "diffuse"}, {"color", vec(0.95, 0.8, 0.2)},
                     {"checker", {{"color2", vec(0.7, 0.12, 0.1)}, {"size", 1.0}}}, {"diffuse", 0.8}, {"ambient", 0.2}}},
          {"wall", {{"type", "diffuse"}, {"color", vec(0.95, 0.95, 0.95)},
                    {"checker", {{"color2", vec(0.1, 0.25, 0.6)}, {"size", 0.5}}}, {"diffuse", 0.8}, {"ambient", 0.2}}},
          {"lamp", {{"type", "emissive"}, {"color", vec(30, 30, 30)}}}}},
        {"objects", json::array({
                        {{"type", "sphere"}, {"name", "sphere"}, {"material", "glass"}, {"center", vec(0, 1, 0)}, {"radius", 1}},
                        {{"type", "plane"}, {"name", "floor"}, {"material", "floor"}, {"normal", vec(0, 1, 0)}, {"offset", 0}},
                        {{"type", "plane"}, {"name", "wall"}, {"material", "wall"}, {"normal", vec(0, 0, -1)}, {"offset", -4}},
                        {{"type", "sphere"}, {"name", "highlight"}, {"material", "lamp"}, {"center", vec(-4, 6, -5)},
                         {"radius", 1.0}},
                    })},
        {"lights", json::array({{{"position", vec(-4, 6, -5)}, {"color", vec(1, 1, 1)}}})},
        {"render", {{"integrator", "fresnel-tree"}, {"max_depth", 20}, {"threshold", 0.001}, {"samples", quick ? 1 : 16},
                    {"jitter", !quick}, {"seed", 1u}, {"polarisation", "natural"}}},
    };
}

std::string fig8_file(const Fig8Sphere& s) { return std::string("fig8_") + s.letter; }
std::string fig9_file(int k) { return std::string("fig9_") + static_cast<char>('a' + k); }

std::string caption8(const Fig8Sphere& s) {
    std::ostringstream c;
    c << "(" << s.letter << ") n = " << fmt(s.n);
    if (!s.label.empty()) c << " (" << s.label << ")";
    return c.str();
}

}  // namespace

json fig8_scene(double n, bool quick) {
    std::ostringstream d;
    d << "Yasuda et al. 1984 Fig. 8: transparent sphere of index n = " << fmt(n)
      << ", exact Fresnel reflectance (eq. 7), fresnel-tree integrator";
    return sphere_scene({{"type", "dielectric"}, {"ior", n}, {"reflectance", "fresnel"}}, d.str(), quick);
}

json fig9_scene(double k, bool quick) {
    std::ostringstream d;
    d << "Yasuda et al. 1984 Fig. 9: sphere with constant reflectivity " << fmt(k)
      << " (transmissivity " << fmt(1 - k) << "), directions from n = 1.52";
    return sphere_scene({{"type", "dielectric"}, {"ior", 1.52}, {"reflectance", "constant"}, {"reflectivity", k}},
                        d.str(), quick);
}

Result compute(const ExperimentOptions& opt) {
    Result r;
    r.quick = opt.quick;
    // Fig. 4: Rs, Rp and their mean for n = 1.5, 0-90 degrees in 0.5 degree steps.
    for (int k = 0; k <= 180; ++k) {
        const double a = 0.5 * k;
        const auto f = optics::fresnel(std::fmax(std::cos(a * M_PI / 180.0), 0.0), 1.5);
        r.fig4.push_back({a, f->Rs, f->Rp, f->R()});
    }
    // Fig. 7: T = 1 - R for several indices, (a) n > 1, (b) n < 1; peaks.
    for (const auto* list : {&fig7_indices_a(), &fig7_indices_b()})
        for (double n : *list) {
            // 0.1° steps, and the critical angle itself where T drops to 0 (n < 1).
            std::vector<double> angles;
            for (int k = 0; k <= 900; ++k) angles.push_back(0.1 * k);
            if (const auto c = optics::critical_angle(n)) angles.push_back(*c * 180.0 / M_PI);
            std::sort(angles.begin(), angles.end());
            for (double a : angles) r.fig7.push_back({n, a, transmissivity(a, n)});
        }
    std::vector<double> ns = fig7_indices_a();
    for (double n : {3.5, 4.0, 4.5, 6.0, 7.0, 8.0}) ns.push_back(n);
    std::sort(ns.begin(), ns.end());
    for (double n : ns) r.peaks.push_back(transmissivity_peak(n));
    r.peak_onset = peak_onset_index();
    r.peak_beyond_70 = peak_beyond_index(70.0);
    // The numbers the summary quotes beside Fig. 4 and 7.
    const double brewster = optics::brewster_angle(1.5);
    const auto f0 = optics::fresnel(1.0, 1.5), fb = optics::fresnel(std::cos(brewster), 1.5),
               f40 = optics::fresnel(std::cos(40 * M_PI / 180), 1.5);
    r.R0 = f0->R();
    r.brewster_deg = brewster * 180.0 / M_PI;
    r.Rp_brewster = fb->Rp;
    r.R_brewster = fb->R();
    r.rs_rp_gap_40 = f40->Rs - f40->Rp;
    r.onset_closed_form = 2 + std::sqrt(3.0);
    for (double n : fig7_indices_b()) r.critical.push_back({n, *optics::critical_angle(n) * 180 / M_PI});
    // Fig. 8: normal-incidence reflectance of the high indices, each sphere's paraxial focus
    // behind its centre (a ball lens of radius 1: n / (2(n − 1)); negative: diverging), and the
    // share of the disc beyond the critical angle for n < 1 (parallel light: 1 − n²).
    r.R0_n5 = optics::fresnel_reflectance(1, 5);
    r.R0_n10 = optics::fresnel_reflectance(1, 10);
    r.wall_distance = kWallDistance;
    // Fig. 9 against Fig. 8(g): the glass's Fresnel reflectance at the centre and near the rim.
    r.glass_R0 = optics::fresnel_reflectance(1, 1.52);
    r.glass_R80 = optics::fresnel_reflectance(std::cos(80 * M_PI / 180), 1.52);
    // Fig. 8 and Fig. 9: the rendered panels.
    RenderOptions ro;
    ro.threads = opt.threads;
    for (const auto& s : fig8_spheres()) {
        RenderedPanel p{fig8_file(s), caption8(s), s.n, fig8_scene(s.n, opt.quick), {}, {}, 0, 0};
        p.focus = s.n / (2 * (s.n - 1));
        p.tir_share = s.n < 1 ? 1 - s.n * s.n : 0;
        auto rr = render(scene_from_json(p.scene, p.file + ".json"), ro);
        p.image = std::move(rr.image);
        p.stats = rr.stats;
        r.fig8.push_back(std::move(p));
    }
    for (size_t k = 0; k < fig9_reflectivities().size(); ++k) {
        const double kr = fig9_reflectivities()[k];
        RenderedPanel p{fig9_file(static_cast<int>(k)),
                        "(" + std::string(1, static_cast<char>('a' + k)) + ") reflectivity " + fmt(kr), kr,
                        fig9_scene(kr, opt.quick), {}, {}, 0, 0};
        auto rr = render(scene_from_json(p.scene, p.file + ".json"), ro);
        p.image = std::move(rr.image);
        p.stats = rr.stats;
        r.fig9.push_back(std::move(p));
    }
    r.cost = compute_cost(opt);
    r.findings = judge(r);
    return r;
}

namespace {

const TransmissivityPeak* peak_of(const Result& r, double n) {
    for (const auto& p : r.peaks)
        if (p.n == n) return &p;
    return nullptr;
}
double peak_angle(const Result& r, double n) {
    const auto* p = peak_of(r, n);
    return p ? p->angle_deg : 0.0;
}
const RenderedPanel* panel_of(const std::vector<RenderedPanel>& panels, double value) {
    for (const auto& p : panels)
        if (p.value == value) return &p;
    return nullptr;
}

}  // namespace

Findings judge(const Result& r) {
    Findings f;
    // Fig. 4.
    f.rs_rp_close_below_40 = r.rs_rp_gap_40 < 0.1;
    f.R_one_at_grazing = !r.fig4.empty() && r.fig4.back().angle_deg == 90 && std::abs(r.fig4.back().R - 1) < 1e-12;
    // Fig. 7: the paper's "for n ≳ 5, T peaks above 70°".
    const auto *p5 = peak_of(r, 5), *p10 = peak_of(r, 10);
    f.paper_peak_holds = p5 && p10 && p5->interior && p10->interior && p5->angle_deg > 70 && p10->angle_deg > 70;
    f.onset_is_closed_form = std::abs(r.peak_onset - r.onset_closed_form) < 1e-5;
    double last = -1;
    int interior = 0;
    f.peak_moves_to_grazing = true;
    for (const auto& p : r.peaks) {  // ascending n
        if (!p.interior) continue;
        f.peak_moves_to_grazing = f.peak_moves_to_grazing && p.angle_deg > last;
        last = p.angle_deg;
        ++interior;
    }
    f.peak_moves_to_grazing = f.peak_moves_to_grazing && interior >= 2;
    // Panel (b): n = 0.2 and 0.1 rise above T(0°) before the critical angle; every n < 1 is
    // 0 beyond its critical angle.
    f.low_n_rise = true;
    for (double n : {0.2, 0.1}) {
        double T0 = -1, top = -1;
        for (const auto& row : r.fig7)
            if (row.n == n) {
                if (T0 < 0) T0 = row.T;
                top = std::max(top, row.T);
            }
        f.low_n_rise = f.low_n_rise && T0 >= 0 && top > T0;
    }
    f.zero_beyond_critical = !r.critical.empty();
    for (const auto& c : r.critical)
        for (const auto& row : r.fig7)
            if (row.n == c.n && row.angle_deg > c.angle_deg && row.T != 0) f.zero_beyond_critical = false;
    // Fig. 8.
    f.lenses_as_described = !r.fig8.empty();
    for (const auto& p : r.fig8)
        if (p.value > 1 ? !(p.focus > 0 && p.focus < r.wall_distance) : !(p.focus < 0)) f.lenses_as_described = false;
    const auto *a08 = panel_of(r.fig8, 0.8), *a01 = panel_of(r.fig8, 0.1);
    f.mirror_rim_and_whole = a08 && a01 && a08->tir_share < 0.5 && a01->tir_share > 0.9;
    f.high_n_mirror_like = r.R0_n10 > r.R0_n5 && r.R0_n5 > 0.25;
    // Fig. 9 against Fig. 8(g).
    f.fresnel_rim_brightens = r.glass_R80 > 2 * r.glass_R0;
    // §5.
    const CostResult& c = r.cost;
    const double inc = counted_increase(c, "yasuda1984");
    f.count_about_40 = inc >= 0.3 && inc <= 0.5;
    const double quarter = c.sphere_test.muldiv() / muldiv_of(c, "yasuda1984", "constant");
    f.test_about_quarter = quarter >= 0.2 && quarter <= 0.3;
    f.identical_trees = c.render_stats[0].segments == c.render_stats[1].segments &&
                        c.render_stats[0].tree_nodes == c.render_stats[1].tree_nodes;
    f.measured_below_counted = measured_render_increase(c) < counted_segment_increase(c);
    if (!c.memory.empty()) {
        const MemoryRow &deep = c.memory.back(), &half = c.memory[(c.memory.size() - 1) / 2];
        const double share =
            static_cast<double>(deep.list_threshold0.peak_list) / static_cast<double>(deep.whitted.peak_list);
        f.list_about_half_tree = share >= 0.25 && share <= 0.75;
        f.threshold_list_flat = deep.list_threshold_1_255.peak_list == half.list_threshold_1_255.peak_list;
    }
    return f;
}

std::string fig4_text(const Result& r) {
    std::ostringstream s;
    if (r.findings.R_one_at_grazing) s << "R rises to 1 at grazing incidence. ";
    else s << "R reaches " << fmt(r.fig4.empty() ? 0.0 : r.fig4.back().R, 6) << " at the last angle computed. ";
    if (r.findings.rs_rp_close_below_40)
        s << "As the paper notes, Rs alone or Rp alone would change the picture little below ~40°, where they differ "
          << "by less than " << fmt(r.rs_rp_gap_40, 2) << ".";
    else
        s << "The paper notes that Rs alone or Rp alone would change the picture little below ~40°; here they differ "
          << "by up to " << fmt(r.rs_rp_gap_40, 2) << " there, which is not little.";
    return s.str();
}

std::string fig7_text(const Result& r) {
    const Findings& f = r.findings;
    std::ostringstream s;
    s << "\nAn interior maximum exists for n > " << fmt(r.peak_onset, 7)
      << " (below that T falls monotonically from normal incidence); it lies beyond 70° for n > "
      << fmt(r.peak_beyond_70, 4) << ". ";
    if (f.paper_peak_holds) s << "So the paper's statement holds for n ≳ 5 (n = 5: peak at ";
    else s << "So the paper's statement does not hold for n ≳ 5, only beyond n = " << fmt(r.peak_beyond_70, 4) << " (n = 5: peak at ";
    s << fmt(peak_angle(r, 5), 4) << "°, n = 10: " << fmt(peak_angle(r, 10), 4)
      << "°). The onset has a closed form: the θ² terms of Rs and Rp cancel in their mean, and the θ⁴ term "
         "of T(θ) = 1 − R(θ) at normal incidence is (n−1)²(n²−4n+1)/(2n³(n+1)²), positive for "
         "n > 2 + √3 = "
      << fmt(r.onset_closed_form, 7);
    if (!f.onset_is_closed_form) s << ", which the measured onset (" << fmt(r.peak_onset, 7) << ") misses";
    if (f.low_n_rise)
        s << " (and for n < 2 − √3 = 0.268, which is why the n = 0.2 and 0.1 curves of panel (b) rise before "
             "their critical angles). ";
    else
        s << " (and for n < 2 − √3 = 0.268, though the n = 0.2 and 0.1 curves of panel (b) computed here do not "
             "rise before their critical angles). ";
    if (f.peak_moves_to_grazing) s << "Past the onset the maximum moves quickly from 0° towards grazing incidence. ";
    else s << "Past the onset the maximum does not move steadily towards grazing incidence (see the table). ";
    s << (f.zero_beyond_critical ? "For n < 1, T = 0 beyond the critical angle arcsin n ("
                                 : "For n < 1, T should be 0 beyond the critical angle arcsin n, but is not 0 there in "
                                   "every curve computed (");
    for (size_t k = 0; k < r.critical.size(); ++k)
        s << (k ? ", " : "") << "n = " << fmt(r.critical[k].n) << ": " << fmt(r.critical[k].angle_deg, 4) << "°";
    s << ").";
    return s.str();
}

std::string fig8_text(const Result& r) {
    const Findings& f = r.findings;
    std::ostringstream s;
    if (f.lenses_as_described)
        s << "Refraction turns the floor and wall upside down inside the sphere for n > 1; for n < 1 the sphere acts "
             "as a diverging lens";
    else
        s << "Not every sphere focuses as a lens of its index should (n > 1: a focus in front of the wall, which turns "
             "floor and wall upside down; n < 1: diverging)";
    const auto *a08 = panel_of(r.fig8, 0.8), *a01 = panel_of(r.fig8, 0.1);
    if (f.mirror_rim_and_whole)
        s << " and total reflection makes its rim (n = 0.8) or nearly all of it (n = 0.1) a mirror. ";
    else
        s << "; total reflection covers " << fmt(a08 ? a08->tir_share : 0.0, 2) << " of the disc at n = 0.8 and "
          << fmt(a01 ? a01->tir_share : 0.0, 2) << " at n = 0.1 (parallel light). ";
    if (f.high_n_mirror_like) s << "High indices (5, 10) look increasingly metallic (R(0°) = ";
    else s << "High indices (5, 10) reflect at normal incidence R(0°) = ";
    s << fmt(r.R0_n5, 3) << " and " << fmt(r.R0_n10, 3) << (f.high_n_mirror_like ? ")." : ".");
    return s.str();
}

std::string fig9_text(const Result& r) {
    if (r.findings.fresnel_rim_brightens)
        return "Against Fig. 8(g) (the same sphere with Fresnel): with a constant ks the rim does not brighten and the "
               "centre is as reflective as the rim, which is what the paper calls the loss of transparent quality.";
    return "Against Fig. 8(g) (the same sphere with Fresnel): there R rises only from " + fmt(r.glass_R0, 3) +
           " at the centre to " + fmt(r.glass_R80, 3) +
           " at 80°, so a constant ks loses little of the transparent quality here.";
}

void write(const Result& res, const std::string& dir) {
    ensure_dir(dir);
    auto path = [&](const std::string& f) { return (fs::path(dir) / f).string(); };
    std::ostringstream md;
    md << "# Yasuda et al. 1984: an improved ray tracing algorithm for transparent objects\n\n"
       << "Reproduced by `refract experiment yasuda1984`" << (res.quick ? " (quick mode: small images)" : "")
       << ". Every number below is measured by this run.\n\n";

    // ---- Fig. 4: Rs, Rp and their mean for n = 1.5, 0-90 degrees in 0.5 degree steps.
    {
        write_csv(path("fig4.csv"), csv_table(res.fig4));
        const double brewster = res.brewster_deg;
        std::ostringstream b;
        b << "set datafile separator ','\nset key top left box opaque\n"
          << "set xlabel 'angle of incidence (degrees)'\nset ylabel 'reflectivity'\n"
          << "set xrange [0:90]\nset yrange [0:1]\nset xtics 10 nomirror\nset mxtics 2\nset ytics 0.1\nset grid\n"
          << "set title 'Fig. 4  Angle of incidence dependence of reflectivity (n = 1.5)'\n"
          // Brewster's angle: a dotted line through the plot, labelled as a tic on the top
          // border, where no curve runs.
          << "set arrow from " << brewster << ",0 to " << brewster << ",1 nohead dt 3 lc rgb 'gray40'\n"
          << "set x2range [0:90]\nset x2tics (sprintf('Brewster %.2f°', " << brewster << ") " << brewster
          << ") scale 0 offset 0,-0.3 font ',10'\nset tmargin 4\n"
          << "plot 'fig4.csv' using 1:2 every ::1 with lines lw 2 lc rgb '#1f77b4' title 'R_s (s-polarised)', \\\n"
          << "     '' using 1:3 every ::1 with lines lw 2 lc rgb '#d62728' title 'R_p (p-polarised)', \\\n"
          << "     '' using 1:4 every ::1 with lines lw 3 lc rgb 'black' title 'R = (R_s + R_p)/2 (eq. 7)'\n";
        gnuplot_figure(dir, "fig4", b.str());
        md << "## Fig. 4: reflectivity against angle of incidence, n = 1.5\n\n"
           << "`fig4.csv` (`angle_deg,Rs,Rp,R`, 0-90° in 0.5° steps), `fig4.png`/`.pdf`. "
           << "R(0°) = " << fmt(res.R0, 6) << " (((n−1)/(n+1))² = 0.04); Brewster's angle "
           << fmt(brewster, 6) << "°, where Rp = " << fmt(res.Rp_brewster, 3) << " and R = " << fmt(res.R_brewster, 4)
           << "; " << fig4_text(res) << "\n\n![Fig. 4](fig4.png)\n\n";
    }

    // ---- Fig. 7: T = 1 - R for several indices, (a) n > 1, (b) n < 1; peaks.
    {
        write_csv(path("fig7.csv"), csv_table(res.fig7));
        auto panel = [&](const std::string& name, const std::vector<double>& ns, const std::string& title,
                         const std::string& key) {
            std::ostringstream b;
            b << "set datafile separator ','\nset key " << key << " box opaque\n"
              << "set xlabel 'angle of incidence (degrees)'\nset ylabel 'transmissivity T = 1 − R'\n"
              << "set xrange [0:90]\nset yrange [0:1]\nset xtics 10\nset ytics 0.1\nset grid\n"
              << "set title '" << title << "'\nplot ";
            for (size_t k = 0; k < ns.size(); ++k)
                b << (k ? ", \\\n     " : "") << "'fig7.csv' using 2:(abs($1 - " << fmt(ns[k])
                  << ") < 1e-9 ? $3 : NaN) every ::1 with lines lw 2 dt " << (k % 5 + 1) << " title 'n = " << fmt(ns[k])
                  << "'";
            b << "\n";
            gnuplot_figure(dir, name, b.str());
        };
        panel("fig7a", fig7_indices_a(), "Fig. 7(a)  Transmissivity against angle of incidence, n > 1",
              "bottom left");
        panel("fig7b", fig7_indices_b(), "Fig. 7(b)  Transmissivity against angle of incidence, n < 1",
              "top right");

        md << "## Fig. 7: transmissivity against angle of incidence and index\n\n"
           << "`fig7.csv` (`n,angle_deg,T`, 0-90° in 0.1° steps plus the critical angle for n < 1) for n = 1.2, 1.5, 2, 3, 5, 10 (panel (a), "
           << "`fig7a.png`) and n = 0.9, 0.8, 0.6, 0.4, 0.2, 0.1 (panel (b), `fig7b.png`); `fig7_peaks.csv`.\n\n"
           << "The paper: for n ≳ 5, T rises with the angle, peaks above 70° and then falls steeply. Measured "
           << "(largest T over 0-90°, located to 1e-6°):\n\n| n | T(0°) | peak angle | T at peak |\n|---|---|---|---|\n";
        for (const auto& p : res.peaks)
            md << "| " << fmt(p.n) << " | " << fmt(p.T0, 4) << " | "
               << (p.interior ? fmt(p.angle_deg, 4) + "°" : std::string("none (T falls from 0°)")) << " | "
               << fmt(p.T, 4) << " |\n";
        write_csv(path("fig7_peaks.csv"), csv_table(res.peaks));
        md << fig7_text(res) << "\n\n![Fig. 7(a)](fig7a.png)\n![Fig. 7(b)](fig7b.png)\n\n";
    }

    // ---- Fig. 8 and Fig. 9: rendered panels, assembled with their captions.
    const std::string scenes = path("scenes");
    {
        std::vector<Panel> panels;
        double total = 0;
        for (const auto& p : res.fig8) {
            save_json(scenes, p.file + ".json", p.scene);
            write_image(path(p.file + ".png"), p.image);
            total += p.stats.seconds;
            panels.push_back({p.file + ".png", p.caption});
        }
        write_csv(path("fig8_stats.csv"), csv_table(res.fig8));
        image_grid_figure(dir, "fig8", 2, 5, panels, "Fig. 8  Transparent spheres, improved ray tracing (exact Fresnel)");
        md << "## Fig. 8: ten transparent spheres (fresnel-tree)\n\n"
           << "Panels `fig8_a.png` ... `fig8_j.png`, assembled with captions in `fig8.png`/`.pdf`; scenes in "
           << "`scenes/fig8_*.json` (re-render with `refract render scenes/fig8_a.json -o a.png`). Sphere of radius 1 "
           << "on a yellow/red checker floor in front of a white/blue checker wall, exact Fresnel reflectance, "
           << "fresnel-tree (threshold 0.001, depth 20, " << (res.quick ? "1 sample" : "16 jittered samples")
           << " per pixel), a point light inside the highlight sphere "
           << "(emissive, 30× the white of the surfaces), whose reflection is the bright spot. " << fig8_text(res)
           << "\n\nRender time of all ten panels: " << fmt(total, 3) << " s (" << (res.quick ? 32 : 256)
           << "² pixels each; `fig8_stats.csv` has rays and tree counters; the paper: about 10 minutes on an "
           << "OKITAC SYSTEM 50/40).\n\n![Fig. 8](fig8.png)\n\n";
    }
    {
        std::vector<Panel> panels;
        for (const auto& p : res.fig9) {
            save_json(scenes, p.file + ".json", p.scene);
            write_image(path(p.file + ".png"), p.image);
            panels.push_back({p.file + ".png", p.caption});
        }
        image_grid_figure(dir, "fig9", 2, 3, panels, "Fig. 9  Constant reflectivity (directions from n = 1.52)");
        md << "## Fig. 9: constant reflectivity (Whitted's ks, kt = 1 − ks)\n\n"
           << "`fig9_a.png` ... `fig9_f.png`, assembled in `fig9.png`/`.pdf`; reflectivity 0.0, 0.2, ..., 1.0 "
           << "everywhere on the sphere, directions from n = 1.52 (where the directions give total internal "
           << "reflection all light is reflected). " << fig9_text(res) << "\n\n![Fig. 9](fig9.png)\n\n";
    }

    md << write_cost(res, dir);
    write_text_atomic(path("summary.md"), md.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::yasuda1984
