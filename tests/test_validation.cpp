// Validation layer: POV-Ray export, refusals, image comparison metrics, the suite's
// skip rules, the POV-Ray-compatible tracer rules; [povray] tests run POV-Ray itself.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <refract/core/optics.h>
#include <refract/core/scene_json.h>
#include <refract/core/tracer.h>
#include <refract/geometry/error.h>
#include <refract/validation/compare.h>
#include <refract/validation/files.h>
#include <refract/validation/pov_export.h>
#include <refract/validation/povray_runner.h>
#include <refract/validation/suite.h>

using namespace refract;
using namespace refract::validation;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

Scene scene_from(const std::string& text) { return parse_scene(nlohmann::json::parse(text), "test.json"); }

// A glass sphere on a checker floor: every kind of statement the exporter writes.
const char* kGlassScene = R"({
  "camera": {"location": [0, 1.5, -5], "look_at": [0, 0.6, 0], "angle": 45, "width": 200, "height": 150},
  "background": [0.6, 0.7, 0.9],
  "materials": {
    "floor": {"type": "diffuse", "color": [0.9, 0.9, 0.9], "checker": {"color2": [0.2, 0.3, 0.6], "size": 0.5}},
    "glass": {"type": "dielectric", "ior": 1.5, "filter": [1, 0.5, 0.25]},
    "ks": {"type": "dielectric", "ior": 1.52, "reflectance": "constant", "reflectivity": 0.3},
    "mirror": {"type": "mirror", "color": [0.8, 0.8, 0.8]},
    "lamp": {"type": "emissive", "color": [2, 2, 2]}
  },
  "objects": [
    {"type": "plane", "normal": [0, 1, 0], "offset": 0, "material": "floor"},
    {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass"},
    {"type": "sphere", "center": [3, 1, 0], "radius": 0.5, "material": "ks"},
    {"type": "sphere", "center": [-3, 1, 0], "radius": 0.5, "material": "mirror"},
    {"type": "sphere", "center": [-4, 8, -6], "radius": 0.3, "material": "lamp"}
  ],
  "lights": [{"position": [-4, 8, -6], "color": [0.9, 0.9, 0.9]}],
  "render": {"max_depth": 8, "threshold": 0.05}
})";

std::string with(std::string base, const std::string& from, const std::string& to) {
    const auto pos = base.find(from);
    REQUIRE(pos != std::string::npos);
    return base.replace(pos, from.size(), to);
}

std::string refusal(const std::string& scene_text) {
    try {
        export_pov(scene_from(scene_text));
    } catch (const InputError& e) {
        return e.what();
    }
    return "(exported)";
}

Image filled(int w, int h, const Vec3& c) {
    Image img(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) img.set(i, j, c);
    return img;
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("refract-test-validation-" + std::to_string(::getpid()) + "-" +
                                            std::to_string(reinterpret_cast<std::uintptr_t>(this)));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

fs::path source_scenes() { return fs::path(REFRACT_SOURCE_DIR) / "scenes" / "validation"; }

}  // namespace

TEST_CASE("POV-Ray export: header, camera, lights, materials of a glass sphere on a checker floor", "[validation]") {
    const std::string pov = export_pov(scene_from(kGlassScene));
    CHECK(pov.rfind("#version 3.7;\n", 0) == 0);  // must be the first statement
    CHECK_THAT(pov, Contains("assumed_gamma 1.0"));
    CHECK_THAT(pov, Contains("max_trace_level 9"));  // max_depth + 1
    CHECK_THAT(pov, Contains("adc_bailout 0.05"));
    CHECK_THAT(pov, Contains("right x*200/150"));
    CHECK_THAT(pov, Contains("angle 45"));
    CHECK_THAT(pov, Contains("look_at <0, 0.6, 0>"));
    CHECK_THAT(pov, Contains("background { rgb <0.6, 0.7, 0.9> }"));
    CHECK_THAT(pov, Contains("light_source { <-4, 8, -6> color rgb <0.9, 0.9, 0.9> }"));
    CHECK_THAT(pov, Contains("plane { <0, 1, 0>, 0"));
    CHECK_THAT(pov, Contains("checker rgb <0.9, 0.9, 0.9> rgb <0.2, 0.3, 0.6> scale 0.5"));
    CHECK_THAT(pov, Contains("finish { ambient 0 emission 0 diffuse 1 }"));
    CHECK_THAT(pov, Contains("pigment { rgbf <1, 0.5, 0.25, 1> }"));
    CHECK_THAT(pov, Contains("reflection { 0, 1 fresnel on } conserve_energy"));
    CHECK_THAT(pov, Contains("interior { ior 1.5 }"));
    CHECK_THAT(pov, Contains("reflection { 0.3 } conserve_energy"));  // constant ks, kt = 1 - ks
    CHECK_THAT(pov, Contains("reflection { rgb <0.8, 0.8, 0.8> }"));
    CHECK_THAT(pov, Contains("emission 1 diffuse 0 } } no_shadow"));
}

