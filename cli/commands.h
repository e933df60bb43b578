#pragma once
// Each subcommand lives in its own file and registers itself here:
//   static refract::cli::Registrar reg{30, [](CLI::App& app) { ... app.add_subcommand ... }};
// Callbacks throw refract::InputError for bad input; main() prints one line and exits 2.
#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

namespace refract::cli {

struct Registrar {
    Registrar(int order, std::function<void(CLI::App&)> add);
};

struct Entry {
    int order;
    std::function<void(CLI::App&)> add;
};
std::vector<Entry>& registry();

// True when stderr is a terminal (progress bars only then).
bool stderr_is_terminal();

}  // namespace refract::cli
