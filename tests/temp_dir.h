#pragma once
// A fresh, empty directory for one test, named after its file's prefix, the test and this
// process (tests that write files: the CLI, the atomic writer, the sweep's journal).
#include <filesystem>
#include <string>

#include <unistd.h>

namespace refract::test {

inline std::filesystem::path fresh_dir(const std::string& prefix, const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("refract-" + prefix + "-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace refract::test
