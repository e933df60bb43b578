#pragma once
// Running the real POV-Ray 3.7 on an exported scene: no antialiasing, no display,
// linear 16-bit PNG output (File_Gamma 1.0, step 1/65535, clipped to [0, 1]), in a
// temporary directory of its own with a clean environment and a time limit.
#include <stdexcept>
#include <string>
#include <vector>

#include <refract/core/image.h>

namespace refract::validation {

// POV-Ray could not be run or did not produce an image: not found on PATH, a parse or
// render error, a time-out, an unreadable output. `what()` is one line naming the cause;
// `log()` holds the tail of POV-Ray's own messages when it ran.
class PovrayError : public std::runtime_error {
public:
    PovrayError(const std::string& what, std::string log = {}) : std::runtime_error(what), log_(std::move(log)) {}
    const std::string& log() const { return log_; }

private:
    std::string log_;
};

struct PovrayOptions {
    std::string executable = "povray";  // a name looked up on PATH, or a path
    int threads = 2;                    // +WT<n>
    double timeout_seconds = 120;       // POV-Ray is killed after this
    // Files the scene refers to by name (an environment map), copied beside it into the
    // run's directory (under their own file names) before POV-Ray starts.
    std::vector<std::string> files;
};

struct PovrayRender {
    Image image;            // linear RGB as written by POV-Ray
    double seconds = 0;     // wall time of the POV-Ray run
    double cpu_seconds = 0; // its CPU time (user + system, every thread)
    std::string version;    // "POV-Ray 3.7.0.10..." from its banner
};

// Full path of the POV-Ray executable, or empty when it is not found (PATH lookup for a
// bare name).
std::string find_povray(const std::string& executable = "povray");

// Renders SDL text `pov_source` at width × height. Throws PovrayError.
PovrayRender render_povray(const std::string& pov_source, int width, int height, const PovrayOptions& opt = {});

}  // namespace refract::validation
