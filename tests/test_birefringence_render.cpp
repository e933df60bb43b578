// Uniaxial crystals in the renderer (material "uniaxial"): the double image of a calcite
// plate against walk-off × thickness, its two images' orthogonal polarisations, and the
// experiment's quick mode.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
namespace fs_path_helper = std::filesystem;

#include <refract/core/birefringence.h>
#include <refract/core/ray_tree.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/experiments/birefringence.h>
#include <refract/experiments/common.h>
#include "tests/render_options.h"

using namespace refract;
using refract::testing::threads;
namespace bx = refract::experiments::birefringence;

namespace {
std::vector<double> middle_row(const RenderResult& r) {
    std::vector<double> v;
    for (int i = 0; i < r.image.width; ++i) v.push_back(r.image.at(i, r.image.height / 2).mean());
    return v;
}
}  // namespace

TEST_CASE("Calcite plate doubles a line by walk-off times thickness", "[birefringence]") {
    const int W = 400, H = 3;
    const double T = 0.5, dx = 0.8 / W, x0 = -0.4 + dx / 2;
    const auto c = *spectrum::uniaxial_crystal("calcite");
    const double no = c.ordinary.n(spectrum::fraunhofer::D), ne = c.extraordinary.n(spectrum::fraunhofer::D);
    const double want = T * std::tan(biref::walk_off_angle(no, ne, M_PI / 4));
    const RenderResult nat = render(experiments::scene_from_json(bx::plate_scene(T, 45, W, H, -1), "plate.json"), threads(2));
    const auto pk = bx::peaks(middle_row(nat), x0, dx);
    REQUIRE(pk.size() == 2);
    CHECK(std::abs(std::abs(pk[0].x - pk[1].x) - want) < 0.5 * dx);  // within half a pixel
    // Both images carry light of the same order (each about half the line's).
    CHECK(pk[0].intensity > 0.3);
    CHECK(pk[1].intensity > 0.3);
    // Without a plate tilt (optic axis along the normal) the line is seen once.
    const RenderResult one = render(experiments::scene_from_json(bx::plate_scene(T, 0, W, H, -1), "plate0.json"), threads(2));
    CHECK(bx::peaks(middle_row(one), x0, dx).size() == 1);
}

TEST_CASE("The two images of a calcite plate are polarised at right angles", "[birefringence]") {
    const int W = 400, H = 3;
    const double dx = 0.8 / W, x0 = -0.4 + dx / 2;
    const auto row = [&](double analyser) {
        return middle_row(render(experiments::scene_from_json(bx::plate_scene(0.5, 45, W, H, analyser), "p.json"), threads(2)));
    };
    const std::vector<double> natural = row(-1);
    const auto nat = bx::peaks(natural, x0, dx);
    REQUIRE(nat.size() == 2);
    const double xo = std::abs(nat[0].x) < std::abs(nat[1].x) ? nat[0].x : nat[1].x;  // the o image, over the line
    const double xe = xo == nat[0].x ? nat[1].x : nat[0].x;
    const auto a0 = bx::peaks(row(0), x0, dx), a90 = bx::peaks(row(90), x0, dx);
    // Analyser across the line (0°): the e image only (its field lies in the plane of the
    // optic axis and the normal); along the line (90°): the o image only.
    REQUIRE(a0.size() == 1);
    REQUIRE(a90.size() == 1);
    CHECK(std::abs(a0[0].x - xe) < 2 * dx);
    CHECK(std::abs(a90[0].x - xo) < 2 * dx);
    // The analyser passes all of the e image's light; in natural light that pixel also sees
    // the paper through the o ray, about half the paper's level seen through the plate
    // (`natural.front()`, far from the line, is the paper through both rays).
    const double e_nat = nat[0].x == xe ? nat[0].intensity : nat[1].intensity;
    CHECK(a0[0].intensity == Approx(e_nat - 0.5 * natural.front()).epsilon(0.01));
}

