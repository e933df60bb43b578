// refract cut brilliant [--preset NAME] [--table ..] ... -o FILE [--json]
// Builds a round brilliant exactly (geometry/gem), writes it by extension and prints the
// requested versus measured proportions and the facet counts.
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/gem/gem_io.h>

namespace cut_command {

struct CutArgs {
    std::string preset = "gia-default";
    double table = 0, crown = 0, pavilion = 0, star = 0, lower_half = 0, girdle = 0, culet = 0;
    int girdle_facets = 0, bruted_planes = 64;
    std::string output;
    bool json = false;
};

struct Row {
    const char* key;    // JSON key
    const char* name;   // table row
    const char* unit;
    double requested;   // requested value, or the closed form for derived heights
    double measured;
    bool derived;
};

std::vector<Row> rows(const refract::BrilliantCut& c, const refract::Gem& g) {
    const refract::BrilliantProportions e = refract::closed_form_proportions(c), &m = g.measured;
    return {{"table", "table", "%", e.table, m.table, false},
            {"crown_angle", "crown angle", "deg", e.crown_angle, m.crown_angle, false},
            {"pavilion_angle", "pavilion angle", "deg", e.pavilion_angle, m.pavilion_angle, false},
            {"star", "star length", "%", e.star, m.star, false},
            {"lower_half", "lower-half length", "%", e.lower_half, m.lower_half, false},
            {"girdle", "girdle thickness", "%", e.girdle, m.girdle, false},
            {"culet", "culet", "%", e.culet, m.culet, false},
            {"crown_height", "crown height", "%", e.crown_height, m.crown_height, true},
            {"pavilion_depth", "pavilion depth", "%", e.pavilion_depth, m.pavilion_depth, true},
            {"total_depth", "total depth", "%", e.total_depth, m.total_depth, true}};
}

void run(const CutArgs& a, const CLI::App& sub) {
    refract::BrilliantCut c = refract::brilliant_preset(a.preset);
    const auto given = [&](const char* name) { return sub.get_option(name)->count() > 0; };
    if (given("--table")) c.table = a.table;
    if (given("--crown-angle")) c.crown_angle = a.crown;
    if (given("--pavilion-angle")) c.pavilion_angle = a.pavilion;
    if (given("--star")) c.star = a.star;
    if (given("--lower-half")) c.lower_half = a.lower_half;
    if (given("--girdle")) c.girdle = a.girdle;
    if (given("--culet")) c.culet = a.culet;
    if (given("--girdle-facets")) c.girdle_facets = a.girdle_facets;
    if (given("--bruted-planes")) c.bruted_planes = a.bruted_planes;

    const refract::Gem gem = refract::build_brilliant(c);  // validates; InputError on bad input
    refract::write_gem(gem, a.output);

    const auto counts = refract::facet_counts(gem);
    if (a.json) {
        nlohmann::json j;
        j["cut"] = "brilliant";
        j["preset"] = a.preset;
        j["girdle"] = refract::girdle_description(c);
        j["girdle_radius"] = 1.0;
        for (const Row& r : rows(c, gem)) {
            j[r.derived ? "closed_form" : "requested"][r.key] = r.requested;
            j["measured"][r.key] = r.measured;
        }
        j["units"] = {{"lengths", "% of girdle diameter"}, {"angles", "degrees"}};
        j["facets"]["total"] = gem.facets.size();
        for (const auto& [kind, n] : counts) j["facets"][kind] = n;
        j["vertices"] = gem.mesh.vertices.size();
        j["output"] = a.output;
        std::cout << j.dump(2) << "\n";
        return;
    }
    std::printf("round brilliant, preset %s; girdle: %s\n", a.preset.c_str(),
                refract::girdle_description(c).c_str());
    std::printf("%-20s %-4s %14s %16s\n", "proportion", "unit", "requested", "measured");
    for (const Row& r : rows(c, gem))
        std::printf("%-20s %-4s %14.6f%s %16.10f\n", r.name, r.unit, r.requested, r.derived ? "*" : " ",
                    r.measured);
    std::printf("(* closed form: crown height = (1 - table) tan(crown angle) / 2, pavilion depth = "
                "(1 - culet) tan(pavilion angle) / 2)\n");
    std::printf("facets: %zu =", gem.facets.size());
    for (std::size_t i = 0; i < counts.size(); ++i)
        std::printf("%s %s %d", i ? "," : "", counts[i].first.c_str(), counts[i].second);
    const bool design = a.output.size() >= 4 && (a.output.compare(a.output.size() - 4, 4, ".asc") == 0 ||
                                                  a.output.compare(a.output.size() - 4, 4, ".ASC") == 0);
    std::printf("\nwrote %s (%s)\n", a.output.c_str(),
                design ? "GemCad design, girdle radius 1"
                       : (std::to_string(gem.mesh.vertices.size()) + " vertices, girdle radius 1, y up").c_str());
}

refract::cli::Registrar reg{40, [](CLI::App& app) {
    auto* cut = app.add_subcommand("cut", "Build gem cuts exactly and export them");
    cut->require_subcommand(1);
    auto a = std::make_shared<CutArgs>();
    auto* sub = cut->add_subcommand(
        "brilliant", "Round brilliant from its proportions (docs/gems.md); prints requested vs measured proportions");
    std::string presets;
    for (const auto& n : refract::brilliant_preset_names()) presets += (presets.empty() ? "" : ", ") + n;
    sub->add_option("--preset", a->preset, "Starting proportions: " + presets + " (default gia-default)");
    sub->add_option("--table", a->table, "Table, % of girdle diameter (44 to 72)");
    sub->add_option("--crown-angle", a->crown, "Crown (bezel) angle, degrees (20 to 41.5)");
    sub->add_option("--pavilion-angle", a->pavilion, "Pavilion main angle, degrees (37.2 to 43.8)");
    sub->add_option("--star", a->star, "Star length, % (35 to 75)");
    sub->add_option("--lower-half", a->lower_half, "Lower-half length, % (60 to 95)");
    sub->add_option("--girdle", a->girdle, "Girdle thickness at the bezels, % (0 = knife edge, or 1.5 to 11)");
    sub->add_option("--culet", a->culet, "Culet across the flats, % (0 = pointed, to 10)");
    sub->add_option("--girdle-facets", a->girdle_facets, "Girdle facets: 0 = bruted, or a multiple of 16 (16 to 192)");
    sub->add_option("--bruted-planes", a->bruted_planes,
                    "Vertical planes approximating a bruted girdle (multiple of 16, default 64)");
    sub->add_option("-o,--output", a->output, "Output file: .obj, .off, .ply, .pov (y up) or .asc (GemCad design)")->required();
    sub->add_flag("--json", a->json, "Print the proportions and facet counts as JSON");
    sub->callback([a, sub] { run(*a, *sub); });
}};

}  // namespace cut_command
using namespace cut_command;
