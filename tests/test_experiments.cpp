// The experiment drivers: the figures' data against the optics they plot, quick runs that
// write every file, the cost model's formulas, the 1/sqrt(spp) convergence, and the
// scene files in scenes/ being the ones the drivers render.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>

#include <refract/core/optics.h>
#include <refract/core/scene_json.h>
#include <refract/experiments/common.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/op_count.h>
#include <refract/experiments/optics_bench.h>
#include <refract/experiments/plot.h>
#include <refract/experiments/polarisation.h>
#include <refract/experiments/rtiow.h>
#include <refract/experiments/yasuda1984.h>

using namespace refract;
using namespace refract::experiments;
namespace fs = std::filesystem;
using Catch::Matchers::WithinAbs;

namespace {

// One quick run of each driver per test binary, into a fresh temporary directory that
// is removed when the test binary exits.
struct QuickRuns {
    std::map<std::string, fs::path> dirs;
    ~QuickRuns() {
        std::error_code ec;
        for (const auto& [name, dir] : dirs) fs::remove_all(dir, ec);
    }
};

const fs::path& quick_run(const std::string& name) {
    static QuickRuns runs;
    auto& done = runs.dirs;
    auto it = done.find(name);
    if (it != done.end()) return it->second;
    const fs::path dir = fs::temp_directory_path() /
                         ("refract-test-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    find(name).run({dir.string(), 2, true});
    return done.emplace(name, dir).first->second;
}

double cell(const Csv& t, size_t row, const std::string& column) {
    for (size_t k = 0; k < t.header.size(); ++k)
        if (t.header[k] == column) return std::stod(t.rows.at(row)[k]);
    FAIL("no column " << column);
    return 0;
}

// The repository's scenes/ directory, found from this source file.
fs::path repo_scenes() { return fs::path(REFRACT_SOURCE_DIR) / "scenes"; }

std::string read_text(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("Yasuda Fig. 4 data: Rs, Rp, R of n = 1.5 are the exact Fresnel terms — R(0) = 0.04, Rp(Brewster) = 0",
          "[experiments][yasuda1984]") {
    const Csv t = read_csv((quick_run("yasuda1984") / "fig4.csv").string());
    REQUIRE(t.header == std::vector<std::string>{"angle_deg", "Rs", "Rp", "R"});
    REQUIRE(t.rows.size() == 181);  // 0-90 degrees in 0.5 degree steps
    CHECK_THAT(cell(t, 0, "R"), WithinAbs(0.04, 1e-15));
    size_t min_rp = 0;
    for (size_t k = 0; k < t.rows.size(); ++k) {
        const double a = cell(t, k, "angle_deg");
        CHECK(a == 0.5 * k);
        const auto f = optics::fresnel(std::fmax(std::cos(a * M_PI / 180), 0.0), 1.5);
        CHECK(cell(t, k, "Rs") == f->Rs);
        CHECK(cell(t, k, "Rp") == f->Rp);
        CHECK(cell(t, k, "R") == f->R());
        if (cell(t, k, "Rp") < cell(t, min_rp, "Rp")) min_rp = k;
    }
    // The grid point nearest Brewster's angle (56.31 degrees) is the minimum of Rp, and
    // at Brewster's angle itself Rp vanishes.
    const double brewster = optics::brewster_angle(1.5) * 180 / M_PI;
    CHECK_THAT(brewster, WithinAbs(56.3099, 1e-4));
    CHECK(std::abs(cell(t, min_rp, "angle_deg") - brewster) <= 0.25);
    CHECK_THAT(optics::fresnel(std::cos(optics::brewster_angle(1.5)), 1.5)->Rp, WithinAbs(0, 1e-30));
}

TEST_CASE("Yasuda Fig. 7 data: T = 1 - R — T = 0 at the critical angle — for n = 10 T peaks above 70 degrees",
          "[experiments][yasuda1984]") {
    const Csv t = read_csv((quick_run("yasuda1984") / "fig7.csv").string());
    REQUIRE(t.header == std::vector<std::string>{"n", "angle_deg", "T"});
    std::map<double, std::pair<double, double>> peak;  // n -> (angle, T) of the largest T
    for (size_t k = 0; k < t.rows.size(); ++k) {
        const double n = cell(t, k, "n"), a = cell(t, k, "angle_deg"), T = cell(t, k, "T");
        CHECK(T == 1.0 - optics::fresnel_reflectance(std::fmax(std::cos(a * M_PI / 180), 0.0), n));
        if (const auto c = optics::critical_angle(n); c && a >= *c * 180 / M_PI) CHECK_THAT(T, WithinAbs(0, 1e-6));
        if (!peak.count(n) || T > peak[n].second) peak[n] = {a, T};
    }
    for (double n : yasuda1984::fig7_indices_a()) REQUIRE(peak.count(n));
    for (double n : yasuda1984::fig7_indices_b()) REQUIRE(peak.count(n));
    // The paper: for n of about 5 and more, T rises, peaks above 70 degrees, then falls.
    CHECK(peak[10.0].first > 70);
    CHECK(peak[5.0].first > 70);
    CHECK(peak[1.5].first == 0);  // glass: T falls monotonically from normal incidence
    const auto p10 = yasuda1984::transmissivity_peak(10);
    CHECK(p10.interior);
    CHECK(p10.angle_deg > 70);
    CHECK(p10.T > p10.T0);
    CHECK_FALSE(yasuda1984::transmissivity_peak(1.5).interior);
    // The interior peak appears where the θ⁴ term of T at normal incidence,
    // (n−1)²(n²−4n+1)/(2n³(n+1)²), turns positive: n = 2 + √3.
    const double onset = yasuda1984::peak_onset_index();
    CHECK_THAT(onset, WithinAbs(2 + std::sqrt(3.0), 1e-4));
    CHECK(yasuda1984::transmissivity_peak(onset + 0.01).interior);
    CHECK_FALSE(yasuda1984::transmissivity_peak(onset - 0.01).interior);
}

TEST_CASE("Yasuda driver (quick) writes its CSV, figures, renders, scenes and summary", "[experiments][yasuda1984]") {
    const fs::path d = quick_run("yasuda1984");
    for (const char* f : {"fig4.csv", "fig4.png", "fig4.pdf", "fig4.gp", "fig7.csv", "fig7a.png", "fig7b.png",
                          "fig7b.pdf", "fig7_peaks.csv", "fig8.png", "fig8.pdf", "fig8_a.png", "fig8_j.png",
                          "fig8_stats.csv", "fig9.png", "fig9_f.png", "cost.csv", "cost_render.csv", "memory.csv",
                          "memory.png", "summary.md", "scenes/fig8_a.json", "scenes/fig9_a.json",
                          "scenes/tree_growth.json"})
        CHECK(fs::file_size(d / f) > 0);
    for (const auto& e : fs::directory_iterator(d)) CHECK(e.path().string().find("refract-tmp") == std::string::npos);
    // The scene files re-render with `refract render`.
    const Scene s = load_scene((d / "scenes/fig8_j.json").string());
    CHECK(s.materials.at(s.objects.at(0).material).dielectric()->ior == 10.0);
    CHECK(read_text(d / "summary.md").find("## Cost of Fresnel reflectance") != std::string::npos);
}

TEST_CASE("Yasuda memory study: the stored tree outgrows the FIFO list — the threshold keeps the list small",
          "[experiments][yasuda1984]") {
    const Csv t = read_csv((quick_run("yasuda1984") / "memory.csv").string());
    REQUIRE(t.rows.size() >= 5);
    for (size_t k = 0; k < t.rows.size(); ++k) {
        CHECK(cell(t, k, "whitted_bytes") > cell(t, k, "list_bytes_threshold0"));
        CHECK(cell(t, k, "list_peak_entries_threshold0") >= cell(t, k, "list_peak_entries_threshold_1_255"));
        if (k > 0) CHECK(cell(t, k, "whitted_peak_nodes") > cell(t, k - 1, "whitted_peak_nodes"));
    }
    const size_t last = t.rows.size() - 1;
    CHECK(cell(t, last, "list_peak_entries_threshold_1_255") == cell(t, 2, "list_peak_entries_threshold_1_255"));
}

TEST_CASE("Cost model: eq. 7 with Cr from the eq. 2-5 direction P equals Snell's-law Fresnel",
          "[experiments][yasuda1984][fresnel]") {
    namespace gen = optics::generic;
    for (double eta : {1.309, 1.52, 2.2, 10.0, 0.8}) {
        for (double deg = 1; deg < 89; deg += 4) {
            const double a = deg * M_PI / 180;
            const Vec3 N(0, 1, 0), V(std::sin(a), -std::cos(a), 0);
            const auto w = gen::whitted_directions(V, N, eta);
            const auto f = optics::fresnel(std::cos(a), eta);
            REQUIRE(w.transmitted.has_value() == f.has_value());
            if (!f) continue;
            const Vec3& P = *w.transmitted;
            const double cr = -P.dot(N) / P.norm();  // §3.2.1
            CHECK_THAT(cr, WithinAbs(f->cos_t, 1e-12));
            CHECK_THAT(gen::fresnel_terms(std::cos(a), cr, eta).R(), WithinAbs(f->R(), 1e-12));
        }
    }
}

TEST_CASE("Counting scalar: the generic laws give the double results and count eq. 7's arithmetic",
          "[experiments][yasuda1984][fresnel]") {
    namespace gen = optics::generic;
    for (double c : {0.05, 0.4, 0.9, 1.0})
        for (double eta : {0.5, 1.5, 2.417}) {
            const auto fc = gen::fresnel<Counted>(c, eta);
            const auto fd = optics::fresnel(c, eta);
            REQUIRE(fc.has_value() == fd.has_value());
            if (fd) CHECK(fc->R().v == fd->R());
            CHECK(gen::schlick<Counted>(c, eta).v == optics::schlick(c, eta));
        }
    // Eq. 7 given Ci and Cr: n·Cr and n·Ci, two quotients, two squares, one halving.
    const OpCounts before = op_counts();
    (void)gen::fresnel_terms<Counted>(0.8, 0.9, 1.5).R();
    const OpCounts d = op_counts() - before;
    CHECK(d.mul == 5);
    CHECK(d.div == 2);
    // The counted node: Fresnel costs more than a constant reflectivity in both formulations.
    const auto costs = yasuda1984::count_node_costs();
    std::map<std::string, std::uint64_t> md;
    for (const auto& c : costs) md[c.formulation + "/" + c.model] = c.ops.muldiv();
    CHECK(md["yasuda1984/fresnel"] > md["yasuda1984/constant"]);
    CHECK(md["refract/fresnel"] > md["refract/constant"]);
    CHECK(yasuda1984::count_sphere_test().mul > 0);
}

TEST_CASE("RTIOW: the solid glass sphere never meets total internal reflection, the hollow one does",
          "[experiments][rtiow][tir]") {
    for (const auto& st : rtiow::stages()) {
        const Scene s = parse_scene(rtiow::stage_scene(st.id, true), st.id);
        const auto tir = rtiow::count_tir_nodes(s);
        if (st.id == "fig1_29_hollow") CHECK(tir > 0);
        else CHECK(tir == 0);
    }
}

TEST_CASE("RTIOW: the scene is mirrored in z so the glass sphere appears on the left as in the book",
          "[experiments][rtiow]") {
    const Scene s = parse_scene(rtiow::stage_scene("fig1_27_always_refract", true), "stage");
    // The image's right vector points to +x, and the glass sphere (x = -1) projects left of centre.
    CHECK(s.camera.basis().R.x() > 0);
    const Ray left = s.camera.ray(s.camera.width * 0.15, s.camera.height * 0.5);
    bool hits_glass = false;
    for (const auto& o : s.objects)
        if (s.materials[o.material].is<material::Dielectric>())
            hits_glass |= intersect(std::get<Sphere>(o.shape), left, 1e-6, 1e9).has_value();
    CHECK(hits_glass);
}

TEST_CASE("RTIOW driver (quick): stages, Schlick error, and RMSE falling like 1/sqrt(spp)", "[experiments][rtiow]") {
    const fs::path d = quick_run("rtiow-dielectric");
    for (const auto& st : rtiow::stages()) CHECK(fs::file_size(d / (st.id + ".png")) > 0);
    for (const char* f : {"stages.png", "stages.pdf", "schlick_error.csv", "schlick_error.png", "convergence.csv",
                          "convergence.png", "convergence.pdf", "summary.md", "scenes/fig1_29_hollow.json"})
        CHECK(fs::file_size(d / f) > 0);
    const Csv conv = read_csv((d / "convergence.csv").string());
    std::vector<double> spp, err;
    for (size_t k = 0; k < conv.rows.size(); ++k) {
        spp.push_back(cell(conv, k, "spp"));
        err.push_back(cell(conv, k, "rmse"));
    }
    REQUIRE(spp.size() >= 4);
    const double slope = loglog_fit(spp, err).slope;
    CHECK(slope > -0.6);
    CHECK(slope < -0.4);
    // Schlick is exact at normal incidence; inside the glass, evaluated with the incident
    // cosine (as RTIOW does) it misses the steep rise before the critical angle.
    const Csv s = read_csv((d / "schlick_error.csv").string());
    double worst_inside_ci = 0;
    for (size_t k = 0; k < s.rows.size(); ++k) {
        if (cell(s, k, "angle_deg") == 0) CHECK_THAT(cell(s, k, "error"), WithinAbs(0, 1e-15));
        if (s.rows[k][0] == "inside eta=1/1.5 (RTIOW: cos_i)")
            worst_inside_ci = std::max(worst_inside_ci, std::abs(cell(s, k, "error")));
    }
    CHECK(worst_inside_ci > 0.5);
}

TEST_CASE("Scene files in scenes/ are exactly the ones the drivers render (full size)", "[experiments][scenes]") {
    const fs::path y = repo_scenes() / "yasuda1984", r = repo_scenes() / "rtiow";
    for (const auto& s : yasuda1984::fig8_spheres())
        CHECK(read_text(y / (std::string("fig8_") + s.letter + ".json")) == json_text(yasuda1984::fig8_scene(s.n, false)));
    for (size_t k = 0; k < yasuda1984::fig9_reflectivities().size(); ++k)
        CHECK(read_text(y / (std::string("fig9_") + static_cast<char>('a' + k) + ".json")) ==
              json_text(yasuda1984::fig9_scene(yasuda1984::fig9_reflectivities()[k], false)));
    CHECK(read_text(y / "tree_growth.json") == json_text(yasuda1984::tree_growth_scene(16, 0, "whitted", false)));
    for (const auto& st : rtiow::stages())
        CHECK(read_text(r / (st.id + ".json")) == json_text(rtiow::stage_scene(st.id, false)));
    CHECK(read_text(r / "convergence_reference.json") == json_text(rtiow::convergence_scene(0, false)));
    CHECK(read_text(r / "convergence_stochastic.json") ==
          json_text(rtiow::convergence_scene(rtiow::convergence_spp(false).back(), false)));
}

TEST_CASE("Plot helpers: CSV round trip, shortest round-trip numbers, a clear error without gnuplot",
          "[experiments][plot]") {
    const fs::path d = fs::temp_directory_path() / ("refract-test-plot-" + std::to_string(::getpid()));
    fs::create_directories(d);
    Csv t{{"x", "y"}, {{fmt(0.1), fmt(1.0 / 3.0)}, {fmt(1e-300), fmt(-2.5)}}};
    write_csv((d / "t.csv").string(), t);
    const Csv back = read_csv((d / "t.csv").string());
    CHECK(back.header == t.header);
    CHECK(std::stod(back.rows[0][1]) == 1.0 / 3.0);
    CHECK(back.rows[0][0] == "0.1");
    CHECK(std::stod(back.rows[1][0]) == 1e-300);
    // Without gnuplot on PATH: one clear error, and the script is still written.
    const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
    ::setenv("PATH", "", 1);
    std::string message;
    try {
        gnuplot_figure(d.string(), "f", "plot 't.csv' using 1:2\n");
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    ::setenv("PATH", path.c_str(), 1);
    CHECK(message.find("gnuplot not found") != std::string::npos);
    CHECK(fs::exists(d / "f.gp"));
    CHECK_FALSE(fs::exists(d / "f.png"));
    if (gnuplot_available()) {
        // A script gnuplot rejects: one line naming the script, no figure, no leftovers.
        message.clear();
        try {
            gnuplot_figure(d.string(), "bad", "plot no_such_function_xyz(x)\n");
        } catch (const std::runtime_error& e) {
            message = e.what();
        }
        CHECK(message.find("bad.gp failed") != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
        CHECK_FALSE(fs::exists(d / "bad.png"));
        gnuplot_figure(d.string(), "good", "set datafile separator ','\nplot 't.csv' every ::1 using 1:2\n");
        CHECK(fs::file_size(d / "good.png") > 0);
        CHECK(fs::file_size(d / "good.pdf") > 0);
        for (const auto& e : fs::directory_iterator(d)) CHECK(e.path().string().find("refract-tmp") == std::string::npos);
    }
    fs::remove_all(d);
}

TEST_CASE("Polarisation driver (quick): sphere DoP per path equals the closed forms, I(0) + I(90) = S0, "
          "natural and exact differ on the diamond",
          "[experiment][polarisation]") {
    namespace pol = refract::experiments::polarisation;
    const fs::path d = fs::temp_directory_path() / ("refract-test-" + std::to_string(::getpid()) + "-polarisation");
    fs::remove_all(d);
    const pol::Result r = pol::compute({d.string(), 2, true});
    pol::write(r, d.string());
    for (const char* f : {"summary.md", "sphere_dop.csv", "sphere_dop_errors.csv", "natural_vs_exact.csv",
                          "depth_split.csv", "analyser.csv", "times.csv", "diamond-natural.png", "diamond-exact.png",
                          "diamond-dolp.png", "diamond-exact.stokes.exr", "diamond-exact.dolp.exr",
                          "diamond-exact.aolp.exr", "diamond-analyser-000.png", "diamond-analyser-135.png",
                          "sphere-exact.png", "scenes/diamond-exact.json", "scenes/diamond-analyser-045.json"})
        CHECK(fs::file_size(d / f) > 0);
    if (gnuplot_available())
        for (const char* f : {"sphere_dop.png", "depth_split.png", "de2000_diamond.png", "analyser.png",
                              "dolp_diamond.png"})
            CHECK(fs::file_size(d / f) > 0);
    for (const auto& e : fs::directory_iterator(d)) CHECK(e.path().string().find("refract-tmp") == std::string::npos);

    // 1. Every class of every sphere, at every angle, against its closed form.
    REQUIRE(r.sphere.errors.size() == 8);
    for (const auto& e : r.sphere.errors) {
        CHECK(e.points == 90);
        CHECK(e.max_dop_error < 1e-9);
        CHECK(e.max_signed_error < 1e-9);
        CHECK(e.max_s23 < 1e-9);
    }
    // Brewster's angle: the reflection is fully s-polarised (the grid point 56 degrees is near it).
    for (const auto& p : r.sphere.points)
        if (p.n == 1.5 && p.theta_deg == 56 && p.cls == 0) CHECK(p.dop > 0.999);
    for (const auto& b : r.sphere.rainbows) CHECK_THAT(b.dop, WithinAbs(b.dop_closed, 1e-9));

    // 2. The models differ on the diamond; they agree exactly where a path meets one interface
    // (depth 0 and 1 of the split).
    CHECK(r.diamond.rmse > 0);
    CHECK(r.diamond.de_max > 0);
    REQUIRE(r.diamond.depth.size() > 2);
    for (const pol::Comparison* c : {&r.diamond, &r.glass}) {
        CHECK_THAT(c->depth[0].exact, WithinAbs(c->depth[0].natural, 1e-9 * c->depth[0].natural));
        CHECK_THAT(c->depth[1].exact, WithinAbs(c->depth[1].natural, 1e-9 * c->depth[1].natural));
    }
    // The glass sphere is rendered by the same walk: its depth split sums to the image.
    double tn = 0, te = 0;
    for (const auto& row : r.glass.depth) tn += row.natural, te += row.exact;
    CHECK_THAT(tn, WithinAbs(r.glass.light_natural, 1e-9 * tn));
    CHECK_THAT(te, WithinAbs(r.glass.light_exact, 1e-9 * te));

    // 3. The analyser: crossed pairs add up to S0 wherever cie-rgb's final clipping does not act.
    CHECK(r.analyser.max_dev_0_90_nonzero < 1e-9);
    CHECK(r.analyser.max_dev_45_135_nonzero < 1e-9);
    CHECK(r.analyser.deviations_at_zeros);
    CHECK(r.analyser.dolp_max_object > 0);
    CHECK(read_text(d / "summary.md").find("## 3. The diamond through a linear analyser") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("optics-bench (quick): the far-field detector agrees with the closed forms of a drop, a rainbow, a prism "
          "and a slab", "[experiments][optics-bench]") {
    namespace ob = refract::experiments::optics_bench;
    ExperimentOptions opt;
    opt.quick = true;
    opt.threads = 2;
    const ob::Result r = ob::compute(opt);
    // 1. Each van de Hulst class's share of the beam, against geometric optics (200 000
    //    photons: σ ≈ 3e-4 for the largest class).
    REQUIRE(r.drop.classes.size() == 4);
    for (const auto& c : r.drop.classes) {
        CHECK(c.total == Approx(c.total_closed).margin(1.5e-3));
        CHECK(c.max_z < 5.0);
    }
    CHECK(r.drop.classes[0].total_closed == Approx(0.0664058).margin(1e-6));
    // 2. Rainbow angles within a bin (0.05°) of Descartes' at every wavelength, red outside.
    CHECK(r.rainbow.max_error < 0.05);
    CHECK(r.rainbow.rows.front().primary > r.rainbow.rows.back().primary);  // violet deviated most
    // 3. Prism deviation within half a 0.01° bin.
    CHECK(r.prism.max_error < 0.0051);
    // 4. Slab transmittance, s and p, all internal reflections: to the threshold's truncation.
    CHECK(r.slab.max_error < 1e-7);
    const fs::path d = fs::temp_directory_path() / ("refract-test-" + std::to_string(::getpid()) + "-optics-bench");
    fs::remove_all(d);
    ob::write(r, d.string());
    for (const char* f : {"drop.csv", "drop_classes.csv", "rainbow.csv", "prism.csv", "slab.csv", "summary.md",
                          "drop_far_field/far_field.exr", "drop_far_field/far_field.csv"})
        CHECK(fs::file_size(d / f) > 0);
    fs::remove_all(d);
}
