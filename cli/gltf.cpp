// refract import MODEL.glb|MODEL.gltf -o SCENE.json [--width W] [--height H]
// refract export-gltf SCENE.json -o OUT.glb|OUT.gltf
// glTF 2.0 scenes as a whole (core/gltf_scene.h, docs/gltf.md); what cannot be honoured is
// named in one warning line per item on stderr.
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include <refract/core/gltf_scene.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace gltf_command {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

void warn(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) std::cerr << "refract: warning: " << refract::cli::printable(w) << "\n";
}

struct ImportArgs {
    std::string model, output;
    int width = 0, height = 0;
};

void run_import(const ImportArgs& a) {
    if (lower_extension(a.output) != ".json")
        throw refract::InputError("--output: '" + a.output + "': a scene file must end in .json");
    // The mesh objects name the model relative to the scene file's directory.
    const fs::path model = fs::absolute(a.model).lexically_normal();
    const fs::path dir = fs::absolute(a.output).lexically_normal().parent_path();
    fs::path rel = model.lexically_relative(dir);
    if (rel.empty()) rel = model;
    const refract::GltfImport im = refract::import_gltf(a.model, rel.generic_string(), a.width, a.height);
    // The scene as refract reads it: anything it would refuse is refused here, before a
    // file is written. The warnings follow the written file (an error stays one line).
    const refract::Scene scene = refract::parse_scene(im.scene, a.output);
    refract::write_file_atomic(a.output, im.scene.dump(1) + "\n");
    warn(im.warnings);
    std::cout << "wrote " << a.output << ": " << scene.objects.size() << " objects, " << scene.materials.size()
              << " materials, " << scene.lights.size() << " lights, " << im.warnings.size() << " warnings\n";
}

struct ExportArgs {
    std::string scene, output;
};

void run_export(const ExportArgs& a) {
    const std::string ext = lower_extension(a.output);
    if (ext != ".glb" && ext != ".gltf")
        throw refract::InputError("--output: '" + a.output + "': a glTF file must end in .glb or .gltf");
    const refract::Scene scene = refract::load_scene(a.scene);
    const refract::GltfExport out = refract::export_gltf(scene, ext == ".glb");
    refract::write_file_atomic(a.output, out.bytes);
    warn(out.warnings);
    std::cout << "wrote " << a.output << " (" << out.bytes.size() << " bytes, " << out.warnings.size() << " warnings)\n";
}

refract::cli::Registrar reg{51, [](CLI::App& app) {
    auto a = std::make_shared<ImportArgs>();
    auto* sub = app.add_subcommand("import", "Turn a glTF 2.0 scene (.glb, .gltf) into a refract scene file (docs/gltf.md)");
    sub->add_option("model", a->model, "glTF file (.glb or .gltf)")->required();
    sub->add_option("-o,--output", a->output, "Output scene file (.json)")->required();
    sub->add_option("--width", a->width, "Image width (default: the camera's extras, else 640)")->check(CLI::Range(1, 1 << 15));
    sub->add_option("--height", a->height, "Image height (default: from the camera's aspect ratio)")->check(CLI::Range(1, 1 << 15));
    sub->callback([a] { run_import(*a); });

    auto e = std::make_shared<ExportArgs>();
    auto* ex = app.add_subcommand("export-gltf", "Write a scene as glTF 2.0 (.glb or .gltf) with its dielectrics' dispersion");
    ex->add_option("scene", e->scene, "Scene file (JSON, see docs/scene-format.md)")->required();
    ex->add_option("-o,--output", e->output, "Output .glb or .gltf file")->required();
    ex->callback([e] { run_export(*e); });
}};

}  // namespace gltf_command
using namespace gltf_command;