TEST_CASE("POV-Ray export: orthographic camera, mesh2, intersection of planes, hollow sphere, RTIOW sky", "[validation]") {
    const std::string pov = export_pov(scene_from(R"({
      "camera": {"type": "orthographic", "location": [0, 0, -5], "look_at": [0, 0, 0], "ortho_height": 3,
                 "width": 40, "height": 20},
      "background": {"type": "gradient", "bottom": [1, 1, 1], "top": [0.5, 0.7, 1.0]},
      "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
      "objects": [
        {"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "glass"},
        {"type": "sphere", "center": [0, 0, 0], "radius": -0.45, "material": "glass"},
        {"type": "mesh", "vertices": [[2,0,0],[3,0,0],[2,1,0],[2,0,1]],
         "triangles": [[0,2,1],[0,1,3],[0,3,2],[1,2,3]], "material": "glass"},
        {"type": "polyhedron", "planes": [[1,0,0,-2],[-1,0,0,3],[0,1,0,1],[0,-1,0,1],[0,0,1,1],[0,0,-1,1]],
         "material": "glass"}
      ]})"));
    CHECK_THAT(pov, Contains("orthographic"));
    CHECK_THAT(pov, Contains("up y*3"));
    CHECK_THAT(pov, Contains("right x*6"));
    CHECK_THAT(pov, Contains("sky_sphere"));
    CHECK_THAT(pov, Contains("gradient y color_map { [0 rgb <1, 1, 1>] [1 rgb <0.5, 0.7, 1>] } scale 2 translate -y"));
    CHECK_THAT(pov, Contains("intersection {\n  sphere { <0, 0, 0>, 0.5 }"));  // the hollow sphere: one interior
    CHECK_THAT(pov, Contains("inside_vector"));  // a transparent mesh is a solid to POV-Ray's inside test
    CHECK_THAT(pov, Contains("sphere { <0, 0, 0>, 0.45 inverse }"));
    CHECK_THAT(pov, Contains("mesh2 {"));
    CHECK_THAT(pov, Contains("vertex_vectors { 4"));
    CHECK_THAT(pov, Contains("face_indices { 4"));
    CHECK_THAT(pov, Contains("intersection {"));
    CHECK_THAT(pov, Contains("plane { <-1, 0, 0>, 3 }"));
}

TEST_CASE("POV-Ray export refuses what POV-Ray cannot express", "[validation]") {
    const std::string g = kGlassScene;
    CHECK_THAT(refusal(with(g, R"("ior": 1.5, "filter")", R"("ior": 1.5, "reflectance": "schlick", "filter")")),
               Contains("schlick"));
    CHECK_THAT(refusal(with(g, R"("ior": 1.5, "filter")", R"("ior": 1.5, "reflectance": "fresnel-s", "filter")")),
               Contains("polarised"));
    {
        Scene s = scene_from(g);
        s.materials[1].as<material::Dielectric>()->dispersion = spectrum::catalogue("BK7");
        CHECK_THROWS_WITH(export_pov(s), Contains("dispersion"));
    }
    CHECK_THAT(refusal(with(g, R"("ior": 1.5, "filter")", R"("ior": 1, "filter")")), Contains("ior 1"));
    CHECK_THAT(refusal(with(g, R"("type": "mirror", "color")", R"("type": "metal", "fuzz": 0.3, "color")")),
               Contains("fuzz"));
    CHECK_THAT(refusal(with(g, R"("type": "mirror", "color")", R"("type": "lambertian", "color")")),
               Contains("lambertian"));
    CHECK_THAT(refusal(with(g, R"("max_depth": 8)", R"("max_depth": 8, "integrator": "stochastic")")),
               Contains("stochastic"));
    CHECK_THAT(refusal(with(g, R"("max_depth": 8)", R"("max_depth": 8, "samples": 4, "jitter": true)")),
               Contains("jitter"));
    CHECK_THAT(refusal(with(g, R"("max_depth": 8)", R"("max_depth": 300)")), Contains("max_trace_level 301"));
    // The 1998 paper's separate limits, only when a scene sets them below max_depth.
    {
        Scene s = scene_from(g);
        s.settings.spectral.enabled = true;
        CHECK_NOTHROW(export_pov(s));
        s.settings.spectral.max_reflections = s.settings.max_depth;
        CHECK_NOTHROW(export_pov(s));
        s.settings.spectral.max_transmissions = 3;
        CHECK_THROWS_WITH(export_pov(s), Contains("/render/spectral/max_transmissions: max_transmissions 3 below max_depth"));
    }
    // Overlapping transparent spheres, a camera inside glass, a lone negative sphere.
    CHECK_THAT(refusal(with(g, R"("center": [3, 1, 0], "radius": 0.5)", R"("center": [0.8, 1, 0], "radius": 0.5)")),
               Contains("overlap"));
    // A camera inside glass is expressible (POV-Ray starts the ray inside it); inside an
    // opaque object the export turns that object inside out (its Fresnel rule at glass
    // exits); an orthographic image plane across an opaque surface is refused.
    CHECK_NOTHROW(export_pov(scene_from(with(g, R"("location": [0, 1.5, -5])", R"("location": [0.3, 1.2, -0.2])"))));
    CHECK_THAT(export_pov(scene_from(with(g, R"("center": [-3, 1, 0], "radius": 0.5)", R"("center": [0, 1, -3], "radius": 4)"))),
               Contains("sphere { <0, 1, -3>, 4 inverse texture"));
    CHECK_THAT(export_pov(scene_from(with(g, R"("normal": [0, 1, 0], "offset": 0)", R"("normal": [0, -1, 0], "offset": 0)"))),
               Contains("plane { <0, -1, 0>, 0 inverse texture"));
    CHECK_THAT(refusal(with(with(with(g, R"("camera": {)", R"("camera": {"type": "orthographic", "ortho_height": 6, )"),
                                 R"("angle": 45, )", ""),
                            R"("location": [0, 1.5, -5])", R"("location": [0, 0.5, -5])")),
               Contains("orthographic image plane crosses"));
    // An index that is 1 in single precision, a mesh wound inside out.
    CHECK_THAT(refusal(with(g, R"("ior": 1.5, "filter")", R"("ior": 1.00000001, "filter")")), Contains("single precision"));
    CHECK_THAT(refusal(with(g, R"("center": [0, 1, 0], "radius": 1,)", R"("center": [0, 1, 0], "radius": -1,)")),
               Contains("negative-radius"));
    // A single glass triangle is not a closed solid.
    CHECK_THAT(refusal(with(g, R"({"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass"})",
                            R"({"type": "mesh", "vertices": [[0,0,1],[1,0,1],[0,1,1]], "triangles": [[0,1,2]],
                                "material": "glass"})")),
               Contains("closed"));
    CHECK_THAT(refusal(with(g, R"({"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass"})",
                            R"({"type": "mesh", "vertices": [[2,0,0],[3,0,0],[2,1,0],[2,0,1]],
                                "triangles": [[0,1,2],[0,3,1],[0,2,3],[1,3,2]], "material": "glass"})")),
               Contains("counter-clockwise"));
    // A refusal is one line naming the file.
    const std::string msg = refusal(with(g, R"("type": "mirror", "color")", R"("type": "lambertian", "color")"));
    CHECK(msg.find('\n') == std::string::npos);
    CHECK(msg.rfind("test.json: ", 0) == 0);
}

TEST_CASE("POV-Ray export numbers read back as the same doubles", "[validation]") {
    for (double v : {0.1, 1.0 / 3.0, -2.5, 1e-20, 6.02214076e23, 1.333, 0.00392156862745098})
        CHECK(std::stod(pov_number(v)) == v);
    CHECK(pov_number(-0.0) == "0");
    CHECK_THROWS_AS(pov_number(NAN), InputError);
}

TEST_CASE("Image comparison: RMSE, max error, fraction over tolerance and PSNR of known differences", "[validation]") {
    const Image a = filled(10, 10, Vec3(0.5, 0.5, 0.5));
    Image b = a;
    b.set(3, 7, Vec3(0.6, 0.5, 0.5));  // one channel of one pixel off by 0.1
    const ImageDifference d = compare_images(a, b, 1e-3);
    CHECK(d.rmse == Approx(std::sqrt(0.01 / 300.0)).epsilon(1e-5));
    CHECK(d.max_error == Approx(0.1).epsilon(1e-5));
    CHECK(d.max_x == 3);
    CHECK(d.max_y == 7);
    CHECK(d.pixels == 100);
    CHECK(d.pixels_over == 1);  // counted per pixel, not per channel
    CHECK(d.fraction_over == Approx(0.01));
    CHECK(d.psnr == Approx(20.0 * std::log10(1.0 / std::sqrt(0.01 / 300.0))).epsilon(1e-5));

    const ImageDifference u = compare_images(a, filled(10, 10, Vec3(0.502, 0.502, 0.502)), 1e-3);
    CHECK(u.rmse == Approx(0.002).epsilon(1e-4));
    CHECK(u.fraction_over == 1.0);
    CHECK(compare_images(a, a, 1e-3).rmse == 0.0);
    CHECK(std::isinf(compare_images(a, a, 1e-3).psnr));
    CHECK_THROWS_AS(compare_images(a, filled(9, 10, Vec3(0, 0, 0)), 1e-3), InputError);

    const Image c = clamp01(filled(2, 2, Vec3(-0.5, 0.25, 3.0)));
    CHECK(c.at(1, 1) == Vec3(0, 0.25, 1));
}

TEST_CASE("Profile comparison along a line of pixels against an analytic curve", "[validation]") {
    const auto px = line_pixels(0, 5, 9, 5);
    REQUIRE(px.size() == 10);
    CHECK(px.front() == std::make_pair(0, 5));
    CHECK(px.back() == std::make_pair(9, 5));
    CHECK(line_pixels(2, 2, 2, 2).size() == 1);
    Image ramp(10, 10);
    for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 10; ++i) ramp.set(i, j, Vec3::Constant(0.1 * i));
    const auto exact = compare_profile(ramp, px, 0, [](int i, int) -> std::optional<double> { return 0.1 * i; });
    CHECK(exact.points.size() == 10);
    CHECK(exact.max_error < 1e-15);
    // An analytic curve defined on half the line; off by 0.01 there.
    const auto half = compare_profile(ramp, px, 1, [](int i, int) -> std::optional<double> {
        if (i < 5) return std::nullopt;
        return 0.1 * i + 0.01;
    });
    CHECK(half.points.size() == 5);
    CHECK(half.max_error == Approx(0.01));
    CHECK(half.rmse == Approx(0.01));
    CHECK_THROWS_AS(compare_profile(ramp, {{10, 0}}, 0, [](int, int) { return std::optional<double>(0); }), InputError);
}

