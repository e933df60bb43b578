// The `refract` command on bad input: one line on stderr, exit code 2, no output file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include "tests/cli_run.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace {

using refract::test::check_refused;
using refract::test::count_lines;
using refract::test::Run;
using refract::test::run;

fs::path fresh_dir(const std::string& name) { return refract::test::fresh_dir("cli", name); }

}  // namespace

TEST_CASE("refract render: bad scenes exit 2 with one line and write nothing", "[cli][errors]") {
    const fs::path dir = fresh_dir("test");
    const fs::path scene = dir / "bad.json";
    const fs::path out = dir / "out.png";
    const char* cases[] = {
        R"({"camera": {"width": 8, "height": 6}, "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1,
            "material": {"type": "dielectric", "ior": -1}}]})",
        R"({"camera": {"width": 0, "height": 6}, "objects": []})",
        R"({"camera": {"width": 8, "height": 6}, "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1e999,
            "material": {"type": "diffuse"}}]})",
        R"({"camera": {"width": 8, "height": 6}, "objects": [})",
    };
    for (const char* text : cases) {
        std::ofstream{scene} << text;
        check_refused(run("render " + scene.string() + " -o " + out.string(), dir), "bad.json");
        CHECK_FALSE(fs::exists(out));
    }
    const Run missing = run("render " + (dir / "nope.json").string() + " -o " + out.string(), dir);
    CHECK(missing.code == 2);
    CHECK(missing.err.find("nope.json") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("refract render writes the image and prints the counters", "[cli]") {
    const fs::path dir = fresh_dir("ok");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 16, "height": 12},
        "background": [1, 1, 1], "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1,
        "material": {"type": "dielectric", "ior": 1.5}}], "render": {"threshold": 0, "max_depth": 200}})";
    const Run r = run("render " + (dir / "s.json").string() + " -o " + (dir / "s.exr").string() + " --stats", dir);
    CHECK(r.code == 0);
    CHECK(fs::exists(dir / "s.exr"));
    fs::remove_all(dir);
}

TEST_CASE("Resource limits: --threads outside [0, 1024] is refused with exit 2 in every subcommand, writing nothing",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("threads");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "diffuse"}}],
        "lights": [{"type": "beam", "position": [0,0,-3], "direction": [0,0,1], "radius": 1}]})";
    const std::string scene = (dir / "s.json").string(), out = (dir / "o.png").string();
    for (const std::string& args :
         {"render " + scene + " -o " + out + " --threads 70000", "render " + scene + " -o " + out + " --threads -1",
          "farfield " + scene + " -o " + (dir / "ff").string() + " --threads 70000",
          "experiment optics-bench -o " + (dir / "ob").string() + " --threads -2"}) {
        check_refused(run(args, dir), "threads");
    }
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(dir / "ff"));
    fs::remove_all(dir);
}

TEST_CASE("Resource limits: a render or far field past --max-memory is refused with exit 2, writing nothing",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("memory");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 400, "height": 300},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "dielectric"}}],
        "lights": [{"type": "beam", "position": [0,0,-3], "direction": [0,0,1], "radius": 1}]})";
    const std::string scene = (dir / "s.json").string(), out = (dir / "o.exr").string();
    for (const std::string& args : {"render " + scene + " -o " + out + " --max-memory 1M",
                                    "render " + scene + " -o " + out + " --max-memory lots",
                                    "farfield " + scene + " -o " + (dir / "ff").string() + " --max-memory 100k"}) {
        check_refused(run(args, dir), "--max-memory");
    }
    CHECK_FALSE(fs::exists(out));
    CHECK((!fs::exists(dir / "ff") || fs::is_empty(dir / "ff")));  // the output directory was checked, nothing written
    CHECK(run("render " + scene + " -o " + out + " --max-memory 64M", dir).code == 0);
    CHECK(fs::exists(out));
    fs::remove_all(dir);
}

