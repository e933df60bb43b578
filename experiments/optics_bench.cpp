#include <refract/experiments/optics_bench.h>

#include <chrono>
#include <cmath>

#include <refract/core/scene_json.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/experiments/optics_closed_forms.h>

namespace refract::experiments::optics_bench {

namespace {

using nlohmann::json;
namespace cf = closed_form;

constexpr double kDeg = M_PI / 180.0;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

// A scene with one object, one beam and the far field's limits: the camera is not used.
json bench_scene(const json& material, const json& object, const Vec3& beam_start, const Vec3& beam_dir,
                 double beam_radius, const json& render) {
    return json{{"description", "optics-bench: a collimated beam and one object, measured by the far-field detector"},
                {"camera", {{"location", {0, 0, -6}}, {"look_at", {0, 0, 0}}, {"angle", 40}, {"width", 64}, {"height", 64}}},
                {"materials", {{"glass", material}}},
                {"objects", json::array({object})},
                {"lights", json::array({{{"type", "beam"}, {"position", vec(beam_start)}, {"direction", vec(beam_dir)},
                                         {"radius", beam_radius}}})},
                {"render", render}};
}

json sphere_object() {
    return {{"type", "sphere"}, {"name", "drop"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "glass"}};
}

FarFieldSettings axis_settings(const Vec3& axis, int bins, int classes, std::uint64_t photons) {
    FarFieldSettings s;
    s.binning = FarFieldSettings::Binning::Axis;
    s.axis = axis;
    s.angle_bins = bins;
    s.classes = classes;
    s.photons = photons;
    return s;
}

DropStudy drop_study(bool quick, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    DropStudy d;
    d.photons = quick ? 200000 : 2000000;
    d.scene = bench_scene({{"type", "dielectric"}, {"ior", d.n}}, sphere_object(), Vec3(0, 0, -3), Vec3(0, 0, 1), 1.0,
                          {{"max_depth", 40}, {"threshold", 1e-9}, {"polarisation", "exact"}});
    const Scene scene = parse_scene(d.scene, "optics-bench drop");
    FarFieldSettings s = axis_settings(Vec3(0, 0, 1), 180, 5, d.photons);
    s.wavelengths = {550};
    d.far_field = far_field(scene, s, threads);
    const FarFieldResult& r = d.far_field;
    d.dropped = r.dropped[0];
    std::vector<double> edges;
    for (int b = 0; b <= r.bins; ++b) edges.push_back(M_PI * b / r.bins);
    for (int p = 0; p <= 3; ++p) {
        const cf::SphereBins c = cf::sphere_scattering(d.n, p, edges);
        DropClass cls;
        cls.cls = p;
        cls.total_closed = c.total_natural;
        for (int b = 0; b < r.bins; ++b) {
            DropBin bin;
            bin.cls = p;
            bin.theta0_deg = 180.0 * b / r.bins;
            bin.theta1_deg = 180.0 * (b + 1) / r.bins;
            const double S0 = r.at(0, p, 0, b), S1 = r.at(0, p, 1, b);
            bin.measured = S0;
            bin.measured_s = 0.5 * (S0 + S1);  // S1 > 0: ⊥ the scattering plane, the s wave
            bin.measured_p = 0.5 * (S0 - S1);
            const size_t k = static_cast<size_t>(b);
            bin.closed = c.natural[k];
            bin.closed_s = 0.5 * c.s[k];  // half the natural beam is s-polarised
            bin.closed_p = 0.5 * c.p[k];
            cls.total += S0;
            cls.max_bin_error = std::fmax(cls.max_bin_error, std::abs(bin.measured - bin.closed));
            if (bin.closed > 0)
                cls.max_z = std::fmax(cls.max_z, std::abs(bin.measured - bin.closed) /
                                                     std::sqrt(bin.closed / static_cast<double>(d.photons)));
            d.bins.push_back(bin);
        }
        d.classes.push_back(cls);
    }
    d.seconds = seconds_since(t0);
    return d;
}

RainbowStudy rainbow_study(bool quick, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    RainbowStudy st;
    st.photons = quick ? 100000 : 1000000;
    st.scene = bench_scene({{"type", "dielectric"}, {"ior", 1.333}, {"dispersion", "water"}}, sphere_object(),
                           Vec3(0, 0, -3), Vec3(0, 0, 1), 1.0, {{"max_depth", 8}, {"threshold", 1e-6}});
    const Scene scene = parse_scene(st.scene, "optics-bench rainbow");
    FarFieldSettings s = axis_settings(Vec3(0, 0, 1), 3600, 5, st.photons);
    s.wavelengths = {400, 450, 500, 550, 600, 650, 700};
    const FarFieldResult r = far_field(scene, s, threads);
    st.bin_deg = 180.0 / r.bins;
    const spectrum::Dispersion& water = spectrum::catalogue("water");
    for (size_t w = 0; w < r.wavelengths.size(); ++w) {
        RainbowRow row;
        row.wavelength_nm = r.wavelengths[w];
        row.n = water.n(row.wavelength_nm);
        // The bow: the first (primary, class 2) and the last (secondary, class 3) bin with
        // light, at its centre.
        int first = -1, last = -1;
        for (int b = 0; b < r.bins; ++b) {
            if (first < 0 && r.at(static_cast<int>(w), 2, 0, b) > 0) first = b;
            if (r.at(static_cast<int>(w), 3, 0, b) > 0) last = b;
        }
        row.primary = r.theta_deg(first);
        row.secondary = r.theta_deg(last);
        row.primary_closed = cf::rainbow_deviation(2, row.n) / kDeg;
        row.secondary_closed = cf::rainbow_deviation(3, row.n) / kDeg;
        st.max_error = std::fmax(st.max_error, std::fmax(std::abs(row.primary - row.primary_closed),
                                                         std::abs(row.secondary - row.secondary_closed)));
        st.rows.push_back(row);
    }
    st.seconds = seconds_since(t0);
    return st;
}

PrismStudy prism_study(bool quick, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    PrismStudy st;
    const double A = st.apex_deg * kDeg;
    const spectrum::Dispersion& bk7 = spectrum::catalogue("n-bk7");
    // Incidence at 550 nm's minimum deviation: sin i = n sin(A/2).
    const double i = std::asin(bk7.n(550) * std::sin(A / 2));
    st.incidence_deg = i / kDeg;
    // Apex edge along y through the origin, apex towards +x; base at x = −1, y in [−1, 1].
    const Vec3 n1(std::sin(A / 2), 0, -std::cos(A / 2)), n2(std::sin(A / 2), 0, std::cos(A / 2));
    const json object = {{"type", "polyhedron"}, {"name", "prism"}, {"material", "glass"},
                         {"planes", {{n1.x(), 0, n1.z(), 0}, {n2.x(), 0, n2.z(), 0}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}}}};
    const Vec3 t(std::cos(A / 2), 0, std::sin(A / 2));  // along the entrance face, towards the apex
    const Vec3 dir = std::cos(i) * -n1 + std::sin(i) * t;
    const Vec3 mid(-0.5, 0, -0.5 * std::tan(A / 2));  // the entrance face's middle (x = −0.5)
    st.scene = bench_scene({{"type", "dielectric"}, {"ior", 1.5168}, {"dispersion", "n-bk7"}}, object, mid - 2.0 * dir, dir,
                           0.02, {{"max_depth", 8}, {"threshold", 1e-6}});
    const Scene scene = parse_scene(st.scene, "optics-bench prism");
    FarFieldSettings s = axis_settings(dir, 18000, 3, quick ? 500 : 2000);
    for (double l = 400; l <= 700; l += 25) s.wavelengths.push_back(l);
    const FarFieldResult r = far_field(scene, s, threads);
    st.bin_deg = 180.0 / r.bins;
    for (size_t w = 0; w < r.wavelengths.size(); ++w) {
        PrismRow row;
        row.wavelength_nm = r.wavelengths[w];
        row.n = bk7.n(row.wavelength_nm);
        double sum = 0, weighted = 0;  // class 1: through both faces, no internal reflection
        for (int b = 0; b < r.bins; ++b) {
            sum += r.at(static_cast<int>(w), 1, 0, b);
            weighted += r.at(static_cast<int>(w), 1, 0, b) * r.theta_deg(b);
        }
        row.deviation = sum > 0 ? weighted / sum : NAN;
        row.deviation_closed = cf::prism_deviation(A, i, row.n).value_or(NAN) / kDeg;
        st.max_error = std::fmax(st.max_error, std::abs(row.deviation - row.deviation_closed));
        st.rows.push_back(row);
    }
    st.seconds = seconds_since(t0);
    return st;
}

SlabStudy slab_study(bool quick, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    SlabStudy st;
    const json object = {{"type", "polyhedron"}, {"name", "slab"}, {"material", "glass"},
                         {"planes", {{0, 0, 1, 0.05}, {0, 0, -1, 0.05}, {1, 0, 0, 10}, {-1, 0, 0, 10}, {0, 1, 0, 10}, {0, -1, 0, 10}}}};
    for (double a = 0; a <= 85; a += quick ? 17 : 5) {
        const Vec3 dir(std::sin(a * kDeg), 0, std::cos(a * kDeg));
        const json js = bench_scene({{"type", "dielectric"}, {"ior", st.n}}, object, -2.0 * dir, dir, 0.001,
                                    {{"max_depth", 80}, {"threshold", 1e-12}, {"polarisation", "exact"}});
        const Scene scene = parse_scene(js, "optics-bench slab");
        FarFieldSettings s = axis_settings(Vec3(0, 0, 1), 2, 2, 64);  // forward and backward hemispheres
        s.wavelengths = {550};
        const FarFieldResult r = far_field(scene, s, threads);
        SlabRow row;
        row.incidence_deg = a;
        double S0 = 0, S1 = 0;
        for (int c = 0; c < r.classes; ++c) {
            S0 += r.at(0, c, 0, 0);
            S1 += r.at(0, c, 1, 0);
        }
        row.T = S0;  // natural light: half s, half p
        row.T_s = S0 + S1;
        row.T_p = S0 - S1;
        const cf::SlabTerms c = cf::slab(a * kDeg, st.n);
        row.T_closed = c.T.natural;
        row.T_s_closed = c.T.s;
        row.T_p_closed = c.T.p;
        st.max_error = std::fmax(st.max_error, std::fmax(std::abs(row.T_s - row.T_s_closed), std::abs(row.T_p - row.T_p_closed)));
        st.rows.push_back(row);
    }
    st.seconds = seconds_since(t0);
    return st;
}

}  // namespace

Result compute(const ExperimentOptions& opt) {
    const auto t0 = std::chrono::steady_clock::now();
    Result r;
    r.quick = opt.quick;
    r.drop = drop_study(opt.quick, opt.threads);
    r.rainbow = rainbow_study(opt.quick, opt.threads);
    r.prism = prism_study(opt.quick, opt.threads);
    r.slab = slab_study(opt.quick, opt.threads);
    r.seconds = seconds_since(t0);
    r.drop.far_field_tables = far_field_tables(r.drop.far_field);
    return r;
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::optics_bench
