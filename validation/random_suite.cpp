#include <refract/validation/random_suite.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/geometry/signal_cleanup.h>
#include <refract/validation/files.h>
#include <refract/validation/knife_edge.h>
#include <refract/validation/pov_export.h>

namespace refract::validation {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* outcome_name(Comparison::Outcome o) {
    switch (o) {
        case Comparison::Outcome::Pass: return "PASS";
        case Comparison::Outcome::Fail: return "FAIL";
        case Comparison::Outcome::Skip: return "SKIP";
    }
    return "?";
}

std::string short_number(double v) {
    std::ostringstream o;
    o.precision(3);
    o << v;
    return o.str();
}

std::string diff_summary(const ImageDifference& d) {
    return "rmse " + short_number(d.rmse) + ", " + short_number(100.0 * d.fraction_over) + " % of pixels over, max " +
           short_number(d.max_error) + " at (" + std::to_string(d.max_x) + ", " + std::to_string(d.max_y) + ")";
}

std::string knife_edge_summary(int pixels, const ImageDifference& outside) {
    return std::to_string(pixels) + " knife-edge pixel" + (pixels == 1 ? "" : "s") + " set aside: rmse " +
           short_number(outside.rmse) + " outside them";
}

}  // namespace

Comparison compare_with_povray(const json& scene_json, const std::string& name, const Targets& targets,
                               const PovrayOptions& povray, int threads) {
    Comparison c;
    Scene scene;
    std::string pov;
    try {
        scene = parse_scene(scene_json, name);
        scene.settings.compat = Compat::PovRay;
        pov = export_pov(scene);
    } catch (const std::exception& e) {
        c.reason = std::string("not expressible: ") + e.what();
        return c;
    }
    try {
        RenderOptions ro;
        ro.threads = threads;
        const RenderResult r = render(scene, ro);
        c.refract = clamp01(r.image);  // POV-Ray's 16-bit PNG holds [0, 1]
        c.refract_seconds = r.stats.seconds;
    } catch (const std::exception& e) {
        c.reason = std::string("refract: ") + e.what();
        return c;
    }
    // POV-Ray is run a second time when it fails: under a heavy load a run has been
    // seen to exit with status 1 on a scene that renders on the next try.
    for (int attempt = 0;; ++attempt) {
        try {
            PovrayOptions po = povray;
            po.threads = std::max(1, threads);
            const PovrayRender pr = render_povray(pov, scene.camera.width, scene.camera.height, po);
            c.povray = pr.image;
            c.povray_seconds = pr.seconds;
            break;
        } catch (const std::exception& e) {
            if (attempt == 0) continue;
            c.reason = std::string("povray: ") + e.what();
            return c;
        }
    }
    c.diff = compare_images(c.refract, c.povray, targets.pixel_tolerance);
    c.outcome = targets.met_by(c.diff) ? Comparison::Outcome::Pass : Comparison::Outcome::Fail;
    if (c.outcome == Comparison::Outcome::Fail && c.diff.fraction_over <= targets.max_fraction_over) {
        try {
            const std::vector<char> edges = knife_edge_pixels(scene, c.refract, targets.pixel_tolerance, threads);
            if (met_outside_knife_edges(c.refract, c.povray, edges, targets, c.knife_edge_pixels,
                                        c.diff_outside_knife_edges))
                c.outcome = Comparison::Outcome::Pass;
            else
                c.knife_edge_pixels = 0;
        } catch (const std::exception& e) {
            c.reason = std::string("refract (camera shifted): ") + e.what();
        }
    }
    return c;
}

