// refract export-pov SCENE.json -o scene.pov
#include <iostream>

#include "cli/commands.h"
#include <refract/core/scene_json.h>
#include <refract/validation/pov_export.h>

namespace export_pov_command {

struct ExportArgs {
    std::string scene, output;
};

refract::cli::Registrar reg{50, [](CLI::App& app) {
    auto args = std::make_shared<ExportArgs>();
    auto* sub = app.add_subcommand(
        "export-pov", "Write a scene as POV-Ray 3.7 SDL that renders what refract's \"compat\": \"povray\" mode renders");
    sub->add_option("scene", args->scene, "Scene file (JSON, see docs/scene-format.md)")->required();
    sub->add_option("-o,--output", args->output, "Output .pov file")->required();
    sub->callback([args] {
        const refract::Scene scene = refract::load_scene(args->scene);
        refract::validation::write_pov(scene, args->output);
    });
}};

}  // namespace export_pov_command
using namespace export_pov_command;
