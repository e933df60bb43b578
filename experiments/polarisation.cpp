// Exact polarisation against natural light: the measurements (experiments/polarisation.h).
// The files are written by experiments/polarisation_report.cpp.
#include <refract/experiments/polarisation.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/ray_tree.h>
#include <refract/core/spectrum/cie.h>
#include <refract/core/tracer.h>
#include <refract/experiments/common.h>
#include <refract/experiments/ohtsuka1998.h>
#include <refract/experiments/plot.h>
#include <refract/core/threads.h>

namespace refract::experiments::polarisation {

using nlohmann::json;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---- 2. Light per path depth ------------------------------------------------------------

template <class P>
struct DepthEnds {
    using Walker = RayTreeWalkerT<P>;
    using Entry = TreeEntryT<P>;
    const SceneTracer& tracer;
    RenderStats& stats;
    std::vector<double>& per_depth;

    void add(const Entry& e, const Vec3& L) {
        const Vec3 v = rgb_of(seen(e.pol, e.weight, L));
        const size_t d = static_cast<size_t>(e.depth);
        if (d >= per_depth.size()) per_depth.resize(d + 1, 0.0);
        per_depth[d] += v.sum();
    }
    void background(const Entry& e) { add(e, tracer.background(e.ray.dir)); }
    void leaf(const Entry& e, const SurfaceHit& h) { add(e, tracer.local_light(h, stats)); }
    bool intercept(Walker&, const Entry&, const SurfaceHit&, typename Walker::List&) { return false; }
    double band_ior(const Entry&, const SurfaceHit&) const { return 0.0; }
    double wavelength(const Entry&) const { return 0.0; }
};

template <class P>
std::vector<double> depth_walk(const Scene& scene, const TreeLimits& limits, int threads) {
    SceneTracer tracer(scene);
    const int W = scene.camera.width, H = scene.camera.height;
    std::vector<std::vector<double>> rows(static_cast<size_t>(H));
    auto body = [&](int j) {
        RenderStats st;
        RayTreeWalkerT<P> walker(tracer, limits, st);
        DepthEnds<P> ends{tracer, st, rows[static_cast<size_t>(j)]};
        for (int i = 0; i < W; ++i) {
            const Ray primary = scene.camera.ray(i + 0.5, j + 0.5);
            typename RayTreeWalkerT<P>::List list{TreeEntryT<P>{primary, Vec3(1, 1, 1)}};
            if constexpr (std::is_same_v<P, EyeStokes>) list.front().pol = camera_stokes(scene, primary);
            walker.walk(list, ends);
        }
    };
    tbb::task_arena arena(worker_threads(threads));
    arena.execute([&] { tbb::parallel_for(0, H, body); });
    std::vector<double> sum;  // rows in order: the same sums whatever the thread count
    for (const auto& r : rows) {
        if (r.size() > sum.size()) sum.resize(r.size(), 0.0);
        for (size_t d = 0; d < r.size(); ++d) sum[d] += r[d];
    }
    return sum;
}

// Pixels whose primary ray first hits the object named `name`.
std::vector<char> object_mask(const Scene& scene, const std::string& name) {
    SceneTracer tracer(scene);
    RenderStats st;
    std::vector<char> m(static_cast<size_t>(scene.camera.width) * scene.camera.height, 0);
    for (int j = 0; j < scene.camera.height; ++j)
        for (int i = 0; i < scene.camera.width; ++i) {
            const auto h = tracer.intersect(scene.camera.ray(i + 0.5, j + 0.5), st);
            m[static_cast<size_t>(j) * scene.camera.width + i] = h && h->object && h->object->name == name;
        }
    return m;
}

double image_sum(const Image& im) {
    double s = 0;
    for (double v : im.rgb) s += v;
    return s;
}

double masked_sum(const Image& im, const std::vector<char>& mask) {
    double s = 0;
    for (size_t p = 0; p < mask.size(); ++p)
        if (mask[p]) s += im.rgb[3 * p] + im.rgb[3 * p + 1] + im.rgb[3 * p + 2];
    return s;
}

// Nearest-rank percentile of a copy of v.
double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t k = static_cast<size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[std::min(v.size() - 1, k > 0 ? k - 1 : 0)];
}

