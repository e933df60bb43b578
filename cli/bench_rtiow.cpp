// refract bench --rtiow PATH: the RTIOW dielectric chapter's last scene (the hollow glass
// sphere, 400×225, 100 samples per pixel, depth 50) rendered by a build of the book's own
// code at PATH and by refract's stochastic integrator, paired (docs/performance.md says how
// to build the book's program; it writes its PPM to standard output).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include <refract/core/image.h>
#include <refract/core/render.h>
#include <refract/experiments/common.h>
#include <refract/experiments/rtiow.h>
#include <refract/geometry/error.h>
#include <refract/validation/files.h>
#include <refract/validation/process.h>

namespace refract::cli::bench {

namespace fs = std::filesystem;

namespace bench_rtiow_command {

// The mean of each channel over a grid of regions (the images are noisy at 100 spp: the
// same work shows as equal region means, not equal pixels).
std::vector<Vec3> region_means(const Image& img, int n) {
    std::vector<Vec3> m(static_cast<size_t>(n * n), Vec3(0, 0, 0));
    std::vector<int> count(m.size(), 0);
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i) {
            const size_t r = static_cast<size_t>(j * n / img.height * n + i * n / img.width);
            m[r] += img.at(i, j);
            ++count[r];
        }
    for (size_t r = 0; r < m.size(); ++r) m[r] /= count[r];
    return m;
}

std::string self_executable() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw InputError("bench: cannot find refract's own executable (/proc/self/exe)");
    return p.string();
}

}  // namespace bench_rtiow_command
using namespace bench_rtiow_command;

void rtiow(const std::string& book, int rounds) {
    if (::access(book.c_str(), X_OK) != 0) throw InputError("bench: --rtiow '" + book + "' is not an executable file");
    const nlohmann::json j = experiments::rtiow::stage_scene("fig1_29_hollow", false);
    const Scene scene = experiments::scene_from_json(j, "RTIOW hollow-sphere scene");
    char tmpl[] = "/tmp/refract-bench-XXXXXX";
    if (!::mkdtemp(tmpl)) throw InputError("bench: cannot create a temporary directory");
    const fs::path dir(tmpl);
    const std::string scene_path = (dir / "rtiow.json").string(), ppm = (dir / "book.ppm").string(),
                      png = (dir / "refract.png").string();
    validation::write_text_file(scene_path, j.dump(1));
    const std::string self = self_executable();
    std::printf("RTIOW dielectric chapter, hollow glass sphere: %dx%d, %d samples per pixel, depth 50; %d paired rounds\n",
                scene.camera.width, scene.camera.height, scene.settings.samples, rounds);
    print_load("before");
    const std::vector<std::string> names = {"the book's code (whole process, 1 thread)", "refract, 1 thread (render only)",
                                            "refract render, 1 thread (whole process)", "refract, 2 threads (render only)"};
    Image book_image, refract_image;
    std::string failure;
    const Paired p = paired_runs(names.size(), rounds, [&](size_t k) {
        if (k == 0 || k == 2) {
            validation::ProcessOptions po;
            po.stdout_path = k == 0 ? ppm : "";
            po.stderr_path = (dir / "stderr.txt").string();
            po.timeout_seconds = 3600;
            const std::vector<std::string> args =
                k == 0 ? std::vector<std::string>{book}
                       : std::vector<std::string>{self, "render", scene_path, "-o", png, "--threads", "1"};
            const auto r = validation::run_process(args, po);
            if (!r.ok() && failure.empty()) failure = args[0] + ": " + r.why();
            return;
        }
        RenderOptions opt;
        opt.threads = k == 1 ? 1 : 2;
        refract_image = render(scene, opt).image;
    });
    print_load("after");
    if (!failure.empty()) {
        fs::remove_all(dir);
        throw InputError("bench: " + failure);
    }
    book_image = read_image(ppm);
    fs::remove_all(dir);
    for (double& v : book_image.rgb) v = v * v;  // the book writes sqrt(colour): gamma 2
    std::printf("  %-44s %12s %10s %12s %10s\n", "", "wall median", "min", "CPU median", "min");
    for (size_t k = 0; k < names.size(); ++k)
        std::printf("  %-44s %12.3f %10.3f %12.3f %10.3f\n", names[k].c_str(), median(p.wall[k]), minimum(p.wall[k]),
                    median(p.cpu[k]), minimum(p.cpu[k]));
    const auto ratio = [&](const std::vector<std::vector<double>>& t, size_t num, size_t den) {
        std::vector<double> r;
        for (size_t i = 0; i < t[num].size(); ++i) r.push_back(t[num][i] / t[den][i]);
        return median(r);
    };
    std::printf("  book / refract, CPU, paired median: %.2fx render only, %.2fx whole process (target >= 2x)\n",
                ratio(p.cpu, 0, 1), ratio(p.cpu, 0, 2));
    std::printf("  refract 1 thread / 2 threads, wall, paired median: %.2fx (target >= 1.9x on an idle machine)\n",
                ratio(p.wall, 1, 3));
    // The same image: 8×8 region means of the linear values.
    if (book_image.width != refract_image.width || book_image.height != refract_image.height) {
        std::printf("  images differ in size (%dx%d against %dx%d)\n", book_image.width, book_image.height,
                    refract_image.width, refract_image.height);
        return;
    }
    const auto a = region_means(book_image, 8), b = region_means(refract_image, 8);
    double worst = 0, mean_a = 0, mean_b = 0;
    for (size_t r = 0; r < a.size(); ++r) {
        worst = std::fmax(worst, (a[r] - b[r]).cwiseAbs().maxCoeff() / std::fmax(1e-3, a[r].maxCoeff()));
        mean_a += a[r].mean() / a.size();
        mean_b += b[r].mean() / b.size();
    }
    std::printf("  same image? mean %.4f (book, 8-bit) against %.4f (refract); largest 8x8 region difference %.1f %%\n",
                mean_a, mean_b, 100 * worst);
}

}  // namespace refract::cli::bench
