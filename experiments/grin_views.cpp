// grin, part 6: rendered views through gradient-index media (experiments/grin.h): the
// scenes built here, rendered by the renderer's one walker (docs/grin.md, "GRIN objects in
// scenes"), their images and counters kept in the result.
#include <chrono>
#include <cmath>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/experiments/grin.h>

namespace refract::experiments::grin_media {

namespace {

using nlohmann::json;

// A Luneburg lens (R = 1) over a checker floor: it images the scene behind the camera
// upside down on its far surface.
json luneburg_scene(int w, int h) {
    return json{
        {"camera", {{"location", {0, 1, -6}}, {"look_at", {0, 1, 0}}, {"angle", 40}, {"width", w}, {"height", h}}},
        {"background", {0.4, 0.5, 0.8}},
        {"materials",
         {{"lens", {{"type", "grin"}, {"profile", {{"kind", "luneburg"}, {"centre", {0, 1, 0}}, {"radius", 1}}}}},
          {"floor",
           {{"type", "diffuse"}, {"color", {0.9, 0.9, 0.9}}, {"checker", {{"color2", {0.1, 0.1, 0.1}}, {"size", 0.5}}}}}}},
        {"objects", json::array({{{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 1}, {"material", "lens"}},
                                 {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}})},
        {"lights", json::array({{{"position", {5, 10, -5}}}})},
        {"render", {{"max_depth", 12}}}};
}

// An inferior mirage: air 400 m long over a road, 2 % of n − 1 hotter at the ground
// (n = 1 − 2e-5·exp(−h / 0.25 m) relative to the air above), a red ball 500 m away.
json road_scene(int w, int h) {
    const json air_box = json::array({{1, 0, 0, 400}, {-1, 0, 0, 10}, {0, 1, 0, 20}, {0, -1, 0, -0.001},
                                      {0, 0, 1, 100}, {0, 0, -1, 100}});
    return json{
        {"camera", {{"location", {0, 1.5, 0}}, {"look_at", {100, 1.45, 0}}, {"angle", 5}, {"width", w}, {"height", h}}},
        {"background", {{"type", "gradient"}, {"bottom", {0.9, 0.93, 1.0}}, {"top", {0.35, 0.55, 0.95}}}},
        {"materials",
         {{"air",
           {{"type", "grin"},
            {"tolerance", 1e-7},
            {"shadows", false},
            {"profile",
             {{"kind", "exponential-height"}, {"n0", 0.99998}, {"scale_height", 0.25}, {"h0", 0}, {"up", {0, 1, 0}}}}}},
          {"road",
           {{"type", "diffuse"}, {"color", {0.25, 0.25, 0.27}}, {"checker", {{"color2", {0.35, 0.35, 0.37}}, {"size", 2}}}}},
          {"car", {{"type", "diffuse"}, {"color", {0.8, 0.1, 0.1}}}}}},
        {"objects", json::array({{{"type", "polyhedron"}, {"material", "air"}, {"planes", air_box}},
                                 {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "road"}},
                                 {{"type", "sphere"}, {"center", {500, 1.5, 0}}, {"radius", 1.5}, {"material", "car"}}})},
        {"lights", json::array({{{"type", "directional"}, {"direction", {1, -0.25, 0.3}}}})},
        {"render", {{"max_depth", 6}}}};
}

ViewStudy render_view(const std::string& name, const std::string& title, const json& scene, int threads) {
    return grin_media::render_view(name, title, scene, parse_scene(scene, name + ".json"), threads);
}

}  // namespace

ViewStudy render_view(const std::string& name, const std::string& title, const json& scene, const Scene& parsed,
                      int threads) {
    ViewStudy v;
    v.name = name;
    v.title = title;
    v.scene = scene;
    RenderOptions o;
    o.threads = threads;
    const auto t0 = std::chrono::steady_clock::now();
    RenderResult r = render(parsed, o);
    v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    v.image = std::move(r.image);
    v.grin_segments = r.stats.grin_segments;
    v.grin_evaluations = r.stats.grin_evaluations;
    v.grin_exhausted = r.stats.grin_exhausted;
    v.finite = true;
    for (double x : v.image.rgb) v.finite = v.finite && std::isfinite(x);
    return v;
}

std::vector<ViewStudy> view_study(bool quick, int threads) {
    const int w = quick ? 160 : 640, h = quick ? 120 : 480;
    return {render_view("luneburg_view", "A Luneburg lens over a checker floor", luneburg_scene(w, h), threads),
            render_view("road_view", "An inferior mirage over a hot road", road_scene(w, h), threads)};
}

}  // namespace refract::experiments::grin_media
