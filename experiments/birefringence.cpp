// Double refraction in uniaxial crystals: the measurements (experiments/birefringence.h).
#include <refract/experiments/birefringence.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <refract/core/birefringence.h>
#include <refract/core/optics.h>
#include <refract/core/render.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/tracer.h>
#include <refract/experiments/common.h>
#include <refract/experiments/field_csv.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::birefringence {

using nlohmann::json;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kPlateView = 0.8;   // scene units across the plate view
constexpr double kTilt = 30.0;       // the tilted optic axis of the moissanite brilliant, degrees
constexpr double kLambdaD = spectrum::fraunhofer::D;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A brilliant (table up, facing +y, girdle centre at y = 0.95) seen from straight above,
// on a checker floor under a point light; RGB rays at the D line.
json gem_scene(const json& material, int width, int height) {
    const json floor = {{"type", "diffuse"},
                        {"color", vec(0.9, 0.9, 0.85)},
                        {"checker", {{"color2", vec(0.15, 0.25, 0.55)}, {"size", 0.25}}}};
    return json{{"camera",
                 {{"location", vec(0, 7, 0)}, {"look_at", vec(0, 0.95, 0)}, {"sky", vec(0, 0, 1)}, {"angle", 20},
                  {"width", width}, {"height", height}}},
                {"background", vec(0.55, 0.7, 0.9)},
                {"materials", {{"floor", floor}, {"gem", material}}},
                {"objects",
                 json::array({{{"type", "plane"}, {"normal", vec(0, 1, 0)}, {"offset", 0}, {"material", "floor"}},
                              {{"type", "brilliant"}, {"name", "gem"}, {"preset", "gia-default"},
                               {"position", vec(0, 0.95, 0)}, {"diameter", 2}, {"material", "gem"}}})},
                {"lights", json::array({{{"position", vec(-2, 8, -5)}, {"color", vec(1, 1, 1)}}})},
                {"render", {{"max_depth", 10}, {"threshold", 0.002}, {"spectral", false}}}};
}

// The walk-off of the e ray that the camera ray at image x offset `x` (scene units at the
// table) spawns on entering the table, against the closed form; and the lateral offset of
// the e ray's next hit from the o ray's line against depth × tan ρ.
void trace_walk_off(const Scene& scene, GemRow& row) {
    SceneTracer tracer(scene);
    RenderStats st;
    const Ray ray{Vec3(0.25, 7, 0.1), Vec3(0, -1, 0)};
    const auto hit = tracer.intersect(ray, st, RayOrigin{});
    if (!hit) return;
    const Interaction in = tracer.interact(*hit, ray, st);
    const Branch *o = nullptr, *e = nullptr;
    for (int b = 0; b < in.branches; ++b) {
        const Branch& br = in.branch[static_cast<size_t>(b)];
        if (!in.transmitted[static_cast<size_t>(b)]) continue;
        if (br.wave == biref::Wave::Extraordinary) e = &br;
        else o = &br;
    }
    if (!o || !e) return;
    row.rho_traced_deg = std::acos(std::clamp(o->ray.dir.dot(e->ray.dir), -1.0, 1.0)) / kDeg;
    const auto eh = tracer.intersect(e->ray, st, tracer.origin_of(*hit));
    if (!eh) return;
    const Vec3 d = eh->hit.point - hit->hit.point;
    const double depth = -d.y();
    row.offset_traced = std::hypot(d.x(), d.z());
    row.offset_theory = depth * std::tan(row.rho_theory_deg * kDeg);
}

// Share of the table disc's pixels (radius 0.8·table/2 around the image centre) whose
// colour differs by more than 0.05 in some channel.
double changed_fraction(const Image& a, const Image& b) {
    const double cx = a.width / 2.0, cy = a.height / 2.0;
    // The camera's 20° view spans 2·6.05·tan 10° ≈ 2.13 units; the table is ~1.1 units wide.
    const double r = 0.8 * 0.55 / (2 * 6.05 * std::tan(10 * kDeg)) * a.height;
    int n = 0, changed = 0;
    for (int j = 0; j < a.height; ++j)
        for (int i = 0; i < a.width; ++i) {
            if (std::hypot(i + 0.5 - cx, j + 0.5 - cy) > r) continue;
            ++n;
            if ((a.at(i, j) - b.at(i, j)).cwiseAbs().maxCoeff() > 0.05) ++changed;
        }
    return n ? static_cast<double>(changed) / n : 0.0;
}

}  // namespace

