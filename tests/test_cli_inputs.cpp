// The `refract` command's work and input bounds (issue 27): a ray tree too large to record,
// input from pipes and devices, images that are not regular files or are truncated, pixel
// options outside the image, ranges in option messages, huge echoed keys. Each refusal is
// one line and exit 2, quickly, in bounded memory (the commands run under a time and an
// address-space limit).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;
using refract::test::check_refused;
using refract::test::count_lines;
using refract::test::Run;
using refract::test::run;

namespace {

fs::path fresh_dir(const std::string& name) { return refract::test::fresh_dir("cli-inputs", name); }

// At most 60 s and 4 GB of address space, whatever the command does.
const std::string kBounded = "ulimit -v 4000000; timeout 60";

// Five glass plates 1 mm thick with 1 mm gaps across the z axis, threshold 1e-10: the
// tree of one ray along the axis has far more than 2^16 segments.
std::string five_plates() {
    std::string objects;
    for (int k = 0; k < 5; ++k) {
        const double z0 = 0.002 * k;
        objects += std::string(k ? ", " : "") + R"({"type": "polyhedron", "material": "glass", "planes": [[0,0,1,)" +
                   std::to_string(z0 + 0.001) + "], [0,0,-1," + std::to_string(-z0) +
                   R"(], [1,0,0,1], [-1,0,0,1], [0,1,0,1], [0,-1,0,1]]})";
    }
    return R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "materials": {"glass": {"type": "dielectric", "ior": 1.5}}, "objects": [)" +
           objects + R"(], "render": {"threshold": 1e-10, "max_depth": 10000}})";
}

const char* kSphere = R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "diffuse"}}]})";

// A 4×3 binary PPM, or one whose header announces 8192×8192 pixels over a 1 KB file.
void write_ppm(const fs::path& p, bool truncated) {
    std::ofstream f(p, std::ios::binary);
    f << (truncated ? "P6\n8192 8192\n255\n" : "P6\n4 3\n255\n") << std::string(truncated ? 1000 : 36, '\x40');
}

}  // namespace

TEST_CASE("refract trace: a tree past 2^16 segments (one ray into five close plates, threshold 1e-10) is refused "
          "naming /render, max_depth and threshold, in bounded memory",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("plates");
    std::ofstream{dir / "plates.json"} << five_plates();
    const std::string scene = (dir / "plates.json").string(), out = (dir / "t.json").string();
    const Run r = run("trace " + scene + " --ray 0 0 -1 0 0 1 -o " + out, dir, kBounded);
    check_refused(r, "plates.json: /render: one ray tree took more than 65536 segments");
    CHECK(r.err.find("max_depth 10000, threshold 1e-10") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    // A threshold the tree stays within: recorded.
    std::string fine = five_plates();
    fine.replace(fine.find("1e-10"), 5, "1e-3");
    std::ofstream{dir / "plates.json"} << fine;
    CHECK(run("trace " + scene + " --ray 0 0 -1 0 0 1 -o " + out, dir, kBounded).code == 0);
    CHECK(fs::exists(out));
    fs::remove_all(dir);
}

TEST_CASE("Scenes through a pipe or a device are bounded by the 64 MiB scene limit while read, and nested at most 64 "
          "deep",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("pipe");
    const std::string out = (dir / "o.png").string();
    // An endless '[' through a pipe: refused at 64 MiB, not read to exhaustion.
    check_refused(run("render /dev/stdin -o " + out, dir, "ulimit -v 4000000; yes '[' | timeout 60"),
                  "/dev/stdin: the scene file is longer than the limit of 64 MiB");
    check_refused(run("render /dev/zero -o " + out, dir, kBounded),
                  "/dev/zero: the scene file is longer than the limit of 64 MiB");
    CHECK_FALSE(fs::exists(out));
    // 65 levels of arrays in a small file.
    std::ofstream{dir / "deep.json"} << std::string(65, '[') << std::string(65, ']');
    check_refused(run("render " + (dir / "deep.json").string() + " -o " + out, dir), "deep.json: line 1: nested more than 64 levels deep");
    // A scene through a pipe within the limit is read as from a file.
    std::ofstream{dir / "s.json"} << kSphere;
    CHECK(run("trace /dev/stdin --pixel 2 1", dir, "cat " + (dir / "s.json").string() + " |").code == 0);
    fs::remove_all(dir);
}

TEST_CASE("Images read (measure, environment maps): a device, a directory, a missing file and a truncated PPM each "
          "refused with their own reason, before reading",
          "[cli][errors][limits]") {
    const fs::path dir = fresh_dir("images");
    fs::create_directories(dir / "adir");
    write_ppm(dir / "short.ppm", true);
    check_refused(run("measure /dev/zero", dir, kBounded), "/dev/zero: not a regular file");
    check_refused(run("measure " + (dir / "adir").string(), dir, kBounded), "adir: is a directory");
    check_refused(run("measure " + (dir / "none.ppm").string(), dir, kBounded), "none.ppm: no such file");
    // 1 KB announcing 8192×8192: refused before a pixel is allocated (1 GB of address space is plenty).
    const Run t = run("measure " + (dir / "short.ppm").string(), dir, "ulimit -v 1000000; timeout 60");
    check_refused(t, "short.ppm: truncated: its header announces a 8192x8192 P6 image of 201326592 bytes");
    for (const std::string& map : {(dir / "adir").string(), std::string("/dev/zero"), (dir / "short.ppm").string()}) {
        std::string scene = kSphere;
        scene.insert(scene.rfind('}'), R"(, "background": {"type": "environment", "map": ")" + map + "\"}");
        std::ofstream{dir / "env.json"} << scene;
        const Run r = run("trace " + (dir / "env.json").string() + " --pixel 2 1", dir, kBounded);
        check_refused(r, "env.json: /background/map: " + map + ": ");
        CHECK(r.err.find("no such file") == std::string::npos);
    }
    fs::remove_all(dir);
}

