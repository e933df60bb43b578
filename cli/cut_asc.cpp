// refract cut asc DESIGN.asc -o FILE [--json]
// Reads a GemCad faceting design (geometry/gem/gemcad.h), builds it exactly, writes it by
// extension (.obj, .off, .ply, .pov in the scene's frame, y up; .asc: the design as read) and
// prints its facet count, volume and proportions over its width W.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>
#include <refract/geometry/gem/gem_io.h>
#include <refract/geometry/gem/gemcad.h>

namespace cut_asc_command {

struct AscArgs {
    std::string design, output;
    bool json = false;
};

void run(const AscArgs& a) {
    std::string ext = std::filesystem::path(a.output).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".pov" && ext != ".asc")
        throw refract::InputError("output file '" + a.output + "': unknown extension '" + ext +
                                  "' (allowed: .obj, .off, .ply, .pov, .asc)");
    const refract::GemcadDesign design = refract::read_gemcad(a.design);
    refract::DesignGem d = refract::build_design(design);
    const std::string name = std::filesystem::path(a.design).filename().string();
    d.gem.description = "GemCad design " + name + " built by refract; the design's own unit";
    if (ext == ".asc") refract::write_file_atomic(a.output, refract::gemcad_text(design));
    else refract::write_gem(d.gem, a.output);

    const double W = d.width;
    if (a.json) {
        nlohmann::json j;
        j["design"] = a.design;
        j["gear"] = design.gear;
        j["symmetry"] = design.symmetry;
        j["mirror"] = design.mirror;
        if (design.index > 0) j["refractive_index"] = design.index;
        j["tiers"] = design.tiers.size();
        j["facets"] = d.gem.facets.size();
        j["facets_listed"] = d.planes;
        j["vertices"] = d.gem.mesh.vertices.size();
        j["volume"] = d.volume;
        j["convex"] = d.gem.convex;
        if (!d.gem.convex) {
            j["preform_volume"] = d.preform_volume;
            j["notch_volume"] = d.notch_volume;
            j["cleft_facets"] = d.cleft_facets;
        }
        j["width"] = W;
        j["length"] = d.length;
        j["height"] = d.height;
        j["length_over_width"] = d.length / W;
        j["height_over_width"] = d.height / W;
        j["volume_over_width_cubed"] = d.volume / (W * W * W);
        j["output"] = a.output;
        std::cout << j.dump(2) << "\n";
        return;
    }
    std::printf("GemCad design %s: gear %d, symmetry %d%s, %zu tiers", name.c_str(), design.gear, design.symmetry,
                design.mirror ? " with mirror" : "", design.tiers.size());
    if (design.index > 0) std::printf(", refractive index %.6g", design.index);
    std::printf("\nfacets: %zu (of %d listed), vertices: %zu, %s\n", d.gem.facets.size(), d.planes,
                d.gem.mesh.vertices.size(),
                d.gem.convex ? "closed and convex" : "closed, convex except at its cleft");
    if (!d.gem.convex)
        std::printf("cleft: %d facets; the convex preform's volume %.10g less the notch's %.10g\n", d.cleft_facets,
                    d.preform_volume, d.notch_volume);
    std::printf("width W %.10g, length %.10g (L/W %.6f), height %.10g (H/W %.6f)\n", W, d.length, d.length / W,
                d.height, d.height / W);
    std::printf("volume %.10g (V/W^3 %.6f)\n", d.volume, d.volume / (W * W * W));
    std::printf("wrote %s (%s)\n", a.output.c_str(), ext == ".asc" ? "GemCad design" : "the design's unit, y up");
}

refract::cli::Registrar reg{41, [](CLI::App& app) {
    CLI::App* cut = app.get_subcommand("cut");  // cli/cut.cpp (order 40)
    auto a = std::make_shared<AscArgs>();
    auto* sub = cut->add_subcommand("asc", "GemCad faceting design (.asc, docs/gems.md): build it exactly and export it");
    sub->add_option("design", a->design, "GemCad .asc design file")->required();
    sub->add_option("-o,--output", a->output, "Output file: .obj, .off, .ply, .pov (y up) or .asc")->required();
    sub->add_flag("--json", a->json, "Print the facet count, volume and proportions as JSON");
    sub->callback([a] { run(*a); });
}};

}  // namespace cut_asc_command
using namespace cut_asc_command;
