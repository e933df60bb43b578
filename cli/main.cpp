// refract: the command line over the geometry, core, validation and experiment libraries.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <unistd.h>

#include "cli/commands.h"
#include "cli/suggest.h"
#include <refract/core/provenance.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace refract::cli {

std::vector<Entry>& registry() {
    static std::vector<Entry> entries;
    return entries;
}

Registrar::Registrar(int order, std::function<void(CLI::App&)> add) {
    registry().push_back({order, std::move(add)});
}

bool stderr_is_terminal() { return isatty(STDERR_FILENO) != 0; }

// An error message as one line of printable text: control characters (a field name's
// newline or terminal escape echoed from a scene) are written as \xNN, and a line past
// 8 KiB (input echoed whole somewhere) keeps its first 6 KiB and last 1 KiB.
std::string printable(const std::string& text) {
    std::string out;
    for (const unsigned char c : text) {
        if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else {
            out += static_cast<char>(c);
        }
    }
    constexpr size_t kMax = 8192, kHead = 6144, kTail = 1024;
    if (out.size() <= kMax) return out;
    const auto inside = [&](size_t k) { return (static_cast<unsigned char>(out[k]) & 0xC0) == 0x80; };
    size_t head = kHead, tail = out.size() - kTail;
    while (head > 0 && inside(head)) --head;
    while (tail < out.size() && inside(tail)) ++tail;
    return out.substr(0, head) + "\u2026(" + std::to_string(tail - head) + " bytes left out)\u2026" +
           out.substr(tail);
}

}  // namespace refract::cli

int main(int argc, char** argv) {
    refract::install_temp_cleanup();  // Ctrl-C or a kill leaves no temporary behind
    refract::set_command_line(argc, argv);  // written into the outputs (core/provenance.h)
    CLI::App app{"refract: a research toolkit for the physics of refraction in rendering"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("refract ") + REFRACT_VERSION);
    auto entries = refract::cli::registry();
    std::sort(entries.begin(), entries.end(),
              [](const auto& a, const auto& b) { return a.order < b.order; });
    for (const auto& e : entries) e.add(app);
    app.parse_complete_callback([&app] { refract::cli::record_settings(app); });  // before the command runs
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        // One line, as every other error; a slip of a command or option name says the
        // nearest known one.
        const auto near = refract::cli::suggestion(app, argc, argv);
        std::cerr << "refract: " << refract::cli::printable(near ? *near : std::string(e.what())) << "\n";
        return 2;
    } catch (const refract::InputError& e) {
        std::cerr << "refract: " << refract::cli::printable(e.what()) << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "refract: error: " << refract::cli::printable(e.what()) << "\n";
        return 1;
    }
    return 0;
}
