// Sampled gradient-index fields (core/grin/grid.h, docs/grin.md "Sampled fields"): the
// tricubic B-spline through the samples, the Gladstone–Dale law for a temperature grid, a
// Luneburg lens sampled on grids of rising resolution, OpenVDB files, and the refusals.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <refract/core/grin/air_index.h>
#include <refract/core/grin/grid.h>
#include <refract/core/grin/media.h>
#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/scene.h>
#include <refract/core/scene_json.h>

#include "input_error.h"

using namespace refract;
using namespace refract::grin;
using nlohmann::json;

namespace {

// Samples of f on an n³ grid over [lo, hi]³.
template <class F>
GridSamples sample(int n, double lo, double hi, F f) {
    GridSamples s;
    s.dims = {n, n, n};
    s.origin = Vec3::Constant(lo);
    s.spacing = Vec3::Constant((hi - lo) / (n - 1));
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) s.values.push_back(f(s.origin + Vec3(i, j, k).cwiseProduct(s.spacing)));
    return s;
}

SampledGrid index_grid(const GridSamples& s) { return sampled_grid(s, GridQuantity::index, 288.15, 101325.0, "values", "t"); }

// The inline "values" of samples, values[i][j][k].
json values_json(const GridSamples& s) {
    json v = json::array();
    for (int i = 0; i < s.dims[0]; ++i) {
        json a = json::array();
        for (int j = 0; j < s.dims[1]; ++j) {
            json b = json::array();
            for (int k = 0; k < s.dims[2]; ++k) b.push_back(s.values[static_cast<size_t>(i + s.dims[0] * (j + s.dims[1] * k))]);
            a.push_back(b);
        }
        v.push_back(a);
    }
    return v;
}

// A scene of one grin sphere (radius 1 at the origin) filled by `profile`.
json sphere_scene(const json& profile) {
    return json{{"camera", {{"location", {0, 0, -4}}, {"look_at", {0, 0, 0}}, {"width", 8}, {"height", 6}}},
                {"materials", {{"g", {{"type", "grin"}, {"profile", profile}}}}},
                {"objects", json::array({{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "g"}}})}};
}

std::string media_error(const json& j, const std::string& file = "g.json") {
    return test::error_of([&] {
        const Scene s = parse_scene(j, file);
        (void)grin::media(s);
    });
}

}  // namespace

TEST_CASE("Tricubic B-spline interpolant reproduces a linear field and its gradient exactly", "[grin][grid]") {
    const Vec3 a(0.3, -1.7, 2.2);
    auto f = [&](const Vec3& x) { return 1.4 + a.dot(x); };
    GridSamples s;
    s.dims = {5, 4, 6};
    s.origin = Vec3(-1, 0.5, 2);
    s.spacing = Vec3(0.25, 0.4, 0.1);
    for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 5; ++i) s.values.push_back(f(s.origin + Vec3(i, j, k).cwiseProduct(s.spacing)));
    const SampledGrid g = index_grid(s);
    double worst = 0, worst_grad = 0;
    for (const Vec3& t : {Vec3(0, 0, 0), Vec3(0.13, 0.77, 0.5), Vec3(0.999, 0.01, 0.31), Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.92)}) {
        const Vec3 x = grid_lo(g) + t.cwiseProduct(grid_hi(g) - grid_lo(g));
        const IndexGradient ng = index_and_gradient(g, x, 0.55);
        worst = std::max(worst, std::abs(ng.n - f(x)));
        worst_grad = std::max(worst_grad, (ng.grad - a).norm());
    }
    CHECK(worst < 1e-13);
    CHECK(worst_grad < 1e-12);
}

