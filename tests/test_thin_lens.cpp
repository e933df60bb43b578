// The thin-lens camera (core/camera.h): a point on the plane in focus images to a point,
// a point off it to a circle of confusion of diameter aperture·|z − f|/z; the scene
// fields; deterministic renders with the fixed seeds.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/camera.h>
#include <refract/core/render.h>
#include <refract/core/scene.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

#include "tests/render_options.h"

using namespace refract;
using Catch::Matchers::Contains;

namespace {

Camera lens_camera(double aperture, double focus) {
    Camera c;
    c.location = {0, 0, -5};
    c.look_at = {0, 0, 0};
    c.angle_deg = 40;
    c.width = 101;
    c.height = 101;
    c.aperture = aperture;
    c.focus_distance = focus;
    return c;
}

// Where ray r reaches depth z along the view direction d̂ from the camera at `from`.
Vec3 at_depth(const Ray& r, const Vec3& from, const Vec3& d_hat, double z) {
    return r.origin + r.dir * ((z - (r.origin - from).dot(d_hat)) / r.dir.dot(d_hat));
}

}  // namespace

TEST_CASE("thin lens: every lens sample of a pixel meets the pinhole ray on the plane in focus (a point in focus "
          "images to a point)",
          "[camera][thin-lens]") {
    const Camera c = lens_camera(0.4, 5.0);
    const Camera::Basis b = c.basis();
    const Vec3 d_hat = b.D.normalized();
    for (const auto& [x, y] : {std::pair{50.5, 50.5}, std::pair{3.2, 97.9}, std::pair{88.0, 10.25}}) {
        const Vec3 focus = at_depth(c.ray(b, x, y), c.location, d_hat, 5.0);
        for (double u : {0.0, 0.3, 1.0})
            for (double v : {0.0, 0.25, 0.7}) {
                const Ray r = c.ray(b, x, y, u, v);
                CHECK((r.origin - c.location).norm() == Approx(0.2 * std::sqrt(u)).margin(1e-15));
                CHECK((at_depth(r, c.location, d_hat, 5.0) - focus).norm() < 1e-12);
            }
    }
}

TEST_CASE("thin lens: one pixel's rays spread at depth z over a disk of diameter aperture*|z - f|/f, the lens "
          "edge on its rim",
          "[camera][thin-lens]") {
    const Camera c = lens_camera(0.4, 5.0);
    const Camera::Basis b = c.basis();
    const Vec3 d_hat = b.D.normalized();
    for (double z : {2.0, 9.0}) {
        const Vec3 centre = at_depth(c.ray(b, 40.5, 60.5), c.location, d_hat, z);
        for (double v = 0; v < 1; v += 0.125)
            CHECK((at_depth(c.ray(b, 40.5, 60.5, 1.0, v), c.location, d_hat, z) - centre).norm() ==
                  Approx(0.5 * 0.4 * std::fabs(z - 5.0) / 5.0).epsilon(1e-12));
    }
    CHECK(thin_lens_blur_diameter(0.4, 5.0, 10.0) == Approx(0.2));
    CHECK(thin_lens_blur_diameter(0.4, 5.0, 5.0) == 0.0);
}