TEST_CASE("refract measure: a --region outside the image, reversed or negative is refused like --line, naming the "
          "option and the image's size",
          "[cli][errors]") {
    const fs::path dir = fresh_dir("region");
    write_ppm(dir / "img.ppm", false);
    const std::string img = (dir / "img.ppm").string();
    for (const char* region : {"0 0 10 10", "3 2 0 0", "-1 0 2 2"}) {
        const Run r = run("measure " + img + " --region " + region, dir);
        check_refused(r, "img.ppm: --region " + std::string(region) + ": needs 0 <= X0 <= X1 <= 3 and 0 <= Y0 <= Y1 <= 2");
        CHECK(r.err.find("(the image is 4x3)") != std::string::npos);
    }
    CHECK(run("measure " + img + " --region 0 0 3 2", dir).code == 0);  // the whole image
    check_refused(run("measure " + img + " --line 0 0 4 0", dir), "img.ppm: --line 0 0 4 0: both ends must be pixels");
    fs::remove_all(dir);
}

TEST_CASE("Options with a range say the range: validate --size 0 0 and its siblings", "[cli][errors]") {
    const fs::path dir = fresh_dir("ranges");
    const std::string out = " -o " + (dir / "v").string();
    check_refused(run("validate --random 1 --size 0 0" + out, dir), "--size: Value 0 not in range 1 to 4096");
    check_refused(run("validate --random 1 --size 80 5000" + out, dir), "--size: Value 5000 not in range 1 to 4096");
    check_refused(run("validate --random 1 --size 80 x" + out, dir), "--size: Value x not in range 1 to 4096");
    check_refused(run("validate --random -2" + out, dir), "--random: Value -2 not in range 0 to 1000000");
    check_refused(run("measure x.png --bins 0", dir), "--bins: Value 0 not in range 1 to 1048576");
    check_refused(run("farfield x.json -o " + (dir / "ff").string() + " --classes 1", dir), "--classes: Value 1 not in range 2 to 64");
    CHECK_FALSE(fs::exists(dir / "v"));
    fs::remove_all(dir);
}