TEST_CASE("Tricubic B-spline interpolant converges at fourth order in the value and third in the gradient on a "
          "smooth field",
          "[grin][grid]") {
    auto f = [](const Vec3& x) { return 1.5 + 0.1 * std::sin(2 * x.x()) * std::cos(1.5 * x.y()) * std::exp(0.5 * x.z()); };
    auto grad = [](const Vec3& x) {
        const double s = std::sin(2 * x.x()), c = std::cos(1.5 * x.y()), e = std::exp(0.5 * x.z());
        return Vec3(0.2 * std::cos(2 * x.x()) * c * e, -0.15 * s * std::sin(1.5 * x.y()) * e, 0.05 * s * c * e);
    };
    // The errors over points in the central half of [−1, 1]³ (the natural ends lose two
    // orders within a few samples of the box's faces).
    auto errors = [&](int n) {
        const SampledGrid g = index_grid(sample(n, -1, 1, f));
        double ev = 0, eg = 0;
        // 20³ points at irrational steps (every position within the cells is met).
        for (int k = 0; k < 20; ++k)
            for (int j = 0; j < 20; ++j)
                for (int i = 0; i < 20; ++i) {
                    const Vec3 x(-0.5 + std::fmod(i * 0.6180339887, 1.0), -0.5 + std::fmod(j * 0.4142135624, 1.0),
                                 -0.5 + std::fmod(k * 0.7320508076, 1.0));
                    const IndexGradient ng = index_and_gradient(g, x, 0.55);
                    ev = std::max(ev, std::abs(ng.n - f(x)));
                    eg = std::max(eg, (ng.grad - grad(x)).norm());
                }
        return std::pair<double, double>{ev, eg};
    };
    const auto [v1, g1] = errors(17);
    const auto [v2, g2] = errors(33);
    const auto [v3, g3] = errors(65);
    const double order_v = std::log2(v2 / v3), order_g = std::log2(g2 / g3);
    INFO("value errors " << v1 << " " << v2 << " " << v3 << ", gradient errors " << g1 << " " << g2 << " " << g3);
    CHECK(order_v > 3.6);
    CHECK(order_v < 4.4);
    CHECK(order_g > 2.6);
    CHECK(order_g < 3.4);
    CHECK(std::log2(v1 / v2) > 3.4);
    CHECK(v3 < 1e-7);
}

TEST_CASE("Luneburg lens sampled on a grid: parallel rays meet near the antipode, the spot shrinking as the grid "
          "refines",
          "[grin][grid]") {
    // n = √(2 − r²) inside the unit sphere, continued smoothly past it (held at √0.25 beyond
    // r² = 1.75, far from the sphere) so that the spline sees no kink at the surface.
    auto n = [](const Vec3& x) { return std::sqrt(2.0 - std::min(x.squaredNorm(), 1.75)); };
    const Region sphere = grin::Sphere{Vec3::Zero(), 1.0};
    Settings st;
    st.abs_tol = st.rel_tol = 1e-11;
    auto spot = [&](int cells) {
        const double h = 2.2 / cells;
        const SampledGrid g = index_grid(sample(cells + 1, -1.1, 1.1, n));
        (void)h;
        double worst = 0;
        for (const double b : {0.15, 0.35, 0.55, 0.75}) {
            const Vec3 x0(b, 0.0, -std::sqrt(1.0 - b * b));
            const Result r = advance(g, sphere, x0, Vec3::UnitZ(), 0.55, st);
            REQUIRE(r.status == Status::left_region);
            worst = std::max(worst, (r.exit_point - Vec3::UnitZ()).norm());
        }
        return worst;
    };
    const double s1 = spot(22), s2 = spot(44), s3 = spot(88);
    INFO("spot radii " << s1 << " " << s2 << " " << s3);
    CHECK(s2 < s1 / 4);
    CHECK(s3 < s2 / 4);
    CHECK(s3 < 1e-4);
}

