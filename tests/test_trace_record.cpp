// The path record (refract trace): every segment of one ray's tree, from the walker that
// renders, so its sum is the pixel and its nodes obey Fresnel and Snell.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include <refract/core/optics.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
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
