// Resource limits (issue 11): a render's memory is estimated before it allocates, and a
// render past the budget (--max-memory) is refused naming the field that needs it.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/memory.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/trace_record.h>
#include <refract/geometry/error.h>

using namespace refract;
using Catch::Matchers::Contains;

namespace {

Scene small_scene(int w, int h, const std::string& polarisation = "natural") {
    return parse_scene(nlohmann::json::parse(R"({"camera": {"location": [0,0,-4], "width": )" + std::to_string(w) +
                                             R"(, "height": )" + std::to_string(h) + R"(},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "diffuse"}}],
        "render": {)" + (polarisation.empty() ? std::string() : R"("polarisation": ")" + polarisation + "\"") + "}}"),
                       "small.json");
}

}  // namespace

TEST_CASE("Memory sizes: binary units, a plain byte count, and everything else refused naming the option",
          "[limits]") {
    CHECK(parse_memory_size("4096", "--max-memory") == 4096);
    CHECK(parse_memory_size("64k", "--max-memory") == 65536);
    CHECK(parse_memory_size("512M", "--max-memory") == 512ull << 20);
    CHECK(parse_memory_size("1.5G", "--max-memory") == 3ull << 29);
    CHECK(parse_memory_size("2TB", "--max-memory") == 2ull << 40);
    for (const char* bad : {"", "abc", "-1", "0", "1e3", "5X", "nan", "1..2M", "2000000000T"})
        CHECK_THROWS_WITH(parse_memory_size(bad, "--max-memory"), Contains("--max-memory"));
    CHECK(default_memory_budget() >= 256ull << 20);
}

TEST_CASE("Memory estimate: the image, each requested channel image and the budget check", "[limits]") {
    const Scene s = small_scene(100, 50);
    RenderOptions o;
    o.threads = 1;
    const double base = estimate_render_memory(s, o, 1).total();
    o.lost_energy = true;
    // Three doubles per pixel and the writer's three floats.
    CHECK(estimate_render_memory(s, o, 1).total() - base == Approx(100.0 * 50 * 3 * 12));
    o.max_memory = static_cast<std::uint64_t>(base);  // the budget below the lost-energy estimate
    CHECK_THROWS_WITH(render(s, o), Contains("small.json") && Contains("--max-memory") && Contains("/camera"));
    o.lost_energy = false;
    const RenderResult r = render(s, o);  // the same budget suffices without it
    CHECK(r.image.width == 100);
    o.max_memory = 1024;
    CHECK_THROWS_WITH(render(s, o), Contains("/camera: width × height") && Contains("1 KiB"));
    // The physical mode's default, exact polarisation, keeps the Stokes, DoLP and AoLP
    // images too: 14 values per pixel, each a double and the writer's float.
    o.max_memory = 0;
    CHECK(estimate_render_memory(small_scene(100, 50, ""), o, 1).total() - base == Approx(100.0 * 50 * 14 * 12));
}

TEST_CASE("Memory estimate: the illumination maps' elements equal those the light pass allocates", "[limits]") {
    Scene s = load_scene(std::string(REFRACT_SOURCE_DIR) + "/scenes/examples/ohtsuka1998-diamond.json");
    REQUIRE(s.settings.light_pass.enabled);
    s.settings.light_pass.photons = 10;
    for (const double element : {0.02, 0.013, 0.05}) {
        s.settings.light_pass.element_size = element;
        const SpectralContext ctx = SpectralContext::build(s);
        const auto maps = light_pass(s, ctx, 1);
        CHECK(illumination_elements(s) == static_cast<double>(maps->elements()));
        CHECK(maps->elements() > 1000);
    }
    // A map finer than the budget is refused naming element_size before the light pass.
    s.settings.light_pass.element_size = 0.002;
    RenderOptions o;
    o.max_memory = 64ull << 20;
    CHECK_THROWS_WITH(render(s, o), Contains("/render/light_pass/element_size") && Contains("--max-memory"));
    // One pixel (refract trace) runs the light pass too: the default budget bounds its maps.
    s.settings.light_pass.element_size = 1e-5;
    CHECK_THROWS_WITH(render_pixel(s, 0, 0), Contains("/render/light_pass/element_size") && Contains("--max-memory"));
}

TEST_CASE("Work bound: trace refuses a tree of more than 2^16 segments (one ray into five close glass plates at "
          "threshold 1e-10), naming /render, max_depth and threshold",
          "[limits]") {
    nlohmann::json objects = nlohmann::json::array();
    for (int k = 0; k < 5; ++k) {  // plates 1 mm thick, 1 mm apart, across the z axis
        const double z0 = 0.002 * k;
        objects.push_back({{"type", "polyhedron"}, {"material", "glass"},
                           {"planes", {{0, 0, 1, z0 + 0.001}, {0, 0, -1, -z0}, {1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}}}});
    }
    nlohmann::json j = {{"camera", {{"location", {0, 0, -4}}, {"width", 4}, {"height", 3}}},
                        {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}}}},
                        {"objects", objects},
                        {"render", {{"threshold", 1e-10}, {"max_depth", 10000}}}};
    const Ray axis{Vec3(0, 0, -1), Vec3(0, 0, 1)};
    CHECK_THROWS_WITH(trace_ray(parse_scene(j, "plates.json"), axis),
                      Contains("plates.json: /render: one ray tree took more than 65536 segments, the most a trace "
                               "records (max_depth 10000, threshold 1e-10): raise /render/threshold"));
    // At threshold 1e-3 the tree is small: its every segment recorded, the first the ray itself.
    j["render"]["threshold"] = 1e-3;
    const TraceRecord r = trace_ray(parse_scene(j, "plates.json"), axis);
    CHECK(r.segments.size() > 20);
    CHECK(r.segments.size() < kMaxTraceSegments);
    CHECK(r.segments.front().parent == -1);
}
