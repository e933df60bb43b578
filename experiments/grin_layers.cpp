// grin-layers: the layered Luneburg stack converging to the continuous lens (grin_layers.h).
#include <refract/experiments/grin_layers.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include <refract/core/render.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::grin_layers {
using nlohmann::json;

double shell_index(int k, int shells) {
    const double r = (k - 0.5) / shells;
    return std::sqrt(2 - r * r);
}

std::vector<int> shell_counts(bool quick) { return quick ? std::vector<int>{2, 4, 8, 16} : std::vector<int>{2, 4, 8, 16, 32, 64}; }

json lens_scene(int shells, const std::string& backdrop, bool compat, bool quick, double constant_ior) {
    json mats = json::object(), objects = json::array();
    json bg = {{"type", "gradient"}, {"bottom", vec(1, 1, 1)}, {"top", vec(0.1, 0.3, 0.9)}};
    if (backdrop == "checker") {
        bg = vec(0.55, 0.7, 0.9);
        mats["backdrop"] = {{"type", "diffuse"}, {"color", vec(0.95, 0.9, 0.8)}, {"ambient", 1}, {"diffuse", 0},
                            {"checker", {{"color2", vec(0.1, 0.2, 0.5)}, {"size", 1.0}}}};
        objects.push_back({{"type", "plane"}, {"name", "backdrop"}, {"normal", vec(0, 0, -1)}, {"offset", -2.5}, {"material", "backdrop"}});
    }
    const auto glass = [](double ior) { return json{{"type", "dielectric"}, {"ior", ior}, {"reflectance", "constant"}, {"reflectivity", 0}}; };
    int depth = 64;
    std::string what;
    if (constant_ior > 0) {
        mats["glass"] = glass(constant_ior);
        objects.push_back({{"type", "sphere"}, {"name", "glass"}, {"center", vec(0, 0, 0)}, {"radius", 1}, {"material", "glass"}});
        what = "a sphere of constant index " + fmt(constant_ior);
    } else if (shells == 0) {
        mats["lens"] = {{"type", "grin"}, {"profile", {{"kind", "luneburg"}, {"centre", vec(0, 0, 0)}, {"radius", 1}}}};
        objects.push_back({{"type", "sphere"}, {"name", "lens"}, {"center", vec(0, 0, 0)}, {"radius", 1}, {"material", "lens"}});
        what = "the continuous Luneburg lens";
    } else {
        // Sphere k's ior is the ratio of the shells its surface parts (inside over outside).
        for (int k = shells; k >= 1; --k) {
            const double outside = k == shells ? 1.0 : shell_index(k + 1, shells);
            const std::string name = "shell" + std::to_string(k);
            mats[name] = glass(shell_index(k, shells) / outside);
            objects.push_back({{"type", "sphere"}, {"name", name}, {"center", vec(0, 0, 0)}, {"radius", double(k) / shells}, {"material", name}});
        }
        depth = std::min(255, 4 * shells + 32);  // every crossing counts a level
        what = "the Luneburg lens as " + std::to_string(shells) + " constant-index shells (mid-radius indices)";
    }
    json render = {{"max_depth", depth}};
    if (compat) render["compat"] = "povray";
    return {{"description", "grin-layers: " + what + ", " + backdrop + " backdrop"},
            {"camera", {{"location", vec(0, 0.6, -4)}, {"look_at", vec(0, 0, 0)}, {"angle", 40},
                        {"width", quick ? 64 : 160}, {"height", quick ? 48 : 120}}},
            {"background", bg}, {"materials", mats}, {"objects", objects}, {"lights", json::array()}, {"render", render}};
}

namespace {

// Pixels whose primary ray meets the unit sphere at the origin.
std::vector<char> disk_mask(const Scene& s) {
    std::vector<char> m(static_cast<size_t>(s.camera.width) * s.camera.height, 0);
    for (int j = 0; j < s.camera.height; ++j)
        for (int i = 0; i < s.camera.width; ++i) {
            const Ray r = s.camera.ray(i + 0.5, j + 0.5);
            const Vec3 d = r.dir.normalized();
            m[static_cast<size_t>(j) * s.camera.width + i] = r.origin.cross(d).norm() < 1.0;
        }
    return m;
}

double disk_mean(const Image& a, const Image& b, const std::vector<char>& mask) {
    double sum = 0;
    size_t n = 0;
    for (size_t p = 0; p < mask.size(); ++p)
        if (mask[p])
            for (int c = 0; c < 3; ++c) sum += std::abs(a.rgb[3 * p + c] - b.rgb[3 * p + c]), ++n;
    return n ? sum / n : 0.0;
}

}  // namespace