TEST_CASE("Uniaxial scene field errors name the field", "[birefringence]") {
    nlohmann::json j = bx::plate_scene(0.5, 45, 8, 2, -1);
    j["materials"]["calcite"]["crystal"] = "ruby";
    CHECK_THROWS_WITH(parse_scene(j, "bad.json"), Catch::Matchers::Contains("/materials/calcite/crystal") &&
                                                      Catch::Matchers::Contains("calcite, quartz, sapphire, moissanite"));
    j["materials"]["calcite"] = {{"type", "uniaxial"}, {"crystal", "calcite"}, {"optic_axis", {0, 0, 0}}};
    CHECK_THROWS_WITH(parse_scene(j, "bad.json"), Catch::Matchers::Contains("optic_axis"));
    // The stochastic integrator samples one direction per hit and keeps no o/e wave: refused.
    nlohmann::json k = bx::plate_scene(0.5, 45, 8, 2, -1);
    k["render"]["integrator"] = "stochastic";
    CHECK_THROWS_WITH(render(parse_scene(k, "stochastic.json"), threads(1)),
                      Catch::Matchers::Contains("material 'calcite'") && Catch::Matchers::Contains("fresnel-tree"));
}

TEST_CASE("Birefringence experiment (quick): plate separation, analyser, moissanite walk-off, doubling and fire",
          "[experiments][birefringence]") {
    experiments::ExperimentOptions opt;
    opt.threads = 2;
    opt.quick = true;
    const bx::Result r = bx::compute(opt);
    const bx::Plate& p = r.plate;
    CHECK(p.rho_deg == Approx(6.23).margin(0.01));
    const double pixel = 0.8 / static_cast<double>(p.x.size());
    CHECK(std::abs(p.separation_measured - p.separation_theory) < pixel);
    // Analyser at 0°: the o image goes dark (only the paper seen through the e ray is left),
    // at 90° the e image.
    CHECK(p.o_intensity[1] < 0.1 * p.o_intensity[0]);
    CHECK(p.e_intensity[2] < 0.1 * p.e_intensity[0]);
    CHECK(p.e_intensity[1] > 0.9 * p.e_intensity[0] - 0.05);
    REQUIRE(r.gems.size() == 4);
    CHECK(r.gems[0].changed_fraction == 0);  // diamond: isotropic
    const auto& normal = r.gems[2];
    const auto& tilted = r.gems[3];
    CHECK(tilted.rho_traced_deg == Approx(tilted.rho_theory_deg).margin(1e-9));
    CHECK(tilted.offset_traced == Approx(tilted.offset_theory).margin(1e-9));
    CHECK(normal.rho_traced_deg < 1e-9);  // along the optic axis: one ray
    CHECK(tilted.changed_fraction > normal.changed_fraction);
    CHECK(normal.changed_fraction > 0.02);  // internal reflections run off the axis and double
    // Fire: diamond's G-B exit spread is the closed form; moissanite's is over twice it for
    // the o ray alone and wider still with its e exits.
    REQUIRE(r.fire.size() == 4);
    for (const bx::FireRow& f : r.fire) {
        CHECK(f.diamond_deg == Approx(f.diamond_closed_deg).margin(1e-9));
        CHECK(f.moissanite_o_deg > 2 * f.diamond_deg);
        CHECK(f.moissanite_oe_deg > f.moissanite_o_deg);
    }
    const fs_path_helper::path dir = fs_path_helper::temp_directory_path() / ("refract-test-birefringence-" + std::to_string(::getpid()));
    bx::write(r, dir.string());
    for (const char* f : {"plate.csv", "plate_profile.csv", "gems.csv", "fire.csv", "plate.png", "summary.md", "plate.json"})
        CHECK(fs_path_helper::exists(dir / f));
    fs_path_helper::remove_all(dir);
}

TEST_CASE("Spectral eye pass doubles the line through calcite at every wavelength", "[birefringence]") {
    // Three wavelengths (450, 550, 650 nm), each with its own n_o and n_e: the two images
    // stay T tan rho apart (calcite's walk-off changes by about 4 % over the range, a pixel).
    const int W = 400, H = 3;
    const double dx = 0.8 / W, x0 = -0.4 + dx / 2;
    nlohmann::json j = bx::plate_scene(0.5, 45, W, H, -1);
    j["render"]["spectral"] = {{"range", {450, 650}}, {"step", 100}};
    const Scene s = parse_scene(j, "spectral_plate.json");
    REQUIRE(s.settings.spectral.enabled);
    const auto pk = bx::peaks(middle_row(render(s, threads(2))), x0, dx);
    REQUIRE(pk.size() == 2);
    const auto c = *spectrum::uniaxial_crystal("calcite");
    const double want = 0.5 * std::tan(biref::walk_off_angle(c.ordinary.n(550), c.extraordinary.n(550), M_PI / 4));
    CHECK(std::abs(std::abs(pk[0].x - pk[1].x) - want) < 2 * dx);
}

