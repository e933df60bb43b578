#include <refract/validation/povray_runner.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <refract/geometry/error.h>
#include <refract/geometry/signal_cleanup.h>
#include <refract/validation/files.h>
#include <refract/validation/process.h>

namespace refract::validation {
namespace fs = std::filesystem;

std::string find_povray(const std::string& executable) {
    auto runnable = [](const fs::path& p) {
        std::error_code ec;
        return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
    };
    if (executable.find('/') != std::string::npos) return runnable(executable) ? executable : std::string();
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        const fs::path p = fs::path(dir) / executable;
        if (runnable(p)) return p.string();
    }
    return {};
}

namespace {

// A temporary directory removed with everything in it when the scope ends, and on
// SIGINT/SIGTERM (geometry/signal_cleanup.h: after POV-Ray, registered later, is killed).
class TempDir {
public:
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "refract-povray-XXXXXX").string();
        std::vector<char> buf(tmpl.begin(), tmpl.end());
        buf.push_back('\0');
        if (!::mkdtemp(buf.data())) throw PovrayError(std::string("cannot create a temporary directory: ") + std::strerror(errno));
        path_ = buf.data();
        on_signal_ = std::make_unique<TreeOnSignal>(path_.c_str());
    }
    ~TempDir() {
        on_signal_.reset();
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
    std::unique_ptr<TreeOnSignal> on_signal_;
};

std::string tail(const std::string& text, size_t lines) {
    size_t pos = text.size();
    for (size_t n = 0; n <= lines && pos > 0; ++n) {
        const size_t p = text.rfind('\n', pos - 1);
        if (p == std::string::npos) return text;
        pos = p;
        if (n == lines) return text.substr(pos + 1);
    }
    return text.substr(pos);
}

// The first POV-Ray message that says what went wrong ("Parse Error: ...").
std::string first_error_line(const std::string& log) {
    std::istringstream in(log);
    std::string line;
    while (std::getline(in, line))
        if (line.find("Error") != std::string::npos || line.find("error") != std::string::npos) return line;
    return {};
}

// "POV-Ray 3.7.0.10.unofficial" from the banner line "Persistence of Vision(tm) Ray
// Tracer Version 3.7.0.10.unofficial (g++ @".
std::string version_line(const std::string& log) {
    std::istringstream in(log);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("Persistence of Vision", 0) != 0) continue;
        const auto v = line.find("Version ");
        if (v == std::string::npos) return line;
        std::istringstream words(line.substr(v + 8));
        std::string version;
        words >> version;
        return "POV-Ray " + version;
    }
    return {};
}

}  // namespace

PovrayRender render_povray(const std::string& pov_source, int width, int height, const PovrayOptions& opt) {
    const std::string exe = find_povray(opt.executable);
    if (exe.empty()) throw PovrayError("povray not found (looked for '" + opt.executable + "' on PATH); install POV-Ray 3.7");
    if (width <= 0 || height <= 0) throw PovrayError("image size must be positive");
    TempDir dir;
    const fs::path scene = dir.path() / "scene.pov";
    const fs::path image = dir.path() / "out.png";
    const fs::path log_path = dir.path() / "povray.log";
    write_text_file(scene.string(), pov_source);
    for (const std::string& f : opt.files) {
        std::error_code ec;
        fs::copy_file(f, dir.path() / fs::path(f).filename(), fs::copy_options::overwrite_existing, ec);
        if (ec) throw PovrayError("cannot copy " + f + " for povray: " + ec.message());
    }

    // Arguments: no antialiasing, no display, no pause, 16-bit linear PNG, terse output,
    // threads; no user ini (the temporary HOME has none).
    std::vector<std::string> args = {exe,
                                     "+I" + scene.filename().string(),
                                     "+O" + image.filename().string(),
                                     "+W" + std::to_string(width),
                                     "+H" + std::to_string(height),
                                     "-A",
                                     "-D",
                                     "-P",
                                     "+WT" + std::to_string(std::max(1, opt.threads)),
                                     "+FN16",
                                     "File_Gamma=1.0",
                                     "-V"};
    // A clean environment: POV-Ray reads and writes its per-user files under HOME.
    const std::string env_home = "HOME=" + dir.path().string();
    const char* path_env = std::getenv("PATH");
    const std::string env_path = std::string("PATH=") + (path_env ? path_env : "/usr/bin:/bin");
    const std::string env_lang = "LC_ALL=C";

    ProcessOptions po;
    po.dir = dir.path().string();
    po.inherit_env = false;
    po.env = {env_home, env_path, env_lang};
    po.stdout_path = log_path.string();
    po.timeout_seconds = opt.timeout_seconds;
    const ProcessResult run = run_process(args, po);
    PovrayRender out;
    out.seconds = run.seconds;
    out.cpu_seconds = run.cpu_seconds;
    std::string log;
    try {
        log = read_text_file(log_path.string());
    } catch (const InputError&) {
    }
    out.version = version_line(log);
    if (run.timed_out)
        throw PovrayError("povray timed out after " + std::to_string(static_cast<int>(opt.timeout_seconds)) + " s", tail(log, 20));
    if (!run.ok()) {
        const std::string why = run.why();
        const std::string err = first_error_line(log);
        throw PovrayError("povray failed (" + why + ")" + (err.empty() ? "" : ": " + err), tail(log, 20));
    }
    try {
        out.image = read_image(image.string());
    } catch (const InputError& e) {
        throw PovrayError(std::string("povray output unreadable: ") + e.what(), tail(log, 20));
    }
    if (out.image.width != width || out.image.height != height)
        throw PovrayError("povray wrote a " + std::to_string(out.image.width) + "x" + std::to_string(out.image.height) +
                              " image, expected " + std::to_string(width) + "x" + std::to_string(height),
                          tail(log, 20));
    return out;
}

}  // namespace refract::validation
