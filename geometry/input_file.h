#pragma once
// Input files read whole (scenes, tolerance files): at most 64 MiB whatever the file is.
// A regular file is refused from its size before it is read; a pipe, standard input or a
// device is read in chunks and refused as soon as it passes the limit (docs/limits.md).
#include <cstdint>
#include <string>

namespace refract {

constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t{64} << 20;

// The bytes of `path`, a `kind` ("scene file", "tolerance file"). InputError naming the
// path: a directory, a file that cannot be opened or read, one longer than `limit` bytes.
std::string read_input_file(const std::string& path, const std::string& kind, std::uintmax_t limit = kMaxInputBytes);

// JSON text (a scene, a tolerance file) is nested at most 64 arrays and objects deep: deep
// nesting costs a parser far more memory than its bytes (some 60 bytes a level), so deeper
// text is refused before it is parsed. InputError "<path>: line L: nested more than 64
// levels deep" (strings skipped).
constexpr int kMaxJsonDepth = 64;
void check_json_depth(const std::string& text, const std::string& path);

}  // namespace refract
