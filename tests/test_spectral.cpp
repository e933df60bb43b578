// Spectral eye pass and light pass (Ohtsuka & Kawai 1998): the split per wavelength,
// Fresnel at the band's index, the three-wavelength shortcut, illumination-map
// convergence and thread determinism.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/optics.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/plot.h>

using namespace refract;

namespace {

// A glass sphere on a diffuse floor under a point light, 40×30.
Scene glass_scene(const std::string& dispersion_json, const std::string& render_json = "{}") {
    std::string mat = R"({"type": "dielectric")";
    mat += dispersion_json.empty() ? R"(, "ior": 1.5)" : R"(, "dispersion": )" + dispersion_json;
    mat += "}";
    const auto j = nlohmann::json::parse(R"({
      "camera": {"location": [0, 1.6, -4], "look_at": [0, 0.5, 0], "angle": 40, "width": 40, "height": 30},
      "background": [0.3, 0.5, 0.8],
      "materials": {"floor": {"type": "diffuse", "color": [0.9, 0.8, 0.6], "checker": {"color2": [0.1, 0.2, 0.5], "size": 0.5}},
                    "glass": )" + mat + R"(},
      "objects": [{"type": "plane", "normal": [0, 1, 0], "offset": 0, "material": "floor"},
                  {"type": "sphere", "center": [0, 0.8, 0], "radius": 0.8, "material": "glass"}],
      "lights": [{"position": [2, 6, -3]}],
      "render": )" + render_json + "}");
    return parse_scene(j, "test.json");
}

double max_difference(const Image& a, const Image& b) {
    double m = 0;
    for (int j = 0; j < a.height; ++j)
        for (int i = 0; i < a.width; ++i) m = std::fmax(m, (a.at(i, j) - b.at(i, j)).cwiseAbs().maxCoeff());
    return m;
}

double rmse(const Image& a, const Image& b) {
    double s = 0;
    for (int j = 0; j < a.height; ++j)
        for (int i = 0; i < a.width; ++i) s += (a.at(i, j) - b.at(i, j)).squaredNorm();
    return std::sqrt(s / (3.0 * a.width * a.height));
}

const char* kNoLimits = R"({"max_depth": 12, "spectral": {"max_reflections": 100, "max_transmissions": 100}})";

}  // namespace

TEST_CASE("Spectral pass without a dispersive material never splits and equals the RGB render", "[spectral]") {
    Scene rgb = glass_scene("");
    Scene spec = glass_scene("", kNoLimits);
    REQUIRE(spec.settings.spectral.enabled);
    const auto a = render(rgb), b = render(spec);
    CHECK(b.stats.spectral_splits == 0);
    CHECK(max_difference(a.image, b.image) == 0.0);
}

TEST_CASE("A constant dispersion splits into 31 wavelengths and white balance returns the RGB image",
          "[spectral]") {
    Scene rgb = glass_scene("");
    rgb.settings.max_depth = 12;
    for (const char* pipeline : {"cie-rgb", "xyz-srgb"}) {
        INFO(pipeline);
        Scene spec = glass_scene(
            "1.5", std::string(R"({"max_depth": 12, "spectral": {"max_reflections": 100, "max_transmissions": 100, "pipeline": ")") +
                       pipeline + "\"}}");
        const auto a = render(rgb), b = render(spec);
        CHECK(b.stats.spectral_splits > 100);
        CHECK(b.stats.wavelength_segments > 31 * b.stats.spectral_splits);
        CHECK(max_difference(a.image, b.image) < 1e-9);
    }
}