json plate_scene(double thickness, double axis_deg, int width, int height, double analyser_deg) {
    const double a = axis_deg * kDeg;
    json render = {{"max_depth", 8}, {"threshold", 1e-4}, {"spectral", false}};
    if (analyser_deg >= 0)
        render["polarisation"] = {{"model", "exact"}, {"analyser", {{"type", "linear"}, {"angle", analyser_deg}}}};
    const double top = 0.05 + thickness;
    return json{{"camera",
                 {{"type", "orthographic"}, {"location", vec(0, 3, 0)}, {"look_at", vec(0, 0, 0)}, {"sky", vec(0, 0, 1)},
                  {"ortho_height", kPlateView * height / width}, {"width", width}, {"height", height}}},
                {"background", vec(0, 0, 0)},
                {"materials",
                 {{"calcite", {{"type", "uniaxial"}, {"crystal", "calcite"}, {"optic_axis", vec(std::sin(a), std::cos(a), 0)}}},
                  {"paper", {{"type", "diffuse"}, {"color", vec(0.08, 0.08, 0.08)}, {"ambient", 1}, {"diffuse", 0}}},
                  {"ink", {{"type", "emissive"}, {"color", vec(1, 1, 1)}}}}},
                {"objects",
                 json::array({{{"type", "polyhedron"},
                               {"name", "plate"},
                               {"planes", {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}, {0, 1, 0, top}, {0, -1, 0, -0.05}}},
                               {"material", "calcite"}},
                              {{"type", "polyhedron"},
                               {"name", "line"},
                               {"planes", {{1, 0, 0, 0.01}, {-1, 0, 0, 0.01}, {0, 0, 1, 0.5}, {0, 0, -1, 0.5}, {0, 1, 0, 0.002}, {0, -1, 0, 0}}},
                               {"material", "ink"}},
                              {{"type", "plane"}, {"normal", vec(0, 1, 0)}, {"offset", 0}, {"material", "paper"}}})},
                {"render", render}};
}

std::vector<Peak> peaks(const std::vector<double>& profile, double x0, double dx) {
    const double top = profile.empty() ? 0.0 : *std::max_element(profile.begin(), profile.end());
    std::vector<Peak> out;
    if (!(top > 0)) return out;
    for (size_t i = 0; i < profile.size();) {
        if (profile[i] <= 0.5 * top) {
            ++i;
            continue;
        }
        double w = 0, wx = 0, sum = 0;
        int n = 0;
        for (; i < profile.size() && profile[i] > 0.5 * top; ++i, ++n) {
            w += profile[i];
            wx += profile[i] * (x0 + dx * static_cast<double>(i));
            sum += profile[i];
        }
        out.push_back({wx / w, sum / n, n});
    }
    std::sort(out.begin(), out.end(), [](const Peak& a, const Peak& b) { return a.intensity * a.pixels > b.intensity * b.pixels; });
    return out;
}