// Light pass (when the scene has one) and eye pass; the maps are returned for reuse.
RenderResult render_timed(const Scene& s, int threads, double& light_s, double& total_s,
                          std::shared_ptr<const IlluminationMaps>* keep = nullptr) {
    RenderOptions o;
    o.threads = threads;
    light_s = 0;
    if (s.settings.spectral.enabled && s.settings.light_pass.enabled) {
        const SpectralContext ctx = SpectralContext::build(s);
        o.maps = light_pass(s, ctx, threads);
        light_s = o.maps->seconds;
        if (keep) *keep = o.maps;
    }
    RenderResult r = render(s, o);
    total_s = light_s + r.stats.seconds;
    return r;
}

void compare(Comparison& c, const std::string& object, int threads,
             std::shared_ptr<const IlluminationMaps>* exact_maps = nullptr) {
    const Scene natural = scene_from_json(c.natural_scene, c.id + "-natural.json");
    const Scene exact = scene_from_json(c.exact_scene, c.id + "-exact.json");
    c.spectral = natural.settings.spectral.enabled;
    c.width = natural.camera.width;
    c.height = natural.camera.height;
    c.natural = render_timed(natural, threads, c.light_pass_natural, c.seconds_natural).image;
    RenderResult ex = render_timed(exact, threads, c.light_pass_exact, c.seconds_exact, exact_maps);
    c.exact = std::move(ex.image);
    c.exact_polarisation = std::move(*ex.polarisation);
    c.rmse = rmse(c.natural, c.exact);
    const size_t n = static_cast<size_t>(c.width) * c.height;
    c.delta_e.assign(n, 0.0);
    c.max_abs = c.de_mean = c.de_max = 0;
    for (size_t p = 0; p < n; ++p) {
        const int i = static_cast<int>(p % c.width), j = static_cast<int>(p / c.width);
        const Vec3 a = c.natural.at(i, j), b = c.exact.at(i, j);
        c.max_abs = std::fmax(c.max_abs, (a - b).cwiseAbs().maxCoeff());
        c.delta_e[p] = spectrum::delta_e2000(a.cwiseMax(0.0), b.cwiseMax(0.0));
        c.de_mean += c.delta_e[p] / static_cast<double>(n);
        c.de_max = std::fmax(c.de_max, c.delta_e[p]);
    }
    c.de_p95 = percentile(c.delta_e, 0.95);
    c.de_p99 = percentile(c.delta_e, 0.99);
    c.light_natural = image_sum(c.natural);
    c.light_exact = image_sum(c.exact);
    const auto mask = object_mask(natural, object);
    c.object_pixels = static_cast<int>(std::count(mask.begin(), mask.end(), 1));
    c.object_natural = masked_sum(c.natural, mask);
    c.object_exact = masked_sum(c.exact, mask);

    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> dn = light_by_depth(natural, threads), de = light_by_depth(exact, threads);
    c.depth.clear();
    for (size_t d = 0; d < std::max(dn.size(), de.size()); ++d)
        c.depth.push_back({static_cast<int>(d), d < dn.size() ? dn[d] : 0.0, d < de.size() ? de[d] : 0.0});
    c.seconds_depth = seconds_since(t0);
    c.depth_natural = c.depth_exact = 0;
    for (const auto& d : c.depth) c.depth_natural += d.natural, c.depth_exact += d.exact;
    c.difference_x10 = Image(c.width, c.height);
    for (size_t k = 0; k < c.natural.rgb.size(); ++k)
        c.difference_x10.rgb[k] = std::fmin(std::abs(c.natural.rgb[k] - c.exact.rgb[k]) * 10.0, 1.0);
}

// The value v in [0, 1] stored so that the sRGB-encoded PNG's grey level is v.
double srgb_decode(double v) {
    v = std::fmin(std::fmax(v, 0.0), 1.0);
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

json with_polarisation(json j, const json& pol, const std::string& note) {
    j["render"]["polarisation"] = pol;
    j["description"] = j["description"].get<std::string>() + note;
    return j;
}

}  // namespace