TEST_CASE("Difference heat map is written as a PNG of the image's size", "[validation]") {
    TempDir dir;
    const std::string path = (dir.path / "diff.png").string();
    Image b = filled(12, 8, Vec3(0.5, 0.5, 0.5));
    b.set(1, 1, Vec3(0.5, 0.51, 0.5));
    write_heatmap(path, filled(12, 8, Vec3(0.5, 0.5, 0.5)), b);
    const Image h = read_image(path);
    CHECK(h.width == 12);
    CHECK(h.height == 8);
    CHECK(h.at(1, 1).norm() > h.at(5, 5).norm());  // the differing pixel is hotter
    CHECK(h.at(5, 5).norm() < 0.05);                // identical pixels are black
}

TEST_CASE("POV-Ray compat mode: refraction adc weight is parent x max(filter x (1 - R))", "[validation]") {
    // POV-Ray (trace.cpp ComputeLightedTexture): with conserve_energy the filter colour
    // is filter·(1 − R); the refracted ray's weight is max3 of it.
    Scene s = scene_from(kGlassScene);
    s.settings.compat = Compat::PovRay;
    const SceneTracer tracer(s);
    const Material& glass = s.materials[1];
    const Ray ray{Vec3(0, 1, -5), Vec3(0, 0, 1)};
    SurfaceHit h{Hit{4, Vec3(0, 1, -1), Vec3(0, 0, -1), -1}, &s.objects[1], &glass, Vec3(0, 0, -1), true};
    RenderStats st;
    const Interaction n = tracer.interact(h, ray, st);
    const double R = optics::fresnel_reflectance(1.0, 1.5);  // 0.04
    REQUIRE(n.branches == 2);
    CHECK(n.branch[0].bailout_factor == Approx(R));
    CHECK(n.branch[1].bailout_factor == Approx((1 - R) * 1.0));  // max(filter) = 1
    CHECK(n.branch[1].factor.y() == Approx((1 - R) * 0.5));
}

