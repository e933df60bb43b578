#pragma once
// Running the `refract` executable in the command-line tests: its exit code and standard
// error, and the error contract (exit 2, one line naming the culprit).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace refract::test {

struct Run {
    int code;
    std::string err;
};

// `before`: what the shell runs before the command: variable assignments (VAR=value ...),
// or a pipe into it (`yes | `).
inline Run run(const std::string& args, const std::filesystem::path& dir, const std::string& before = "") {
    const std::filesystem::path err = dir / "stderr.txt";
    const std::string cmd = before + " " + REFRACT_EXE + " " + args + " 2>" + err.string() + " >/dev/null";
    const int status = std::system(cmd.c_str());
    std::ifstream f(err);
    std::stringstream s;
    s << f.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str()};
}

inline int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

// The error contract: exit 2 and one line on stderr naming `what`.
inline void check_refused(const Run& r, const std::string& what) {
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(what) != std::string::npos);
}

}  // namespace refract::test
