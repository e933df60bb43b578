#pragma once
// What produced an output, written into it: refract's version, the command line (set once
// by the program, e.g. the CLI's main), and, beside every CSV file, a JSON sidecar
// NAME.csv.json holding them and the settings of the run (docs/limits.md, "Outputs").
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace refract {

// refract's version (the project's, as built).
const char* version();

// The command line of this process, each argument quoted when it needs it; empty until a
// program sets it (a library user: no command line).
void set_command_line(int argc, const char* const* argv);
const std::string& command_line();

// The settings of the running command (an object; empty until set), written into every
// CSV sidecar this process writes; a command sets them once, before its outputs.
void set_run_settings(const nlohmann::json& settings);

// FNV-1a 64-bit hash of `bytes`, 16 hex digits (a file's fingerprint in a header).
std::string fnv1a64_hex(const std::string& bytes);

// CSV → CSV.json.
std::string csv_sidecar_path(const std::string& csv_path);

// Writes CSV.json atomically: {"csv": file name, "refract_version", "command_line",
// "settings": `settings` when it is an object with members, else the run's settings}.
// InputError naming the sidecar on failure.
void write_csv_sidecar(const std::string& csv_path, const nlohmann::json& settings);
void write_csv_sidecar(const std::string& csv_path);  // the run's settings

}  // namespace refract
