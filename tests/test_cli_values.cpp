// The `refract` command on the values of issue 27's reproducers: colours that were written
// as infinite or negative pixels are refused on loading (exit 2, one line, nothing
// written), vectors of 1e200 keep their direction, and an index that goes negative between
// whole nanometres is refused before `trace` prints NaN.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace {

struct Run {
    int code;
    std::string out, err;
};

std::string read(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

Run run(const std::string& args, const fs::path& dir) {
    const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    const std::string cmd = std::string(REFRACT_EXE) + " " + args + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read(out), read(err)};
}

// A glass sphere on a diffuse floor; `extra` is spliced into the scene object.
std::string scene(const std::string& floor, const std::string& extra = "") {
    return R"({"camera": {"location": [0, 1, -6], "look_at": [0, 0.5, 0], "width": 8, "height": 6},
        "materials": {"glass": {"type": "dielectric", "ior": 1.5}, "floor": )" + floor + R"(},
        "objects": [{"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass"},
                    {"type": "plane", "normal": [0, 1, 0], "offset": 0, "material": "floor"}],
        "lights": [{"position": [5, 10, -5]}])" + extra + "}";
}

}  // namespace

TEST_CASE("refract render: colours that gave infinite or negative pixels with exit 0 are refused on loading (exit 2, "
          "one line, nothing written)",
          "[cli][errors][limits]") {
    const fs::path dir = refract::test::fresh_dir("cli-values", "render");
    const std::pair<std::string, std::string> cases[] = {
        {scene(R"({"type": "diffuse", "ambient": 1e300})"), "/materials/floor/ambient: must be in [0, 1e30] (got 1e+300)"},
        {scene(R"({"type": "diffuse", "color": [1e300, 1, 1]})"), "/materials/floor/color: components must be in [0, 1e30]"},
        {scene(R"({"type": "diffuse"})", R"(, "background": [1e300, 1e300, 1e300])"), "/background: components must be"},
        {scene(R"({"type": "diffuse"})", R"(, "background": [-1, 0, 0])"), "/background: components must be in [0, 1e30] (got -1)"},
        {scene(R"({"type": "diffuse", "diffuse": -5})"), "/materials/floor/diffuse: must be in [0, 1e30] (got -5)"},
        {scene(R"({"type": "diffuse", "ambient": -3})"), "/materials/floor/ambient"},
        {scene(R"({"type": "diffuse", "checker": {"color2": [-200, 0, 0]}})"), "/materials/floor/checker/color2"},
        {scene(R"({"type": "mirror", "color": [1e300, 1e300, 1e300]})"), "/materials/floor/color"},
    };
    const fs::path out = dir / "o.exr";
    for (const auto& [text, says] : cases) {
        std::ofstream{dir / "s.json"} << text;
        for (const std::string& opts : {std::string(), std::string(" --spectral-channels")}) {
            const Run r = run("render " + (dir / "s.json").string() + " -o " + out.string() + opts, dir);
            INFO(text << opts << "\n" << r.err);
            CHECK(r.code == 2);
            CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
            CHECK(r.err.find("s.json: " + says) != std::string::npos);
            CHECK_FALSE(fs::exists(out));
            CHECK_FALSE(fs::exists(dir / "o.spectral.exr"));
        }
    }
    // A filter of 1e300 was an internal error (exit 1) after the render.
    std::string filter = scene(R"({"type": "diffuse"})");
    filter.replace(filter.find(R"("ior": 1.5)"), 10, R"("ior": 1.5, "filter": [1e300, 1, 1])");
    std::ofstream{dir / "s.json"} << filter;
    const Run f = run("render " + (dir / "s.json").string() + " -o " + out.string(), dir);
    CHECK(f.code == 2);
    CHECK(f.err.find("/materials/glass/filter: components must be in [0, 1e30]") != std::string::npos);
    // The Stokes images of exact polarisation: written, S1–S3 signed, the rest >= 0.
    std::ofstream{dir / "s.json"} << scene(R"({"type": "diffuse"})", R"(, "render": {"polarisation": "exact"})");
    REQUIRE(run("render " + (dir / "s.json").string() + " -o " + out.string(), dir).code == 0);
    const refract::Channels stokes = refract::read_channels((dir / "o.stokes.exr").string());
    bool signed_seen = false;
    for (size_t k = 0; k < stokes.data.size(); ++k) {
        const std::string& name = stokes.names[k % stokes.names.size()];
        if (name[1] == '0') CHECK(stokes.data[k] >= 0);
        signed_seen = signed_seen || stokes.data[k] < 0;
    }
    CHECK(signed_seen);
    fs::remove_all(dir);
}