TEST_CASE("Output paths are checked before the work: a missing directory, a directory, a format without a writer",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("out");
    fs::create_directories(dir / "sub");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "diffuse"}}]})";
    const std::string scene = (dir / "s.json").string();
    const std::pair<std::string, std::string> cases[] = {
        {(dir / "nodir" / "out.exr").string(), "does not exist"},
        {(dir / "sub").string() + "/", "unknown image extension"},
        {(dir / "sub.exr").string(), ""},  // fine: the control
        {(dir / "out.pfm").string(), "pfm"},
    };
    fs::create_directories(dir / "adir.exr");
    for (const auto& [out, says] : cases) {
        const Run r = run("render " + scene + " -o " + out, dir);
        if (says.empty()) {
            CHECK(r.code == 0);
            continue;
        }
        check_refused(r, says);
    }
    const Run d = run("render " + scene + " -o " + (dir / "adir.exr").string(), dir);
    CHECK(d.code == 2);
    CHECK(d.err.find("is a directory") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("The image module is loaded only for images: --help and trace run without it, and a module that cannot "
          "be loaded is bad input (exit 2), writing nothing",
          "[cli][errors]") {
    const fs::path dir = fresh_dir("module");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "diffuse"}}]})";
    const std::string scene = (dir / "s.json").string();
    const std::string missing = "REFRACT_IMAGE_IO=" + (dir / "missing.so").string();
    CHECK(run("--help", dir, missing).code == 0);
    CHECK(run("trace " + scene + " --pixel 2 1", dir, missing).code == 0);
    for (const char* out : {"out.png", "out.exr"}) {
        check_refused(run("render " + scene + " -o " + (dir / out).string(), dir, missing), "image module");
        CHECK_FALSE(fs::exists(dir / out));
    }
    fs::remove_all(dir);
}