TEST_CASE("POV-Ray compat mode: total internal reflection with a constant ks carries all the light", "[validation]") {
    // Inside glass of n = 1.52 at 60° incidence (beyond the 41.1° critical angle): the
    // refracted ray turns into a mirror ray of factor 1 with adc weight (1 − ks)·max(filter).
    Scene s = scene_from(kGlassScene);
    s.settings.compat = Compat::PovRay;
    const SceneTracer tracer(s);
    const Material& ks = s.materials[2];
    const double a = 60.0 * M_PI / 180.0;
    const Ray ray{Vec3(0, 0, 0), Vec3(std::sin(a), 0, std::cos(a))};
    SurfaceHit h{Hit{1, Vec3(std::sin(a), 0, std::cos(a)), Vec3(0, 0, 1), -1}, &s.objects[2], &ks, Vec3(0, 0, -1), false};
    RenderStats st;
    const Interaction n = tracer.interact(h, ray, st);
    REQUIRE(n.branches == 1);
    CHECK(n.branch[0].factor == Vec3(1, 1, 1));
    CHECK(n.branch[0].bailout_factor == Approx(0.7));
    CHECK(n.branch[0].ray.dir.z() == Approx(-std::cos(a)));
}

TEST_CASE("Reflected rays stay unit length through 50 internal reflections in a sphere", "[validation]") {
    // Regression: an unnormalised reflection direction drifts tenfold per bounce (the
    // sphere intersection assumes |dir| = 1), breaking paths after ~10 bounces.
    Scene s = scene_from(kGlassScene);
    s.objects.erase(s.objects.begin());  // keep the glass sphere first, no floor
    s.objects.resize(1);
    const SceneTracer tracer(s);
    RenderStats st;
    Ray ray{Vec3(0.3, 1.2, 0.1), Vec3(0.3, 0.2, 1).normalized()};
    std::optional<double> first_cos;
    for (int k = 0; k < 50; ++k) {
        const auto h = tracer.intersect(ray, st);
        REQUIRE(h);
        const double c = -ray.dir.dot(h->normal);
        if (!first_cos) first_cos = c;
        CHECK(c == Approx(*first_cos).margin(1e-12));  // a sphere keeps the chord angle
        ray = tracer.interact(*h, ray, st).branch[0].ray;
        CHECK(std::abs(ray.dir.norm() - 1.0) < 1e-15);
    }
}

