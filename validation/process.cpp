#include <refract/validation/process.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <optional>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include <refract/geometry/error.h>
#include <refract/geometry/signal_cleanup.h>

extern char** environ;

namespace refract::validation {

std::string ProcessResult::why() const {
    if (timed_out) return "timed out after " + std::to_string(static_cast<long>(seconds)) + " s";
    return exited ? "exit code " + std::to_string(status) : "signal " + std::to_string(status);
}

namespace {

// On SIGINT/SIGTERM (geometry/signal_cleanup.h): the child's process group is killed and
// the child reaped, so that no program refract started outlives it.
void kill_child(void* p) {
    const pid_t pid = static_cast<pid_t>(reinterpret_cast<std::intptr_t>(p));
    ::kill(-pid, SIGKILL);
    ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
}

// The child's entry in the signal cleanups, removed once it is reaped.
struct ChildOnSignal {
    int handle = -1;
    ~ChildOnSignal() { remove_signal_cleanup(handle); }
};

}  // namespace

ProcessResult run_process(const std::vector<std::string>& args, const ProcessOptions& opt) {
    if (args.empty()) throw InputError("run_process: no program");
    // Everything the child needs is built before fork (no allocation after it).
    std::vector<std::string> a = args, e = opt.env;
    std::vector<char*> argv, envp;
    for (auto& s : a) argv.push_back(s.data());
    argv.push_back(nullptr);
    if (!opt.inherit_env) {
        for (auto& s : e) envp.push_back(s.data());
        envp.push_back(nullptr);
    }
    const std::string out = opt.stdout_path.empty() ? "/dev/null" : opt.stdout_path;
    const std::string err = opt.stderr_path;
    const bool path_search = args[0].find('/') == std::string::npos;

    rusage before{};
    getrusage(RUSAGE_CHILDREN, &before);
    const auto t0 = std::chrono::steady_clock::now();
    ChildOnSignal on_signal;
    // SIGINT and SIGTERM wait (in this thread) until the child is registered for them.
    std::optional<SignalsHeld> held(std::in_place);
    const pid_t pid = ::fork();
    if (pid < 0) throw InputError("cannot start " + args[0] + ": " + std::strerror(errno));
    if (pid == 0) {
        held->in_child();  // the default actions and the signal mask it had
        ::setpgid(0, 0);  // its own process group, so a time-out kills it whole
        if (!opt.dir.empty() && ::chdir(opt.dir.c_str()) != 0) ::_exit(126);
        const int fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
        if (fd >= 0) {
            ::dup2(fd, 1);
            if (err.empty()) ::dup2(fd, 2);
            ::close(fd);
        }
        if (!err.empty()) {
            const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
            if (fe >= 0) {
                ::dup2(fe, 2);
                ::close(fe);
            }
        }
        const int devnull = ::open("/dev/null", O_RDONLY);
        if (devnull >= 0) ::dup2(devnull, 0);
        char** env = opt.inherit_env ? environ : envp.data();
        if (path_search) {
            environ = env;
            ::execvp(argv[0], argv.data());
        } else {
            ::execve(argv[0], argv.data(), env);
        }
        ::_exit(127);
    }
    ::setpgid(pid, pid);
    on_signal.handle = add_signal_cleanup(kill_child, reinterpret_cast<void*>(static_cast<std::intptr_t>(pid)));
    held.reset();
    ProcessResult r;
    int status = 0;
    while (true) {
        const pid_t w = ::waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) throw InputError("waiting for " + args[0] + ": " + std::strerror(errno));
        const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (el > opt.timeout_seconds) {
            ::kill(-pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            r.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rusage after{};
    getrusage(RUSAGE_CHILDREN, &after);
    const auto secs = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    r.cpu_seconds = secs(after.ru_utime) - secs(before.ru_utime) + secs(after.ru_stime) - secs(before.ru_stime);
    r.exited = WIFEXITED(status);
    r.status = r.exited ? WEXITSTATUS(status) : WTERMSIG(status);
    return r;
}

}  // namespace refract::validation