std::vector<FireRow> fire_spread(const std::vector<double>& thetas_deg) {
    using spectrum::fraunhofer::B;
    using spectrum::fraunhofer::G;
    const auto& diamond = spectrum::catalogue("diamond");
    const auto moissanite = *spectrum::uniaxial_crystal("moissanite");
    const double crown = 34.5 * kDeg;
    const Vec3 n(0, 0, -1);                                       // facet normal, on the inside
    const Vec3 axis(std::sin(crown), 0, std::cos(crown));         // the table normal
    const biref::Medium air{1.0, 1.0, Vec3::Zero()};
    const auto exit_dir = [&](const biref::Medium& m, biref::Wave w, const Vec3& d) {
        const auto s = biref::split_at_interface(m, w, air, d, n);
        for (int i = 0; i < s.count; ++i)
            if (s.beam[static_cast<size_t>(i)].transmitted) return s.beam[static_cast<size_t>(i)].dir;
        return Vec3(Vec3::Zero());
    };
    const auto angle = [](const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) / kDeg; };
    std::vector<FireRow> rows;
    for (const double t : thetas_deg) {
        FireRow r;
        r.theta_deg = t;
        const Vec3 d(std::sin(t * kDeg), 0, std::cos(t * kDeg));
        const biref::Medium dG{diamond.n(G), diamond.n(G), Vec3::Zero()}, dB{diamond.n(B), diamond.n(B), Vec3::Zero()};
        r.diamond_deg = angle(exit_dir(dG, biref::Wave::Isotropic, d), exit_dir(dB, biref::Wave::Isotropic, d));
        // Closed form: each line's exit angle from Snell's law (core/optics.h), η = 1/n.
        const auto exit_deg = [&](double n) {
            const auto c = optics::cos_transmitted(std::cos(t * kDeg), 1.0 / n);
            return c ? std::acos(*c) / kDeg : 90.0;
        };
        r.diamond_closed_deg = exit_deg(diamond.n(G)) - exit_deg(diamond.n(B));
        const biref::Medium mG{moissanite.ordinary.n(G), moissanite.extraordinary.n(G), axis};
        const biref::Medium mB{moissanite.ordinary.n(B), moissanite.extraordinary.n(B), axis};
        const std::array<Vec3, 4> e{exit_dir(mG, biref::Wave::Ordinary, d), exit_dir(mB, biref::Wave::Ordinary, d),
                                    exit_dir(mG, biref::Wave::Extraordinary, d), exit_dir(mB, biref::Wave::Extraordinary, d)};
        r.moissanite_o_deg = angle(e[0], e[1]);
        for (size_t i = 0; i < 4; ++i)
            for (size_t j = i + 1; j < 4; ++j) r.moissanite_oe_deg = std::max(r.moissanite_oe_deg, angle(e[i], e[j]));
        rows.push_back(r);
    }
    return rows;
}