TEST_CASE("refract trace --ray and farfield --axis: a direction of 1e200 is the unit one, not (0, 0, 0)",
          "[cli][limits]") {
    const fs::path dir = refract::test::fresh_dir("cli-values", "vectors");
    std::ofstream{dir / "s.json"} << scene(R"({"type": "diffuse"})");
    const std::string s = (dir / "s.json").string();
    const Run unit = run("trace " + s + " --ray 0 1 -6 0 0 1", dir);
    const Run huge = run("trace " + s + " --ray 0 1 -6 0 0 1e200", dir);
    REQUIRE(unit.code == 0);
    REQUIRE(huge.code == 0);
    CHECK(huge.out == unit.out);  // was a ray along (0, 0, 0): the background only
    // Down to the floor, 45° (1e200 · (0, −1, 1) rescaled: the same to rounding).
    const Run down = run("trace " + s + " --ray 0 1 -6 0 -1 1", dir);
    const Run down_huge = run("trace " + s + " --ray 0 1 -6 0 -1e200 1e200", dir);
    REQUIRE(down_huge.code == 0);
    const auto a = nlohmann::json::parse(down.out), b = nlohmann::json::parse(down_huge.out);
    CHECK(a["segments"].size() == b["segments"].size());
    for (int c = 0; c < 3; ++c) CHECK(b["radiance"][c].get<double>() == Approx(a["radiance"][c].get<double>()).epsilon(1e-12));
    CHECK(a["radiance"][0].get<double>() > 0);
    CHECK(run("trace " + s + " --ray 0 1 -6 0 0 0", dir).code == 2);
    // The far field of a beam, along an axis given as 1e200 times +z.
    std::ofstream{dir / "b.json"} << R"({"camera": {"width": 4, "height": 3},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {"type": "dielectric"}}],
        "lights": [{"type": "beam", "position": [0, 0, -3], "direction": [0, 0, 1e200], "radius": 1}]})";
    const Run ff = run("farfield " + (dir / "b.json").string() + " -o " + (dir / "ff").string() +
                           " --axis 0 0 1e200 --photons 2000 --no-plot --threads 1",
                       dir);
    INFO(ff.err);
    REQUIRE(ff.code == 0);
    const refract::Channels map = refract::read_channels((dir / "ff" / "far_field.exr").string());
    REQUIRE(map.attribute("refract:far_field_axis"));
    CHECK(*map.attribute("refract:far_field_axis") == "0 0 1");
    const auto col = std::find(map.names.begin(), map.names.end(), "total");
    REQUIRE(col != map.names.end());
    double total = 0;
    for (size_t k = size_t(col - map.names.begin()); k < map.data.size(); k += map.names.size()) total += map.data[k];
    CHECK(total > 0);
    fs::remove_all(dir);
}

TEST_CASE("refract trace --wavelength 500.5: a crystal's index negative between whole nanometres is refused on "
          "loading, not printed as NaN",
          "[cli][errors][limits]") {
    const fs::path dir = refract::test::fresh_dir("cli-values", "dispersion");
    // n_o = (1/λ² − 1/0.5005²)² − 1e-6 (λ in µm): −1e-6 at 500.5 nm, +6.2e-5 at 500 and 501 nm.
    const std::string crystal = R"({"type": "uniaxial", "optic_axis": [0, 1, 0], "extraordinary": 1.5,
        "ordinary": {"model": "cauchy", "A": 15.936158680559116, "B": -7.9840239680399545, "C": 1.0}})";
    std::string text = scene(R"({"type": "diffuse"})");
    text.replace(text.find(R"({"type": "dielectric", "ior": 1.5})"), 34, crystal);
    std::ofstream{dir / "s.json"} << text;
    const Run r = run("trace " + (dir / "s.json").string() + " --ray 0 1 -6 0 0 1 --wavelength 500.5", dir);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find("s.json: /materials/glass/ordinary: the model gives n = -") != std::string::npos);
    CHECK(r.out.empty());  // was "radiance": [null, null, null] with exit 0
    fs::remove_all(dir);
}
