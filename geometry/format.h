#pragma once
// Numbers as text, one way for the whole project (messages, CSV cells, exported scenes and
// meshes, reports), and input echoed in messages: base layer, beside the error type
// (error.h) and the atomic writer (atomic_file.h).
#include <cstddef>
#include <string>

namespace refract {

// The shortest "%.Ng" (N from 6 to 17) that reads back as the same double: CSV cells,
// generated scenes. Round-trips every finite double.
std::string format_shortest(double v);

// "%.Ng" with N = `significant` digits (1 to 17): messages (10), reports (3), exports (17).
std::string format_significant(double v, int significant);

// Text from the input echoed in a message (a field name, a value): as it is up to `keep`
// bytes, else its first `keep` bytes (whole UTF-8 characters) and "…(N bytes)", N the
// text's length: a megabyte-long key is not printed whole.
std::string clip_echo(const std::string& text, std::size_t keep = 64);

}  // namespace refract
