#include <refract/core/image_io.h>

#include <dlfcn.h>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <refract/geometry/error.h>

namespace refract {
namespace {

namespace fs = std::filesystem;

// Set by core/CMakeLists.txt: the module's file name, its path in the build tree and the
// build tree's root.
constexpr const char* kModuleName = REFRACT_IMAGE_IO_NAME;
constexpr const char* kBuildPath = REFRACT_IMAGE_IO_BUILD_PATH;
constexpr const char* kBuildDir = REFRACT_BUILD_DIR;

// The file holding this code: the executable when core is linked statically, else the
// shared library or the Python module core is part of.
fs::path this_object() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&image_io), &info) == 0 || !info.dli_fname || !*info.dli_fname) return {};
    std::error_code ec;
    const fs::path p = fs::canonical(info.dli_fname, ec);
    return ec ? fs::path() : p;
}

bool inside(const fs::path& file, const fs::path& dir) {
    std::error_code ec;
    const fs::path d = fs::weakly_canonical(dir, ec);
    if (ec || d.empty()) return false;
    const auto rel = file.lexically_relative(d);
    return !rel.empty() && *rel.begin() != "..";
}

}  // namespace
}  // namespace refract

// Defined by cmake/image_io_location.cpp in programs linking the installed refract::core:
// the image module of that prefix (a static core cannot find it from its own file).
extern "C" __attribute__((weak)) const char* refract_image_io_installed();

namespace refract {
namespace {

// Where to look, in order: $REFRACT_IMAGE_IO alone when set; else beside the executable
// and in its ../lib/refract; beside the object holding core (a shared library or the
// Python module) and in its refract/ and ../lib/refract; the installed prefix's module of a
// program built against the installed package; then, for a program inside the
// build tree only, the build tree's module (an installed tree never depends on the build).
std::vector<std::string> candidates() {
    if (const char* env = std::getenv("REFRACT_IMAGE_IO"); env && *env) return {env};
    std::vector<std::string> paths;
    const auto add = [&](const fs::path& p) {
        const std::string s = p.lexically_normal().string();
        if (std::find(paths.begin(), paths.end(), s) == paths.end()) paths.push_back(s);
    };
    std::error_code ec;
    const fs::path exe = fs::canonical("/proc/self/exe", ec);
    if (!ec) {
        add(exe.parent_path() / kModuleName);
        add(exe.parent_path() / ".." / "lib" / "refract" / kModuleName);
    }
    const fs::path object = this_object();
    if (!object.empty()) {
        add(object.parent_path() / kModuleName);
        add(object.parent_path() / "refract" / kModuleName);
        add(object.parent_path() / ".." / "lib" / "refract" / kModuleName);
    }
    if (refract_image_io_installed) add(refract_image_io_installed());
    if ((!ec && inside(exe, kBuildDir)) || (!object.empty() && inside(object, kBuildDir))) add(kBuildPath);
    return paths;
}

// The table, or the one-line reason it could not be loaded.
const ImageIoModule* load(std::string& error) {
    const auto paths = candidates();
    std::string first_failure;  // dlerror() for a file that exists but did not load
    for (const auto& path : paths) {
        std::error_code ec;
        if (paths.size() > 1 && !fs::exists(path, ec)) continue;
        void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
        if (!handle) {
            const char* e = dlerror();
            if (first_failure.empty()) first_failure = e ? e : path + ": cannot be loaded";
            continue;
        }
        const auto entry = reinterpret_cast<ImageIoEntry>(dlsym(handle, kImageIoEntry));
        const ImageIoModule* m = entry ? entry() : nullptr;
        if (m && m->version == kImageIoVersion && m->size == sizeof(ImageIoModule)) return m;  // never unloaded
        if (first_failure.empty()) first_failure = path + ": not an image module of this version of refract";
        dlclose(handle);
    }
    error = std::string("cannot load the image module ") + kModuleName + ": ";
    if (!first_failure.empty()) {
        error += first_failure;
    } else {
        error += "not found at";
        for (size_t k = 0; k < paths.size(); ++k) error += (k ? ", " : " ") + paths[k];
        error += " (set REFRACT_IMAGE_IO to its path)";
    }
    return nullptr;
}

}  // namespace

const ImageIoModule& image_io() {
    static std::once_flag once;
    static const ImageIoModule* module = nullptr;
    static std::string error;
    std::call_once(once, [] { module = load(error); });
    if (!module) throw InputError(error);
    return *module;
}

void throw_if_failed(const IoStatus& status, const std::string& path) {
    if (status.ok()) return;
    if (status.exception) throw std::runtime_error(status.error);
    throw InputError(path.empty() ? status.error : path + ": " + status.error);
}

}  // namespace refract
