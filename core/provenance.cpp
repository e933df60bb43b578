#include <refract/core/provenance.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <mutex>

#include <nlohmann/json.hpp>

#include <refract/geometry/atomic_file.h>

#ifndef REFRACT_VERSION
#define REFRACT_VERSION "unknown"
#endif

namespace refract {
namespace {

std::mutex& lock() {
    static std::mutex m;
    return m;
}
std::string& line() {
    static std::string s;
    return s;
}
nlohmann::json& settings() {
    static nlohmann::json s = nlohmann::json::object();
    return s;
}

// An argument as a shell reads it back: bare when it is plain, else in single quotes.
std::string quoted(const std::string& a) {
    bool plain = !a.empty();
    for (const unsigned char c : a)
        if (!(std::isalnum(c) || std::string("-_./:=,+@%").find(static_cast<char>(c)) != std::string::npos)) plain = false;
    if (plain) return a;
    std::string q = "'";
    for (const char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

}  // namespace

const char* version() { return REFRACT_VERSION; }

void set_command_line(int argc, const char* const* argv) {
    std::string s;
    for (int k = 0; k < argc; ++k) s += (k ? " " : "") + quoted(k == 0 ? std::filesystem::path(argv[k]).filename().string() : argv[k]);
    std::lock_guard<std::mutex> g(lock());
    line() = s;
}

const std::string& command_line() {
    std::lock_guard<std::mutex> g(lock());
    return line();
}

void set_run_settings(const nlohmann::json& s) {
    std::lock_guard<std::mutex> g(lock());
    settings() = s;
}

std::string fnv1a64_hex(const std::string& bytes) {
    std::uint64_t h = 1469598103934665603ull;
    for (const unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string csv_sidecar_path(const std::string& csv_path) { return csv_path + ".json"; }

void write_csv_sidecar(const std::string& csv_path, const nlohmann::json& given) {
    nlohmann::json j;
    j["csv"] = std::filesystem::path(csv_path).filename().string();
    j["refract_version"] = version();
    {
        std::lock_guard<std::mutex> g(lock());
        j["command_line"] = line().empty() ? nlohmann::json(nullptr) : nlohmann::json(line());
        j["settings"] = given.is_object() && !given.empty() ? given : settings();
    }
    write_file_atomic(csv_sidecar_path(csv_path), j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

void write_csv_sidecar(const std::string& csv_path) { write_csv_sidecar(csv_path, nlohmann::json()); }

}  // namespace refract
