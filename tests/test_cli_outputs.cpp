// The command's outputs and the files it reads back (docs/limits.md "Files"): every
// output and sidecar checked before the work, nothing left on exit 2, journals read
// without following links and never quoted, an interrupted `validate` leaving no POV-Ray
// process, no temporary and no partial case directory.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/temp_dir.h"

extern char** environ;

namespace fs = std::filesystem;

namespace {

struct Run {
    int code;
    std::string err;
    double seconds;
};

Run run(const std::string& args, const fs::path& dir) {
    const fs::path err = dir / "stderr.txt";
    const std::string cmd = std::string(REFRACT_EXE) + " " + args + " 2>" + err.string() + " >/dev/null";
    const auto t0 = std::chrono::steady_clock::now();
    const int status = std::system(cmd.c_str());
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::ifstream f(err);
    std::stringstream text;
    text << f.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str(), s};
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Exit 2, one line on stderr naming `what`.
void check_refused(const Run& r, const std::string& what) {
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(what) != std::string::npos);
}

// Names in `dir`, but stderr.txt and those listed in `keep`.
std::vector<std::string> left_in(const fs::path& dir, const std::vector<std::string>& keep) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string n = e.path().filename().string();
        if (n != "stderr.txt" && std::find(keep.begin(), keep.end(), n) == keep.end()) names.push_back(n);
    }
    return names;
}

const char* kScene = R"({"camera": {"location": [0,0,-4], "width": 8, "height": 6},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "dielectric", "ior": 1.5}}]})";

const std::string kSweep = "sweep brilliant --crown-angle 30:31:1 --wavelengths 3 --threads 1 --quiet";
const std::string kSmallSweep = kSweep + " --rays 16";

}  // namespace

TEST_CASE("render: a sidecar name that is a directory (.lost.exr, .spectral.exr, .dolp.exr) is refused before the "
          "work, writing nothing",
          "[cli][errors][files]") {
    const fs::path dir = refract::test::fresh_dir("outputs", "sidecars");
    std::ofstream{dir / "s.json"} << kScene;
    std::string polarised = kScene;
    polarised.insert(polarised.rfind('}'), R"(, "render": {"polarisation": "exact"})");
    std::ofstream{dir / "p.json"} << polarised;
    const std::string out = (dir / "out.exr").string();
    const std::pair<std::string, std::string> cases[] = {
        {"render " + (dir / "s.json").string() + " -o " + out + " --lost-energy", "out.lost.exr"},
        {"render " + (dir / "s.json").string() + " -o " + out + " --spectral-channels", "out.spectral.exr"},
        {"render " + (dir / "p.json").string() + " -o " + out, "out.dolp.exr"},
    };
    for (const auto& [args, sidecar] : cases) {
        fs::create_directories(dir / sidecar);
        const Run r = run(args, dir);
        check_refused(r, sidecar);
        CHECK(r.err.find("is a directory") != std::string::npos);
        CHECK(left_in(dir, {"s.json", "p.json", sidecar}).empty());  // out.exr was not written
        fs::remove(dir / sidecar);
    }
    CHECK(run("render " + (dir / "p.json").string() + " -o " + out, dir).code == 0);  // the control
    for (const char* f : {"out.exr", "out.stokes.exr", "out.dolp.exr", "out.aolp.exr"}) CHECK(fs::is_regular_file(dir / f));
    fs::remove_all(dir);
}

TEST_CASE("sweep: an -o that is a directory, --rays below 16 and a range whose values overflow are refused before "
          "the work, leaving no journal",
          "[cli][errors][files][sweep]") {
    const fs::path dir = refract::test::fresh_dir("outputs", "sweep");
    fs::create_directories(dir / "adir.csv");
    const std::string out = (dir / "s.csv").string();
    const Run d = run(kSmallSweep + " -o " + (dir / "adir.csv").string(), dir);
    check_refused(d, "adir.csv: is a directory");
    CHECK(d.seconds < 5);  // refused at once, not after the sweep
    for (const char* rays : {"1", "15"}) {
        const Run r = run(kSweep + " --rays " + rays + " -o " + out, dir);
        check_refused(r, "--rays");
        CHECK(r.err.find("16") != std::string::npos);  // the library's lower limit
    }
    const Run big = run("sweep brilliant --crown-angle 999999999999999:999999999999999:0.000001 -o " + out, dir);
    check_refused(big, "--crown-angle");
    CHECK(big.err.find("too large") != std::string::npos);
    CHECK(left_in(dir, {"adir.csv"}).empty());  // no CSV, no journal
    CHECK(fs::is_empty(dir / "adir.csv"));
    CHECK(run(kSmallSweep + " -o " + out, dir).code == 0);  // the control
    fs::remove_all(dir);
}