TEST_CASE("Error contract: a field name's escape and newline are printed as hex escapes on one line — a missing povray "
          "is bad input (exit 2) in validate and bench",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("contract");
    std::ofstream{dir / "esc.json"} << "{\"camera\": {\"width\": 4, \"height\": 3, \"bad\\u001b[31m\\nkey\": 1}}";
    const Run esc = run("render " + (dir / "esc.json").string() + " -o " + (dir / "o.png").string(), dir);
    CHECK(esc.code == 2);
    CHECK(count_lines(esc.err) == 1);
    CHECK(esc.err.find('\x1b') == std::string::npos);
    CHECK(esc.err.find("bad\\x1b[31m\\x0akey") != std::string::npos);
    const Run val = run("validate fresnel-sphere -o " + (dir / "v").string() + " --povray refract-no-such-povray", dir);
    CHECK(val.code == 2);
    CHECK(count_lines(val.err) == 1);
    CHECK(val.err.find("refract-no-such-povray") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "v"));
    const Run bench = run("bench --povray refract-no-such-povray", dir);
    CHECK(bench.code == 2);
    CHECK(bench.err.find("not found") != std::string::npos);
    for (const char* t : {"nan", "-1"}) {
        const Run timeout = run(std::string("bench --no-povray --timeout ") + t, dir);
        CHECK(timeout.code == 2);
        CHECK(timeout.err.find("--timeout") != std::string::npos);
    }
    const Run name = run("validate ../x -o " + (dir / "v").string(), dir);
    CHECK(name.code == 2);
    CHECK(name.err.find("case names") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("An unwritable experiment or far-field output directory is bad input (exit 2), refused before the work",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("outdir");
    { std::ofstream{dir / "file"} << "x"; }  // a file where the directory would go
    const Run e = run("experiment optics-bench --quick -o " + (dir / "file" / "ob").string(), dir);
    CHECK(e.code == 2);
    CHECK(count_lines(e.err) == 1);
    CHECK(e.err.find("file/ob") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("refract trace --polarisation: each segment's Stokes vector written — a bad state exits 2 with one line "
          "and writes nothing",
          "[cli][errors]") {
    const fs::path dir = fresh_dir("tracepol");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"}]})";
    const std::string scene = (dir / "s.json").string(), out = (dir / "t.json").string();
    const std::string ray = " --ray 0 0.6 -4 0 0 1 -o " + out;
    CHECK(run("trace " + scene + ray + " --polarisation '{\"type\": \"linear\", \"angle\": 30}'", dir).code == 0);
    std::ifstream f(out);
    std::stringstream text;
    text << f.rdbuf();
    CHECK(text.str().find("\"stokes\"") != std::string::npos);
    CHECK(text.str().find("\"stokes_x\"") != std::string::npos);
    fs::remove(out);
    check_refused(run("trace " + scene + ray + " --polarisation '{\"type\": '", dir), "--polarisation");
    check_refused(run("trace " + scene + ray + " --polarisation sideways", dir), "unknown polarisation 'sideways'");
    check_refused(run("trace " + scene + ray + " --polarisation '{\"type\": \"linear\", \"angle\": 1e999}'", dir),
                  "--polarisation");
    CHECK_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST_CASE("refract trace through calcite: each segment inside names its wave (o/e) and its index in the JSON",
          "[cli][birefringence]") {
    const fs::path dir = fresh_dir("tracecalcite");
    // A calcite slab, optic axis at 45 degrees to its normal, seen straight down.
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,3,-3], "look_at": [0,0.3,0], "width": 4, "height": 3},
        "materials": {"calcite": {"type": "uniaxial", "crystal": "calcite", "optic_axis": [0.7071067811865476, 0.7071067811865476, 0]}},
        "objects": [{"type": "polyhedron", "material": "calcite",
                     "planes": [[1,0,0,1], [-1,0,0,1], [0,0,1,1], [0,0,-1,1], [0,1,0,0.55], [0,-1,0,-0.05]]}],
        "render": {"spectral": false, "max_depth": 3}})";
    const std::string out = (dir / "t.json").string();
    REQUIRE(run("trace " + (dir / "s.json").string() + " --ray 0.1 2 0.2 0 -1 0 -o " + out, dir).code == 0);
    std::ifstream f(out);
    std::stringstream text;
    text << f.rdbuf();
    const std::string t = text.str();
    CHECK(t.find("\"wave\": \"o\"") != std::string::npos);
    CHECK(t.find("\"wave\": \"e\"") != std::string::npos);
    CHECK(t.find("\"index\": 1.65") != std::string::npos);  // n_o of calcite at the D line, 1.6583
    CHECK(t.find("\"index\": 1.56") != std::string::npos);  // n_e(45°) = 1.5652
    CHECK(t.find("\"wave_normal\"") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("Command-line slips: an unknown command, subcommand or option names the nearest known one, and --version",
          "[cli][errors]") {
    const fs::path dir = fresh_dir("slips");
    check_refused(run("rendr scene.json -o x.png", dir), "unknown command 'rendr' (did you mean 'render'?)");
    check_refused(run("frobnicate", dir), "unknown command 'frobnicate' (see --help)");
    check_refused(run("cut brillant -o x.obj", dir), "unknown subcommand 'brillant' of 'cut' (did you mean 'brilliant'?)");
    check_refused(run("render scene.json -o x.png --thread 2", dir), "unknown option '--thread' (did you mean '--threads'?)");
    check_refused(run("farfield s.json -o d --photon 10", dir), "unknown option '--photon' (did you mean '--photons'?)");
    // A word far from every option keeps the parser's own message.
    check_refused(run("render scene.json -o x.png --zzzzzzzz", dir), "--zzzzzzzz");
    CHECK(!fs::exists(dir / "x.png"));

    const fs::path out = dir / "version.txt";
    const std::string cmd = std::string(REFRACT_EXE) + " --version >" + out.string() + " 2>&1";
    CHECK(std::system(cmd.c_str()) == 0);
    std::ifstream f(out);
    std::string line;
    std::getline(f, line);
    CHECK(line.rfind("refract ", 0) == 0);
    CHECK(line.size() > 8);
}

TEST_CASE("render --seed replaces the scene's render.seed, and a negative seed is refused, not wrapped", "[cli]") {
    const fs::path dir = fresh_dir("seed");
    std::ifstream in(std::string(REFRACT_SOURCE_DIR) + "/scenes/rtiow/convergence_stochastic.json");
    std::stringstream text;
    text << in.rdbuf();
    std::string scene = text.str();
    const auto set = [&](const std::string& key, const std::string& from, const std::string& to) {
        const size_t at = scene.find("\"" + key + "\": " + from);
        REQUIRE(at != std::string::npos);
        scene.replace(at, key.size() + 4 + from.size(), "\"" + key + "\": " + to);
    };
    set("samples", "1024", "4");
    set("width", "200", "24");
    set("height", "112", "14");
    std::ofstream(dir / "s.json") << scene;
    const auto bytes = [&](const std::string& name) {
        std::ifstream f(dir / name, std::ios::binary);
        std::stringstream s;
        s << f.rdbuf();
        return s.str();
    };
    const std::string s = (dir / "s.json").string();
    REQUIRE(run("render " + s + " -o " + (dir / "scene7.png").string(), dir).code == 0);
    REQUIRE(run("render " + s + " --seed 7 -o " + (dir / "seed7.png").string(), dir).code == 0);
    REQUIRE(run("render " + s + " --seed 8 -o " + (dir / "seed8.png").string(), dir).code == 0);
    CHECK(bytes("scene7.png") == bytes("seed7.png"));
    CHECK(bytes("seed7.png") != bytes("seed8.png"));
    check_refused(run("render " + s + " --seed -1 -o " + (dir / "neg.png").string(), dir), "--seed");
    check_refused(run("farfield " + s + " --seed -1 -o " + (dir / "ff").string(), dir), "--seed");
    CHECK(!fs::exists(dir / "neg.png"));
}