TEST_CASE("Per-wavelength Fresnel uses the band's index (physical) and the nominal one (POV-Ray)", "[spectral]") {
    Scene s = glass_scene("\"diamond\"");
    SceneTracer tracer(s);
    RenderStats st;
    const Ray ray{Vec3(0.5, 0.8, -3), Vec3(0, 0, 1)};  // off-axis: cos θi = 0.78
    const auto hit = tracer.intersect(ray, st);
    REQUIRE(hit);
    const auto* glass = hit->material->dielectric();
    REQUIRE(glass);
    REQUIRE(glass->dispersion);
    const double cos_i = -ray.dir.dot(hit->normal);
    const double n450 = glass->dispersion->n(450), n650 = glass->dispersion->n(650);
    CHECK(n450 - n650 > 0.02);  // diamond's dispersion
    const Interaction blue = tracer.interact(*hit, ray, st, n450), red = tracer.interact(*hit, ray, st, n650);
    CHECK(blue.reflectance == Approx(optics::fresnel_reflectance(cos_i, n450)).epsilon(1e-14));
    CHECK(red.reflectance == Approx(optics::fresnel_reflectance(cos_i, n650)).epsilon(1e-14));
    CHECK(blue.reflectance > red.reflectance + 1e-3);
    // Snell at the band's index: the blue ray bends more (smaller sin θt).
    const double sin_b = blue.branch[1].ray.dir.cross(hit->normal).norm();
    const double sin_r = red.branch[1].ray.dir.cross(hit->normal).norm();
    const double sin_i = ray.dir.cross(hit->normal).norm();
    CHECK(sin_b == Approx(sin_i / n450).epsilon(1e-12));
    CHECK(sin_r == Approx(sin_i / n650).epsilon(1e-12));
    // POV-Ray mode: Fresnel keeps the nominal (single-precision) index for every band.
    Scene pov = s;
    pov.settings.compat = Compat::PovRay;
    SceneTracer ptracer(pov);
    const Interaction pblue = ptracer.interact(*hit, ray, st, n450);
    CHECK(pblue.reflectance ==
          Approx(optics::fresnel_reflectance(cos_i, static_cast<float>(glass->ior))).epsilon(1e-14));
}

TEST_CASE("Dispersion: ior absent takes the model's nominal index — an explicit ior must agree with it", "[spectral]") {
    const auto j = nlohmann::json::parse(R"({"camera": {}, "objects": [],
        "materials": {"a": {"type": "dielectric", "dispersion": "diamond"},
                      "b": {"type": "dielectric", "ior": 2.4175, "dispersion": "diamond"}}})");
    const Scene s = parse_scene(j, "t.json");
    CHECK(s.materials[0].dielectric()->ior == spectrum::catalogue("diamond").nominal());
    CHECK(s.materials[1].dielectric()->ior == spectrum::catalogue("diamond").nominal());
    CHECK(s.settings.spectral.enabled);
    CHECK_THROWS_WITH(parse_scene(nlohmann::json::parse(R"({"camera": {}, "objects": [],
        "render": {"spectral": {"step": 7}}})"), "t.json"), Catch::Contains("t.json: /render/spectral"));
}

TEST_CASE("Shortcut (Ohtsuka & Kawai §3.3): three wavelengths stand for the split where they agree",
          "[spectral]") {
    // Weakly dispersive N-BK7: most split rays see three nearly equal colours.
    const std::string lim = R"("max_depth": 10, "spectral": {"max_reflections": 8, "max_transmissions": 8)";
    Scene full = glass_scene("\"N-BK7\"", "{" + lim + "}}");
    Scene fast = glass_scene("\"N-BK7\"", "{" + lim + R"(, "shortcut": true, "shortcut_threshold": 0.02}})");
    const auto a = render(full), b = render(fast);
    CHECK(a.stats.shortcut_tests == 0);
    CHECK(b.stats.shortcut_tests == a.stats.spectral_splits);
    CHECK(b.stats.shortcut_taken > b.stats.shortcut_tests / 2);
    CHECK(b.stats.wavelength_segments < a.stats.wavelength_segments);
    const double e = rmse(a.image, b.image);
    CHECK(e > 0);
    CHECK(e < 0.01);
}

namespace {

Scene caustic_scene(std::uint64_t photons) {
    Scene s = glass_scene("\"N-BK7\"", R"({"max_depth": 10, "spectral": {"step": 50}, "light_pass": {"photons": )" +
                                           std::to_string(photons) + R"(, "element_size": 0.1, "region": 1.5}})");
    return s;
}

std::vector<Vec3> map_of(const Scene& s, int threads) {
    const SpectralContext ctx = SpectralContext::build(s);
    const auto maps = light_pass(s, ctx, threads);
    return maps->by_object[0]->irradiance;
}

double l1(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double e = 0;
    for (size_t k = 0; k < a.size(); ++k) e += (a[k] - b[k]).cwiseAbs().sum();
    return e / static_cast<double>(a.size());
}

}  // namespace