TEST_CASE("Validation cases are the NAME.json files beside NAME.tol.json", "[validation]") {
    TempDir dir;
    write_text_file((dir.path / "b.json").string(), "{}");
    write_text_file((dir.path / "a.json").string(), "{}");
    write_text_file((dir.path / "a.tol.json").string(), "{}");
    write_text_file((dir.path / "notes.txt").string(), "");
    CHECK(list_cases(dir.path.string()) == std::vector<std::string>{"a", "b"});
    CHECK_THROWS_AS(list_cases((dir.path / "missing").string()), InputError);
}

TEST_CASE("A case POV-Ray cannot run or express is skipped with its reason, never passed", "[validation]") {
    TempDir dir;
    const fs::path scenes = dir.path / "scenes";
    fs::create_directories(scenes);
    const std::string small = with(with(kGlassScene, R"("width": 200, "height": 150)", R"("width": 8, "height": 6)"),
                                   R"("max_depth": 8)", R"("max_depth": 2)");
    write_text_file((scenes / "fine.json").string(), small);
    write_text_file((scenes / "fine.tol.json").string(), R"({"description": "x"})");
    write_text_file((scenes / "schlick.json").string(),
                    with(small, R"("ior": 1.5, "filter")", R"("ior": 1.5, "reflectance": "schlick", "filter")"));
    write_text_file((scenes / "schlick.tol.json").string(), "{}");
    write_text_file((scenes / "notol.json").string(), small);
    write_text_file((scenes / "badtol.json").string(), small);
    write_text_file((scenes / "badtol.tol.json").string(), R"({"povray": {"rsme": 1}})");

    SuiteOptions opt;
    opt.scenes_dir = scenes.string();
    opt.out_dir = (dir.path / "out").string();
    opt.threads = 1;
    opt.povray.executable = "refract-no-such-povray";
    const SuiteResult r = run_suite(opt);
    REQUIRE(r.cases.size() == 4);
    for (const CaseResult& c : r.cases) CHECK(c.status == Status::Skip);
    CHECK(r.passed == 0);
    CHECK(r.skipped == 4);
    const auto reason = [&](const std::string& name) {
        for (const CaseResult& c : r.cases)
            if (c.name == name) return c.skip_reason;
        return std::string("(no case)");
    };
    CHECK_THAT(reason("fine"), Contains("povray not found"));
    CHECK_THAT(reason("schlick"), Contains("not expressible"));
    CHECK_THAT(reason("notol"), Contains("cannot open tolerance file"));
    CHECK_THAT(reason("badtol"), Contains("rsme"));
    CHECK(fs::exists(dir.path / "out" / "report.md"));
    CHECK(fs::exists(dir.path / "out" / "report.html"));
    CHECK_THAT(format_table(r), Contains("0 passed, 0 failed, 4 skipped"));
    opt.cases = {"nonexistent"};
    CHECK_THROWS_AS(run_suite(opt), InputError);
}

