#include "cli/suggest.h"

#include <algorithm>

namespace refract::cli {

std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

std::optional<std::string> nearest_word(const std::string& word, const std::vector<std::string>& known) {
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
    std::optional<std::string> best;
    std::size_t best_d = limit + 1;
    for (const std::string& k : known) {
        const std::size_t d = edit_distance(word, k);
        if (d < best_d) {
            best_d = d;
            best = k;
        }
    }
    return best;
}

namespace suggest_command {

std::vector<std::string> subcommand_names(CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(s->get_name());
    return names;
}

// The long option names ("--name") of `app` and of the subcommands above it.
void add_long_names(const CLI::App& app, std::vector<std::string>& names) {
    for (const CLI::Option* o : app.get_options())
        for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
}

}  // namespace suggest_command
using namespace suggest_command;

std::optional<std::string> suggestion(CLI::App& app, int argc, char** argv) {
    CLI::App* level = &app;
    std::vector<std::string> options;
    add_long_names(app, options);
    bool seen_positional = false;
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word.rfind("--", 0) == 0 && word.size() > 2) {
            const std::string name = word.substr(0, word.find('='));
            if (std::find(options.begin(), options.end(), name) != options.end()) continue;
            if (const auto near = nearest_word(name, options))
                return "unknown option '" + name + "' (did you mean '" + *near + "'?)";
            continue;
        }
        if (word.empty() || word[0] == '-') continue;
        const std::vector<std::string> subs = subcommand_names(*level);
        if (std::find(subs.begin(), subs.end(), word) != subs.end()) {
            level = level->get_subcommand(word);
            add_long_names(*level, options);
            seen_positional = false;
            continue;
        }
        // The first plain word where a subcommand is required: an unknown command.
        if (!seen_positional && !subs.empty() && level->get_require_subcommand_min() > 0) {
            const std::string what =
                level == &app ? "command '" + word + "'" : "subcommand '" + word + "' of '" + level->get_name() + "'";
            if (const auto near = nearest_word(word, subs)) return "unknown " + what + " (did you mean '" + *near + "'?)";
            return "unknown " + what + " (see --help)";
        }
        seen_positional = true;
    }
    return std::nullopt;
}

}  // namespace refract::cli