TEST_CASE("Illumination map converges as the photon count grows", "[spectral][light-pass]") {
    const auto ref = map_of(caustic_scene(160000), 0);
    double total = 0;
    for (const Vec3& v : ref) total += v.sum();
    REQUIRE(total > 0);
    std::vector<double> err;
    for (std::uint64_t n : {1000u, 4000u, 16000u}) err.push_back(l1(map_of(caustic_scene(n), 0), ref));
    INFO("errors " << err[0] << " " << err[1] << " " << err[2]);
    CHECK(err[1] < 0.8 * err[0]);
    CHECK(err[2] < 0.8 * err[1]);
    // Focusing: the sphere's caustic is brighter than the direct irradiance cos θ <= 1.
    double peak = 0;
    for (const Vec3& v : ref) peak = std::fmax(peak, v.maxCoeff());
    CHECK(peak > 1.0);
}

TEST_CASE("Light pass and spectral render are identical for 1 and 2 threads", "[spectral][light-pass]") {
    const Scene s = caustic_scene(5000);
    const auto m1 = map_of(s, 1), m2 = map_of(s, 2);
    REQUIRE(m1.size() == m2.size());
    bool same = true;
    for (size_t k = 0; k < m1.size(); ++k) same = same && m1[k] == m2[k];
    CHECK(same);
    RenderOptions o1, o2;
    o1.threads = 1;
    o2.threads = 2;
    const auto a = render(s, o1), b = render(s, o2);
    CHECK(max_difference(a.image, b.image) == 0.0);
    CHECK(a.stats.deposits == b.stats.deposits);
    CHECK(a.stats.deposits > 0);
}

