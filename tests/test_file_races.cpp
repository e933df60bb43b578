// The temporary-file race (docs/limits.md "Files"): while refract writes images, another
// process swaps every temporary it can see (the file inside the private directory, the
// private directory itself, a bare .refract-tmp-* file) for a link to a victim. Images
// are written through the descriptor refract created, so the victim is never written and
// the output is the image or a refusal, never the victim's bytes.
#include <catch2/catch.hpp>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <dirent.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <refract/core/image.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>
#include "tests/temp_dir.h"

namespace fs = std::filesystem;
using namespace refract;

namespace {

constexpr const char* kPrecious = "precious: never to be written by refract\n";

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// One attacker's round over `dir`: each `.refract-tmp-*` entry swapped for a link to the
// victim (a file: replaced; a directory: its files replaced, or the directory moved away and
// replaced). Returns the swaps made. What it cannot do (another user's 0700 directory) fails
// quietly.
int attack_round(const fs::path& dir, const fs::path& victim_file, const fs::path& victim_dir, unsigned& turn) {
    int swaps = 0;
    DIR* d = ::opendir(dir.c_str());
    if (!d) return 0;
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(d)) {
        const std::string n = e->d_name;
        if (n.rfind(".refract-tmp-", 0) == 0) names.push_back(n);
        if (n.rfind(".moved-", 0) == 0) ::rmdir((dir / n).c_str());  // emptied by refract's rename: gone
    }
    ::closedir(d);
    for (const auto& n : names) {
        const fs::path p = dir / n;
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0) continue;
        if (S_ISLNK(st.st_mode)) {  // a link of an earlier round: removed, keeping the directory small
            ::unlink(p.c_str());
            continue;
        }
        const fs::path link = dir / (".atk-" + std::to_string(::getpid()) + "-" + std::to_string(++turn));
        if (S_ISREG(st.st_mode)) {  // a bare temporary: the race of old
            if (::symlink(victim_file.c_str(), link.c_str()) == 0 && ::rename(link.c_str(), p.c_str()) == 0) ++swaps;
        } else if (S_ISDIR(st.st_mode) && turn % 2 == 0) {  // the private directory, moved away
            const fs::path moved = dir / (".moved-" + std::to_string(::getpid()) + "-" + std::to_string(turn));
            if (::rename(p.c_str(), moved.c_str()) == 0) {
                ++swaps;
                (void)::symlink(victim_dir.c_str(), p.c_str());
            }
        } else if (S_ISDIR(st.st_mode)) {  // the files inside it
            DIR* inner = ::opendir(p.c_str());
            if (!inner) continue;
            std::vector<std::string> files;
            while (const dirent* e = ::readdir(inner))
                if (e->d_name[0] != '.') files.push_back(e->d_name);
            ::closedir(inner);
            for (const auto& f : files)
                if (::symlink(victim_file.c_str(), link.c_str()) == 0 && ::rename(link.c_str(), (p / f).c_str()) == 0)
                    ++swaps;
            ::unlink(link.c_str());
        }
    }
    return swaps;
}

// Image magic numbers: the output is an image or absent, never the victim.
bool is_image_or_absent(const fs::path& p) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) return true;
    if (!S_ISREG(st.st_mode)) return false;
    const std::string head = slurp(p).substr(0, 4);
    return head == std::string("\x76\x2f\x31\x01", 4) || head == "\x89PNG";
}

struct Victims {
    fs::path file, dir;
    explicit Victims(const fs::path& root) : file(root / "victim.txt"), dir(root / "victim-dir") {
        fs::create_directories(dir);
        std::ofstream{file} << kPrecious;
        // What a write through the moved directory's link would reach: the temporary
        // inside it is named after the target.
        for (const char* n : {"out.exr", "out.png"}) std::ofstream{dir / n} << kPrecious;
    }
    bool untouched() const {
        return slurp(file) == kPrecious && slurp(dir / "out.exr") == kPrecious && slurp(dir / "out.png") == kPrecious &&
               std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) == 2;
    }
};

struct Tally {
    int written = 0, refused = 0, bad_outputs = 0;
};