TEST_CASE("Physical mode renders the Fresnel sphere as R(theta) to 1e-6 (Yasuda eq. 7)", "[validation]") {
    // The suite's physics check runs without POV-Ray: the case is then skipped (not
    // validated against POV-Ray) but its analytic metric is measured and passes.
    TempDir dir;
    SuiteOptions opt;
    opt.scenes_dir = source_scenes().string();
    opt.out_dir = dir.path.string();
    opt.threads = 2;
    opt.povray.executable = "refract-no-such-povray";
    for (const std::string name : {"fresnel-sphere", "fresnel-sphere-n0.8"}) {
        const CaseResult c = run_case(name, opt);
        CHECK(c.status == Status::Skip);
        bool seen = false;
        for (const Metric& m : c.metrics)
            if (m.name == "physical vs analytic: max abs diff") {
                seen = true;
                CHECK(m.status == Status::Pass);
                CHECK(m.value <= 1e-6);
            }
        CHECK(seen);
    }
}

TEST_CASE("POV-Ray runner: a missing executable is reported, not crashed on", "[validation]") {
    PovrayOptions opt;
    opt.executable = "/nonexistent/povray";
    CHECK(find_povray(opt.executable).empty());
    CHECK_THROWS_AS(render_povray("#version 3.7;", 4, 4, opt), PovrayError);
}

// ---- tests that run POV-Ray ---------------------------------------------------------------

