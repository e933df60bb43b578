// Gradient-index objects in scenes (docs/grin.md): the one walker bends a ray inside a
// "grin" material along the ray equation (SceneTracer::through), the exact Fresnel split at
// its surface takes the profile's index at the hit point, and the far field, renders and
// `trace` go through it without a walk of their own.
#include <catch2/catch.hpp>

#include <cmath>

#include <refract/core/far_field.h>
#include <refract/core/grin/atmosphere.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/trace_record.h>
#include <refract/core/tracer.h>

#include "input_error.h"

using namespace refract;
using nlohmann::json;

namespace {
constexpr double kPi = 3.14159265358979323846;

json luneburg_scene(double tolerance) {
    json j = json::parse(R"({
      "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 40, "width": 24, "height": 18},
      "background": {"type": "gradient"},
      "materials": {"lens": {"type": "grin", "profile": {"kind": "luneburg", "centre": [0, 0, 0], "radius": 1}}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lens"}],
      "lights": [{"type": "beam", "position": [0, 0, -3], "direction": [0, 0, 1], "radius": 1.2}]
    })");
    j["materials"]["lens"]["tolerance"] = tolerance;
    return j;
}
}  // namespace

TEST_CASE("Luneburg lens in a scene: the walker's curved segment takes a parallel ray to the antipodal point",
          "[grin]") {
    const Scene scene = parse_scene(luneburg_scene(1e-12), "luneburg.json");
    for (const double b : {0.1, 0.45, 0.8, 0.97}) {
        const TraceRecord rec = trace_ray(scene, Ray{Vec3(b, 0, -3), Vec3(0, 0, 1)});
        REQUIRE(rec.segments.size() >= 2);
        const TraceSegment& in = rec.segments[0];
        REQUIRE(in.hit);
        CHECK(in.entering);
        CHECK(in.eta == Approx(1.0).margin(1e-15));  // n(R) = 1: no interface at the surface
        // The transmitted ray, inside: it leaves at (0, 0, 1) whatever its height.
        const TraceSegment* inside = nullptr;
        for (const TraceSegment& s : rec.segments)
            if (s.parent == 0 && s.transmissions == 1) inside = &s;
        REQUIRE(inside != nullptr);
        CHECK((inside->point - Vec3(0, 0, 1)).norm() < 1e-9);
        CHECK_FALSE(inside->entering);
        // Curved: longer than the chord from the entry point, and arriving along the normal
        // turned by the lens (the arrival direction is not the departure's).
        CHECK(inside->length > (inside->point - in.point).norm());
        CHECK(inside->ray.dir.z() < 1.0 - 1e-6);
    }
}

TEST_CASE("Far field through a Luneburg sphere: the beam's power is conserved to 1e-9, natural light and exact "
          "polarisation (the Stokes frame carried along the curved rays)",
          "[grin]") {
    for (const char* model : {"natural", "exact"}) {
        json j = luneburg_scene(1e-10);
        j["render"] = {{"polarisation", model}};
        const Scene scene = parse_scene(j, "luneburg.json");
        FarFieldSettings s;
        s.photons = 3000;
        s.wavelengths = {550.0};
        s.azimuth_bins = 36;
        s.polar_bins = 18;
        const FarFieldResult r = far_field(scene, s, 2);
        const double total = r.scattered(0) + r.unscattered[0] + r.absorbed[0] + r.dropped[0];
        CHECK(std::abs(total - 1.0) < 1e-9);
        CHECK(r.scattered(0) > 0.5);  // the beam covers the sphere (radius 1 of 1.2)
        if (r.components == 4) {      // every bin's degree of polarisation ≤ 1
            for (int b = 0; b < r.bins; ++b) {
                double S[4] = {0, 0, 0, 0};
                for (int c = 0; c < r.classes; ++c)
                    for (int k = 0; k < 4; ++k) S[k] += r.at(0, c, k, b);
                CHECK(std::sqrt(S[1] * S[1] + S[2] * S[2] + S[3] * S[3]) <= S[0] * (1 + 1e-12) + 1e-300);
            }
        }
    }
}