std::vector<double> light_by_depth(const Scene& scene, int threads) {
    TreeLimits limits = tree_limits(scene.settings);
    if (scene.settings.spectral.enabled) limits = SpectralContext::build(scene).limits(scene.settings);
    return polarisation_model(scene) == PolarisationModel::Exact ? depth_walk<EyeStokes>(scene, limits, threads)
                                                                   : depth_walk<NaturalLight>(scene, limits, threads);
}

json glass_sphere_scene(bool quick) {
    // scenes/examples/glass-sphere.json, the objects named.
    return json{
        {"description", "A glass sphere (n = 1.5) on a checker floor, lit by one point light, with an emissive "
                        "highlight sphere (scenes/examples/glass-sphere.json)"},
        {"camera", {{"location", vec(0, 1, -6)}, {"look_at", vec(0, 0.5, 0)}, {"angle", 45},
                    {"width", quick ? 64 : 320}, {"height", quick ? 48 : 240}}},
        {"background", vec(0.4, 0.5, 0.8)},
        {"materials",
         {{"glass", {{"type", "dielectric"}, {"ior", 1.5}}},
          {"floor", {{"type", "diffuse"}, {"color", vec(0.9, 0.9, 0.9)},
                     {"checker", {{"color2", vec(0.1, 0.1, 0.1)}, {"size", 1}}}}}}},
        {"objects",
         json::array({{{"type", "sphere"}, {"name", "glass sphere"}, {"center", vec(0, 1, 0)}, {"radius", 1},
                       {"material", "glass"}},
                      {{"type", "plane"}, {"name", "floor"}, {"normal", vec(0, 1, 0)}, {"offset", 0},
                       {"material", "floor"}},
                      {{"type", "sphere"}, {"name", "highlight"}, {"center", vec(3, 5, 4)}, {"radius", 0.5},
                       {"material", {{"type", "emissive"}, {"color", vec(20, 20, 20)}}}}})},
        {"lights", json::array({{{"position", vec(5, 10, -5)}}})},
        {"render", {{"max_depth", 12}, {"threshold", 0.001}}},
    };
}

