// grin, part 7: heat shimmer through a sampled temperature field (experiments/grin.h,
// docs/grin.md "Heat shimmer"). A warm turbulent plume over a road, sampled on a grid, its
// index by Gladstone–Dale from Ciddor's air (core/grin/grid.h): the apparent displacement of
// a target's points against the plume's temperature amplitude, and a rendered view through
// the same field written as an OpenVDB file and read back by the scene reader.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include <refract/core/grin/grid.h>
#include <refract/core/grin/media.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/image.h>
#include <refract/experiments/common.h>
#include <refract/experiments/grin.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::grin_media {

namespace {

using nlohmann::json;
using grin::Vec3;

// The air box over the road: x along the view, y up (the road at y = 0), z across.
constexpr double kLength = 40.0, kHeight = 1.0, kHalfWidth = 2.0, kSpacing = 0.1;
constexpr double kBottom = 0.001;  // the box stands just above the road plane
constexpr double kAirTemperature = 300.0, kPlumeHeight = 0.3;
const Vec3 kEye(-5.0, 0.3, 0.0);
constexpr double kTargetX = 50.0;

// A fixed-seed draw in [0, 1) (the same on every platform: the engine is specified, the
// conversion is ours).
double uniform(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

struct Mode {
    Vec3 k;
    double phase, amplitude;
};
// Twelve Fourier modes, wavelengths 0.5–3 m in random directions, the sum's RMS 1.
std::vector<Mode> turbulence() {
    std::mt19937_64 g(30);
    std::vector<Mode> m;
    const int count = 12;
    for (int i = 0; i < count; ++i) {
        const double wavelength = 0.5 + 2.5 * uniform(g);
        const double cz = 2 * uniform(g) - 1, phi = 2 * kPi * uniform(g), sz = std::sqrt(1 - cz * cz);
        m.push_back({Vec3(sz * std::cos(phi), sz * std::sin(phi), cz) * (2 * kPi / wavelength), 2 * kPi * uniform(g),
                     std::sqrt(2.0 / count)});
    }
    return m;
}

// The temperature: T₀ + A·exp(−y/h)·w(x)·w(z)·(1 + ½ Σ a cos(k·x + φ)), w a sin² taper to 0 at the
// box's ends and sides (so the air there is the surroundings').
grin::GridSamples temperature_field(double amplitude, const std::vector<Mode>& modes) {
    grin::GridSamples s;
    s.dims = {static_cast<int>(std::lround(kLength / kSpacing)) + 1, static_cast<int>(std::lround(kHeight / kSpacing)) + 1,
              static_cast<int>(std::lround(2 * kHalfWidth / kSpacing)) + 1};
    s.origin = Vec3(0, 0, -kHalfWidth);
    s.spacing = Vec3::Constant(kSpacing);
    s.values.reserve(static_cast<size_t>(s.dims[0]) * s.dims[1] * s.dims[2]);
    for (int k = 0; k < s.dims[2]; ++k)
        for (int j = 0; j < s.dims[1]; ++j)
            for (int i = 0; i < s.dims[0]; ++i) {
                const Vec3 x = s.origin + Vec3(i, j, k) * kSpacing;
                const double wx = std::pow(std::sin(kPi * x.x() / kLength), 2);
                const double wz = std::pow(std::sin(kPi * (x.z() + kHalfWidth) / (2 * kHalfWidth)), 2);
                double turb = 0;
                for (const Mode& m : modes) turb += m.amplitude * std::cos(m.k.dot(x) + m.phase);
                s.values.push_back(kAirTemperature + amplitude * std::exp(-x.y() / kPlumeHeight) * wx * wz * (1 + 0.5 * turb));
            }
    return s;
}

grin::SampledGrid grid_of(const grin::GridSamples& s) {
    return grin::sampled_grid(s, grin::GridQuantity::temperature, kAirTemperature, 101325.0, "values", "shimmer");
}

// Where the sight line from the eye towards target point p lands on the target plane
// through the field: straight to the box, the ray equation inside, straight after.
Vec3 landing(const grin::SampledGrid& g, const grin::Region& box, const Vec3& p, double lambda_um, long& evaluations) {
    const Vec3 d = (p - kEye).normalized();
    const Vec3 entry = kEye + d * (-kEye.x() / d.x());  // on the face x = 0
    grin::Settings st;
    st.abs_tol = st.rel_tol = 1e-9;
    const grin::Result r = grin::advance(g, box, entry, d, lambda_um, st);
    evaluations += r.evaluations;
    if (r.status != grin::Status::left_region) return Vec3::Constant(std::nan(""));
    return r.exit_point + r.exit_dir * ((kTargetX - r.exit_point.x()) / r.exit_dir.x());
}

json shimmer_scene(int w, int h, const std::string& vdb) {
    const json air_box = json::array({{1, 0, 0, kLength}, {-1, 0, 0, 0}, {0, 1, 0, kHeight}, {0, -1, 0, -kBottom},
                                      {0, 0, 1, kHalfWidth}, {0, 0, -1, kHalfWidth}});
    return json{
        {"camera",
         {{"location", {kEye.x(), kEye.y(), kEye.z()}}, {"look_at", {kTargetX, 0.21, 0}}, {"angle", 0.6}, {"width", w},
          {"height", h}}},
        {"background", {{"type", "gradient"}, {"bottom", {0.9, 0.93, 1.0}}, {"top", {0.35, 0.55, 0.95}}}},
        {"materials",
         {{"air",
           {{"type", "grin"},
            {"tolerance", 1e-6},
            {"shadows", false},
            {"profile", {{"kind", "grid"}, {"quantity", "temperature"}, {"file", vdb}, {"grid", "temperature"},
                         {"reference_temperature", kAirTemperature}, {"relative", true}}}}},
          {"road", {{"type", "diffuse"}, {"color", {0.25, 0.25, 0.27}}}},
          {"target",
           {{"type", "diffuse"}, {"color", {0.95, 0.95, 0.95}}, {"checker", {{"color2", {0.05, 0.05, 0.05}}, {"size", 0.02}}}}}}},
        {"objects", json::array({{{"type", "polyhedron"}, {"material", "air"}, {"planes", air_box}},
                                 {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "road"}},
                                 {{"type", "plane"}, {"normal", {-1, 0, 0}}, {"offset", -kTargetX}, {"material", "target"}}})},
        {"lights", json::array({{{"type", "directional"}, {"direction", {1, -0.5, 0.3}}}})},
        {"render", {{"max_depth", 6}}}};
}

}  // namespace