Result compute(const ExperimentOptions& opt) {
    const auto t0 = std::chrono::steady_clock::now();
    Result res;
    res.quick = opt.quick;
    RenderOptions ro;
    ro.threads = opt.threads;
    for (const std::string backdrop : {"sky", "checker"}) {
        Series se;
        se.backdrop = backdrop;
        const Scene cont = scene_from_json(lens_scene(0, backdrop, false, opt.quick), "continuous.json");
        const auto mask = disk_mask(cont);
        res.width = cont.camera.width, res.height = cont.camera.height;
        res.disk_pixels = 0;
        for (char c : mask) res.disk_pixels += c;
        const RenderResult reference = render(cont, ro);
        se.continuous_seconds = reference.stats.seconds;
        // The floor: the same glass in both modes.
        const Image fc = render(scene_from_json(lens_scene(0, backdrop, true, opt.quick, 1.2), "floor.json"), ro).image;
        const Image fp = render(scene_from_json(lens_scene(0, backdrop, false, opt.quick, 1.2), "floor.json"), ro).image;
        se.floor_rmse = rmse(fc, fp);
        se.floor_disk = disk_mean(fc, fp, mask);
        std::vector<double> xs, yr, yd;
        for (int n : shell_counts(opt.quick)) {
            const RenderResult r = render(scene_from_json(lens_scene(n, backdrop, true, opt.quick), "stack.json"), ro);
            se.rows.push_back({n, rmse(r.image, reference.image), disk_mean(r.image, reference.image, mask), r.stats.seconds});
            xs.push_back(n), yr.push_back(se.rows.back().rmse), yd.push_back(se.rows.back().disk_mean);
        }
        se.rmse_fit = loglog_fit(xs, yr);
        se.disk_fit = loglog_fit(xs, yd);
        se.tail_fit = loglog_fit({xs.end() - 3, xs.end()}, {yd.end() - 3, yd.end()});
        res.series.push_back(std::move(se));
    }
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
}

void write(const Result& r, const std::string& dir) {
    ensure_dir(dir);
    const auto path = [&](const std::string& f) { return dir + "/" + f; };
    std::ostringstream md;
    md << "# grin-layers: a Luneburg lens as N constant-index shells against the continuous lens\n\n"
       << "The stack (shell k of N between (k − 1)/N and k/N, the profile's index at its mid radius, each sphere's "
          "`ior` the ratio of the shells it parts, constant reflectivity 0) in the POV-Ray compatibility mode, the "
          "continuous `grin` Luneburg lens (n = √(2 − r²)) in the physical mode; same camera, no lights, "
       << r.width << "×" << r.height << " pixels, " << r.disk_pixels << " on the lens's disk. "
       << "The stack for N = 8 is the validation case `grin-stack` (agrees with POV-Ray 3.7 to the output step).\n\n"
       << "`convergence.csv` (`backdrop,shells,rmse,disk_mean,seconds`), `convergence.png`.\n\n";
    Csv csv;
    csv.header = {"backdrop", "shells", "rmse", "disk_mean", "seconds"};
    for (const Series& s : r.series) {
        for (const Row& row : s.rows) csv.add({s.backdrop, std::to_string(row.shells), fmt(row.rmse), fmt(row.disk_mean), fmt(row.seconds)});
        md << "## " << s.backdrop << " backdrop\n\n| N | RMSE | mean abs diff on the disk |\n|---:|---:|---:|\n";
        for (const Row& row : s.rows) md << "| " << row.shells << " | " << fmt(row.rmse, 3) << " | " << fmt(row.disk_mean, 3) << " |\n";
        md << "\nFitted order (log-log slope over N = " << s.rows.front().shells << "–" << s.rows.back().shells
           << "): RMSE " << fmt(s.rmse_fit.slope, 3) << ", disk mean " << fmt(s.disk_fit.slope, 3)
           << ". Floor (a sphere of n = 1.2, compat against physical mode): RMSE " << fmt(s.floor_rmse, 3)
           << ", disk mean " << fmt(s.floor_disk, 3) << ".\n\n";
        // Findings by predicates on the numbers.
        bool monotone = true;
        for (size_t k = 1; k < s.rows.size(); ++k) monotone = monotone && s.rows[k].disk_mean < s.rows[k - 1].disk_mean;
        md << "- The disk's difference " << (monotone ? "falls at every doubling of N" : "does not fall at every doubling of N")
           << "; it falls as N^" << fmt(s.disk_fit.slope, 2) << ".\n";
        const double last = s.rows.back().disk_mean;
        md << "- Over the last three N it falls as N^" << fmt(s.tail_fit.slope, 2) << ".\n";
        if (s.floor_disk == 0)
            md << "- The floor is 0: the two modes render the constant-index sphere identically.\n\n";
        else
            md << "- At N = " << s.rows.back().shells << " it is " << fmt(last / s.floor_disk, 3)
               << (last > s.floor_disk ? "× the floor: the stack, not the modes, is what differs"
                                       : "× the floor: the modes' own difference dominates")
               << ".\n\n";
    }
    write_csv(path("convergence.csv"), csv);
    if (gnuplot_available()) {
        std::ostringstream b;
        b << "set datafile separator ','\nset logscale xy\nset format y '%g'\nset grid\nset key top right box opaque\nset yrange [0.005:2]\n"
          << "set xlabel 'shells N'\nset ylabel 'difference from the continuous lens'\n"
          << "set title 'Luneburg lens: N constant-index shells against the continuous grin'\nset xtics (2, 4, 8, 16, 32, 64)\n"
          << "plot ";
        int k = 0;
        for (const Series& s : r.series) {
            const std::string sel = "(strcol(1) eq '" + s.backdrop + "' ? $2 : NaN)";
            if (k++) b << ", \\\n     ";
            b << "'convergence.csv' using " << sel << ":3 every ::1 with linespoints pt 7 title '" << s.backdrop << ": RMSE', \\\n"
              << "     'convergence.csv' using " << sel << ":4 every ::1 with linespoints pt 5 title '" << s.backdrop
              << ": mean |Δ| on the disk (slope " << fmt(s.disk_fit.slope, 2) << ")'";
        }
        b << "\n";
        gnuplot_figure(dir, "convergence", b.str());
        md << "![convergence](convergence.png)\n";
    }
    md << "\nRun time " << fmt(r.seconds, 3) << " s" << (r.quick ? " (--quick)" : "") << ".\n";
    write_text_atomic(path("summary.md"), md.str());
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::grin_layers
