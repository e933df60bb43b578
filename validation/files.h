#pragma once
// Small file helpers of the validation layer: whole-file text writes that never leave a
// half-written file behind (temporary name beside the target, then rename).
#include <string>

namespace refract::validation {

// Writes `text` to `path` atomically; creates no directories. Throws InputError naming
// the path on failure.
void write_text_file(const std::string& path, const std::string& text);

// Reads a whole text file; throws InputError naming the path when it cannot be read.
std::string read_text_file(const std::string& path);

// Escapes &, <, > and " for HTML text and attribute values.
std::string html_escape(const std::string& s);

}  // namespace refract::validation
