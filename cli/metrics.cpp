// refract metrics DESIGN.asc [--rays N] [--observer NAME] [--json] [--aset FILE] [--ideal-scope FILE]
// The gem metrics of a faceting design (experiments/design_metrics.h, docs/gems.md "Metrics
// of a design"): light return, fire, scintillation, leakage and the ASET shares, the stone
// built exactly at width 2; the viewers' images on request.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/gem_options.h"
#include <refract/core/image.h>
#include <refract/experiments/design_metrics.h>
#include <refract/geometry/error.h>

namespace metrics_command {

namespace dm = refract::experiments::design_metrics;

struct Args {
    refract::cli::GemOptionArgs gem;
    std::string design, aset, ideal_scope;
    int size = 256, samples = 2;
    bool json = false;
};

void run(const Args& a) {
    const auto m = refract::cli::metric_options(a.gem);
    for (const std::string* out : {&a.aset, &a.ideal_scope})
        if (!out->empty()) refract::check_image_path(*out);
    const refract::DesignGem stone = dm::build_at_width_2(refract::read_gemcad(a.design));
    const refract::gem_metrics::GemMetrics g = dm::measure(stone, m);
    if (!a.aset.empty()) refract::write_image(a.aset, dm::render_view(stone, "aset", a.size, a.samples, m));
    if (!a.ideal_scope.empty())
        refract::write_image(a.ideal_scope, dm::render_view(stone, "ideal-scope", a.size, a.samples, m));
    const std::string name = std::filesystem::path(a.design).filename().string();
    if (a.json) {
        nlohmann::json j;
        j["design"] = a.design;
        j["facets"] = stone.gem.facets.size();
        j["volume_at_width_2"] = stone.volume;
        j["length_over_width"] = stone.length / stone.width;
        j["height_over_width"] = stone.height / stone.width;
        const auto metric = [](const refract::gem_metrics::Metric& x) { return nlohmann::json{{"value", x.value}, {"error", x.error}}; };
        j["light_return"] = metric(g.light_return);
        j["fire"] = metric(g.fire);
        j["scintillation"] = metric(g.scintillation);
        j["leakage"] = metric(g.leakage);
        j["aset"] = {{"red", g.aset.red}, {"green", g.aset.green}, {"blue", g.aset.blue}, {"white", g.aset.white}};
        j["balance"] = {{"crown", g.balance.crown}, {"girdle", g.balance.girdle}, {"pavilion", g.balance.pavilion},
                        {"lost", g.balance.lost}, {"missed", g.balance.missed}};
        j["material"] = a.gem.material;
        j["observer"] = g.observer;
        j["rays"] = a.gem.rays;
        std::cout << j.dump(2) << "\n";
        return;
    }
    // The observer is named when it is not the default (whose line stays as it was).
    const std::string observer = g.observer == "aset" ? "" : ", observer " + g.observer;
    std::printf("%s: %zu facets, volume %.6g at width 2, L/W %.4f, H/W %.4f (%s, %d rays%s)\n", name.c_str(),
                stone.gem.facets.size(), stone.volume, stone.length / stone.width, stone.height / stone.width,
                a.gem.material.c_str(), a.gem.rays, observer.c_str());
    const auto line = [](const char* what, const refract::gem_metrics::Metric& x) {
        std::printf("%-14s %.4f +- %.4f\n", what, x.value, x.error);
    };
    line("light return", g.light_return);
    line("fire", g.fire);
    line("scintillation", g.scintillation);
    line("leakage", g.leakage);
    std::printf("ASET           red %.4f  green %.4f  blue %.4f  white %.4f\n", g.aset.red, g.aset.green, g.aset.blue,
                g.aset.white);
}

refract::cli::Registrar reg{36, [](CLI::App& app) {
    auto a = std::make_shared<Args>();
    auto* sub = app.add_subcommand(
        "metrics", "Gem metrics of a faceting design (.asc): light return, fire, scintillation, leakage, ASET (docs/gems.md)");
    sub->add_option("design", a->design, "GemCad .asc design file")->required();
    refract::cli::add_gem_options(sub, a->gem, "Seed of the eye rays");
    sub->add_flag("--json", a->json, "Print the metrics as JSON");
    sub->add_option("--aset", a->aset, "Write the ASET image here (any format OpenImageIO writes)");
    sub->add_option("--ideal-scope", a->ideal_scope, "Write the ideal-scope image here");
    sub->add_option("--image-size", a->size, "Images: pixels square (256)")->check(CLI::Range(1, 4096));
    sub->add_option("--image-samples", a->samples, "Images: eye rays per pixel, squared (2)")->check(CLI::Range(1, 16));
    sub->callback([a] { run(*a); });
}};

}  // namespace metrics_command
using namespace metrics_command;