TEST_CASE("A render through a gradient-index sphere is the same on 1 and 2 threads, and finite", "[grin]") {
    const Scene scene = parse_scene(luneburg_scene(1e-9), "luneburg.json");
    RenderOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const RenderResult a = render(scene, one), b = render(scene, two);
    REQUIRE(a.image.rgb.size() == b.image.rgb.size());
    double sum = 0;
    for (size_t k = 0; k < a.image.rgb.size(); ++k) sum += a.image.rgb[k];
    CHECK(a.image.rgb == b.image.rgb);
    CHECK(std::isfinite(sum));
    CHECK(a.stats.grin_segments > 0);
    CHECK(a.stats.grin_evaluations > 10 * a.stats.grin_segments);
    CHECK(a.stats.grin_exhausted == 0);
}

TEST_CASE("Hyperbolic-secant rod in a box: rays from an axial point on its face meet the axis again one pitch on",
          "[grin]") {
    const double L = 2 * kPi;  // α = 1
    json j = json::parse(R"({
      "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "width": 8, "height": 8},
      "materials": {"rod": {"type": "grin", "tolerance": 1e-12,
                            "profile": {"kind": "sech-rod", "point": [0, 0, 0], "axis": [0, 0, 1], "n0": 1.5, "alpha": 1}}},
      "lights": []
    })");
    j["objects"] = json::array({json{{"type", "polyhedron"},
                                     {"material", "rod"},
                                     {"planes", {{1, 0, 0, 1.5}, {-1, 0, 0, 1.5}, {0, 1, 0, 1.5}, {0, -1, 0, 1.5},
                                                 {0, 0, 1, L}, {0, 0, -1, 0}}}}});
    const Scene scene = parse_scene(j, "rod.json");
    for (const double deg : {5.0, 12.0, 20.0}) {
        const double a = deg * kPi / 180;
        const Vec3 d(std::sin(a), 0.0, std::cos(a));
        const TraceRecord rec = trace_ray(scene, Ray{-d, d});
        const TraceSegment* inside = nullptr;
        for (const TraceSegment& s : rec.segments)
            if (s.parent == 0 && s.transmissions == 1) inside = &s;
        REQUIRE(inside != nullptr);
        CHECK(inside->point.z() == Approx(L).epsilon(1e-12));
        CHECK(std::abs(inside->point.x()) < 1e-9);
        CHECK(std::abs(inside->point.y()) < 1e-12);
    }
}

TEST_CASE("Gradient-index media: impossible input is refused naming the file and the field", "[grin]") {
    auto error = [](const json& j) {
        return test::error_of([&] {
            const Scene s = parse_scene(j, "g.json");
            render(s);
        });
    };
    json plane = luneburg_scene(1e-9);
    plane["objects"] = json::array({json{{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "lens"}}});
    CHECK_THAT(error(plane), Catch::Contains("g.json: /objects/0: a plane has no inside"));

    json inside = luneburg_scene(1e-9);
    inside["objects"].push_back(json{{"type", "sphere"}, {"center", {0, 0, 0.2}}, {"radius", 0.1},
                                     {"material", {{"type", "dielectric"}, {"ior", 1.5}}}});
    CHECK_THAT(error(inside), Catch::Contains("g.json: /objects/1: reaches into the gradient-index medium of /objects/0") &&
                                      Catch::Contains("only lit or emitting surfaces"));

    json rod = luneburg_scene(1e-9);
    rod["materials"]["lens"]["profile"] = {{"kind", "parabolic-rod"}, {"axis", {0, 0, 1}}, {"n0", 1.5}, {"A", 4}};
    CHECK_THAT(error(rod), Catch::Contains("g.json: /materials/lens/profile/A: the index falls to"));

    json kind = luneburg_scene(1e-9);
    kind["materials"]["lens"]["profile"]["kind"] = "lunebrug";
    CHECK_THAT(error(kind), Catch::Contains("/materials/lens/profile/kind: unknown profile 'lunebrug'"));

    json tol = luneburg_scene(0.5);
    CHECK_THAT(error(tol), Catch::Contains("/materials/lens/tolerance: 0.5 must be in [1e-14, 1e-2]"));

    json pov = luneburg_scene(1e-9);
    pov["render"] = {{"compat", "povray"}};
    CHECK_THAT(error(pov), Catch::Contains("material 'lens': a \"grin\" material needs the physical mode (POV-Ray has no curved rays)"));
}

TEST_CASE("A ray that exhausts a gradient-index medium's step budget is lost light, counted, never a hang", "[grin]") {
    json j = luneburg_scene(1e-12);
    j["materials"]["lens"]["max_steps"] = 10;
    const Scene scene = parse_scene(j, "budget.json");
    const RenderResult r = render(scene);
    CHECK(r.stats.grin_exhausted > 0);
    CHECK(r.stats.lost_limits > 0);
}

