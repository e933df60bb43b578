#pragma once
// Running another program: the one way (POV-Ray runner, gnuplot, benchmarks) to start a
// process, wait for it with a time limit, and read how it ended.
#include <string>
#include <vector>

namespace refract::validation {

struct ProcessOptions {
    std::string dir;                  // working directory (empty: this process's)
    std::vector<std::string> env;     // "NAME=value" entries; with inherit_env false, the whole environment
    bool inherit_env = true;
    std::string stdout_path;          // file for the child's standard output (empty: /dev/null)
    std::string stderr_path;          // file for its standard error (empty: the same as stdout)
    double timeout_seconds = 120;     // the child's process group is killed after this
};

struct ProcessResult {
    bool timed_out = false;
    bool exited = false;   // ended by exit (status below) rather than a signal
    int status = 0;        // exit code, or the signal number
    double seconds = 0;    // wall time from start to end
    double cpu_seconds = 0;  // user + system CPU time of the child (and the children it waited for)
    bool ok() const { return !timed_out && exited && status == 0; }
    std::string why() const;  // "exit code 3", "signal 9", "timed out after 5 s"
};

// Runs args[0] (a path, or a name looked up on PATH) with args as its argv, its standard
// input /dev/null, in its own process group. Throws InputError when it cannot start.
ProcessResult run_process(const std::vector<std::string>& args, const ProcessOptions& opt);

}  // namespace refract::validation
