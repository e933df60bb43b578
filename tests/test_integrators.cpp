// Whole-render physics: white furnace, Fresnel sphere, the 1984 tree algorithm against
// Whitted's stored tree, determinism.
#include <catch2/catch.hpp>

#include <cmath>

#include <refract/core/optics.h>
#include <refract/core/random.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>

#include <nlohmann/json.hpp>
#include <refract/validation/analytic.h>

using namespace refract;

namespace {

Scene sphere_scene(double n, Vec3 filter, Vec3 background, int size) {
    Scene s;
    s.camera.location = Vec3(0, 0, -4);
    s.camera.look_at = Vec3(0, 0, 0);
    s.camera.angle_deg = 32;
    s.camera.width = s.camera.height = size;
    material::Dielectric glass;
    glass.ior = n;
    glass.filter = filter;
    s.materials.push_back({"glass", glass});
    s.objects.push_back({"sphere", Sphere{Vec3(0, 0, 0), 1.0}, 0});
    s.background.color = background;
    return s;
}

Scene tree_scene() {
    // Two glass spheres, a mirror and a diffuse checker floor with a point light.
    Scene s = sphere_scene(1.5, Vec3(1, 1, 1), Vec3(0.3, 0.5, 0.9), 48);
    s.camera.location = Vec3(0, 1.5, -6);
    s.camera.angle_deg = 50;
    Material water = s.materials[0];
    water.as<material::Dielectric>()->ior = 1.333;
    s.materials.push_back(water);
    material::Diffuse floor;
    floor.pigment = Pigment{Vec3(0.9, 0.8, 0.7), Checker{Vec3(0.1, 0.2, 0.1), 0.7}};
    floor.ambient = 0.1;
    s.materials.push_back({"floor", floor});
    s.materials.push_back({"mirror", material::Mirror{Vec3(0.8, 0.8, 0.8)}});
    s.objects.push_back({"water", Sphere{Vec3(1.2, -0.3, 0.8), 0.7}, 1});
    s.objects.push_back({"floor", Plane{Vec3(0, 1, 0), -1.0}, 2});
    s.objects.push_back({"mirror", Sphere{Vec3(-1.8, -0.2, 1.5), 0.8}, 3});
    Light light;
    light.position = Vec3(4, 8, -5);
    s.lights.push_back(light);
    s.settings.max_depth = 8;
    s.settings.threshold = 0;
    return s;
}

}  // namespace

TEST_CASE("White furnace: a lossless glass sphere in a white background renders 1 everywhere",
          "[furnace][fresnel-tree]") {
    for (double n : {1.5, 2.417, 0.5}) {
        Scene s = sphere_scene(n, Vec3(1, 1, 1), Vec3(1, 1, 1), 48);
        s.settings.threshold = 0;
        s.settings.max_depth = 2000;
        const auto r = render(s);
        double worst = 0;
        for (double v : r.image.rgb) worst = std::max(worst, std::abs(v - 1.0));
        INFO("n = " << n);
        CHECK(worst < 1e-6);
    }
}

TEST_CASE("A black Fresnel-reflecting sphere on white renders exactly R(theta) per pixel",
          "[fresnel][yasuda1984]") {
    // Filter 0: the refracted light is absorbed, so a pixel is R·background = R(θ).
    Scene s = sphere_scene(1.5, Vec3(0, 0, 0), Vec3(1, 1, 1), 64);
    s.settings.threshold = 0;
    const auto r = render(s);
    int on_sphere = 0;
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) {
            const auto R = analytic::fresnel_sphere_pixel(s.camera, std::get<Sphere>(s.objects[0].shape), 1.5, i, j);
            const double expect = R ? *R : 1.0;
            on_sphere += R.has_value();
            REQUIRE(std::abs(r.image.at(i, j).x() - expect) < 1e-12);
        }
    CHECK(on_sphere > 1000);
}

TEST_CASE("fresnel-tree with threshold 0 equals Whitted's stored tree with Fresnel coefficients",
          "[yasuda1984][whitted][fresnel-tree]") {
    Scene a = tree_scene();
    a.settings.integrator = IntegratorKind::FresnelTree;
    a.settings.requested_polarisation = PolarisationModel::Natural;  // Whitted's model
    Scene b = a;
    b.settings.integrator = IntegratorKind::Whitted;
    const auto ra = render(a), rb = render(b);
    double worst = 0;
    for (size_t k = 0; k < ra.image.rgb.size(); ++k) worst = std::max(worst, std::abs(ra.image.rgb[k] - rb.image.rgb[k]));
    CHECK(worst < 1e-12);
    // Same tree: the same segments traced, the same nodes.
    CHECK(ra.stats.segments == rb.stats.segments);
    CHECK(ra.stats.tree_nodes == rb.stats.tree_nodes);
    // The list never holds more than the stored tree.
    CHECK(ra.stats.peak_list < rb.stats.peak_list);
}