namespace {

// Smaller variants of a scene, the biggest reductions first.
std::vector<json> shrink_candidates(const json& s) {
    std::vector<json> out;
    const auto& objs = s.at("objects");
    if (objs.size() > 1)
        for (size_t k = 0; k < objs.size(); ++k) {
            json c = s;
            c["objects"].erase(k);
            out.push_back(std::move(c));
        }
    if (s.contains("lights"))
        for (size_t k = 0; k < s["lights"].size(); ++k) {
            json c = s;
            c["lights"].erase(k);
            out.push_back(std::move(c));
        }
    const int depth = s.contains("render") && s["render"].contains("max_depth") ? s["render"]["max_depth"].get<int>() : 16;
    std::vector<int> depths{0, 1, depth / 2, depth - 1};
    std::sort(depths.begin(), depths.end());
    depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
    for (int d : depths)
        if (d >= 0 && d < depth) {
            json c = s;
            c["render"]["max_depth"] = d;
            out.push_back(std::move(c));
        }
    if (s.contains("materials"))
        for (const auto& [name, m] : s["materials"].items()) {
            if (!m.is_object() || !m.contains("dispersion")) continue;
            {
                json c = s;
                c["materials"][name].erase("dispersion");
                out.push_back(std::move(c));
            }
            const json& d = m["dispersion"];
            if (!d.is_object() || !d.contains("samples")) continue;
            const int n = d["samples"].get<int>();
            for (int k : {2, n / 2, n - 1})
                if (k >= 2 && k < n) {
                    json c = s;
                    c["materials"][name]["dispersion"]["samples"] = k;
                    out.push_back(std::move(c));
                }
        }
    const json& cam = s.at("camera");
    const int w = cam.value("width", 320), h = cam.value("height", 240);
    if (w >= 16 && h >= 16) {
        json c = s;
        c["camera"]["width"] = w / 2;
        c["camera"]["height"] = h / 2;
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace

ShrinkResult shrink_failure(const json& scene, const Comparison& failing, const Targets& targets,
                            const PovrayOptions& povray, int threads, int max_attempts, const std::string& name) {
    ShrinkResult r{scene, failing, 0, 0};
    bool progress = true;
    while (progress && r.attempts < max_attempts) {
        progress = false;
        for (json& cand : shrink_candidates(r.scene)) {
            if (r.attempts >= max_attempts) break;
            ++r.attempts;
            Comparison c = compare_with_povray(cand, name, targets, povray, threads);
            if (c.outcome != Comparison::Outcome::Fail) continue;
            r.scene = std::move(cand);
            r.comparison = std::move(c);
            ++r.accepted;
            progress = true;
            break;
        }
    }
    return r;
}

namespace {

void write_failure_images(const fs::path& dir, const std::string& prefix, const Comparison& c) {
    write_image((dir / (prefix + "refract.png")).string(), c.refract);
    write_image((dir / (prefix + "povray.png")).string(), c.povray);
    write_heatmap((dir / (prefix + "diff.png")).string(), c.refract, c.povray);
}

RandomCase run_one(std::uint64_t seed, const RandomOptions& opt) {
    const auto t0 = std::chrono::steady_clock::now();
    RandomCase rc;
    rc.seed = seed;
    const RandomSceneFiles sf = random_scene_files(seed, opt.scene);
    const json& scene = sf.scene;
    rc.description = scene.value("description", "");
    const fs::path dir = fs::path(opt.out_dir) / ("seed-" + std::to_string(seed));
    // The case's directory: made for a failure, or first for a scene that names files
    // (written beside its scene.json, removed again when the case passes or is skipped).
    std::error_code ec;
    std::unique_ptr<TreeOnSignal> partial;  // removed on SIGINT/SIGTERM while this run writes it
    bool made = false;
    const auto make_dir = [&] {
        if (!rc.dir.empty()) return;
        if (!fs::exists(fs::symlink_status(dir, ec))) {
            partial = std::make_unique<TreeOnSignal>(dir.c_str());
            made = true;
        }
        fs::create_directories(dir);
        rc.dir = dir.string();
        write_text_file((dir / "scene.json").string(), scene.dump(2) + "\n");
    };
    std::string name = "random-" + std::to_string(seed);
    if (!sf.files.empty()) {
        make_dir();
        for (const auto& [file, text] : sf.files) write_text_file((dir / file).string(), text);
        name = (dir / "scene.json").string();
    }
    const Comparison c = compare_with_povray(scene, name, opt.targets, opt.povray, 1);
    rc.outcome = c.outcome;
    rc.reason = c.reason;
    rc.diff = c.diff;
    rc.knife_edge_pixels = c.knife_edge_pixels;
    rc.diff_outside_knife_edges = c.diff_outside_knife_edges;
    if (c.outcome != Comparison::Outcome::Fail && !rc.dir.empty() && made) {
        fs::remove_all(dir, ec);
        rc.dir.clear();
    }
    if (c.outcome == Comparison::Outcome::Fail) {
        make_dir();
        write_failure_images(dir, "", c);
        if (opt.shrink) {
            ShrinkResult s = shrink_failure(scene, c, opt.targets, opt.povray, 1, opt.max_shrink_attempts, name);
            json minimal = s.scene;
            minimal["description"] = "minimal failing case shrunk from random seed " + std::to_string(seed) + " (" +
                                     std::to_string(s.accepted) + " reductions)";
            s.scene = minimal;
            write_text_file((dir / "minimal.json").string(), minimal.dump(2) + "\n");
            write_failure_images(dir, "minimal-", s.comparison);
            Scene ms = parse_scene(minimal, (dir / "minimal.json").string());
            ms.settings.compat = Compat::PovRay;
            write_text_file((dir / "minimal.pov").string(), export_pov(ms));
            rc.minimal = std::move(s);
        }
    }
    rc.seconds = seconds_since(t0);
    return rc;
}

}  // namespace

RandomResult run_random(const RandomOptions& opt, std::ostream* progress) {
    if (opt.count < 0) throw InputError("validate: --random must be >= 0");
    std::error_code ec;
    fs::create_directories(opt.out_dir, ec);
    if (ec) throw InputError(opt.out_dir + ": cannot create output directory: " + ec.message());
    RandomResult result;
    result.cases.resize(static_cast<size_t>(opt.count));
    const int jobs = std::max(1, std::min(opt.count, opt.jobs > 0 ? opt.jobs
                                                                   : static_cast<int>(std::thread::hardware_concurrency())));
    std::atomic<int> next{0};
    std::mutex mu;
    std::exception_ptr error;
    auto worker = [&] {
        for (int k; (k = next++) < opt.count;) {
            try {
                RandomCase rc = run_one(opt.seed + static_cast<std::uint64_t>(k), opt);
                std::lock_guard<std::mutex> lock(mu);
                if (progress) {
                    *progress << outcome_name(rc.outcome) << "  seed " << rc.seed;
                    if (rc.outcome != Comparison::Outcome::Skip) *progress << "  " << diff_summary(rc.diff);
                    else *progress << "  (" << rc.reason << ")";
                    if (rc.knife_edge_pixels > 0)
                        *progress << "  -> " << knife_edge_summary(rc.knife_edge_pixels, rc.diff_outside_knife_edges);
                    if (rc.minimal)
                        *progress << "  -> minimal: " << diff_summary(rc.minimal->comparison.diff) << " after "
                                  << rc.minimal->attempts << " tries";
                    *progress << std::endl;
                }
                result.cases[static_cast<size_t>(k)] = std::move(rc);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mu);
                if (!error) error = std::current_exception();
                next = opt.count;
            }
        }
    };
    std::vector<std::thread> pool;
    for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
    for (const RandomCase& c : result.cases)
        (c.outcome == Comparison::Outcome::Pass ? result.passed
         : c.outcome == Comparison::Outcome::Fail ? result.failed
                                                   : result.skipped) += 1;
    for (const RandomCase& c : result.cases) result.passed_with_knife_edges += c.knife_edge_pixels > 0 ? 1 : 0;

    std::ostringstream md;
    md << "# Random scenes: refract (compat povray) vs POV-Ray 3.7\n\n"
       << opt.count << " scenes, generator seeds " << opt.seed << " to " << opt.seed + opt.count - 1 << ", "
       << opt.scene.width << "x" << opt.scene.height << ", dispersion " << (opt.scene.dispersion ? "on" : "off")
       << ". Targets: |d| <= " << opt.targets.pixel_tolerance << " in all but " << 100.0 * opt.targets.max_fraction_over
       << " % of the pixels, RMSE <= " << opt.targets.rmse << ".\n\n"
       << "**" << result.passed << " passed, " << result.failed << " failed, " << result.skipped << " skipped.**\n\n";
    if (result.passed_with_knife_edges > 0) {
        md << result.passed_with_knife_edges << " of the passes meet the targets only with their knife-edge pixels set "
           << "aside (pixels whose value moves by more than the tolerance when the camera ray moves by "
           << kKnifeEdgeShift << " pixel; counted in the fraction over, not in the RMSE):\n\n"
           << "| seed | difference | knife-edge pixels set aside | scene |\n|---|---|---|---|\n";
        for (const RandomCase& c : result.cases)
            if (c.knife_edge_pixels > 0)
                md << "| " << c.seed << " | " << diff_summary(c.diff) << " | "
                   << knife_edge_summary(c.knife_edge_pixels, c.diff_outside_knife_edges) << " | " << c.description
                   << " |\n";
        md << "\n";
    }
    if (result.failed + result.skipped > 0) {
        md << "| seed | status | difference | minimal case | scene |\n|---|---|---|---|---|\n";
        for (const RandomCase& c : result.cases) {
            if (c.outcome == Comparison::Outcome::Pass) continue;
            md << "| " << c.seed << " | " << outcome_name(c.outcome) << " | "
               << (c.outcome == Comparison::Outcome::Skip ? c.reason : diff_summary(c.diff)) << " | ";
            if (c.minimal)
                md << "[minimal.json](seed-" << c.seed << "/minimal.json): " << diff_summary(c.minimal->comparison.diff);
            md << " | " << c.description << " |\n";
        }
    }
    write_text_file((fs::path(opt.out_dir) / "report.md").string(), md.str());
    return result;
}

std::string format_random(const RandomResult& r) {
    std::ostringstream o;
    for (const RandomCase& c : r.cases) {
        if (c.outcome == Comparison::Outcome::Pass) continue;
        o << outcome_name(c.outcome) << "  seed " << c.seed << "  "
          << (c.outcome == Comparison::Outcome::Skip ? c.reason : diff_summary(c.diff));
        if (!c.dir.empty()) o << "  (" << c.dir << ")";
        o << "\n";
    }
    for (const RandomCase& c : r.cases)
        if (c.knife_edge_pixels > 0)
            o << "PASS  seed " << c.seed << "  " << diff_summary(c.diff) << "  -> "
              << knife_edge_summary(c.knife_edge_pixels, c.diff_outside_knife_edges) << "\n";
    o << r.passed << " passed";
    if (r.passed_with_knife_edges > 0) o << " (" << r.passed_with_knife_edges << " with knife-edge pixels set aside)";
    o << ", " << r.failed << " failed, " << r.skipped << " skipped (of " << r.cases.size() << " random scenes)\n";
    return o.str();
}

}  // namespace refract::validation