TEST_CASE("thin lens render: a lamp at depth 10 seen with focus 5 spreads over the circle of confusion, diameter "
          "aperture*|z - f|/z = 0.5 on the plane in focus (8.38 px), at depth 5 it stays a point",
          "[camera][thin-lens]") {
    // 61×61 pixels, 40° across: the plane in focus (depth 5) is 2·5·tan 20° = 3.640 wide,
    // 0.05967 per pixel. The lamp's radius is 0.012·z, 0.06 (1 px) on the plane in focus.
    const auto render_lamp = [](double z) {
        const nlohmann::json j = nlohmann::json::parse(R"({
            "camera": {"location": [0,0,-5], "look_at": [0,0,0], "angle": 40, "width": 61, "height": 61,
                       "aperture": 1.0, "focus_distance": 5},
            "background": [0,0,0],
            "objects": [{"type": "sphere", "center": [0,0,)" + std::to_string(z - 5) + R"(], "radius": )" +
                                                       std::to_string(0.012 * z) + R"(,
                         "material": {"type": "emissive", "color": [1,1,1]}}],
            "render": {"samples": 1000, "jitter": true, "seed": 3}})");
        return render(parse_scene(j, "lamp.json"), refract::testing::threads(2)).image;
    };
    const double px = 2 * 5 * std::tan(20 * M_PI / 180) / 61;  // scene units per pixel on the plane in focus
    const double expected = thin_lens_blur_diameter(1.0, 5, 10) / px;
    CHECK(expected == Approx(8.380).margin(1e-3));
    // The lamp's light is spread evenly over the disk: the disk's area is the total light
    // over the light per pixel inside it, read within 2 px of the centre (the disk's
    // radius 4.19 px less the lamp's 1 px and half a pixel's diagonal).
    const Image far = render_lamp(10);
    double total = 0, inside = 0;
    int n = 0;
    for (int j = 0; j < far.height; ++j)
        for (int i = 0; i < far.width; ++i) {
            total += far.at(i, j).x();
            if ((i - 30) * (i - 30) + (j - 30) * (j - 30) <= 4) {
                inside += far.at(i, j).x();
                ++n;
            }
        }
    const double diameter = 2 * std::sqrt(total / (inside / n) / M_PI);
    // 13 pixels × 1000 samples, each seeing the lamp with probability 1/17.6: about 740
    // hits, 3.7 % on the area, 1.8 % on the diameter; 6 % is over 3 σ.
    CHECK(diameter == Approx(expected).epsilon(0.06));
    // In focus: the light stays within 2 px of the centre.
    const Image near = render_lamp(5);
    double all = 0, centre = 0;
    for (int j = 0; j < near.height; ++j)
        for (int i = 0; i < near.width; ++i) {
            all += near.at(i, j).x();
            if (std::abs(i - 30) <= 2 && std::abs(j - 30) <= 2) centre += near.at(i, j).x();
        }
    CHECK(centre / all > 0.999);
}

TEST_CASE("thin lens render is deterministic with the fixed seed and differs from the pinhole image",
          "[camera][thin-lens]") {
    const auto scene = [](const char* camera) {
        return parse_scene(nlohmann::json::parse(std::string(R"({"camera": )") + camera + R"(,
            "materials": {"m": {"type": "diffuse", "checker": {"color2": [0,0,0], "size": 0.5}}},
            "objects": [{"type": "plane", "normal": [0,1,0], "offset": -1, "material": "m"}],
            "lights": [{"position": [0, 5, -3], "color": [1,1,1]}],
            "render": {"samples": 8, "seed": 7}})"),
                           "s.json");
    };
    const char* lens = R"({"location": [0,0,-4], "width": 24, "height": 16, "aperture": 0.5, "focus_distance": 4})";
    const Image a = render(scene(lens), refract::testing::threads(1)).image;
    const Image b = render(scene(lens), refract::testing::threads(2)).image;
    CHECK(a.rgb == b.rgb);
    const Image pin = render(scene(R"({"location": [0,0,-4], "width": 24, "height": 16})"), refract::testing::threads(1)).image;
    CHECK(a.rgb != pin.rgb);
}

TEST_CASE("thin lens fields: aperture >= 0 on a perspective camera, focus_distance > 0 and only with an aperture",
          "[camera][thin-lens][errors]") {
    const auto parse = [](const char* camera) {
        return parse_scene(nlohmann::json::parse(std::string(R"({"camera": )") + camera +
                                                 R"(, "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1,
                                                 "material": {"type": "diffuse"}}]})"),
                           "c.json");
    };
    const Scene s = parse(R"({"location": [0,0,-3], "look_at": [0,4,0], "aperture": 0.1})");
    CHECK(s.camera.focus_distance == Approx(5.0));  // |look_at − location|
    CHECK_THROWS_WITH(parse(R"({"aperture": -1})"), Contains("c.json: /camera/aperture: must be a lens diameter >= 0"));
    CHECK_THROWS_WITH(parse(R"({"aperture": 0.1, "focus_distance": 0})"), Contains("c.json: /camera/focus_distance: must be > 0"));
    CHECK_THROWS_WITH(parse(R"({"focus_distance": 3})"), Contains("c.json: /camera/focus_distance: applies with an \"aperture\" only"));
    CHECK_THROWS_WITH(parse(R"({"type": "orthographic", "aperture": 0.1})"),
                      Contains("c.json: /camera/aperture: applies to a perspective camera only"));
    CHECK_FALSE(parse(R"({"aperture": 0})").camera.thin_lens());
}
