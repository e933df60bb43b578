// Knife-edge pixels (validation/knife_edge.h; docs/validation.md, "Random scenes"): the
// camera shift, the predicate on a cube's edges, the rule with such pixels set aside, and
// the two scenes of the 1 000-scene batch (seed 20270000) that meet the rule only so.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/validation/knife_edge.h>
#include <refract/validation/random_suite.h>

using namespace refract;
using namespace refract::validation;

namespace {

// A 2-unit cube in ambient white on black, seen orthographically by 5×1 pixels of one unit:
// pixel centres at x = −2, −1, 0, 1, 2, so pixels 1 and 3 look exactly along an edge.
Scene cube_on_edges() {
    const nlohmann::json j = {
        {"camera", {{"type", "orthographic"}, {"location", {0, 0, -5}}, {"look_at", {0, 0, 0}}, {"ortho_height", 1},
                    {"width", 5}, {"height", 1}}},
        {"background", {{"type", "solid"}, {"color", {0, 0, 0}}}},
        {"materials", {{"white", {{"type", "diffuse"}, {"color", {1, 1, 1}}, {"ambient", 1}, {"diffuse", 0}}}}},
        {"objects",
         {{{"type", "polyhedron"},
           {"material", "white"},
           {"planes", {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}}}}}},
        {"render", {{"compat", "povray"}, {"max_depth", 2}}}};
    return parse_scene(j, "cube.json");
}

}  // namespace

TEST_CASE("Knife edge: the shifted camera moves every pixel's ray by about the shift: exactly at the centre, within a "
          "fifth of it at the corners of a 50° view",
          "[validation]") {
    Camera c;
    c.location = Vec3(0.3, 1.2, -4);
    c.look_at = Vec3(-0.2, 0.1, 0.5);
    c.angle_deg = 50;
    c.width = 40;
    c.height = 30;
    for (const auto type : {Camera::Type::Perspective, Camera::Type::Orthographic}) {
        c.type = type;
        const Camera s = shifted_camera(c, kKnifeEdgeShift, -2 * kKnifeEdgeShift);
        for (const auto& [x, y] : {std::pair{0.5, 0.5}, {20.0, 15.0}, {39.5, 29.5}}) {
            const Ray a = s.ray(x, y), b = c.ray(x + kKnifeEdgeShift, y - 2 * kKnifeEdgeShift), o = c.ray(x, y);
            const double shift = (b.dir - o.dir).norm() + (b.origin - o.origin).norm();
            const double residue = (a.dir - b.dir).norm() + (a.origin - b.origin).norm();
            INFO("pixel " << x << " " << y << ": shift " << shift << ", residue " << residue);
            CHECK(shift > 1e-6);  // a pixel spans ~0.02 rad (perspective) or 0.05 units
            // The perspective camera turns, so its image plane tilts: off the centre the
            // rays move by the shift to within 20 % (measured 15 % at the corners).
            CHECK(residue < (type == Camera::Type::Orthographic || x == 20.0 ? 1e-9 : 0.2 * shift));
        }
    }
}

TEST_CASE("Knife edge: the pixels looking along a cube's edges are knife-edge, the others not", "[validation]") {
    const Scene scene = cube_on_edges();
    RenderOptions ro;
    ro.threads = 1;
    const Image centre = clamp01(render(scene, ro).image);
    CHECK(centre.at(0, 0).maxCoeff() == 0.0);  // background
    CHECK(centre.at(2, 0).minCoeff() == 1.0);  // the cube's face, ambient 1
    const std::vector<char> edge = knife_edge_pixels(scene, centre, 1e-3, 1);
    REQUIRE(edge.size() == 5);
    CHECK(edge == std::vector<char>{0, 1, 0, 1, 0});
}

TEST_CASE("Knife edge: set-aside pixels count in the fraction over, not in the RMSE", "[validation]") {
    Image pov(40, 30), ref(40, 30);  // 1 200 pixels: the default targets allow 1.2 over
    ref.set(3, 3, Vec3(0.5, 0.5, 0.5));
    std::vector<char> edge(1200, 0);
    const Targets t;
    int aside = -1;
    ImageDifference out;
    CHECK_FALSE(t.met_by(compare_images(ref, pov, t.pixel_tolerance)));  // RMSE 0.0144
    CHECK_FALSE(met_outside_knife_edges(ref, pov, edge, t, aside, out));   // nothing set aside
    CHECK(aside == 0);
    edge[3 * 40 + 3] = 1;
    CHECK(met_outside_knife_edges(ref, pov, edge, t, aside, out));
    CHECK(aside == 1);
    CHECK(out.rmse == 0.0);
    // A second pixel over the tolerance elsewhere: 2 of 1 200 over, more than 0.1 %.
    ref.set(10, 20, Vec3(0, 0.01, 0));
    CHECK_FALSE(met_outside_knife_edges(ref, pov, edge, t, aside, out));
}

TEST_CASE("Random scenes 20270169 and 20270172 meet POV-Ray 3.7 with their knife-edge pixels set aside, and only so",
          "[povray]") {
    // The two failures of the batch of 1 000 from seed 20270000 (80x60): one pixel of 0.11
    // and two of up to 0.077, each on a ray passing within 1e-4 of a corner (R6's residue).
    for (const std::uint64_t seed : {20270169u, 20270172u}) {
        INFO("seed " << seed);
        const Comparison c = compare_with_povray(random_scene(seed, RandomSceneOptions{}), "seed", Targets{}, PovrayOptions{}, 2);
        INFO(c.reason);
        REQUIRE(c.outcome == Comparison::Outcome::Pass);
        INFO("rmse " << c.diff.rmse << ", max " << c.diff.max_error << " at (" << c.diff.max_x << ", " << c.diff.max_y << ")");
        CHECK_FALSE(Targets{}.met_by(c.diff));  // as it stands, the rule fails
        CHECK(c.knife_edge_pixels >= 1);
        CHECK(c.knife_edge_pixels <= 2);
        CHECK(c.diff_outside_knife_edges.rmse <= Targets{}.rmse);
    }
}
