#include <refract/validation/suite.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include <refract/core/json_reader.h>
#include <refract/core/provenance.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>
#include <refract/geometry/input_file.h>
#include <refract/geometry/signal_cleanup.h>
#include <refract/validation/analytic.h>
#include <refract/validation/compare.h>
#include <refract/validation/files.h>
#include <refract/validation/pov_export.h>

namespace refract::validation {
namespace fs = std::filesystem;

const char* status_name(Status s) {
    switch (s) {
        case Status::Pass: return "PASS";
        case Status::Fail: return "FAIL";
        case Status::Skip: return "SKIP";
        case Status::Info: return "result";
    }
    return "?";
}

namespace {

// ---- tolerance files ------------------------------------------------------------------

struct Profile {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    double tolerance = 1e-5;
};
struct Analytic {
    std::string kind;  // "fresnel-sphere"
    double tolerance = 1e-6;
    std::optional<Profile> profile;
};
struct Tolerances {
    std::string description;
    Targets povray;  // the suite's rule (validation/compare.h)
    int block = 1;   // > 1: compared as means of block×block pixels (statistical cases)
    std::optional<Analytic> analytic;
    double timeout = 60;
};

int pixel_coord(const JsonReader& r, const std::string& key, int index) {
    const auto& v = r.raw(key);
    if (!v.is_array() || v.size() != 2 || !v[index].is_number_integer())
        r.fail_at(key, "must be [x, y] pixel indices");
    // Images are at most 32 768 pixels wide: larger indices (which would overflow the
    // profile's arithmetic) are refused.
    if (v[index].is_number_unsigned() ? v[index].get<unsigned long long>() > 32767 : v[index].get<long long>() < 0 ||
                                                                                         v[index].get<long long>() > 32767)
        r.fail_at(key, "pixel indices must be in [0, 32767]");
    return v[index].get<int>();
}

Tolerances load_tolerances(const std::string& path) {
    nlohmann::json j;
    const std::string text = read_input_file(path, "tolerance file");  // at most 64 MiB
    check_json_depth(text, path);
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(path + ": malformed JSON: " + e.what());
    }
    const JsonReader r(j, path, "");
    if (!j.is_object()) r.fail("a tolerance file must be a JSON object");
    r.only({"description", "povray", "analytic", "timeout"});
    Tolerances t;
    t.description = r.string("description", "");
    if (r.has("povray")) {
        const JsonReader p = r.child("povray");
        p.only({"pixel_tolerance", "max_fraction_over", "rmse", "block"});
        t.povray.pixel_tolerance = p.positive("pixel_tolerance", t.povray.pixel_tolerance);
        t.povray.max_fraction_over = p.number("max_fraction_over", t.povray.max_fraction_over);
        if (t.povray.max_fraction_over < 0 || t.povray.max_fraction_over > 1)
            p.fail_at("max_fraction_over", "must be in [0, 1]");
        t.povray.rmse = p.positive("rmse", t.povray.rmse);
        t.block = p.integer("block", 1, 1, 64);
    }
    if (r.has("analytic")) {
        const JsonReader a = r.child("analytic");
        a.only({"kind", "tolerance", "profile"});
        Analytic an;
        an.kind = a.string("kind");
        if (an.kind != "fresnel-sphere") a.fail_at("kind", "unknown analytic reference '" + clip_echo(an.kind) + "' (fresnel-sphere)");
        an.tolerance = a.positive("tolerance", an.tolerance);
        if (a.has("profile")) {
            const JsonReader p = a.child("profile");
            p.only({"from", "to", "tolerance"});
            an.profile = Profile{pixel_coord(p, "from", 0), pixel_coord(p, "from", 1), pixel_coord(p, "to", 0),
                                 pixel_coord(p, "to", 1), p.positive("tolerance", 1e-5)};
        }
        t.analytic = an;
    }
    t.timeout = r.positive("timeout", t.timeout);
    return t;
}

// ---- helpers ------------------------------------------------------------------------

Metric checked(const std::string& name, double value, double tolerance, bool percent = false) {
    return Metric{name, value, tolerance, value <= tolerance ? Status::Pass : Status::Fail, percent};
}
Metric result(const std::string& name, double value, bool percent = false) {
    return Metric{name, value, std::nullopt, Status::Info, percent};
}

void add_skip(CaseResult& c, const std::string& reason) {
    if (!c.skip_reason.empty()) c.skip_reason += "; ";
    c.skip_reason += reason;
}

struct FresnelSphereSetup {
    Sphere sphere;
    double n = 1;
};

// The analytic Fresnel sphere needs exactly: one dielectric sphere, black inside
// (filter 0), Fresnel reflectance, a white solid background.
FresnelSphereSetup fresnel_sphere_setup(const Scene& s) {
    const std::string f = s.source;
    if (s.objects.size() != 1) throw InputError(f + ": analytic fresnel-sphere needs exactly one object");
    const auto* sp = std::get_if<Sphere>(&s.objects[0].shape);
    const auto* m = s.materials[s.objects[0].material].dielectric();
    if (!sp || sp->radius <= 0 || !m || m->reflectance != ReflectanceModel::Fresnel || m->filter != Vec3(0, 0, 0))
        throw InputError(f + ": analytic fresnel-sphere needs a sphere of a Fresnel dielectric with filter [0, 0, 0]");
    if (s.background.kind != Background::Kind::Solid || s.background.color != Vec3(1, 1, 1))
        throw InputError(f + ": analytic fresnel-sphere needs a solid white background [1, 1, 1]");
    return {*sp, m->ior};
}

// The images of a case in report order (side by side): what exists is listed.
void list_images(CaseResult& c, const fs::path& case_dir, const fs::path& out_dir) {
    static const std::pair<const char*, const char*> order[] = {
        {"refract-compat.png", "refract, compat povray"}, {"povray.png", "POV-Ray 3.7"},
        {"diff-compat-povray.png", "abs(compat - povray)"}, {"refract-physical.png", "refract, physical"},
        {"diff-physical-compat.png", "abs(physical - compat)"}};
    for (const auto& [file, title] : order) {
        std::error_code ec;
        if (!fs::exists(case_dir / file, ec)) continue;
        c.images.push_back(fs::relative(case_dir / file, out_dir).string());
        c.image_titles.push_back(title);
    }
}

void finish(CaseResult& c) {
    bool failed = false;
    for (const Metric& m : c.metrics) failed = failed || m.status == Status::Fail;
    c.status = failed ? Status::Fail : !c.skip_reason.empty() ? Status::Skip : Status::Pass;
}

}  // namespace

