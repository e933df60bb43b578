// A consumer of the installed refract package: a glass sphere in a white sky, built in
// code, one ray traced through it (its tree's light must sum to 1: no absorption, no
// threshold) and a small render, written to the image named by the first argument if any.
// Prints the numbers; exit code 1 if energy is not conserved.
#include <cmath>
#include <cstdio>
#include <exception>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/core/optics.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/trace_record.h>

int main(int argc, char** argv) {
    using namespace refract;
    const nlohmann::json j = {
        {"camera", {{"location", {0, 0, -5}}, {"look_at", {0, 0, 0}}, {"width", 64}, {"height", 48}}},
        {"background", {1, 1, 1}},
        {"materials", {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}}}},
        {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}}}},
        {"render", {{"max_depth", 60}, {"threshold", 0}}}};
    const Scene scene = parse_scene(j, "consumer scene");

    const TraceRecord tree = trace_ray(scene, Ray{Vec3(0, 0.5, -5), Vec3(0, 0, 1)});
    std::printf("ray tree: %zu segments, radiance %.15f\n", tree.segments.size(), tree.radiance.x());
    std::printf("first hit: cos_i %.6f Rs %.6f Rp %.6f (optics::fresnel: Rs %.6f)\n", tree.segments[0].cos_i,
                tree.segments[0].Rs, tree.segments[0].Rp, optics::fresnel(tree.segments[0].cos_i, 1.5)->Rs);

    const RenderResult r = render(scene);
    double sum = 0;
    for (double v : r.image.rgb) sum += v;
    std::printf("render: %dx%d, mean %.6f, %llu primary rays\n", r.image.width, r.image.height,
                sum / static_cast<double>(r.image.rgb.size()), static_cast<unsigned long long>(r.stats.primary_rays));
    if (argc > 1) {
        try {
            write_image(argv[1], r.image);  // through the installed image module
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s\n", e.what());
            return 1;
        }
        std::printf("wrote %s\n", argv[1]);
    }
    return std::abs(tree.radiance.x() - 1.0) < 1e-12 ? 0 : 1;
}
