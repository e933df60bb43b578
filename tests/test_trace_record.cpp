// The path record (refract trace): every segment of one ray's tree, from the walker that
// renders, so its sum is the pixel and its nodes obey Fresnel and Snell.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/integrators/integrator.h>
#include <refract/core/optics.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/trace_record.h>
#include <refract/geometry/error.h>

using namespace refract;
using nlohmann::json;

namespace {

Scene sphere_on_floor(const json& glass) {
    const json j = {{"camera", {{"location", {0, 1, -6}}, {"look_at", {0, 0.5, 0}}, {"angle", 45}, {"width", 40}, {"height", 30}}},
                    {"background", {0.4, 0.5, 0.8}},
                    {"materials", {{"glass", glass}, {"floor", {{"type", "diffuse"}, {"color", {0.9, 0.9, 0.9}}}}}},
                    {"objects", {{{"type", "sphere"}, {"name", "ball"}, {"center", {0, 1, 0}}, {"radius", 1}, {"material", "glass"}},
                                 {{"type", "plane"}, {"name", "floor"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}}},
                    {"lights", {{{"position", {5, 10, -5}}}}},
                    {"render", {{"max_depth", 10}, {"threshold", 0.001}}}};
    return parse_scene(j, "trace.json");
}

}  // namespace

TEST_CASE("Path record: the segments' light sums to the rendered pixel, every node obeys Fresnel", "[trace]") {
    const Scene s = sphere_on_floor({{"type", "dielectric"}, {"ior", 1.5}});
    for (const auto& [i, j] : {std::pair{20, 14}, std::pair{22, 9}, std::pair{5, 25}}) {
        const TraceRecord r = trace_pixel(s, i, j);
        const Vec3 v = render_pixel(s, i, j);
        CHECK((r.radiance - v).cwiseAbs().maxCoeff() == 0.0);  // the same walk, the same sums
        REQUIRE_FALSE(r.segments.empty());
        CHECK(r.segments[0].parent == -1);
        for (const TraceSegment& seg : r.segments) {
            if (seg.parent >= 0) {
                const TraceSegment& p = r.segments[static_cast<size_t>(seg.parent)];
                CHECK(seg.ray.origin == p.point);  // a child starts where its parent ended
                CHECK(seg.depth == p.depth + 1);
            }
            if (seg.eta > 0) {
                const auto f = optics::fresnel(seg.cos_i, seg.eta);
                if (f) {
                    CHECK(seg.Rs == f->Rs);
                    CHECK(seg.Rp == f->Rp);
                    CHECK(seg.R == Approx(f->R()).epsilon(1e-15));
                } else {
                    CHECK(seg.event == "total internal reflection");
                }
            }
        }
    }
}

TEST_CASE("Path record at one wavelength: the refracted ray obeys Snell's law with n(lambda)", "[trace]") {
    const Scene s = sphere_on_floor({{"type", "dielectric"}, {"dispersion", "diamond"}});
    const Ray ray{Vec3(0.4, 1.3, -5), Vec3(0, 0, 1)};
    for (double nm : {450.0, 650.0}) {
        const TraceRecord r = trace_ray(s, ray, nm);
        const double n = s.materials.at(s.objects.at(0).material).dielectric()->dispersion->n(nm);
        REQUIRE(r.segments.size() >= 3);
        const TraceSegment& first = r.segments[0];
        CHECK(first.eta == n);
        // The refracted child: sin θt = sin θi / n.
        bool found = false;
        for (const TraceSegment& c : r.segments)
            if (c.parent == 0 && c.transmissions == 1) {
                const Vec3 normal = (first.point - Vec3(0, 1, 0)).normalized();
                CHECK(c.ray.dir.cross(normal).norm() == Approx(ray.dir.cross(normal).norm() / n).epsilon(1e-12));
                found = true;
            }
        CHECK(found);
    }
}

TEST_CASE("Path record: a pixel outside the image and a wavelength outside the tables are refused", "[trace]") {
    const Scene s = sphere_on_floor({{"type", "dielectric"}, {"ior", 1.5}});
    CHECK_THROWS_WITH(trace_pixel(s, 40, 0), Catch::Contains("--pixel 40 0"));
    CHECK_THROWS_WITH(trace_ray(s, Ray{Vec3(0, 1, -5), Vec3(0, 0, 1)}, 1200), Catch::Contains("--wavelength"));
    CHECK_THROWS_WITH(trace_ray(s, Ray{Vec3(0, 1, -5), Vec3(0, 0, 0)}), Catch::Contains("direction"));
}

TEST_CASE("Path record: the normal at each hit is unit, faces the incoming ray and gives cos_i", "[trace]") {
    const Scene s = sphere_on_floor({{"type", "dielectric"}, {"ior", 1.5}});
    const TraceRecord r = trace_pixel(s, 20, 14);
    int dielectric = 0;
    for (const auto& seg : r.segments) {
        if (!seg.hit) continue;
        CHECK(seg.normal.norm() == Approx(1.0).epsilon(1e-14));
        CHECK(seg.ray.dir.dot(seg.normal) < 0);
        if (seg.eta > 0) {
            ++dielectric;
            CHECK(-seg.ray.dir.dot(seg.normal) == Approx(seg.cos_i).epsilon(1e-14));
            if (seg.object == "ball") CHECK(seg.normal.dot(seg.point - Vec3(0, 1, 0)) * (seg.entering ? 1 : -1) > 0);
        }
    }
    CHECK(dielectric >= 2);
}

namespace {

// A calcite slab 0.5 thick (0.05 < y < 0.55) under a sky, its optic axis in the x-y plane
// at `axis_deg` to the slab's normal (+y).
Scene calcite_slab(double axis_deg, const std::string& polarisation = "") {
    const double a = axis_deg * M_PI / 180;
    json j = {{"camera", {{"location", {0, 3, -3}}, {"look_at", {0, 0.3, 0}}, {"width", 8}, {"height", 6}}},
              {"background", {0.3, 0.5, 0.7}},
              {"materials", {{"calcite", {{"type", "uniaxial"}, {"crystal", "calcite"}, {"optic_axis", {std::sin(a), std::cos(a), 0}}}}}},
              {"objects", {{{"type", "polyhedron"}, {"name", "slab"}, {"material", "calcite"},
                            {"planes", {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}, {0, 1, 0, 0.55}, {0, -1, 0, -0.05}}}}}},
              {"render", {{"max_depth", 4}, {"threshold", 1e-6}, {"spectral", false}}}};
    if (!polarisation.empty()) j["render"]["polarisation"] = polarisation;
    return parse_scene(j, "calcite.json");
}

// The index ellipsoid in closed form: n_e(θ) = n_o n_e / √(n_e² cos²θ + n_o² sin²θ).
double closed_form_e_index(double no, double ne, double theta) {
    const double c = std::cos(theta), s = std::sin(theta);
    return no * ne / std::sqrt(ne * ne * c * c + no * no * s * s);
}

}  // namespace