Result compute(const ExperimentOptions& opt) {
    const auto t_all = std::chrono::steady_clock::now();
    Result r;
    r.quick = opt.quick;
    r.threads = opt.threads > 0 ? opt.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int T = opt.threads;

    // ---- 1. Sphere ---------------------------------------------------------------------
    auto t0 = std::chrono::steady_clock::now();
    r.sphere = sphere_study();
    r.seconds_sphere = seconds_since(t0);

    // ---- 2. Natural against exact: the diamond and the glass sphere ---------------------
    ohtsuka1998::SceneParams dp;
    if (opt.quick) {
        dp.width = 64;
        dp.height = 48;
        dp.photons = 300;
    }
    const json diamond = ohtsuka1998::scene_json(dp);
    r.diamond.id = "diamond";
    r.diamond.title = "1998 diamond";
    r.diamond.natural_scene = with_polarisation(diamond, "natural", "; natural light at every interface");
    r.diamond.exact_scene = with_polarisation(diamond, "exact", "; exact polarisation");
    std::shared_ptr<const IlluminationMaps> maps;
    compare(r.diamond, "diamond", T, &maps);

    const json glass = glass_sphere_scene(opt.quick);
    r.glass.id = "sphere";
    r.glass.title = "glass sphere";
    r.glass.natural_scene = with_polarisation(glass, "natural", "; natural light at every interface");
    r.glass.exact_scene = with_polarisation(glass, "exact", "; exact polarisation");
    compare(r.glass, "glass sphere", T);

    // ---- 3. The diamond through a linear analyser -----------------------------------------
    t0 = std::chrono::steady_clock::now();
    AnalyserStudy& an = r.analyser;
    {
        RenderOptions o;
        o.threads = T;
        o.maps = maps;  // the exact light pass: the analyser is on the camera's side only
        an.width = r.diamond.width;
        an.height = r.diamond.height;
        for (size_t k = 0; k < an.angles.size(); ++k) {
            an.scenes[k] = with_polarisation(
                diamond, json{{"model", "exact"}, {"analyser", {{"type", "linear"}, {"angle", an.angles[k]}}}},
                "; exact polarisation through a linear analyser at " + fmt(an.angles[k]) + " degrees");
            an.images[k] = render(scene_from_json(an.scenes[k], "diamond-analyser.json"), o).image;
            an.light[k] = image_sum(an.images[k]);
        }
        const Image& S0 = r.diamond.exact;  // the unanalysed exact render
        for (size_t v = 0; v < S0.rgb.size(); ++v) {
            const double d1 = std::abs(an.images[0].rgb[v] + an.images[2].rgb[v] - S0.rgb[v]);
            const double d2 = std::abs(an.images[1].rgb[v] + an.images[3].rgb[v] - S0.rgb[v]);
            an.max_dev_0_90 = std::fmax(an.max_dev_0_90, d1);
            an.max_dev_45_135 = std::fmax(an.max_dev_45_135, d2);
            bool zero = S0.rgb[v] == 0;
            for (const auto& im : an.images) zero = zero || im.rgb[v] == 0;
            if (std::fmax(d1, d2) > 1e-9) {
                ++an.deviating_channels;
                an.deviations_at_zeros = an.deviations_at_zeros && zero;
            }
            if (zero) {
                ++an.zero_channels;
                continue;
            }
            an.max_dev_0_90_nonzero = std::fmax(an.max_dev_0_90_nonzero, d1);
            an.max_dev_45_135_nonzero = std::fmax(an.max_dev_45_135_nonzero, d2);
        }
        const auto mask = object_mask(scene_from_json(r.diamond.exact_scene, "diamond"), "diamond");
        int count = 0;
        for (size_t p = 0; p < mask.size(); ++p)
            if (mask[p]) {
                an.dolp_mean_object += r.diamond.exact_polarisation.dolp[p];
                an.dolp_max_object = std::fmax(an.dolp_max_object, r.diamond.exact_polarisation.dolp[p]);
                ++count;
            }
        if (count > 0) an.dolp_mean_object /= count;
        const PolarisationImages& pol = r.diamond.exact_polarisation;
        for (size_t p = 0; p < mask.size(); ++p) {
            if (mask[p] && pol.dolp[p] > 1 + 1e-9) ++an.dolp_above_one;
            for (size_t c = 0; c < 3; ++c) {
                const double* s = &pol.stokes[12 * p + c];
                if (std::sqrt(s[3] * s[3] + s[6] * s[6] + s[9] * s[9]) > s[0] * (1 + 1e-9) + 1e-15)
                    ++an.channels_outside_cone;
            }
        }
    }
    an.seconds = seconds_since(t0);
    {
        const PolarisationImages& pol = r.diamond.exact_polarisation;
        an.dolp_grey = Image(an.width, an.height);
        for (size_t p = 0; p < pol.dolp.size(); ++p) {
            const double v = srgb_decode(pol.dolp[p]);
            an.dolp_grey.rgb[3 * p] = an.dolp_grey.rgb[3 * p + 1] = an.dolp_grey.rgb[3 * p + 2] = v;
        }
    }
    r.seconds_total = seconds_since(t_all);
    r.findings = judge(r);
    return r;
}

Findings judge(const Result& r) {
    Findings f;
    auto match = [](const Comparison& c) {
        auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::fmax(std::abs(a), std::abs(b)); };
        return !c.spectral && close(c.depth_natural, c.light_natural) && close(c.depth_exact, c.light_exact);
    };
    f.diamond_depth_sums_match = match(r.diamond);
    f.glass_depth_sums_match = match(r.glass);
    f.clipping_deviates = r.analyser.deviating_channels > 0;
    f.outside_cone = r.analyser.dolp_above_one > 0 || r.analyser.channels_outside_cone > 0;
    return f;
}

}  // namespace refract::experiments::polarisation