void check_case_name(const std::string& name, const std::string& where) {
    // A case writes into OUT/NAME: a name is one plain path component.
    const bool plain = !name.empty() && name[0] != '.' && name.size() <= 200 &&
                       std::all_of(name.begin(), name.end(), [](char ch) {
                           return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                                  ch == '.' || ch == '_' || ch == '-';
                       });
    if (!plain)
        throw InputError(where + ": case names hold letters, digits, '.', '_' and '-' only, not first '.' "
                                 "(at most 200 characters)");
}

std::vector<std::string> list_cases(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(dir + ": no such scenes directory");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string file = e.path().filename().string();
        const auto ends = [&](const std::string& suffix) {
            return file.size() > suffix.size() && file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0;
        };
        if (e.is_regular_file() && ends(".json") && !ends(".tol.json")) {
            names.push_back(file.substr(0, file.size() - 5));
            check_case_name(names.back(), (fs::path(dir) / file).string());
        }
    }
    if (ec) throw InputError(dir + ": cannot read scenes directory: " + ec.message());
    std::sort(names.begin(), names.end());
    return names;
}

namespace {
CaseResult run_case_inner(const std::string& name, const SuiteOptions& opt, std::string* povray_version);
}

CaseResult run_case(const std::string& name, const SuiteOptions& opt, std::string* povray_version) {
    check_case_name(name, "validation case");
    CaseResult c = run_case_inner(name, opt, povray_version);
    list_images(c, fs::path(opt.out_dir) / name, fs::path(opt.out_dir));
    return c;
}

