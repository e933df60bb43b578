// refract render SCENE.json -o IMAGE [--threads N] [--stats]
#include <filesystem>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include <refract/core/polarisation_output.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/tracer.h>

namespace {

struct RenderArgs {
    std::string scene, output;
    int threads = 0;
    bool stats = false;
    bool linear16 = false;
    bool lost = false;
    bool spectral = false;
    bool full_plane_loop = false;
    bool no_lanes = false;
    std::uint64_t max_memory = 0;
};

refract::cli::Registrar reg{10, [](CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    auto* sub = app.add_subcommand("render", "Render a scene file to an image (.exr linear, .png sRGB)");
    sub->add_option("scene", args->scene, "Scene file (JSON, see docs/scene-format.md)")->required();
    sub->add_option("-o,--output", args->output, "Output image; the extension picks the format")->required();
    sub->add_option("--threads", args->threads, "Worker threads (0: all cores); the image does not depend on it")
        ->check(refract::cli::thread_range());
    refract::cli::add_max_memory(sub, args->max_memory);
    sub->add_flag("--stats", args->stats, "Print ray, tree and list counters");
    sub->add_flag("--linear16", args->linear16, "PNG output as 16-bit linear instead of 8-bit sRGB");
    sub->add_flag("--spectral-channels", args->spectral,
                  "Also write IMAGE.spectral.exr: the light at every wavelength of the spectral eye pass, one "
                  "channel each (names like 550nm; the wavelengths also in the header attribute refract:wavelengths_nm)");
    sub->add_flag("--lost-energy", args->lost,
                  "Also write IMAGE.lost.exr: per pixel the weight dropped by the depth limit, the "
                  "reflection/transmission limits and the threshold");
    sub->add_flag("--full-plane-loop", args->full_plane_loop,
                  "Intersect every ray leaving a gem facet with all of the gem's planes, not the planes around "
                  "the facet (the same image, slower; for comparison)");
    sub->add_flag("--no-lanes", args->no_lanes,
                  "Walk the wavelengths of a spectral split and the samples of a pixel (stochastic) one by one "
                  "instead of in packets of 8 (the same image to the last bit, slower; for comparison)");
    sub->callback([args] {
        refract::check_image_path(args->output);  // before the work, not after it
        const refract::Scene scene = refract::load_scene(args->scene);
        refract::RenderOptions opt;
        opt.threads = args->threads;
        opt.progress = refract::cli::stderr_is_terminal();
        opt.spectral_channels = args->spectral;
        opt.lost_energy = args->lost;
        opt.max_memory = args->max_memory;
        opt.trace.facet_local = !args->full_plane_loop;
        opt.trace.packets = !args->no_lanes;
        const auto result = refract::render(scene, opt);
        refract::write_image(args->output, result.image, {args->linear16, result.signed_colours});
        if (result.polarisation)
            refract::write_polarisation(args->output, result.image.width, result.image.height, *result.polarisation,
                                        result.signed_colours);
        if (args->spectral) {
            const std::filesystem::path p(args->output);
            std::vector<std::string> names;
            std::string list;
            for (double nm : result.wavelengths) {
                std::ostringstream s;
                s << nm;
                names.push_back(s.str() + "nm");
                list += (list.empty() ? "" : " ") + s.str();
            }
            refract::write_channels((p.parent_path() / p.stem()).string() + ".spectral.exr", result.image.width,
                                    result.image.height, names, result.spectral, {{"refract:wavelengths_nm", list}});
        }
        if (args->lost) {
            const std::filesystem::path p(args->output);
            refract::write_channels((p.parent_path() / p.stem()).string() + ".lost.exr", result.image.width,
                                    result.image.height, {"depth", "limits", "threshold"}, result.lost);
        }
        const std::string warning = result.stats.lost_warning();
        if (!warning.empty()) std::cerr << "refract render: " << args->scene << ": " << warning << "\n";
        if (args->stats) std::cout << result.stats.summary();
    });
}};

}  // namespace