TEST_CASE("A gradient-index medium with \"shadows\": false lets shadow rays through, and by default it blocks them",
          "[grin]") {
    auto lit = [](bool shadows) {
        json j = luneburg_scene(1e-9);
        j["materials"]["lens"]["shadows"] = shadows;
        j["materials"]["lens"]["profile"]["centre"] = {0, 2, 0};
        j["objects"] = json::array({json{{"type", "sphere"}, {"center", {0, 2, 0}}, {"radius", 1}, {"material", "lens"}},
                                    json{{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0},
                                         {"material", {{"type", "diffuse"}, {"color", {1, 1, 1}}}}}});
        j["lights"] = json::array({json{{"position", {0, 10, 0}}}});
        const Scene scene = parse_scene(j, "shadow.json");
        const SceneTracer tracer(scene);
        RenderStats st;
        const auto h = tracer.intersect(Ray{Vec3(3, 1, 0), Vec3(-3, -1, 0).normalized()}, st);
        REQUIRE(h);
        CHECK(h->hit.point.norm() < 1e-9);  // the floor under the sphere, seen beside it
        return tracer.local_light(*h, st).sum();
    };
    CHECK(lit(false) > 1.0);
    CHECK(lit(true) < 1e-12);
}

TEST_CASE("A dispersive gradient-index medium: each wavelength's curved ray is the ray of the profile at that "
          "wavelength's index, and the render splits the rays by wavelength",
          "[grin]") {
    auto scene = [](double A, double B) {
        json j = luneburg_scene(1e-11);
        j["materials"]["lens"]["profile"] = {{"kind", "linear-height"}, {"n0", A}, {"cauchy_b", B}, {"slope", 0.2},
                                             {"h0", 0}, {"up", {0, 1, 0}}};
        j["objects"] = json::array({json{{"type", "polyhedron"},
                                         {"material", "lens"},
                                         {"planes", {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1},
                                                     {0, 0, 1, 1}, {0, 0, -1, 1}}}}});
        return parse_scene(j, "prism.json");
    };
    const double A = 1.5, B = 0.01;  // Cauchy, B in µm²
    const Scene dispersive = scene(A, B);
    const Ray ray{Vec3(0.2, 0.3, -3), Vec3(0.05, 0, 1).normalized()};
    auto inside_exit = [&](const Scene& s, double nm) {
        const TraceRecord rec = trace_ray(s, ray, nm);
        for (const TraceSegment& t : rec.segments)
            if (t.parent == 0 && t.transmissions == 1) return t.point;
        FAIL("no transmitted segment");
        return Vec3(Vec3::Zero());
    };
    const Vec3 blue = inside_exit(dispersive, 450), red = inside_exit(dispersive, 650);
    CHECK((blue - red).norm() > 1e-4);  // the gradient bends each wavelength by its own index
    for (const double nm : {450.0, 650.0}) {
        const double um = nm * 1e-3;
        const Vec3 same = inside_exit(scene(A + B / (um * um), 0.0), nm);
        CHECK((inside_exit(dispersive, nm) - same).norm() < 1e-12);
    }
    RenderResult r = render(dispersive);
    CHECK(r.stats.spectral_splits > 0);
    CHECK(r.stats.grin_segments > r.stats.spectral_splits);  // the bands' own curved segments
    double sum = 0;
    for (double v : r.image.rgb) sum += v;
    CHECK(std::isfinite(sum));
}