TEST_CASE("Gladstone-Dale law for heated air: n(T) - 1 = (n_ref - 1) T_ref / T, and the temperature grid's index",
          "[grin][grid]") {
    // By hand: refractivity 2.7e-4 at 288.15 K is 2.7e-4 · 288.15 / 330 = 2.357591e-4 at 330 K.
    CHECK(gladstone_dale_refractivity_at(2.7e-4, 288.15, 330.0) == Approx(2.3575909090909e-4).epsilon(1e-12));
    // The ratio form the grid uses: density ratio q = 288.15/330 gives the same refractivity.
    CHECK(gladstone_dale_refractivity(2.7e-4, 288.15 / 330.0) == Approx(2.3575909090909e-4).epsilon(1e-12));
    // A uniform 330 K grid: its index is Ciddor's at 288.15 K scaled by the density, which
    // Ciddor's own procedure at 330 K matches to the compressibility's share (< 1e-3 relative).
    GridSamples s = sample(3, -1, 1, [](const Vec3&) { return 330.0; });
    const SampledGrid g = sampled_grid(s, GridQuantity::temperature, 288.15, 101325.0, "values", "t");
    AirState ref;
    const double n_ref = ciddor_index(0.55, ref);
    const double n = index(g, Vec3(0.1, 0.2, 0.3), 0.55);
    CHECK(n - 1 == Approx((n_ref - 1) * 288.15 / 330.0).epsilon(1e-12));
    AirState hot;
    hot.temperature_K = 330.0;
    CHECK(std::abs((n - 1) / (ciddor_index(0.55, hot) - 1) - 1) < 1e-3);
    // Relative to the reference air: 1 at T_ref, (n_ref − 1)(T_ref/T − 1) below 1 in hotter air.
    SampledGrid rel = g;
    rel.relative = true;
    CHECK(index(rel, Vec3::Zero(), 0.55) - 1 == Approx((n_ref - 1) * (288.15 / 330.0 - 1)).epsilon(1e-12));
    const SampledGrid at_ref = sampled_grid(sample(3, -1, 1, [](const Vec3&) { return 288.15; }), GridQuantity::temperature,
                                            288.15, 101325.0, "values", "t");
    rel = at_ref;
    rel.relative = true;
    CHECK(std::abs(index(rel, Vec3(0.3, 0.1, 0.2), 0.55) - 1.0) < 1e-15);
    // It disperses: bluer light, the higher index.
    CHECK(index(g, Vec3::Zero(), 0.45) > index(g, Vec3::Zero(), 0.65));
    CHECK(dispersive(Profile{g}));
    // The gradient of a linear temperature ramp, where the ramp is ∂T/∂x = 10 K per unit:
    // ∇n = −(n_ref − 1)·T_ref/T²·∂T/∂x.
    GridSamples ramp = sample(5, -1, 1, [](const Vec3& x) { return 300.0 + 10.0 * x.x(); });
    const SampledGrid gr = sampled_grid(ramp, GridQuantity::temperature, 288.15, 101325.0, "values", "t");
    const Vec3 grad = gradient(gr, Vec3::Zero(), 0.55);
    CHECK(grad.x() == Approx(-(n_ref - 1) * 288.15 / (300.0 * 300.0) * 10.0).epsilon(2e-4));
}