Result compute(const ExperimentOptions& opt) {
    Result r;
    r.quick = opt.quick;
    RenderOptions ro;
    ro.threads = opt.threads;

    // ---- 1. The calcite plate ----
    Plate& p = r.plate;
    p.thickness = 0.5;
    p.axis_deg = 45;
    const auto calcite = *spectrum::uniaxial_crystal("calcite");
    p.n_o = calcite.ordinary.n(kLambdaD);
    p.n_e = calcite.extraordinary.n(kLambdaD);
    p.rho_deg = biref::walk_off_angle(p.n_o, p.n_e, p.axis_deg * kDeg) / kDeg;
    p.separation_theory = p.thickness * std::tan(p.rho_deg * kDeg);
    const int W = opt.quick ? 200 : 800, H = opt.quick ? 20 : 200;
    const double dx = kPlateView / W, x0 = -kPlateView / 2 + dx / 2;
    p.x.resize(static_cast<size_t>(W));
    for (int i = 0; i < W; ++i) p.x[static_cast<size_t>(i)] = x0 + dx * i;
    const std::array<double, 3> analysers{-1, 0, 90};
    for (size_t a = 0; a < 3; ++a) {
        const json j = plate_scene(p.thickness, p.axis_deg, W, H, analysers[a]);
        const RenderResult img = render(scene_from_json(j, "birefringence_plate.json"), ro);
        if (a == 0) {
            p.image = img.image;
            p.scene = j;
        }
        // Abscissae: position on the image from its centre (the image's right is the scene's −x).
        auto& prof = p.profile[a];
        prof.resize(static_cast<size_t>(W));
        for (int i = 0; i < W; ++i) prof[static_cast<size_t>(i)] = img.image.at(i, H / 2).mean();
    }
    // The o image lies over the line (the image centre), the e image walked off.
    const auto pk = peaks(p.profile[0], x0, dx);
    p.bright_runs = static_cast<int>(pk.size());
    p.pixel = kPlateView / W;
    if (pk.size() >= 2) p.separation_measured = std::abs(pk[0].x - pk[1].x);
    const auto intensity_near = [&](const std::vector<double>& prof, double x) {
        const int i = static_cast<int>(std::lround((x - x0) / dx));
        double m = 0;
        for (int k = std::max(0, i - 3); k <= std::min(W - 1, i + 3); ++k) m = std::max(m, prof[static_cast<size_t>(k)]);
        return m;
    };
    if (pk.size() >= 2) {
        const Peak& o = std::abs(pk[0].x) < std::abs(pk[1].x) ? pk[0] : pk[1];
        const Peak& e = &o == &pk[0] ? pk[1] : pk[0];
        for (size_t a = 0; a < 3; ++a) {
            p.o_intensity[a] = intensity_near(p.profile[a], o.x);
            p.e_intensity[a] = intensity_near(p.profile[a], e.x);
        }
    }

    // ---- 2. Brilliants through the table ----
    const int gw = opt.quick ? 48 : 240, gh = opt.quick ? 48 : 240;
    const auto moissanite = *spectrum::uniaxial_crystal("moissanite");
    const double no_m = moissanite.ordinary.n(kLambdaD), ne_m = moissanite.extraordinary.n(kLambdaD);
    struct Case {
        std::string id, gem, axis;
        json material;
        double rho_deg;
    };
    const double t = kTilt * kDeg;
    const std::vector<Case> cases{
        {"diamond", "diamond", "isotropic", {{"type", "dielectric"}, {"dispersion", "diamond"}}, 0},
        {"cubic-zirconia", "cubic zirconia", "isotropic", {{"type", "dielectric"}, {"dispersion", "cubic-zirconia"}}, 0},
        {"moissanite-axis-normal", "moissanite", "along the table normal",
         {{"type", "uniaxial"}, {"crystal", "moissanite"}, {"optic_axis", vec(0, 1, 0)}}, 0},
        {"moissanite-axis-tilted", "moissanite", "tilted 30° from the table normal",
         {{"type", "uniaxial"}, {"crystal", "moissanite"}, {"optic_axis", vec(std::sin(t), std::cos(t), 0)}},
         std::abs(biref::walk_off_angle(no_m, ne_m, t)) / kDeg},
    };
    // The o-index twin of moissanite: the same render without double refraction.
    const json twin = {{"type", "dielectric"}, {"ior", no_m}};
    const Image twin_image = render(scene_from_json(gem_scene(twin, gw, gh), "birefringence_twin.json"), ro).image;
    for (const Case& c : cases) {
        GemRow row{c.id, c.gem, c.axis, 0, c.rho_deg, 0, 0, 0, 0, Image(), gem_scene(c.material, gw, gh)};
        const auto t0 = std::chrono::steady_clock::now();
        const Scene scene = scene_from_json(row.scene, "birefringence_" + c.id + ".json");
        row.image = render(scene, ro).image;
        row.seconds = seconds_since(t0);
        if (c.gem == "moissanite") {
            row.changed_fraction = changed_fraction(row.image, twin_image);
            trace_walk_off(scene, row);
        }
        r.gems.push_back(std::move(row));
    }
    // ---- 3. Fire ----
    r.fire = fire_spread({5, 10, 15, 20});
    r.findings = judge(r);
    return r;
}

Findings judge(const Result& r) {
    Findings f;
    const Plate& p = r.plate;
    f.line_doubled = p.bright_runs >= 2;
    const auto& o = p.o_intensity;
    const auto& e = p.e_intensity;
    f.crossed_images = f.line_doubled && o[1] < 0.1 * o[0] && e[1] > 0.5 * e[0] && e[2] < 0.1 * e[0] && o[2] > 0.5 * o[0];
    return f;
}

std::string doubling_text(const Result& r) {
    return r.findings.line_doubled ? "the line appears twice."
                                   : "the render shows " + std::to_string(r.plate.bright_runs) +
                                         " bright run(s) across the middle row, not the line twice.";
}

