#include <refract/geometry/input_file.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include <refract/geometry/error.h>

namespace refract {

namespace {

std::string mib(std::uintmax_t bytes) {
    return bytes % (std::uintmax_t{1} << 20) == 0 ? std::to_string(bytes >> 20) + " MiB" : std::to_string(bytes) + " bytes";
}

}  // namespace

std::string read_input_file(const std::string& path, const std::string& kind, std::uintmax_t limit) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (fs::is_directory(st)) throw InputError(path + ": is a directory, not a " + kind);
    const bool regular = fs::is_regular_file(st);
    std::uintmax_t size = 0;
    if (regular) {
        size = fs::file_size(path, ec);
        if (ec) size = 0;
        if (size > limit)
            throw InputError(path + ": the " + kind + " has " + std::to_string(size) + " bytes, more than the limit of " +
                             mib(limit));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open " + kind);
    // A pipe or a device has no size: read it in chunks, refused once past the limit.
    std::string text;
    text.reserve(static_cast<std::size_t>(size));
    std::vector<char> chunk(std::size_t{1} << 16);
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (text.size() + got > limit)
            throw InputError(path + ": the " + kind + " is longer than the limit of " + mib(limit) +
                             (regular ? "" : " (read from a pipe or device, stopped there)"));
        text.append(chunk.data(), got);
    }
    if (in.bad()) throw InputError(path + ": cannot read " + kind);
    return text;
}

void check_json_depth(const std::string& text, const std::string& path) {
    int depth = 0;
    std::size_t line = 1;
    bool in_string = false, escaped = false;
    for (const char c : text) {
        if (c == '\n') ++line;
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw InputError(path + ": line " + std::to_string(line) + ": nested more than " +
                                 std::to_string(kMaxJsonDepth) + " levels deep");
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
}

}  // namespace refract