TEST_CASE("The cumulative-attenuation threshold prunes branches and bounds the error",
          "[yasuda1984][fresnel-tree]") {
    Scene full = tree_scene();
    Scene pruned = full;
    pruned.settings.threshold = 0.01;
    const auto rf = render(full), rp = render(pruned);
    CHECK(rp.stats.pruned > 0);
    CHECK(rp.stats.segments < rf.stats.segments);
    double worst = 0;
    for (size_t k = 0; k < rf.image.rgb.size(); ++k) worst = std::max(worst, std::abs(rf.image.rgb[k] - rp.image.rgb[k]));
    CHECK(worst > 0);
    CHECK(worst < 0.05);
}

TEST_CASE("Images are identical for 1 and 2 threads", "[determinism]") {
    for (auto integ : {IntegratorKind::FresnelTree, IntegratorKind::Stochastic}) {
        Scene s = tree_scene();
        s.settings.integrator = integ;
        s.settings.samples = 4;
        s.settings.jitter = true;
        s.settings.seed = 7;
        RenderOptions one, two;
        one.threads = 1;
        two.threads = 2;
        const auto r1 = render(s, one), r2 = render(s, two);
        CHECK(r1.image.rgb == r2.image.rgb);
        CHECK(r1.stats.segments == r2.stats.segments);
    }
}

TEST_CASE("Sampling: Marsaglia's unit vectors are uniform on the sphere, cube rejection uniform in the ball",
          "[rtiow][stochastic][sampling]") {
    Rng rng(5, 11);
    const int n = 200000;
    Vec3 mean = Vec3::Zero(), second = Vec3::Zero();
    int cap = 0;
    double worst = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 v = rng.unit_vector();
        worst = std::max(worst, std::abs(v.norm() - 1.0));
        mean += v;
        second += v.cwiseProduct(v);
        cap += v.z() > 0.5 ? 1 : 0;
    }
    mean /= n;
    second /= n;
    CHECK(worst < 1e-15);
    // E[x] = 0, E[x^2] = 1/3 per axis; Archimedes: the cap z > 1/2 holds a quarter of the
    // sphere. Standard errors: 1.3e-3 (mean), 6.7e-4 (second moment), 9.7e-4 (cap).
    CHECK(mean.cwiseAbs().maxCoeff() < 0.008);
    CHECK((second - Vec3::Constant(1.0 / 3.0)).cwiseAbs().maxCoeff() < 0.004);
    CHECK(std::abs(cap / double(n) - 0.25) < 0.006);
    // In the ball: |p| < 1, E[|p|^2] = 3/5, and P(|p| < 1/2) = 1/8.
    double r2 = 0, largest = 0;
    int inner = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 p = rng.in_unit_sphere();
        largest = std::max(largest, p.norm());
        r2 += p.squaredNorm();
        inner += p.norm() < 0.5 ? 1 : 0;
    }
    CHECK(largest < 1.0);
    CHECK(std::abs(r2 / n - 0.6) < 0.004);  // standard error 5.6e-4
    CHECK(std::abs(inner / double(n) - 0.125) < 0.005);  // standard error 7.4e-4
}

TEST_CASE("Stochastic reflect/refract choice converges to the tree's value", "[rtiow][stochastic]") {
    Scene tree = sphere_scene(1.5, Vec3(1, 1, 1), Vec3(0.2, 0.4, 0.9), 8);
    tree.background.kind = Background::Kind::Gradient;
    tree.settings.threshold = 0;
    tree.settings.max_depth = 50;
    Scene mc = tree;
    mc.settings.integrator = IntegratorKind::Stochastic;
    mc.settings.samples = 20000;
    const Vec3 expect = render_pixel(tree, 3, 4);
    const Vec3 got = render_pixel(mc, 3, 4);
    // The pixel's variance is below 0.25 per channel; 20000 samples: 5 sigma < 0.018.
    CHECK((got - expect).cwiseAbs().maxCoeff() < 0.018);
}

TEST_CASE("The tree integrators bound their work whatever the threshold: an exploding tree is refused, naming the "
          "settings", "[integrators][limits]") {
    // A glass sphere inside a mirror room: every branch stays inside and splits again.
    const std::string room = R"({"camera": {"location": [0,0,-4], "look_at": [0,0,0], "width": 1, "height": 1},
        "materials": {"g": {"type": "dielectric", "ior": 1.5}, "m": {"type": "mirror", "color": [0.9,0.9,0.9]}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "g"},
                    {"type": "sphere", "center": [0.3,0.2,0], "radius": 9, "material": "m"}],
        "render": RENDER})";
    const auto scene = [&](const std::string& render) {
        std::string t = room;
        t.replace(t.find("RENDER"), 6, render);
        return parse_scene(nlohmann::json::parse(t), "room.json");
    };
    CHECK_THROWS_WITH(render(scene(R"({"integrator": "whitted", "max_depth": 60})")),
                      Catch::Contains("room.json: /render") && Catch::Contains("max_depth 60"));
    CHECK_THROWS_WITH(render(scene(R"({"integrator": "fresnel-tree", "threshold": 0, "max_depth": 10000})")),
                      Catch::Contains("raise /render/threshold"));
    // With the default threshold the same room renders.
    CHECK_NOTHROW(render(scene(R"({"integrator": "fresnel-tree", "max_depth": 10000})")));
}