std::string analyser_text(const Result& r) {
    const Plate& p = r.plate;
    if (r.findings.crossed_images)
        return "Through a linear analyser (exact polarisation) at 0° the ordinary image (field along the line) vanishes "
               "and at 90° the extraordinary one: the two images are polarised at right angles.";
    return "Through a linear analyser (exact polarisation) at 0° the ordinary image keeps " +
           fmt(p.o_intensity[1] / p.o_intensity[0], 3) + " of its brightness and the extraordinary one " +
           fmt(p.e_intensity[1] / p.e_intensity[0], 3) + ", at 90° " + fmt(p.o_intensity[2] / p.o_intensity[0], 3) +
           " and " + fmt(p.e_intensity[2] / p.e_intensity[0], 3) +
           ": the render does not show two images polarised at right angles.";
}

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    const Plate& p = r.plate;
    const Csv plate = csv_table(std::vector<Plate>{p});
    write_csv(dir + "/plate.csv", plate);
    Csv prof{{"x", "natural", "analyser_0", "analyser_90"}, {}};
    for (size_t i = 0; i < p.x.size(); ++i)
        prof.add({fmt(p.x[i]), fmt(p.profile[0][i]), fmt(p.profile[1][i]), fmt(p.profile[2][i])});
    write_csv(dir + "/plate_profile.csv", prof);
    write_image(dir + "/plate.png", p.image);
    save_json(dir, "plate.json", p.scene);

    const Csv gems = csv_table(r.gems);
    for (const GemRow& g : r.gems) {
        write_image(dir + "/gem_" + g.id + ".png", g.image);
        save_json(dir, "gem_" + g.id + ".json", g.scene);
    }
    write_csv(dir + "/gems.csv", gems);
    const Csv fire = csv_table(r.fire);
    write_csv(dir + "/fire.csv", fire);

    if (gnuplot_available()) {
        std::ostringstream b;
        b << "set datafile separator ','\nset xlabel 'position across the line on the image, from its centre (scene units)'\nset ylabel 'pixel value'\n"
          << "set key top left\nset title 'Calcite plate " << fmt(p.thickness) << " thick, optic axis at "
          << fmt(p.axis_deg) << "°: double image of one line'\n"
          << "plot 'plate_profile.csv' using 1:2 with lines lw 2 title 'natural light', "
          << "'' using 1:3 with lines title 'analyser 0°', '' using 1:4 with lines title 'analyser 90°'\n";
        gnuplot_figure(dir, "plate_profile", b.str());
    }

    std::ostringstream md;
    md << "# Double refraction in uniaxial crystals\n\n"
       << "Physics: `core/birefringence.h` (docs/birefringence.md). Renders are RGB rays at the sodium D line"
       << " (`\"spectral\": false`), so the measured separations compare with one wavelength's theory.\n\n"
       << "## Calcite plate over a printed line\n\n"
       << "A calcite plate " << fmt(p.thickness) << " units thick, optic axis at " << fmt(p.axis_deg)
       << "° to its normal, seen straight down (orthographic) over one bright line: " << doubling_text(r) << "\n\n"
       << plate.markdown(5) << "\n"
       << "Walk-off ρ = " << fmt(p.rho_deg, 5) << "° (tan ρ = (r − 1) tan θ / (1 + r tan²θ), r = n_o²/n_e²); "
       << "separation T·tan ρ = " << fmt(p.separation_theory, 5) << ", measured between the two images' centroids "
       << fmt(p.separation_measured, 5) << " (pixel " << fmt(p.pixel, 3) << "). " << analyser_text(r) << "\n\n"
       << "![plate](plate.png)\n\n![profile](plate_profile.png)\n\n"
       << "## Round brilliants seen through the table\n\n"
       << "`changed_fraction`: share of the table's pixels that differ by more than 0.05 from the same moissanite"
       << " render with its ordinary index alone (no double refraction) — the doubled facet edges. Diamond and"
       << " cubic zirconia are isotropic: one ray, nothing doubles (0 by construction). `walk_off_traced`: the angle"
       << " between the o and e rays a camera ray spawns on entering the table, against the closed form;"
       << " `offset`: the e ray's lateral offset from the o ray where it next meets the pavilion, against depth × tan ρ.\n\n"
       << gems.markdown(4) << "\n";
    for (const GemRow& g : r.gems) md << "![" << g.id << "](gem_" << g.id << ".png) ";
    md << "\n\n## Angular spread of fire\n\n"
       << "A ray inside the gem meets a crown facet (34.5° from the table; moissanite's optic axis along the table"
       << " normal) at internal incidence θ and leaves: the angle between its exit directions at the G (430.8 nm) and"
       << " B (686.7 nm) lines. Moissanite leaves twice per wavelength (o and e); `moissanite_o_and_e` is the widest"
       << " angle among the four exits.\n\n"
       << fire.markdown(4) << "\n";
    write_text_atomic(dir + "/summary.md", md.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::birefringence
