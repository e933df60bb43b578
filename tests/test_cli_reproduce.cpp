// `refract reproduce` where its validation cannot run: refused before any experiment, exit 2,
// one line, no output directory.
#include <catch2/catch.hpp>

#include <filesystem>
#include "tests/cli_run.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

TEST_CASE("refract reproduce: validation scenes not found, exit 2 with one line before any work", "[cli][errors]") {
    const fs::path dir = refract::test::fresh_dir("cli-reproduce", "scenes");
    const fs::path out = dir / "out";
    const auto r = refract::test::run("reproduce --quick -o " + out.string() + " --scenes " + (dir / "nope").string(), dir);
    refract::test::check_refused(r, "reproduce: the validation cannot run: ");
    CHECK(r.err.find("nope: no such scenes directory") != std::string::npos);
    CHECK(r.err.find("--skip-validation") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST_CASE("refract reproduce: POV-Ray not found, exit 2 with one line before any work", "[cli][errors]") {
    const fs::path dir = refract::test::fresh_dir("cli-reproduce", "povray");
    const fs::path out = dir / "out";
    const std::string scenes = std::string(REFRACT_SOURCE_DIR) + "/scenes/validation";
    const auto r = refract::test::run("reproduce --quick -o " + out.string() + " --scenes " + scenes, dir,
                                      "PATH=" + dir.string());
    refract::test::check_refused(r, "POV-Ray executable 'povray' not found");
    CHECK_FALSE(fs::exists(out));
    fs::remove_all(dir);
}