TEST_CASE("Ohtsuka driver (quick) writes images, tables and studies — the shortcut pays", "[spectral][experiments]") {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() / ("refract-ohtsuka-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    experiments::find("ohtsuka1998").run({d.string(), 2, true});
    for (const char* f : {"diamond.png", "diamond-shortcut.png", "difference-x10.png", "scene.json", "times.csv",
                          "wavelength_step.csv", "element_size.csv", "photon_count.csv", "shortcut_threshold.csv",
                          "shortcut_peaks.csv", "summary.md", "diamond-box.png", "diamond-first.png"})
        CHECK(fs::file_size(d / f) > 0);
    // The map studies: box and bilinear rows per configuration, from the same two runs;
    // bilinear weights average the noise down (to about 2/3 for white noise).
    for (const char* f : {"photon_count.csv", "element_size.csv"}) {
        const experiments::Csv m = experiments::read_csv((d / f).string());
        REQUIRE(m.rows.size() == (std::string(f) == "photon_count.csv" ? 4u : 6u));
        for (size_t k = 0; k + 1 < m.rows.size(); k += 2) {
            CHECK(m.rows[k][3] == "box");
            CHECK(m.rows[k + 1][3] == "bilinear");
            CHECK(std::stod(m.rows[k + 1][6]) < 0.85 * std::stod(m.rows[k][6]));  // noise
            CHECK(std::stod(m.rows[k][6]) > 0);
        }
    }
    const experiments::Csv steps = experiments::read_csv((d / "wavelength_step.csv").string());
    REQUIRE(steps.rows.size() == 5);
    CHECK(std::stod(steps.rows[0][2]) == 0.0);                            // 1 nm against itself
    CHECK(std::stod(steps.rows[4][2]) > std::stod(steps.rows[1][2]));     // 50 nm worse than 5 nm
    const experiments::Csv thr = experiments::read_csv((d / "shortcut_threshold.csv").string());
    REQUIRE(thr.rows.size() == 6);
    CHECK(std::stod(thr.rows[5][3]) > std::stod(thr.rows[0][3]));         // larger threshold, fewer segments
    CHECK(std::stod(thr.rows[5][3]) > 1.0);
    // The light the limits drop: the paper's 8/8 limits drop weight; deeper trees drop less.
    const experiments::Csv lost = experiments::read_csv((d / "lost_light.csv").string());
    REQUIRE(lost.rows.size() == 5);
    CHECK(std::stod(lost.rows[0][4]) > 0);                                  // lost_limits, 8/8
    CHECK(std::stod(lost.rows[2][4]) == 0);                                 // no limits
    CHECK(std::stod(lost.rows[4][6]) < std::stod(lost.rows[2][6]));         // lost_total falls with depth
    const Scene s = load_scene((d / "scene.json").string());
    CHECK(s.settings.spectral.max_reflections.value_or(0) == 8);
    CHECK(s.materials.at(s.objects.at(1).material).dielectric()->dispersion->label.find("iamond") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("Illumination map of a mesh: each triangle is cut into k^2 similar elements of equal area", "[spectral]") {
    TriangleMesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)};
    m.triangles = {Eigen::Vector3i(0, 1, 2)};
    const IlluminationMap map = IlluminationMap::for_mesh(m, 0.3);  // longest edge √2 → k = 5
    REQUIRE(map.elements() == 25);
    CHECK(map.element_area(0) == Approx(0.5 / 25).epsilon(1e-12));
    // The centroid of every sub-triangle of the 5×5 grid lands in a distinct element.
    std::vector<int> seen(25, 0);
    const int k = 5;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i + j < k; ++i)
            for (int up = 0; up < 2; ++up) {
                if (up && i + j == k - 1) continue;
                const double s = (i + (up ? 2.0 : 1.0) / 3.0) / k, t = (j + (up ? 2.0 : 1.0) / 3.0) / k;
                Hit h;
                h.point = Vec3(s, 0, t);
                h.facet = 0;
                const int e = map.element(h);
                REQUIRE(e >= 0);
                REQUIRE(e < 25);
                ++seen[static_cast<size_t>(e)];
            }
    for (int c : seen) CHECK(c == 1);
    // A plane map: the square under the centre, elements of edge 0.1.
    const IlluminationMap p = IlluminationMap::for_plane(Plane{Vec3(0, 1, 0), 0}, Vec3(0.05, 3, 0.05), 1.0, 0.1);
    CHECK(p.elements() == 400);
    Hit h;
    h.point = Vec3(0.06, 0, 0.06);
    const int e0 = p.element(h);
    h.point = Vec3(0.14, 0, 0.14);  // cell edges at 0.05 + 0.1·k: the same element
    CHECK(p.element(h) == e0);
    h.point = Vec3(0.16, 0, 0.06);  // the neighbour along one axis of the grid
    const int e1 = p.element(h);
    CHECK((std::abs(e1 - e0) == 1 || std::abs(e1 - e0) == 20));
    h.point = Vec3(5, 0, 0);
    CHECK(p.element(h) == -1);
}

TEST_CASE("The paper's 8/8 path limits apply only when a scene sets them (POV-Ray has none)", "[spectral]") {
    // A diamond sphere: with the limits unset every path up to max_depth counts; set to 1/1
    // a ray can enter but never leave, and the image changes.
    const std::string deep = R"({"max_depth": 14, "threshold": 0)";
    for (const char* compat : {"physical", "povray"}) {
        INFO(compat);
        Scene free = glass_scene("\"diamond\"", deep + R"(, "compat": ")" + compat + "\"}");
        Scene lim = glass_scene("\"diamond\"", deep + R"(, "compat": ")" + compat +
                                                   R"(", "spectral": {"max_reflections": 1, "max_transmissions": 1}})");
        Scene same = glass_scene("\"diamond\"", deep + R"(, "compat": ")" + compat +
                                                    R"(", "spectral": {"max_reflections": 14, "max_transmissions": 14}})");
        CHECK_FALSE(free.settings.spectral.max_reflections.has_value());
        CHECK_FALSE(free.settings.spectral.max_transmissions.has_value());
        const SpectralContext c = SpectralContext::build(free);
        CHECK(c.max_reflections == SpectralContext::kUnlimited);
        CHECK(c.max_transmissions == SpectralContext::kUnlimited);
        const auto a = render(free), b = render(lim), c14 = render(same);
        CHECK(max_difference(a.image, b.image) > 1e-3);
        // Limits at max_depth never bind before max_depth does.
        CHECK(max_difference(a.image, c14.image) == 0.0);
    }
}