TEST_CASE("Path record in calcite: each segment's wave (o/e) and index, the e wave's against n_e(theta) in closed form",
          "[trace][birefringence]") {
    const auto calcite = *spectrum::uniaxial_crystal("calcite");
    const double no = calcite.ordinary.n(spectrum::fraunhofer::D), ne = calcite.extraordinary.n(spectrum::fraunhofer::D);
    for (double axis_deg : {30.0, 45.0, 70.0}) {
        INFO("optic axis at " << axis_deg << " degrees to the normal");
        const double theta = axis_deg * M_PI / 180;
        const Vec3 axis(std::sin(theta), std::cos(theta), 0);
        // Normal incidence: both wave normals stay on the normal, so the e wave's is at θ
        // to the axis, while its ray walks off.
        const TraceRecord r = trace_ray(calcite_slab(axis_deg), Ray{Vec3(0.1, 2, 0.2), Vec3(0, -1, 0)});
        int o = 0, e = 0;
        for (const TraceSegment& s : r.segments) {
            if (s.wave == biref::Wave::Isotropic) {
                CHECK(s.index == 0);  // in the air: no crystal wave
                continue;
            }
            REQUIRE(s.parent >= 0);
            CHECK(r.segments[static_cast<size_t>(s.parent)].object == "slab");
            if (s.wave == biref::Wave::Ordinary) {
                ++o;
                CHECK(s.index == Approx(no).epsilon(1e-15));
            } else {
                ++e;
                const double cos_k = std::abs(s.wave_normal.dot(axis));
                CHECK(s.index == Approx(closed_form_e_index(no, ne, std::acos(cos_k))).epsilon(1e-13));
                CHECK(s.wave_normal.norm() == Approx(1.0).epsilon(1e-14));
            }
            if (s.parent == 0) {  // the two waves entering from the first hit
                CHECK(std::abs(s.wave_normal.y()) == Approx(1.0).epsilon(1e-13));
                if (s.wave == biref::Wave::Extraordinary) {
                    CHECK(s.index == Approx(closed_form_e_index(no, ne, theta)).epsilon(1e-13));
                    CHECK(s.ray.dir.dot(s.wave_normal) < 1 - 1e-4);  // the ray walks off the wave normal
                } else {
                    CHECK((s.ray.dir - s.wave_normal).norm() < 1e-15);  // o: the ray is along its wave normal
                }
            }
        }
        CHECK(o >= 1);
        CHECK(e >= 1);
    }
    // Oblique incidence, 35° in the plane of the normal and the axis: the e wave's wave
    // normal keeps the tangential component (phase matching, n_e(θ_k) sin θ_k = sin θ_i),
    // and its index is the closed form at its own angle to the axis.
    const double ti = 35 * M_PI / 180;
    const Vec3 d(std::sin(ti), -std::cos(ti), 0);
    const TraceRecord r = trace_ray(calcite_slab(45), Ray{Vec3(0, 0.55, 0) - 3 * d, d});
    bool e_seen = false;
    for (const TraceSegment& s : r.segments)
        if (s.parent == 0 && s.wave != biref::Wave::Isotropic) {
            const Vec3 k = s.index * s.wave_normal;
            CHECK(k.x() == Approx(std::sin(ti)).epsilon(1e-12));  // the tangential part of the incident wave vector
            CHECK(k.z() == Approx(0).margin(1e-15));
            if (s.wave == biref::Wave::Extraordinary) {
                e_seen = true;
                const Vec3 axis(std::sin(M_PI / 4), std::cos(M_PI / 4), 0);
                CHECK(s.index == Approx(closed_form_e_index(no, ne, std::acos(std::abs(s.wave_normal.dot(axis))))).epsilon(1e-13));
                CHECK(s.index != Approx(no).epsilon(1e-3));
            } else {
                CHECK(s.index == Approx(no).epsilon(1e-15));
            }
        }
    CHECK(e_seen);
    // At another wavelength the indices are the crystal's there.
    const TraceRecord blue = trace_ray(calcite_slab(45), Ray{Vec3(0.1, 2, 0.2), Vec3(0, -1, 0)}, 450.0);
    for (const TraceSegment& s : blue.segments)
        if (s.parent == 0 && s.wave == biref::Wave::Ordinary) CHECK(s.index == Approx(calcite.ordinary.n(450.0)).epsilon(1e-15));
}

