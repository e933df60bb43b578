// Atomic, exclusive file writes (geometry/atomic_file.h): never half-written, never through
// a planted link, no temporary left behind on errors or on SIGTERM.
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>
#include "tests/temp_dir.h"

namespace fs = std::filesystem;
using namespace refract;

namespace {

fs::path fresh_dir(const std::string& name) { return refract::test::fresh_dir("atomic", name); }

int temporaries(const fs::path& d) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(d)) n += e.path().filename().string().find("refract-tmp") != std::string::npos;
    return n;
}

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("Atomic write: a link planted at the target is replaced, never followed", "[files][limits]") {
    const fs::path d = fresh_dir("link");
    { std::ofstream{d / "precious.txt"} << "keep"; }
    fs::create_symlink(d / "precious.txt", d / "out.txt");
    write_file_atomic((d / "out.txt").string(), "new");
    CHECK(read(d / "precious.txt") == "keep");
    CHECK_FALSE(fs::is_symlink(d / "out.txt"));
    CHECK(read(d / "out.txt") == "new");
    CHECK(temporaries(d) == 0);
    fs::remove_all(d);
}

TEST_CASE("Atomic write: errors name the path and leave no temporary — an uncommitted TempFile is removed",
          "[files][limits]") {
    const fs::path d = fresh_dir("errors");
    CHECK_THROWS_WITH(write_file_atomic((d / "no" / "x.txt").string(), "x"), Catch::Contains("no/x.txt"));
    fs::create_directories(d / "adir");
    CHECK_THROWS_WITH(write_file_atomic((d / "adir").string(), "x"), Catch::Contains("adir"));
    CHECK(temporaries(d) == 0);
    {
        TempFile t((d / "y.exr").string());
        CHECK(fs::exists(t.path()));
        CHECK(fs::path(t.path()).extension() == ".exr");
        CHECK(temporaries(d) == 1);
    }
    CHECK(temporaries(d) == 0);
    CHECK(random_token() != random_token());
    fs::remove_all(d);
}

TEST_CASE("SIGTERM during a write removes the temporary and ends the process by the signal", "[files][limits]") {
    const fs::path d = fresh_dir("signal");
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        install_temp_cleanup();
        TempFile t((d / "big.txt").string());
        const char c = 1;
        (void)!::write(ready[1], &c, 1);
        ::pause();  // killed here, mid-"write"
        ::_exit(0);
    }
    char c = 0;
    REQUIRE(::read(ready[0], &c, 1) == 1);
    CHECK(temporaries(d) == 1);
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGTERM);
    CHECK(temporaries(d) == 0);
    ::close(ready[0]);
    ::close(ready[1]);
    fs::remove_all(d);
}
