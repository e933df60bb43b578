#pragma once
// Each subcommand lives in its own file and registers itself here:
//   static refract::cli::Registrar reg{30, [](CLI::App& app) { ... app.add_subcommand ... }};
// Callbacks throw refract::InputError for bad input; main() prints one line and exits 2.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <refract/core/memory.h>
#include <refract/core/threads.h>

namespace refract::cli {

struct Registrar {
    Registrar(int order, std::function<void(CLI::App&)> add);
};

struct Entry {
    int order;
    std::function<void(CLI::App&)> add;
};
std::vector<Entry>& registry();

// Worker threads: --threads N takes 0 (all cores) to kMaxThreads (core/threads.h).
inline CLI::Range thread_range(int min = 0) { return CLI::Range(min, refract::kMaxThreads); }

// --max-memory SIZE (core/memory.h): a render refuses, before allocating, to need more.
inline void add_max_memory(CLI::App* sub, std::uint64_t& bytes) {
    sub->add_option_function<std::string>(
        "--max-memory", [&bytes](const std::string& v) { bytes = refract::parse_memory_size(v, "--max-memory"); },
        "Memory budget (e.g. 512M, 4G; default 3/4 of physical memory): refused before allocating beyond it");
}

// A message as one line of printable text (cli/main.cpp): warnings and errors alike.
std::string printable(const std::string& text);

// True when stderr is a terminal (progress bars only then).
bool stderr_is_terminal();

// Records the chosen subcommand and the options given (core/provenance.h: set_run_settings),
// for the sidecar of every CSV the command writes; main() calls it once parsing is complete.
void record_settings(const CLI::App& app);

}  // namespace refract::cli
