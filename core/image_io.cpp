#include <refract/core/image_io.h>

#include <dlfcn.h>
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

// Set by core/CMakeLists.txt: the module's file name, and its path in the build tree.
constexpr const char* kModuleName = REFRACT_IMAGE_IO_NAME;
constexpr const char* kBuildPath = REFRACT_IMAGE_IO_BUILD_PATH;

// Where to look, in order: $REFRACT_IMAGE_IO alone when set; else beside the executable,
// in its ../lib/refract, then in the build tree.
std::vector<std::string> candidates() {
    if (const char* env = std::getenv("REFRACT_IMAGE_IO"); env && *env) return {env};
    std::vector<std::string> paths;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        paths.push_back((exe.parent_path() / kModuleName).string());
        paths.push_back((exe.parent_path() / ".." / "lib" / "refract" / kModuleName).string());
    }
    paths.push_back(kBuildPath);
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