TEST_CASE("Objects inside a gradient-index medium: a ray in Maxwell's fish-eye ends on a diffuse plane where its "
          "circle meets the plane",
          "[grin]") {
    // n = 2 / (1 + r²) inside the unit sphere (1 at its surface: no refraction there). A ray
    // entering at P = (b, 0, −s), s = √(1 − b²), along +z follows the circle through P and its
    // conjugate point −P: centre (−s²/b, 0, −s), radius 1/b. A diffuse plane z = 0.3 inside
    // ends it where that circle meets the plane.
    json j = json::parse(R"({
      "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 40, "width": 16, "height": 12},
      "materials": {"lens": {"type": "grin", "tolerance": 1e-12, "shadows": false,
                             "profile": {"kind": "maxwell-fish-eye", "centre": [0, 0, 0], "n0": 2, "a": 1}},
                    "card": {"type": "diffuse", "color": [0.8, 0.8, 0.8]}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lens"},
                  {"type": "plane", "normal": [0, 0, 1], "offset": 0.3, "material": "card"}],
      "lights": [{"position": [0, 0, -5]}]
    })");
    const Scene scene = parse_scene(j, "fish.json");
    for (const double b : {0.2, 0.5, 0.8}) {
        const TraceRecord rec = trace_ray(scene, Ray{Vec3(b, 0, -3), Vec3(0, 0, 1)});
        const TraceSegment* card = nullptr;
        for (const TraceSegment& seg : rec.segments)
            if (seg.event == "diffuse" && seg.parent == 0) card = &seg;
        REQUIRE(card != nullptr);
        const double s = std::sqrt(1 - b * b), cx = -s * s / b, rho = 1 / b;
        const double x = cx + std::sqrt(rho * rho - (0.3 + s) * (0.3 + s));
        INFO("b " << b << ": hit " << card->point.transpose() << ", circle meets the plane at x = " << x);
        CHECK(std::abs(card->point.z() - 0.3) < 1e-12);   // on the plane: its own intersection
        CHECK(std::abs(card->point.x() - x) < 1e-9);       // on the ray's circle
        CHECK(std::abs(card->point.y()) < 1e-12);
        CHECK(card->path.size() >= 3);                      // curved: its points recorded
        CHECK((card->path.back() - card->point).norm() < 1e-15);
    }
    // A render of it is finite and the same on 1 and 2 threads.
    RenderOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const RenderResult a = render(scene, one), c = render(scene, two);
    CHECK(a.image.rgb == c.image.rgb);
    CHECK(a.stats.grin_exhausted == 0);
}

TEST_CASE("Dip of the horizon through the standard atmosphere: the Earth inside the air, traced against "
          "sqrt(2h(1 - k)/R)",
          "[grin]") {
    // An observer 10 m above a diffuse Earth inside a sphere of the 1976 standard air (the
    // scene in metres). Rays below the dip meet the ground; the dip is found by bisection.
    // Geometric optics: a ray's curvature is −(dn/dh)/n, the refraction coefficient
    // k = −R (dn/dh)/n; near the ground the ray sees an Earth of radius R/(1 − k), so the
    // dip is √(2h(1 − k)/R) (k about 0.17 for this air at 550 nm).
    const double R = 6371e3, h = 10.0;
    json j = json::parse(R"({
      "camera": {"location": [0, 10, 0], "look_at": [1, 10, 0], "angle": 1, "width": 4, "height": 4},
      "materials": {"air": {"type": "grin", "tolerance": 1e-10, "shadows": false, "profile": {"kind": "earth-atmosphere"}},
                    "ground": {"type": "diffuse", "color": [0.3, 0.3, 0.3]}},
      "objects": [{"type": "sphere", "center": [0, -6371000, 0], "radius": 6471000, "material": "air"},
                  {"type": "sphere", "center": [0, -6371000, 0], "radius": 6371000, "material": "ground"}],
      "lights": []
    })");
    const Scene scene = parse_scene(j, "earth.json");
    const grin::Atmosphere air;
    const grin::Atmosphere::Index at = air.index(h, 0.55);
    const double k = -R * at.dn_dh / at.n;
    const double predicted = std::sqrt(2 * h * (1 - k) / R), geometric = std::sqrt(2 * h / R);
    auto meets_ground = [&](double dip) {
        const Vec3 d(std::cos(dip), -std::sin(dip), 0);
        const TraceRecord rec = trace_ray(scene, Ray{Vec3(0, h, 0), d}, 550.0);
        for (const TraceSegment& seg : rec.segments)
            if (seg.event == "diffuse") return true;
        return false;
    };
    double lo = 0.5 * geometric, hi = 1.5 * geometric;
    REQUIRE_FALSE(meets_ground(lo));
    REQUIRE(meets_ground(hi));
    for (int it = 0; it < 30; ++it) {
        const double mid = 0.5 * (lo + hi);
        (meets_ground(mid) ? hi : lo) = mid;
    }
    const double dip = 0.5 * (lo + hi);
    INFO("k " << k << ", dip traced " << dip << " rad, predicted " << predicted << ", geometric " << geometric);
    CHECK(k > 0.1);
    CHECK(k < 0.25);
    CHECK(dip < geometric);                                   // refraction lowers the dip
    CHECK(std::abs(dip / predicted - 1) < 0.01);
}
