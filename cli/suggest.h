#pragma once
// "Did you mean": the closest subcommand or option name to a word the command line did not
// know, for the one-line error of a failed parse (cli/main.cpp).
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace refract::cli {

// Levenshtein distance (insertions, deletions, substitutions, each 1).
std::size_t edit_distance(const std::string& a, const std::string& b);

// The known word nearest `word` among `known`, when it is close enough to be a slip
// (at most 2 edits, or a third of the word's length for long words); none otherwise.
std::optional<std::string> nearest_word(const std::string& word, const std::vector<std::string>& known);

// The error line for the arguments argv[1..argc) that `app` failed to parse, when one of
// them is an unknown subcommand or an unknown long option near a known one: "unknown
// command 'rendr' (did you mean 'render'?)"; none when no word is near.
std::optional<std::string> suggestion(CLI::App& app, int argc, char** argv);

}  // namespace refract::cli
