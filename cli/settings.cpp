// The settings of the command being run, recorded for the outputs' sidecars
// (core/provenance.h): the subcommand and every option given, as given.
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include <refract/core/provenance.h>

namespace refract::cli {

void record_settings(const CLI::App& app) {
    nlohmann::json options = nlohmann::json::object();
    std::string command;
    const CLI::App* a = &app;
    while (true) {
        const auto subs = a->get_subcommands();
        if (subs.empty()) break;
        a = subs.front();
        command += (command.empty() ? "" : " ") + a->get_name();
        for (const CLI::Option* o : a->get_options()) {
            if (o->count() == 0 || o->get_name() == "--help") continue;
            const auto& r = o->results();
            options[o->get_name()] = r.size() == 1 ? nlohmann::json(r.front()) : nlohmann::json(r);
        }
    }
    set_run_settings({{"command", command}, {"options", options}});
}

}  // namespace refract::cli