// 1 000 small images, EXR and PNG in turn, into `out_dir` while the attack runs.
Tally write_images(const fs::path& out_dir, const Victims& v) {
    Tally t;
    Image img(4, 3);
    for (int i = 0; i < 1000; ++i) {
        img.set(i % 4, (i / 4) % 3, {0.25, 0.5, 0.75});
        const fs::path out = out_dir / (i % 2 ? "out.png" : "out.exr");
        try {
            write_image(out.string(), img);
            ++t.written;
        } catch (const InputError& e) {
            ++t.refused;
            CHECK_THAT(e.what(), Catch::Matchers::StartsWith(out.string()));
        }
        t.bad_outputs += !is_image_or_absent(out);
        if (i % 100 == 0) REQUIRE(v.untouched());
    }
    return t;
}

}  // namespace

TEST_CASE("Temporary-file race: 1000 image writes while a thread swaps every temporary for a link never write the "
          "victim, and each output is the image or a refusal",
          "[files][limits]") {
    const fs::path root = test::fresh_dir("race", "thread");
    const fs::path out_dir = root / "out";
    fs::create_directories(out_dir);
    const Victims v(root);
    std::atomic<bool> stop{false};
    std::atomic<int> swaps{0};
    std::thread attacker([&] {
        unsigned turn = 0;
        while (!stop.load()) {
            swaps += attack_round(out_dir, v.file, v.dir, turn);
            ::usleep(20);  // a breath for the writer on a loaded machine
        }
    });
    const Tally t = write_images(out_dir, v);
    stop = true;
    attacker.join();
    INFO("written " << t.written << ", refused " << t.refused << ", swaps " << swaps.load());
    CHECK(v.untouched());
    CHECK(t.bad_outputs == 0);
    CHECK(t.written + t.refused == 1000);
    CHECK(t.written > 0);
    CHECK(swaps.load() > 0);  // the race was run, not missed
    fs::remove_all(root);
}

TEST_CASE("Temporary-file race, another user: as root, writing into a 0777 directory while a process of user "
          "nobody swaps the temporaries, the victim is never written",
          "[files][limits]") {
    if (::geteuid() != 0) {
        WARN("not root: the other-user variant is skipped");
        return;
    }
    const fs::path root = test::fresh_dir("race", "nobody");
    const fs::path out_dir = root / "out";
    fs::create_directories(out_dir);
    ::chmod(root.c_str(), 0755);
    ::chmod(out_dir.c_str(), 0777);
    const Victims v(root);
    int counter[2];
    REQUIRE(::pipe(counter) == 0);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::close(counter[0]);
        if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(3);
        unsigned turn = 0;
        for (;;) {
            const int n = attack_round(out_dir, v.file, v.dir, turn);
            if (n > 0) (void)!::write(counter[1], &n, sizeof n);
            ::usleep(20);
        }
    }
    ::close(counter[1]);
    const Tally t = write_images(out_dir, v);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    int swaps = 0, n = 0;
    while (::read(counter[0], &n, sizeof n) == static_cast<ssize_t>(sizeof n)) swaps += n;
    ::close(counter[0]);
    INFO("written " << t.written << ", refused " << t.refused << ", swaps by nobody " << swaps);
    CHECK(v.untouched());
    CHECK(t.bad_outputs == 0);
    CHECK(t.written + t.refused == 1000);
    CHECK(swaps > 0);
    fs::remove_all(root);
}

TEST_CASE("Every image format refract writes goes through the temporary's descriptor and reads back", "[files]") {
    const fs::path dir = test::fresh_dir("race", "formats");
    Image img(5, 3);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 5; ++i) img.set(i, j, {0.1 * i, 0.2 * j, 0.5});
    for (const char* ext : {".exr", ".hdr", ".tif", ".png", ".jpg", ".ppm", ".bmp"}) {
        INFO(ext);
        const fs::path out = dir / (std::string("img") + ext);
        write_image(out.string(), img);
        const Image back = read_image(out.string());
        REQUIRE(back.width == 5);
        REQUIRE(back.height == 3);
        const bool linear = std::string(ext) == ".exr" || std::string(ext) == ".hdr" || std::string(ext) == ".tif";
        // Linear formats hold the value (.hdr: 8-bit mantissas); the others hold it sRGB-encoded.
        const double expected = linear ? 0.4 : srgb_encode(0.4);
        CHECK(back.at(2, 2)[1] == Approx(expected).margin(std::string(ext) == ".jpg" ? 0.05 : 0.01));
    }
    for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().rfind(".refract-tmp", 0) != 0);
    fs::remove_all(dir);
}
