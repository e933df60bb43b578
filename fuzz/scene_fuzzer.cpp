// libFuzzer target: the scene reader and a tiny render (docs/limits.md, "Fuzzing").
// Any input must end in a scene or one InputError; a scene that loads is rendered small
// (at most 8×6 pixels, depth 6, a few photons, one thread) and every pixel must be finite.
// Anything else (a crash, a sanitizer report, another exception, a non-finite pixel) is a
// finding. Build and run: `bash run.sh fuzz [SECONDS]`.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    using namespace refract;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(data, data + size);
    } catch (const nlohmann::json::exception&) {
        return 0;  // not JSON: the reader's syntax errors are nlohmann's
    }
    Scene scene;
    try {
        scene = parse_scene(j, "fuzz.json");
    } catch (const InputError&) {
        return 0;
    }
    // Keep the render tiny: the limits themselves are tested elsewhere.
    scene.camera.width = std::min(scene.camera.width, 8);
    scene.camera.height = std::min(scene.camera.height, 6);
    RenderSettings& s = scene.settings;
    s.max_depth = std::min(s.max_depth, 6);
    s.samples = std::min(s.samples, 2);
    s.light_pass.photons = std::min<std::uint64_t>(s.light_pass.photons, 200);
    s.light_pass.element_size = std::max(s.light_pass.element_size, 0.05);
    RenderOptions o;
    o.threads = 1;
    try {
        const RenderResult r = render(scene, o);
        for (double v : r.image.rgb)
            if (!std::isfinite(v)) std::abort();  // render() reports these itself; belt and braces
    } catch (const InputError&) {
        return 0;
    }
    return 0;
}