namespace {

CaseResult run_case_inner(const std::string& name, const SuiteOptions& opt, std::string* povray_version) {
    CaseResult c;
    c.name = name;
    const fs::path scene_path = fs::path(opt.scenes_dir) / (name + ".json");
    const fs::path tol_path = fs::path(opt.scenes_dir) / (name + ".tol.json");
    const fs::path out_dir(opt.out_dir);
    const fs::path case_dir = out_dir / name;
    Scene scene;
    Tolerances tol;
    // A case directory this run makes is removed on SIGINT/SIGTERM until the case is done
    // (geometry/signal_cleanup.h): an interrupted case leaves no partial directory.
    std::unique_ptr<TreeOnSignal> partial;
    try {
        scene = load_scene(scene_path.string());
        tol = load_tolerances(tol_path.string());
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(case_dir, ec))) partial = std::make_unique<TreeOnSignal>(case_dir.c_str());
        fs::create_directories(case_dir);
    } catch (const std::exception& e) {
        add_skip(c, e.what());
        finish(c);
        return c;
    }
    c.description = tol.description;
    RenderOptions ropt;
    ropt.threads = opt.threads;

    // refract, both modes.
    Scene compat = scene, physical = scene;
    compat.settings.compat = Compat::PovRay;
    physical.settings.compat = Compat::Physical;
    Image img_compat, img_physical;
    try {
        const auto rc = render(compat, ropt);
        const auto rp = render(physical, ropt);
        img_compat = rc.image;
        img_physical = rp.image;
        c.refract_seconds = rc.stats.seconds + rp.stats.seconds;
        write_image((case_dir / "refract-compat.png").string(), img_compat);
        write_image((case_dir / "refract-compat.exr").string(), img_compat);
        write_image((case_dir / "refract-physical.png").string(), img_physical);
        const ImageDifference d = compare_images(img_physical, img_compat, tol.povray.pixel_tolerance);
        c.metrics.push_back(result("physical vs compat: rmse", d.rmse));
        c.metrics.push_back(result("physical vs compat: max abs diff", d.max_error));
        c.metrics.push_back(
            result("physical vs compat: pixels over " + pov_number(tol.povray.pixel_tolerance), d.fraction_over, true));
        write_heatmap((case_dir / "diff-physical-compat.png").string(), img_physical, img_compat);
    } catch (const std::exception& e) {
        add_skip(c, std::string("refract: ") + e.what());
        finish(c);
        return c;
    }

    // Physics against the closed form.
    std::optional<FresnelSphereSetup> fs_setup;
    if (tol.analytic) {
        try {
            fs_setup = fresnel_sphere_setup(physical);
            const Camera& cam = physical.camera;
            const auto expected = [&](int i, int j) -> std::optional<double> {
                const auto v = analytic::fresnel_sphere_pixel(cam, fs_setup->sphere, fs_setup->n, i, j);
                return v ? *v : 1.0;  // a miss sees the white background
            };
            std::vector<std::pair<int, int>> all;
            for (int j = 0; j < cam.height; ++j)
                for (int i = 0; i < cam.width; ++i) all.emplace_back(i, j);
            double worst = 0;
            for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, compare_profile(img_physical, all, ch, expected).max_error);
            c.metrics.push_back(checked("physical vs analytic: max abs diff", worst, tol.analytic->tolerance));
        } catch (const std::exception& e) {
            add_skip(c, std::string("analytic: ") + e.what());
        }
    }

    // POV-Ray.
    std::string pov;
    std::vector<std::string> pov_files;  // what scene.pov refers to, beside it
    try {
        const ExportOptions eo;
        pov = export_pov(compat, eo);
        write_text_file((case_dir / "scene.pov").string(), pov);
        if (has_environment_map(compat)) {
            pov_files.push_back((case_dir / eo.environment_map).string());
            write_environment_map(compat, pov_files.back());
        }
    } catch (const std::exception& e) {
        add_skip(c, std::string("not expressible in POV-Ray: ") + e.what());
        finish(c);
        return c;
    }
    Image img_pov;
    try {
        PovrayOptions popt = opt.povray;
        popt.timeout_seconds = tol.timeout;
        if (opt.threads > 0) popt.threads = opt.threads;
        popt.files = pov_files;
        const PovrayRender pr = render_povray(pov, compat.camera.width, compat.camera.height, popt);
        img_pov = pr.image;
        c.povray_seconds = pr.seconds;
        if (povray_version && povray_version->empty()) *povray_version = pr.version;
    } catch (const PovrayError& e) {
        add_skip(c, std::string("povray: ") + e.what());
        if (!e.log().empty()) {
            try {
                write_text_file((case_dir / "povray.log").string(), e.log());
                c.povray_log = fs::relative(case_dir / "povray.log", out_dir).string();
            } catch (const std::exception&) {
            }
        }
        finish(c);
        return c;
    } catch (const std::exception& e) {
        add_skip(c, std::string("povray: ") + e.what());
        finish(c);
        return c;
    }
    try {
        write_image((case_dir / "povray.png").string(), img_pov);
        write_image((case_dir / "povray-linear16.png").string(), img_pov, {true});
        // POV-Ray's 16-bit PNG holds [0, 1]: refract clipped the same way; the suite's rule
        // (Targets::met_by) is both checked metrics passing.
        const Image clipped = clamp01(img_compat);
        // A statistical case compares the means of blocks of pixels, both images clipped first.
        const ImageDifference d =
            tol.block > 1 ? compare_with_povray_image(block_means(clipped, tol.block), block_means(img_pov, tol.block), tol.povray)
                          : compare_with_povray_image(img_compat, img_pov, tol.povray);
        if (tol.block > 1) c.metrics.push_back(result("compared as means of " + std::to_string(tol.block) + "×" +
                                                      std::to_string(tol.block) + " pixels", tol.block));
        c.metrics.push_back(checked("compat vs povray: rmse", d.rmse, tol.povray.rmse));
        c.metrics.push_back(checked("compat vs povray: pixels over " + pov_number(tol.povray.pixel_tolerance),
                                    d.fraction_over, tol.povray.max_fraction_over, true));
        c.metrics.push_back(result("compat vs povray: max abs diff", d.max_error));
        c.metrics.push_back(result("compat vs povray: psnr (dB)", d.psnr));
        write_heatmap((case_dir / "diff-compat-povray.png").string(), clipped, img_pov);
        if (fs_setup && tol.analytic->profile) {
            const Profile& p = *tol.analytic->profile;
            const auto pixels = line_pixels(p.x0, p.y0, p.x1, p.y1);
            const auto expected = [&](int i, int j) -> std::optional<double> {
                return analytic::fresnel_sphere_pixel(physical.camera, fs_setup->sphere, fs_setup->n, i, j);
            };
            const ProfileComparison pc = compare_profile(img_pov, pixels, 0, expected);
            c.metrics.push_back(checked("povray profile vs analytic: max abs diff", pc.max_error, p.tolerance));
            std::ostringstream csv;
            csv << "x,y,analytic,refract_physical,refract_compat,povray\n";
            csv.precision(10);
            for (const ProfilePoint& q : pc.points)
                csv << q.x << "," << q.y << "," << q.expected << "," << img_physical.at(q.x, q.y)[0] << ","
                    << img_compat.at(q.x, q.y)[0] << "," << q.value << "\n";
            write_text_file((case_dir / "profile.csv").string(), csv.str());
            write_csv_sidecar((case_dir / "profile.csv").string(), {{"case", c.name}});  // core/provenance.h
        }
    } catch (const std::exception& e) {
        add_skip(c, std::string("comparison: ") + e.what());
    }
    finish(c);
    return c;
}

}  // namespace

SuiteResult run_suite(const SuiteOptions& opt, std::ostream* progress) {
    const std::vector<std::string> known = list_cases(opt.scenes_dir);
    std::vector<std::string> names = opt.cases.empty() ? known : opt.cases;
    for (const std::string& n : names)
        if (std::find(known.begin(), known.end(), n) == known.end()) {
            std::string list;
            for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
            throw InputError("validate: unknown case '" + n + "' in " + opt.scenes_dir + " (cases: " + list + ")");
        }
    std::error_code ec;
    fs::create_directories(opt.out_dir, ec);
    if (ec) throw InputError(opt.out_dir + ": cannot create output directory: " + ec.message());
    SuiteResult r;
    for (const std::string& n : names) {
        CaseResult c = run_case(n, opt, &r.povray_version);
        if (progress) {
            *progress << status_name(c.status) << "  " << c.name;
            if (!c.skip_reason.empty()) *progress << "  (" << c.skip_reason << ")";
            *progress << std::endl;
        }
        (c.status == Status::Pass ? r.passed : c.status == Status::Fail ? r.failed : r.skipped) += 1;
        r.cases.push_back(std::move(c));
    }
    write_reports(r, opt.out_dir);
    return r;
}

}  // namespace refract::validation