TEST_CASE("OpenVDB grid written and read back through a scene equals the same samples given inline", "[grin][grid]") {
    // Float samples (an OpenVDB FloatGrid holds floats): the inline grid gets the same.
    GridSamples s = sample(9, -1.2, 1.2, [](const Vec3& x) {
        return static_cast<double>(static_cast<float>(1.3 + 0.1 * std::cos(x.x()) * std::sin(x.y() + 0.3 * x.z())));
    });
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "refract_test_grin_grid";
    std::filesystem::create_directories(dir);
    write_vdb_grid((dir / "field.vdb").string(), "n", s);
    const Scene from_file =
            parse_scene(sphere_scene({{"kind", "grid"}, {"file", "field.vdb"}, {"grid", "n"}}), (dir / "a.json").string());
    const Scene inline_ = parse_scene(
            sphere_scene({{"kind", "grid"}, {"origin", {-1.2, -1.2, -1.2}}, {"spacing", 0.3}, {"values", values_json(s)}}),
            "b.json");
    const auto ma = grin::media(from_file), mb = grin::media(inline_);
    REQUIRE(ma.size() == 1);
    REQUIRE(mb.size() == 1);
    const auto& ga = std::get<SampledGrid>(ma[0].profile);
    const auto& gb = std::get<SampledGrid>(mb[0].profile);
    CHECK(ga.dims == gb.dims);
    CHECK((ga.origin - gb.origin).norm() < 1e-12);
    CHECK((ga.spacing - gb.spacing).norm() < 1e-12);
    double worst = 0;
    for (const Vec3& x : {Vec3(0, 0, 0), Vec3(0.3, -0.41, 0.77), Vec3(-0.9, 0.1, 0.2)})
        worst = std::max(worst, std::abs(index(ga, x, 0.55) - index(gb, x, 0.55)) + (gradient(ga, x, 0.55) - gradient(gb, x, 0.55)).norm());
    CHECK(worst < 1e-12);
    // The first scalar grid when none is named; a name not in the file refused.
    CHECK(media_error(sphere_scene({{"kind", "grid"}, {"file", "field.vdb"}}), (dir / "a.json").string()).empty());
    const std::string e =
            media_error(sphere_scene({{"kind", "grid"}, {"file", "field.vdb"}, {"grid", "T"}}), (dir / "a.json").string());
    CHECK(e.find("/materials/g/profile/grid: no grid 'T'") != std::string::npos);
    // An OpenVDB file's active voxels far apart: 4097³ dense samples, past kMaxGridSamples,
    // refused before anything is allocated; 400³ allowed.
    try {
        check_grid_size(4097, 4097, 4097, "v.json: /materials/g/profile/file");
        FAIL("not refused");
    } catch (const InputError& err) {
        CHECK(std::string(err.what()) == "v.json: /materials/g/profile/file: the grid's active voxels span "
                                         "4097×4097×4097 samples, more than 67108864");
    }
    CHECK_NOTHROW(check_grid_size(400, 400, 400, "v.json"));
    std::filesystem::remove_all(dir);
}

TEST_CASE("Sampled grids refused: a grid not covering the region, a temperature <= 0, a missing file, wrong "
          "dimensions",
          "[grin][grid]") {
    GridSamples s = sample(4, -1.2, 1.2, [](const Vec3&) { return 300.0; });
    json grid = {{"kind", "grid"}, {"quantity", "temperature"}, {"origin", {-1.2, -1.2, -1.2}}, {"spacing", 0.8},
                 {"values", values_json(s)}};
    CHECK(media_error(sphere_scene(grid)).empty());
    // Not covering: the box [−0.8, 1.6]³ misses the sphere's x < −0.8.
    json shifted = grid;
    shifted["origin"] = {-0.8, -1.2, -1.2};
    const std::string cover = media_error(sphere_scene(shifted));
    INFO(cover);
    CHECK(cover.rfind("g.json: /materials/g/profile/values: the grid's box [-0.8, 1.6]", 0) == 0);
    CHECK(cover.find("does not cover the medium's region [-1, 1]") != std::string::npos);
    // A temperature of 0 K.
    json cold = grid;
    cold["values"][2][1][3] = 0.0;
    CHECK(media_error(sphere_scene(cold)) ==
          "g.json: /materials/g/profile/values/2/1/3: the temperature 0 must be finite and > 0");
    json neg = grid;
    neg["quantity"] = "index";
    neg["values"][0][0][0] = -1.0;
    CHECK(media_error(sphere_scene(neg)) == "g.json: /materials/g/profile/values/0/0/0: the index -1 must be finite and > 0");
    // A missing file.
    const std::string missing = media_error(sphere_scene({{"kind", "grid"}, {"file", "nowhere.vdb"}}));
    CHECK(missing.rfind("g.json: /materials/g/profile/file: no such file", 0) == 0);
    // Wrong dimensions: a ragged row, and one sample along an axis.
    json ragged = grid;
    ragged["values"][1][2].erase(0);
    CHECK(media_error(sphere_scene(ragged)) == "g.json: /materials/g/profile/values/1/2: 3 values, the first row has 4");
    json flat = grid;
    flat["values"] = json::array({json::array({json::array({300.0, 300.0})})});
    CHECK(media_error(sphere_scene(flat)).rfind("g.json: /materials/g/profile/values: 1 samples along x, at least 2", 0) == 0);
}