ShimmerStudy shimmer_study(bool quick, int threads) {
    ShimmerStudy s;
    s.air_temperature_K = kAirTemperature;
    s.plume_height = kPlumeHeight;
    s.length = kLength;
    s.spacing = kSpacing;
    s.eye_to_target = kTargetX - kEye.x();
    const std::vector<Mode> modes = turbulence();
    const grin::Region box = grin::Box{Vec3(0, kBottom, -kHalfWidth), Vec3(kLength, kHeight, kHalfWidth)};
    // The target's points: a 7 × 5 lattice on the plane x = 50 m, 0.1–0.7 m up.
    std::vector<Vec3> targets;
    for (int j = 0; j < 7; ++j)
        for (int k = 0; k < 5; ++k) targets.emplace_back(kTargetX, 0.1 + 0.1 * j, -0.4 + 0.2 * k);
    s.target_points = static_cast<int>(targets.size());
    const grin::SampledGrid still = grid_of(temperature_field(0.0, modes));
    s.grid_dims = still.dims;
    std::vector<Vec3> base;
    long evaluations = 0;
    for (const Vec3& p : targets) base.push_back(landing(still, box, p, 0.55, evaluations));
    const std::vector<double> amplitudes =
            quick ? std::vector<double>{0.5, 1, 2, 4} : std::vector<double>{0.25, 0.5, 1, 2, 4, 8, 16};
    for (const double a : amplitudes) {
        const grin::SampledGrid g = grid_of(temperature_field(a, modes));
        ShimmerRow row;
        row.amplitude_K = a;
        double sum2 = 0;
        for (size_t i = 0; i < targets.size(); ++i) {
            const double d = (landing(g, box, targets[i], 0.55, evaluations) - base[i]).norm();
            sum2 += d * d;
            row.max_displacement = std::max(row.max_displacement, d);
        }
        row.rms_displacement = std::sqrt(sum2 / static_cast<double>(targets.size()));
        row.rms_angle_urad = 1e6 * row.rms_displacement / s.eye_to_target;
        s.rows.push_back(row);
    }
    s.evaluations = evaluations;
    // The exponent p of rms ∝ A^p: least squares in log–log over the amplitudes ≤ 4 K.
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const ShimmerRow& r : s.rows) {
        if (r.amplitude_K > 4.0 + 1e-12) continue;
        const double x = std::log(r.amplitude_K), y = std::log(r.rms_displacement);
        n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    s.exponent = (n * sxy - sx * sy) / (n * sxx - sx * sx);

    // The view: the field at the view's amplitude written as OpenVDB and read by the scene.
    s.view_amplitude_K = 20.0;
    s.field = temperature_field(s.view_amplitude_K, modes);
    // A scratch directory of its own (the file is written again beside the report by `write`).
    const std::filesystem::path dir =
            std::filesystem::temp_directory_path() / ("refract_shimmer_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir);
    grin::write_vdb_grid((dir / "shimmer.vdb").string(), "temperature", s.field);
    const int w = quick ? 96 : 128, h = quick ? 72 : 96;
    const json scene = shimmer_scene(w, h, "shimmer.vdb");
    const Scene parsed = parse_scene(scene, (dir / "shimmer_view.json").string());
    // The grid read back against the one sampled here (rounded to float by the file).
    {
        grin::GridSamples rounded = s.field;
        for (double& v : rounded.values) v = static_cast<double>(static_cast<float>(v));
        grin::SampledGrid direct = grid_of(rounded);
        direct.relative = true;
        const auto media = grin::media(parsed);
        const auto& read = std::get<grin::SampledGrid>(media.at(0).profile);
        s.vdb_dims_match = read.dims == direct.dims && (read.origin - direct.origin).norm() < 1e-9 &&
                           (read.spacing - direct.spacing).norm() < 1e-12;
        for (const Vec3& p : targets) {
            const Vec3 x(20.0, p.y(), p.z());
            s.vdb_max_index_difference = std::max(
                    s.vdb_max_index_difference, std::abs(grin::index(read, x, 0.55) - grin::index(direct, x, 0.55)));
        }
    }
    s.view = render_view("shimmer_view",
                         "Heat shimmer: a checkerboard 55 m away through a " +
                                 std::to_string(static_cast<int>(s.view_amplitude_K)) +
                                 " K turbulent plume read from shimmer.vdb",
                         scene, parsed, threads);
    std::filesystem::remove_all(dir);
    return s;
}

}  // namespace refract::experiments::grin_media

