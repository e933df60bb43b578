// Exact polarisation against natural light, part 1: parallel rays through a sphere, the
// degree of polarisation of each path class against its closed form
// (experiments/polarisation.h).
#include <cmath>

#include <refract/core/optics.h>
#include <refract/core/ray_tree.h>
#include <refract/core/tracer.h>
#include <refract/experiments/common.h>
#include <refract/experiments/plot.h>
#include <refract/experiments/polarisation.h>

namespace refract::experiments::polarisation {

using nlohmann::json;

namespace {

constexpr double kDeg = M_PI / 180.0;

// Classifies the background leaves of an exact walk by their (reflections,
// transmissions) and sums the Stokes vector each brings to the camera, for white
// unpolarised light behind every leaf.
struct ClassEnds {
    using Walker = RayTreeWalkerT<EyeStokes>;
    using Entry = TreeEntryT<EyeStokes>;
    std::array<polar::Stokes, 4> S;

    ClassEnds() {
        for (auto& s : S) s.setZero();
    }
    void background(const Entry& e) {
        const auto& cs = path_classes();
        for (size_t c = 0; c < cs.size(); ++c)
            if (e.reflections == cs[c].reflections && e.transmissions == cs[c].transmissions)
                S[c] += seen(e.pol, e.weight, Vec3(1, 1, 1)).col(0);
    }
    void leaf(const Entry&, const SurfaceHit&) {}
    bool intercept(Walker&, const Entry&, const SurfaceHit&, Walker::List&) { return false; }
    double band_ior(const Entry&, const SurfaceHit&) const { return 0.0; }
    double wavelength(const Entry&) const { return 0.0; }
};

}  // namespace

const std::array<PathClass, 4>& path_classes() {
    static const std::array<PathClass, 4> c{{{"reflection", 1, 0, -1},
                                             {"transmission", 0, 2, 0},
                                             {"1 internal", 1, 2, 1},
                                             {"2 internal", 2, 2, 2}}};
    return c;
}

double closed_form_signed(const PathClass& c, double n, double theta_i_deg) {
    const auto f = optics::fresnel(std::fmax(std::cos(theta_i_deg * kDeg), 0.0), n);
    if (!f) return 0;
    if (c.internal < 0) return (f->Rs - f->Rp) / (f->Rs + f->Rp);
    const double Ts = 1 - f->Rs, Tp = 1 - f->Rp;
    const double s = Ts * Ts * std::pow(f->Rs, c.internal), p = Tp * Tp * std::pow(f->Rp, c.internal);
    return (s - p) / (s + p);
}

json sphere_dop_scene(double n) {
    return json{
        {"description", "Unit sphere of index " + fmt(n) +
                            " in a black background; the experiment traces parallel rays along +z at impact "
                            "parameters sin(theta_i) in the x-z plane with exact polarisation, threshold 0"},
        {"camera", {{"type", "orthographic"}, {"location", vec(0, 0, -3)}, {"look_at", vec(0, 0, 0)},
                    {"ortho_height", 2.2}, {"width", 64}, {"height", 64}}},
        {"background", vec(0, 0, 0)},
        {"materials", {{"glass", {{"type", "dielectric"}, {"ior", n}, {"reflectance", "fresnel"}}}}},
        {"objects", json::array({{{"type", "sphere"}, {"name", "sphere"}, {"center", vec(0, 0, 0)},
                                  {"radius", 1}, {"material", "glass"}}})},
        {"render", {{"integrator", "fresnel-tree"}, {"max_depth", 8}, {"threshold", 0}, {"polarisation", "exact"}}},
    };
}

std::vector<SpherePoint> sphere_points(double n, const std::vector<double>& angles_deg) {
    const Scene scene = scene_from_json(sphere_dop_scene(n), "sphere-dop");
    const SceneTracer tracer(scene);
    RenderStats st;
    RayTreeWalkerT<EyeStokes> walker(tracer, tree_limits(scene.settings), st);
    std::vector<SpherePoint> out;
    for (double a : angles_deg) {
        // Light leaves towards the camera along −z; the frame x̂ = +y is ŝ of every
        // interface on the path (all in the x-z plane), so S1/S0 is (Is − Ip)/(Is + Ip).
        const Ray primary{Vec3(std::sin(a * kDeg), 0, -3), Vec3(0, 0, 1)};
        RayTreeWalkerT<EyeStokes>::List list{TreeEntryT<EyeStokes>{primary, Vec3(1, 1, 1)}};
        list.front().pol.x = Vec3(0, 1, 0);
        ClassEnds ends;
        walker.walk(list, ends);
        for (size_t c = 0; c < path_classes().size(); ++c) {
            SpherePoint p;
            p.n = n;
            p.theta_deg = a;
            p.cls = static_cast<int>(c);
            p.S = ends.S[c];
            p.dop = polar::degree_of_polarisation(p.S);
            p.s1 = p.S(0) > 0 ? p.S(1) / p.S(0) : 0.0;
            p.s1_closed = closed_form_signed(path_classes()[c], n, a);
            p.dop_closed = std::abs(p.s1_closed);
            out.push_back(p);
        }
    }
    return out;
}

SphereStudy sphere_study() {
    SphereStudy sp;
    sp.indices = {1.5, 1.333};
    for (int k = 0; k < 90; ++k) sp.angles_deg.push_back(k);
    for (double n : sp.indices) {
        sp.scenes[n] = sphere_dop_scene(n);
        const auto pts = sphere_points(n, sp.angles_deg);
        for (size_t c = 0; c < path_classes().size(); ++c) {
            SphereClassError e;
            e.n = n;
            e.cls = static_cast<int>(c);
            for (const auto& p : pts) {
                if (p.cls != e.cls) continue;
                ++e.points;
                e.max_dop_error = std::fmax(e.max_dop_error, std::abs(p.dop - p.dop_closed));
                e.max_signed_error = std::fmax(e.max_signed_error, std::abs(p.s1 - p.s1_closed));
                e.max_s23 = std::fmax(e.max_s23, std::hypot(p.S(2), p.S(3)) / p.S(0));
            }
            sp.max_dop_error = std::fmax(sp.max_dop_error, e.max_dop_error);
            sp.errors.push_back(e);
        }
        sp.points.insert(sp.points.end(), pts.begin(), pts.end());
        // The primary rainbow: minimum deviation of the one-internal-reflection path.
        RainbowRay rb;
        rb.n = n;
        rb.theta_deg = std::acos(std::sqrt((n * n - 1) / 3)) / kDeg;
        const double theta_t = std::asin(std::sin(rb.theta_deg * kDeg) / n) / kDeg;
        rb.deviation_deg = 180 + 2 * rb.theta_deg - 4 * theta_t;
        const auto p = sphere_points(n, {rb.theta_deg});
        rb.dop = p.at(2).dop;
        rb.dop_closed = p.at(2).dop_closed;
        sp.rainbows.push_back(rb);
    }
    return sp;
}

}  // namespace refract::experiments::polarisation
