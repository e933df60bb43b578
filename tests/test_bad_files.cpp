// Bad files on the command line (issue 28): one line naming the file and the item, exit 2,
// nothing written. The .asc tier that cuts the stone away (test_gemcad.cpp) and the
// refractiveindex.info entry with an unknown formula (test_cli_inputs.cpp) are tested where
// their readers are; here the non-manifold transparent mesh, and the design refused by
// `refract metrics` and `refract sweep design` as by `refract cut asc`.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "tests/cli_run.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

TEST_CASE("A transparent mesh file with an edge shared by four triangles (two tetrahedra on one edge) exits 2 "
          "naming the file and the count, nothing written",
          "[meshfile][cli][errors]") {
    const fs::path dir = refract::test::fresh_dir("bad-files", "nonmanifold");
    // Each tetrahedron closed and outward; the second is the first turned half a turn about x.
    std::ofstream(dir / "bowtie.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nv 0 0 -1\n"
                                         "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
                                         "f 1 5 2\nf 1 2 6\nf 1 6 5\nf 2 5 6\n";
    std::ofstream(dir / "s.json") << R"({"camera": {"location": [0, 0, -5], "width": 8, "height": 6},
        "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
        "objects": [{"type": "mesh", "file": "bowtie.obj", "material": "glass"}]})";
    refract::test::check_refused(
        refract::test::run("render " + (dir / "s.json").string() + " -o " + (dir / "x.png").string(), dir),
        "s.json: /objects/0/file: " + (dir / "bowtie.obj").string() +
            ": a transparent mesh must be closed and consistently oriented: 0 open edges, 0 inconsistently oriented edges, 1 edges "
            "shared by more than two triangles");
    CHECK_FALSE(fs::exists(dir / "x.png"));
    fs::remove_all(dir);
}

TEST_CASE("A design whose tier cuts the stone away exits 2 naming the file and the tier in refract metrics and "
          "refract sweep design, nothing written",
          "[gemcad][cli][errors]") {
    const fs::path dir = refract::test::fresh_dir("bad-files", "away");
    std::ofstream(dir / "away.asc") << "GemCad 5.0\ng 96 0.0\ny 4 y\nI 1.54\nH test box\n"
                                       "a -90 1 0 n G 24 48 72\na 0 0.5 0 n T\na -0 0.5 0 n C\na 0 -0.75 0 n T2\n";
    const std::string away = (dir / "away.asc").string();
    refract::test::check_refused(refract::test::run("metrics " + away + " --aset " + (dir / "a.png").string(), dir),
                                 "away.asc: tier 4 ('T2', line 9) cuts the stone away");
    CHECK_FALSE(fs::exists(dir / "a.png"));
    refract::test::check_refused(
        refract::test::run("sweep design " + away + " --tier G:80:90:10 -o " + (dir / "s.csv").string(), dir),
        "away.asc: tier 4 ('T2', line 9) cuts the stone away");
    fs::remove_all(dir);
}