TEST_CASE("Path record under the physical mode's default (exact polarisation) sums to the rendered pixel", "[trace]") {
    const Scene s = sphere_on_floor({{"type", "dielectric"}, {"ior", 1.5}});
    REQUIRE(polarisation_model(s) == PolarisationModel::Exact);
    for (const auto& [i, j] : {std::pair{20, 14}, std::pair{22, 9}}) {
        const TraceRecord r = trace_pixel(s, i, j);
        CHECK((r.radiance - render_pixel(s, i, j)).cwiseAbs().maxCoeff() == 0.0);
    }
    // A calcite slab too (its o and e waves carry their own Mueller matrices).
    const Scene c = calcite_slab(45);
    REQUIRE(polarisation_model(c) == PolarisationModel::Exact);
    const TraceRecord r = trace_pixel(c, 4, 3);
    CHECK((r.radiance - render_pixel(c, 4, 3)).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("Trace session: the tracers built once give every query trace_ray's record to the last bit", "[trace]") {
    const auto s = std::make_shared<const Scene>(
        sphere_on_floor({{"type", "dielectric"}, {"ior", 1.5168}, {"dispersion", "BK7"}}));
    const TraceSession session(s);
    PolarisationState linear;
    linear.kind = PolarisationState::Kind::Linear;
    linear.angle_deg = 30;
    const auto same = [](const TraceRecord& a, const TraceRecord& b) {
        REQUIRE(a.segments.size() == b.segments.size());
        CHECK(a.radiance == b.radiance);
        for (size_t k = 0; k < a.segments.size(); ++k) {
            const TraceSegment &x = a.segments[k], &y = b.segments[k];
            CHECK(x.ray.origin == y.ray.origin);
            CHECK(x.ray.dir == y.ray.dir);
            CHECK(x.weight == y.weight);
            CHECK(x.event == y.event);
            CHECK(x.Rs == y.Rs);
            CHECK(x.Rp == y.Rp);
            CHECK(x.light == y.light);
            CHECK(x.stokes == y.stokes);
        }
    };
    for (int rep = 0; rep < 2; ++rep) {  // the second round on the kept tracers
        for (const auto& [i, j] : {std::pair{20, 14}, std::pair{22, 9}, std::pair{5, 25}}) {
            same(session.pixel(i, j), trace_pixel(*s, i, j));
            same(session.pixel(i, j, 550), trace_pixel(*s, i, j, 550));
            same(session.pixel(i, j, 480, &linear), trace_pixel(*s, i, j, 480, &linear));
        }
    }
    const Ray r{Vec3(0, 1, -5), Vec3(0.05, 0, 1)};
    same(session.ray(r, 600), trace_ray(*s, r, 600));
    CHECK_THROWS_AS(session.pixel(40, 0), InputError);
    CHECK_THROWS_AS(session.ray(r, 100), InputError);
}