TEST_CASE("sweep: a journal that is a link, a hard link, a directory or not refract's is refused with one line "
          "naming it, quoting nothing of it, and its target is left untouched",
          "[cli][errors][files][sweep]") {
    const fs::path dir = refract::test::fresh_dir("outputs", "journal");
    const fs::path secret = dir / "secret.txt";
    const std::string content = "SECRET-FIRST-LINE do not print\nsecond\n";
    std::ofstream{secret} << content;
    const std::string out = (dir / "s.csv").string();
    const auto attempt = [&](const std::string& planted, const std::string& says) {
        const Run r = run(kSmallSweep + " -o " + out, dir);
        check_refused(r, planted);
        CHECK(r.err.find(says) != std::string::npos);
        CHECK(r.err.find("SECRET") == std::string::npos);
        CHECK(slurp(secret) == content);
        CHECK_FALSE(fs::exists(out));
    };
    fs::create_symlink(secret, dir / "s.csv.journal");
    attempt("s.csv.journal", "symbolic link");
    fs::remove(dir / "s.csv.journal");
    fs::create_symlink(secret, dir / "s.csv.journal.3");  // an MPI rank's journal
    attempt("s.csv.journal.3", "symbolic link");
    fs::remove(dir / "s.csv.journal.3");
    fs::create_hard_link(secret, dir / "s.csv.journal");
    attempt("s.csv.journal", "hard links");
    fs::remove(dir / "s.csv.journal");
    fs::create_directories(dir / "s.csv.journal");
    attempt("s.csv.journal", "not a regular file");
    fs::remove(dir / "s.csv.journal");
    REQUIRE(::mkfifo((dir / "s.csv.journal").c_str(), 0644) == 0);  // no read blocks on it
    attempt("s.csv.journal", "not a regular file");
    fs::remove(dir / "s.csv.journal");
    std::ofstream{dir / "s.csv.journal"} << content;  // a regular file, not a journal
    attempt("s.csv.journal", "not a journal of refract sweep");
    fs::remove(dir / "s.csv.journal");
    CHECK(run(kSmallSweep + " -o " + out, dir).code == 0);  // the control
    CHECK_FALSE(fs::exists(dir / "s.csv.journal"));
    fs::remove_all(dir);
}

TEST_CASE("farfield: an output file name that is a directory is refused before the work, and a refused run removes "
          "the directory it made",
          "[cli][errors][files]") {
    const fs::path dir = refract::test::fresh_dir("outputs", "farfield");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "dielectric"}}],
        "lights": [{"type": "beam", "position": [0,0,-3], "direction": [0,0,1], "radius": 1}]})";
    const std::string scene = (dir / "s.json").string();
    fs::create_directories(dir / "ff" / "far_field.exr");
    const Run r = run("farfield " + scene + " -o " + (dir / "ff").string() + " --photons 100000000 --no-plot", dir);
    check_refused(r, "far_field.exr: is a directory");
    CHECK(r.seconds < 5);
    CHECK(left_in(dir / "ff", {"far_field.exr"}).empty());
    check_refused(run("farfield " + scene + " -o " + (dir / "new").string() + " --max-memory 100k", dir), "--max-memory");
    CHECK_FALSE(fs::exists(dir / "new"));  // made for the run, removed with its refusal
    fs::remove_all(dir);
}

TEST_CASE("validate: SIGTERM or SIGINT while POV-Ray runs kills and reaps it, removes its temporary directory and "
          "the partial case directory, and ends refract by the signal",
          "[cli][files]") {
    const fs::path dir = refract::test::fresh_dir("outputs", "validate");
    const fs::path scenes = dir / "scenes", tmp = dir / "tmp";
    fs::create_directories(scenes);
    fs::create_directories(tmp);
    std::ofstream{scenes / "slow.json"} << kScene;
    std::ofstream{scenes / "slow.tol.json"} << R"({"description": "POV-Ray that takes its time"})";
    // A POV-Ray that says where it runs, then sleeps (exec: the sleeping process is refract's child).
    const fs::path povray = dir / "povray", pid_file = dir / "povray.pid";
    std::ofstream{povray} << "#!/bin/sh\necho $$ > " << pid_file.string() << ".tmp\nmv " << pid_file.string()
                          << ".tmp " << pid_file.string() << "\nexec sleep 60\n";
    fs::permissions(povray, fs::perms::owner_all);
    for (const int sig : {SIGTERM, SIGINT}) {
        fs::remove(pid_file);
        const fs::path out = dir / "report";
        const std::string tmpdir = "TMPDIR=" + tmp.string();
        const std::vector<std::string> args{REFRACT_EXE, "validate", "slow", "--scenes", scenes.string(), "--povray",
                                            povray.string(), "-o", out.string(), "--threads", "1"};
        std::vector<char*> argv;
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        std::vector<std::string> env_text{tmpdir};
        for (char** e = environ; *e; ++e)
            if (std::string(*e).rfind("TMPDIR=", 0) != 0) env_text.push_back(*e);
        std::vector<char*> envp;
        for (auto& e : env_text) envp.push_back(e.data());
        envp.push_back(nullptr);
        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&fa, 2, (dir / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        pid_t pid = 0;
        REQUIRE(posix_spawn(&pid, REFRACT_EXE, &fa, nullptr, argv.data(), envp.data()) == 0);
        posix_spawn_file_actions_destroy(&fa);
        int status = 0;
        bool exited = false;
        for (int i = 0; i < 3000 && !fs::exists(pid_file); ++i) {  // up to 30 s for refract's own renders
            if (::waitpid(pid, &status, WNOHANG) == pid) {
                exited = true;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        INFO(slurp(dir / "stderr.txt"));
        REQUIRE_FALSE(exited);
        REQUIRE(fs::exists(pid_file));
        const pid_t pov = static_cast<pid_t>(std::stol(slurp(pid_file)));
        CHECK(fs::exists(out / "slow"));  // the case is half-way
        ::kill(pid, sig);
        ::waitpid(pid, &status, 0);
        CHECK(WIFSIGNALED(status));
        CHECK((WIFSIGNALED(status) && WTERMSIG(status) == sig));
        CHECK(::kill(pov, 0) != 0);  // killed and reaped: no such process
        CHECK(fs::is_empty(tmp));    // no refract-povray-* left
        CHECK_FALSE(fs::exists(out / "slow"));
        if (::kill(pov, 0) == 0) ::kill(pov, SIGKILL);
        fs::remove_all(out);
    }
    fs::remove_all(dir);
}