namespace {
// Sums what leaves a calcite slab along every branch of one ray's tree, for each
// polarisation payload (core/polarisation_state.h).
template <class P>
struct LeavingEnds {
    using Walker = RayTreeWalkerT<P>;
    using Entry = TreeEntryT<P>;
    double sum = 0;
    void background(const Entry& e) { sum += e.weight.mean() * throughput(e.pol); }
    void leaf(const Entry&, const SurfaceHit&) {}
    bool intercept(Walker&, const Entry&, const SurfaceHit&, typename Walker::List&) { return false; }
    double band_ior(const Entry&, const SurfaceHit&) const { return 0.0; }
    double wavelength(const Entry&) const { return 0.0; }
};

template <class P>
double leaving(const Scene& scene, const Ray& ray, const P& start, double& lost) {
    SceneTracer tracer(scene);
    RenderStats st;
    TreeLimits limits;
    limits.threshold = 1e-12;
    limits.max_depth = 400;
    RayTreeWalkerT<P> walker(tracer, limits, st);
    LeavingEnds<P> ends;
    typename RayTreeWalkerT<P>::List list{TreeEntryT<P>{ray, Vec3(1, 1, 1)}};
    list.front().pol = start;
    walker.walk(list, ends);
    lost = st.lost_threshold + st.lost_depth + st.lost_limits;
    return ends.sum;
}
}  // namespace

TEST_CASE("Energy through a calcite slab: every branch of the tree sums to the incoming power", "[birefringence]") {
    // A slab alone under a black sky, one oblique ray: what leaves along all branches (o and
    // e, every internal reflection) plus what the threshold drops is 1, for natural light,
    // the light pass's Stokes vectors and the eye pass's camera-side Mueller matrix.
    nlohmann::json j = bx::plate_scene(0.5, 45, 8, 2, -1);
    j["objects"] = nlohmann::json::array({j["objects"][0]});
    j["materials"]["calcite"]["optic_axis"] = {0.3, 0.8, 0.52};
    j["render"]["polarisation"] = "natural";
    const Scene s = parse_scene(j, "slab.json");
    const Vec3 d = Vec3(0.5, -1.0, 0.3).normalized();
    const Ray ray{Vec3(0, 2, 0) - 2.5 * d, d};
    const Vec3 x = d.cross(Vec3(0, 0, 1)).normalized();
    double lost = 0;
    const double natural = leaving(s, ray, NaturalLight{}, lost);
    CHECK(natural + lost == Approx(1.0).margin(1e-9));
    j["render"]["polarisation"] = "exact";
    const Scene e = parse_scene(j, "slab_exact.json");
    const double light = leaving(e, ray, LightStokes{polar::unpolarised(1.0), x}, lost);
    CHECK(light + lost == Approx(1.0).margin(1e-9));
    const double eye = leaving(e, ray, EyeStokes{polar::Mueller::Identity(), x}, lost);
    CHECK(eye + lost == Approx(1.0).margin(1e-9));
    // A linearly polarised photon: all its power still comes out.
    CHECK(leaving(e, ray, LightStokes{polar::linear(1.0, 0.7), x}, lost) + lost == Approx(1.0).margin(1e-9));
}

TEST_CASE("The example calcite plate scene is the experiment's plate", "[birefringence]") {
    std::ifstream in(std::string(REFRACT_SOURCE_DIR) + "/scenes/examples/calcite-plate.json");
    std::stringstream text;
    text << in.rdbuf();
    CHECK(text.str() == experiments::json_text(bx::plate_scene(0.5, 45, 800, 200, -1)));
}