TEST_CASE("Scene text echoed in a message is clipped: a 1 MB unknown key, and description must be a string",
          "[cli][errors]") {
    const fs::path dir = fresh_dir("echo");
    const std::string key(1 << 20, 'k');
    std::string scene = kSphere;
    scene.insert(scene.find("\"width\""), "\"" + key + "\": 1, ");
    std::ofstream{dir / "key.json"} << scene;
    const Run r = run("trace " + (dir / "key.json").string() + " --pixel 2 1", dir);
    check_refused(r, "key.json: /camera/" + std::string(64, 'k') + "\u2026(1048576 bytes): unknown field");
    CHECK(r.err.size() < 1000);
    for (const char* description : {"5", "[\"a\"]", "{}", "null"}) {
        scene = kSphere;
        scene.insert(1, std::string("\"description\": ") + description + ", ");
        std::ofstream{dir / "d.json"} << scene;
        check_refused(run("trace " + (dir / "d.json").string() + " --pixel 2 1", dir), "d.json: /description: must be a string");
    }
    scene = kSphere;
    scene.insert(1, "\"description\": \"a sphere\", ");
    std::ofstream{dir / "d.json"} << scene;
    CHECK(run("trace " + (dir / "d.json").string() + " --pixel 2 1", dir).code == 0);
    fs::remove_all(dir);
}

TEST_CASE("refract render and trace: a refractiveindex.info dispersion file with an unknown formula is refused "
          "naming the scene field, the file and the item, exit 2, nothing written",
          "[cli][errors][refractiveindex]") {
    const fs::path dir = fresh_dir("rii-formula");
    std::ofstream{dir / "bad.yml"} << "DATA:\n  - type: formula 12\n    wavelength_range: 0.3 1\n    coefficients: 1\n";
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "materials": {"glass": {"type": "dielectric", "dispersion": {"file": "bad.yml"}}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"}]})";
    const std::string scene = (dir / "s.json").string();
    const std::string line = "s.json: /materials/glass/dispersion/file: " + (dir / "bad.yml").string() +
                             ": /DATA/0/type: unknown formula \"12\" (formula 1–9)";
    check_refused(run("render " + scene + " -o " + (dir / "out.png").string(), dir, kBounded), line);
    CHECK_FALSE(fs::exists(dir / "out.png"));
    check_refused(run("trace " + scene + " --pixel 2 1 -o " + (dir / "t.json").string(), dir, kBounded), line);
    CHECK_FALSE(fs::exists(dir / "t.json"));
}

TEST_CASE("refract export-pov: a refractiveindex.info dispersion is refused with its label (POV-Ray has no "
          "Sellmeier law), and a thin lens is written as focal blur",
          "[cli][errors][refractiveindex]") {
    const fs::path dir = fresh_dir("rii-pov");
    const std::string data = std::string(REFRACT_SOURCE_DIR) + "/tests/data/refractiveindex/N-BK7.yml";
    fs::copy_file(data, dir / "N-BK7.yml");
    std::ofstream{dir / "s.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3},
        "materials": {"glass": {"type": "dielectric", "dispersion": {"file": "N-BK7.yml"}}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"}]})";
    const Run r = run("export-pov " + (dir / "s.json").string() + " -o " + (dir / "s.pov").string(), dir, kBounded);
    check_refused(r, "dispersion 'N-BK7.yml (refractiveindex.info formula 2)'");
    CHECK_FALSE(fs::exists(dir / "s.pov"));
    std::ofstream{dir / "lens.json"} << R"({"camera": {"location": [0,0,-4], "width": 4, "height": 3, "aperture": 0.25,
        "focus_distance": 3}, "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"type": "diffuse"}}],
        "render": {"samples": 16, "jitter": true}})";
    REQUIRE(run("export-pov " + (dir / "lens.json").string() + " -o " + (dir / "lens.pov").string(), dir, kBounded).code == 0);
    std::ifstream f(dir / "lens.pov");
    const std::string pov((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    CHECK(pov.find("aperture 0.5\n  focal_point <0, 0, -1>\n  blur_samples 16, 16") != std::string::npos);
}
