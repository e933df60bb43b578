// refract render SCENE.json -o IMAGE [--threads N] [--stats]
#include <cctype>
#include <filesystem>
#include <optional>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include <refract/core/integrators/integrator.h>
#include <refract/core/polarisation_output.h>
#include <refract/core/render.h>
#include <refract/core/render_metadata.h>
#include <refract/core/scene_json.h>
#include <refract/core/tracer.h>

namespace render_command {

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
    std::optional<std::uint64_t> seed;
};

// OUT.stem + suffix beside OUT (OUT.lost.exr, OUT.spectral.exr).
std::string sidecar(const std::string& output, const std::string& suffix) {
    const std::filesystem::path p(output);
    return (p.parent_path() / p.stem()).string() + suffix;
}

bool is_exr(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr";
}

// Writes the image and its sidecars, appending each path to `done` once it is written.
void write_outputs(const RenderArgs& args, const refract::Scene& scene, const refract::RenderResult& result,
                   std::vector<std::string>& done) {
    const int w = result.image.width, h = result.image.height;
    if (is_exr(args.output)) {
        // The same float RGB write_image stores, with a header saying what made it and
        // its chromaticities (core/render_metadata.h).
        const std::vector<std::string> rgb{"R", "G", "B"};
        refract::write_channels(args.output, w, h, rgb, result.image.rgb, refract::render_attributes(scene, args.scene),
                                result.signed_colours ? rgb : std::vector<std::string>{});
    } else {
        refract::write_image(args.output, result.image, {args.linear16, result.signed_colours});
    }
    done.push_back(args.output);
    if (result.polarisation)
        for (const auto& p : refract::write_polarisation(args.output, w, h, *result.polarisation, result.signed_colours)) done.push_back(p);
    if (args.spectral) {
        std::vector<std::string> names;
        std::string list;
        for (double nm : result.wavelengths) {
            std::ostringstream s;
            s << nm;
            names.push_back(s.str() + "nm");
            list += (list.empty() ? "" : " ") + s.str();
        }
        const std::string path = sidecar(args.output, ".spectral.exr");
        refract::write_channels(path, w, h, names, result.spectral, {{"refract:wavelengths_nm", list}});
        done.push_back(path);
    }
    if (args.lost) {
        const std::string path = sidecar(args.output, ".lost.exr");
        refract::write_channels(path, w, h, {"depth", "limits", "threshold"}, result.lost);
        done.push_back(path);
    }
}

refract::cli::Registrar reg{10, [](CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    auto* sub = app.add_subcommand("render", "Render a scene file to an image (.exr linear, .png sRGB)");
    sub->add_option("scene", args->scene, "Scene file (JSON, see docs/scene-format.md)")->required();
    sub->add_option("-o,--output", args->output, "Output image; the extension picks the format")->required();
    sub->add_option("--threads", args->threads, "Worker threads (0: all cores); the image does not depend on it")
        ->check(refract::cli::thread_range());
    refract::cli::add_max_memory(sub, args->max_memory);
    sub->add_option("--seed", args->seed, "Random seed of the stochastic integrator and of jitter (default: the "
                                          "scene's render.seed)")
        ->check(CLI::NonNegativeNumber);
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
        refract::Scene scene = refract::load_scene(args->scene);
        if (args->seed) scene.settings.seed = *args->seed;
        // Every file the render writes, checked before the work too: the image, then the
        // sidecars its options and the scene ask for.
        std::vector<std::string> outputs{args->output};
        if (refract::polarisation_model(scene) == refract::PolarisationModel::Exact)
            for (const auto& p : refract::polarisation_paths(args->output)) outputs.push_back(p);
        if (args->spectral) outputs.push_back(sidecar(args->output, ".spectral.exr"));
        if (args->lost) outputs.push_back(sidecar(args->output, ".lost.exr"));
        for (const auto& p : outputs) refract::check_image_path(p);
        refract::RenderOptions opt;
        opt.threads = args->threads;
        opt.progress = refract::cli::stderr_is_terminal();
        opt.spectral_channels = args->spectral;
        opt.lost_energy = args->lost;
        opt.max_memory = args->max_memory;
        opt.trace.facet_local = !args->full_plane_loop;
        opt.trace.packets = !args->no_lanes;
        const auto result = refract::render(scene, opt);
        // A write refused after the first (a disk full) removes what this run wrote.
        std::vector<std::string> done;
        try {
            write_outputs(*args, scene, result, done);
        } catch (const refract::InputError&) {
            std::error_code ec;
            for (const auto& p : done) std::filesystem::remove(p, ec);
            throw;
        }
        const std::string warning = result.stats.lost_warning();
        if (!warning.empty()) std::cerr << "refract render: " << args->scene << ": " << warning << "\n";
        if (args->stats) std::cout << result.stats.summary();
    });
}};

}  // namespace render_command
using namespace render_command;
