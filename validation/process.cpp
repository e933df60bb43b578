#include <refract/validation/process.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include <refract/geometry/error.h>

extern char** environ;

namespace refract::validation {

std::string ProcessResult::why() const {
    if (timed_out) return "timed out after " + std::to_string(static_cast<long>(seconds)) + " s";
    return exited ? "exit code " + std::to_string(status) : "signal " + std::to_string(status);
}

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
    const pid_t pid = ::fork();
    if (pid < 0) throw InputError("cannot start " + args[0] + ": " + std::strerror(errno));
    if (pid == 0) {
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