TEST_CASE("POV-Ray runner: renders a white background, reports parse errors and time-outs", "[povray]") {
    REQUIRE_FALSE(find_povray().empty());
    const PovrayRender r = render_povray("#version 3.7;\nbackground { rgb <1, 0.5, 0.25> }\n", 16, 8);
    REQUIRE(r.image.width == 16);
    CHECK(r.image.at(5, 5).x() == Approx(1.0).margin(1e-5));
    CHECK(r.image.at(5, 5).y() == Approx(0.5).margin(1e-5));  // linear output: no gamma
    CHECK(r.image.at(5, 5).z() == Approx(0.25).margin(1e-5));
    CHECK_THAT(r.version, Contains("3.7"));
    try {
        render_povray("#version 3.7;\nsphere { <0,0,0> 1 pigment { rgb 1 }\n", 8, 8);
        FAIL("a broken scene rendered");
    } catch (const PovrayError& e) {
        CHECK_THAT(std::string(e.what()), Contains("povray failed"));
        CHECK_FALSE(e.log().empty());
    }
    PovrayOptions quick;
    quick.timeout_seconds = 0.01;
    CHECK_THROWS_WITH(render_povray("#version 3.7;\nbackground { rgb 1 }\n", 8, 8, quick), Contains("timed out"));
}

TEST_CASE("refract (compat povray) and POV-Ray 3.7 agree on the validation scenes", "[povray]") {
    TempDir dir;
    SuiteOptions opt;
    opt.scenes_dir = source_scenes().string();
    opt.out_dir = dir.path.string();
    opt.threads = 2;
    // Every case of scenes/validation: nothing skipped, nothing failed.
    const SuiteResult r = run_suite(opt);
    INFO(format_table(r));
    CHECK(r.cases.size() == list_cases(opt.scenes_dir).size());
    CHECK(r.cases.size() >= 26);
    CHECK(r.skipped == 0);
    CHECK(r.failed == 0);
    CHECK(r.passed == static_cast<int>(r.cases.size()));
    // About the 16-bit output step, but for the cases compared under their own tolerance
    // (docs/validation.md): focal blur, whose lens samples differ from POV-Ray's (compared as
    // 8×8 means), and the area light, whose shadow POV-Ray samples adaptively.
    const std::set<std::string> own_tolerance{"focal-blur", "area-light"};
    for (const CaseResult& c : r.cases) {
        if (own_tolerance.count(c.name)) continue;
        for (const Metric& m : c.metrics)
            if (m.name == "compat vs povray: rmse") CHECK(m.value < 2e-5);
    }
}

TEST_CASE("validate stays inside its output directory: a case named '..' or with a slash is refused",
          "[validation][limits]") {
    const fs::path dir = fs::temp_directory_path() / ("refract-case-names-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    { std::ofstream{dir / "good-case_1.5.json"} << "{}"; }
    CHECK(list_cases(dir.string()) == std::vector<std::string>{"good-case_1.5"});
    { std::ofstream{dir / "...json"} << "{}"; }  // the case ".."
    CHECK_THROWS_WITH(list_cases(dir.string()), Contains("...json") && Contains("case names"));
    for (const std::string bad : {"..", ".", "../x", "a/b", "", ".hidden", "tab\there"})
        CHECK_THROWS_WITH(check_case_name(bad, "validate"), Contains("validate: case names"));
    CHECK_NOTHROW(check_case_name("fig8-n1.333", "validate"));
    fs::remove_all(dir);
}

TEST_CASE("A tolerance file's profile indices outside an image are refused, not overflowed", "[validation][limits]") {
    const fs::path dir = fs::temp_directory_path() / ("refract-tol-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "scenes");
    { std::ofstream{dir / "scenes" / "x.json"} << R"({"camera": {"width": 4, "height": 3}, "objects": []})"; }
    { std::ofstream{dir / "scenes" / "x.tol.json"} << R"({"analytic": {"kind": "fresnel-sphere",
          "profile": {"from": [0, 9223372036854775807], "to": [-2147483648, 0]}}})"; }
    SuiteOptions opt;
    opt.scenes_dir = (dir / "scenes").string();
    opt.out_dir = (dir / "out").string();
    opt.povray.executable = "refract-no-such-povray";
    const CaseResult c = run_case("x", opt);
    CHECK(c.status == Status::Skip);
    CHECK_THAT(c.skip_reason, Contains("x.tol.json") && Contains("pixel indices must be in [0, 32767]"));
    fs::remove_all(dir);
}