// ---------------------------------------------------------------------------------------
// Its files and its section of summary.md, from the study alone.

namespace refract::experiments::grin_media {

std::string write_shimmer(const ShimmerStudy& s, const Findings& f, const std::string& dir) {
    const auto path = [&](const std::string& name) { return dir + "/" + name; };
    auto g = [](double v, int digits = 4) { return std::isfinite(v) ? fmt(v, digits) : std::string("—"); };
    Csv t{{"amplitude_K", "rms_displacement_mm", "max_displacement_mm", "rms_angle_urad"}, {}};
    for (const ShimmerRow& r : s.rows)
        t.add({fmt(r.amplitude_K, 6), fmt(1e3 * r.rms_displacement, 6), fmt(1e3 * r.max_displacement, 6),
               fmt(r.rms_angle_urad, 6)});
    write_csv(path("shimmer.csv"), t);
    if (gnuplot_available())
        gnuplot_figure(dir, "shimmer",
                       "set datafile separator ','\nset logscale xy\nset title 'Heat shimmer: apparent displacement of "
                       "the target against the plume amplitude'\nset xlabel 'temperature amplitude (K)'\n"
                       "set ylabel 'displacement on the target (mm)'\nset key left top\n"
                       "plot 'shimmer.csv' using 1:2 skip 1 with linespoints pt 7 title 'RMS', "
                       "'shimmer.csv' using 1:3 skip 1 with linespoints pt 6 title 'largest'\n");
    const std::string tmp = path("shimmer.vdb.part");
    grin::write_vdb_grid(tmp, "temperature", s.field);
    std::filesystem::rename(tmp, path("shimmer.vdb"));
    write_image(path(s.view.name + ".png"), s.view.image);
    write_text_atomic(path(s.view.name + ".json"), s.view.scene.dump(1) + "\n");

    std::ostringstream md;
    md << "## 7. Heat shimmer\n\nA warm turbulent plume over a road, " << g(s.length) << " m long, as a sampled "
       << "temperature grid (" << s.grid_dims[0] << "×" << s.grid_dims[1] << "×" << s.grid_dims[2] << " samples, "
       << g(s.spacing) << " m apart): T = " << g(s.air_temperature_K) << " K + A·exp(−y/" << g(s.plume_height)
       << " m)·(1 + ½·twelve Fourier modes of 0.5–3 m, fixed seed), tapered to the surroundings at the box's ends and "
       << "sides; its index by Gladstone–Dale from Ciddor's air at " << g(s.air_temperature_K)
       << " K (docs/grin.md, \"Sampled fields\"). An eye " << g(s.eye_to_target) << " m from a target looks through it; "
       << s.target_points << " target points, each sight line traced by `advance()` (tolerance 1e-9, "
       << s.evaluations << " index-gradient evaluations in all), displaced against the same air without the plume "
       << "(shimmer.csv, shimmer.png).\n\n"
       << t.markdown(4) << "\n"
       << (f.shimmer_linear ? "For small amplitudes the displacement is proportional to the amplitude: "
                            : "The displacement is not proportional to the amplitude at small amplitudes: ")
       << "fitted exponent " << g(s.exponent, 4) << " over A ≤ 4 K"
       << (s.rows.size() > 1 && s.rows.back().amplitude_K > 4
                   ? "; at " + g(s.rows.back().amplitude_K) + " K the ratio to the linear extrapolation is " +
                             g(s.rows.back().rms_displacement / (s.rows.front().rms_displacement *
                                                                 s.rows.back().amplitude_K / s.rows.front().amplitude_K),
                               4)
                   : std::string())
       << ".\n\n"
       << "**The view** (" << s.view.name << ".png, " << s.view.image.width << "×" << s.view.image.height << ", "
       << g(s.view.seconds, 3) << " s, " << s.view.grin_evaluations << " evaluations, " << s.view.grin_exhausted
       << " rays out of steps): the field at A = " << g(s.view_amplitude_K) << " K written as shimmer.vdb (an OpenVDB "
       << "FloatGrid of temperatures) and read by the scene's \"file\" field. "
       << (f.shimmer_vdb_same ? "Read back, it is the grid sampled here (same dimensions, origin and spacing; the "
                                "index differs by at most " + g(s.vdb_max_index_difference, 2) + " at probes)."
                              : "Read back, it differs from the grid sampled here (index difference " +
                                        g(s.vdb_max_index_difference, 2) + ").")
       << " The scene's outside (n = 1) stands for the air at " << g(s.air_temperature_K)
       << " K, so the grid gives the index relative to it (`\"relative\": true`)."
       << "\n";
    return md.str();
}

}  // namespace refract::experiments::grin_media
