// The values of a scene and of the files written from it: colours and coefficients in
// [0, 1e30], user vectors normalised without overflow, dispersion models positive over the
// whole continuous range, and images whose stored values are finite and >= 0 where they
// must be (docs/limits.md).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include <refract/core/camera.h>
#include <refract/core/far_field.h>
#include <refract/core/image.h>
#include <refract/core/material.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/trace_record.h>
#include <refract/geometry/error.h>
#include "tests/temp_dir.h"

using namespace refract;
using nlohmann::json;
using Catch::Contains;

namespace {

// A sphere of material `m` on a diffuse floor under one light, the whole scene's JSON.
json scene_with(const json& m) {
    return {{"camera", {{"location", {0, 1, -6}}, {"look_at", {0, 0.5, 0}}, {"width", 8}, {"height", 6}}},
            {"materials", {{"m", m}, {"floor", {{"type", "diffuse"}}}}},
            {"objects", {{{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 1}, {"material", "m"}},
                         {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}, {"material", "floor"}}}},
            {"lights", {{{"position", {5, 10, -5}}}}}};
}

std::string error_of(const json& j) {
    try {
        parse_scene(j, "s.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// n = A + B/λ² + C/λ⁴ = (1/λ² − 1/0.5005²)² + m (λ in µm): its minimum m lies at 500.5 nm,
// between whole nanometres, where n(500) and n(501) are 6.3e-5 above m.
json cauchy_dip(double m) {
    const double x = 1.0 / (0.5005 * 0.5005);
    return {{"model", "cauchy"}, {"A", x * x + m}, {"B", -2.0 * x}, {"C", 1.0}};
}

}  // namespace

TEST_CASE("Colours, radiances and coefficients outside [0, 1e30] are refused on loading, naming the field",
          "[scene][limits]") {
    const json diffuse = {{"type", "diffuse"}};
    struct Case {
        json material;
        const char* field;
    };
    const Case cases[] = {
        {{{"type", "diffuse"}, {"diffuse", -5}}, "/materials/m/diffuse"},
        {{{"type", "diffuse"}, {"ambient", -3}}, "/materials/m/ambient"},
        {{{"type", "diffuse"}, {"ambient", 1e300}}, "/materials/m/ambient"},
        {{{"type", "diffuse"}, {"color", {1e300, 1, 1}}}, "/materials/m/color"},
        {{{"type", "diffuse"}, {"checker", {{"color2", {-200, 0, 0}}}}}, "/materials/m/checker/color2"},
        {{{"type", "lambertian"}, {"color", {1, -0.5, 1}}}, "/materials/m/color"},
        {{{"type", "mirror"}, {"color", {1e300, 1e300, 1e300}}}, "/materials/m/color"},
        {{{"type", "metal"}, {"color", {1, 1, 2e30}}}, "/materials/m/color"},
        {{{"type", "emissive"}, {"color", {-1, 1, 1}}}, "/materials/m/color"},
        {{{"type", "dielectric"}, {"filter", {1e300, 1, 1}}}, "/materials/m/filter"},
        {{{"type", "dielectric"}, {"filter", {1, -0.1, 1}}}, "/materials/m/filter"},
        {{{"type", "uniaxial"}, {"crystal", "calcite"}, {"filter", {1, 1, 1e31}}}, "/materials/m/filter"},
    };
    for (const Case& c : cases) {
        INFO(c.material.dump());
        CHECK_THAT(error_of(scene_with(c.material)),
                   Contains(std::string("s.json: ") + c.field + ": ") && Contains("[0, 1e30]"));
    }
    // The background in each of its forms, and a light.
    for (const auto& [background, field] : {std::pair{json{-1, 0, 0}, "/background: "},
                                            std::pair{json{1e300, 1, 1}, "/background: "},
                                            std::pair{json{{"color", {0, -2, 0}}}, "/background/color: "},
                                            std::pair{json{{"type", "gradient"}, {"top", {1e300, 0, 0}}}, "/background/top: "},
                                            std::pair{json{{"type", "gradient"}, {"bottom", {0, 0, -1}}}, "/background/bottom: "},
                                            std::pair{json{{"type", "environment"}, {"color", {-1, 0, 0}}}, "/background/color: "}}) {
        json j = scene_with(diffuse);
        j["background"] = background;
        INFO(background.dump());
        CHECK_THAT(error_of(j), Contains(std::string("s.json: ") + field) && Contains("[0, 1e30]"));
    }
    json light = scene_with(diffuse);
    light["lights"][0]["color"] = {1, 1, -1};
    CHECK_THAT(error_of(light), Contains("/lights/0/color: components must be in [0, 1e30] (got -1)"));
    // The ends of the range are accepted.
    json ends = scene_with({{"type", "diffuse"}, {"color", {0, 1e30, 1}}, {"ambient", 1e30}, {"diffuse", 0},
                            {"checker", {{"color2", {1e30, 0, 0}}}}});
    ends["background"] = {1e30, 0, 0};
    const Scene s = parse_scene(ends, "ends.json");
    const auto* d = s.materials[1].as<material::Diffuse>();  // "m", after "floor"
    REQUIRE(d);
    CHECK(d->ambient == 1e30);
    CHECK(d->pigment.checker->color2.x() == 1e30);
    CHECK(s.background.color.x() == 1e30);
}

TEST_CASE("Colours each within [0, 1e30] that multiply past a float's range are refused after the render, naming the "
          "pixel", "[scene][limits]") {
    json j = scene_with({{"type", "diffuse"}, {"color", {1e30, 1e30, 1e30}}});
    j["lights"][0]["color"] = {1e30, 1e30, 1e30};
    const Scene s = parse_scene(j, "bright.json");
    CHECK_THROWS_AS(render(s), InputError);
    CHECK_THROWS_WITH(render(s), Contains("bright.json: pixel (") &&
                                     Contains("past the largest value an image file holds (3.4e38)"));
    j["lights"][0]["color"] = {1e8, 1e8, 1e8};  // 1e38: within
    const RenderResult r = render(parse_scene(j, "bright.json"));
    CHECK(*std::max_element(r.image.rgb.begin(), r.image.rgb.end()) > 1e37);
}

TEST_CASE("Vector normalisation: ordinary vectors as Eigen's normalized() to the bit, huge and tiny ones to their "
          "direction, zero refused", "[scene][limits]") {
    for (const Vec3& v : {Vec3(0, 1, 0), Vec3(3, -4, 12), Vec3(0.1, 0.2, 0.3), Vec3(1e150, 2e150, -1e150),
                          Vec3(1e-150, 0, 3e-151)}) {
        REQUIRE(unit_vector(v));
        CHECK((*unit_vector(v) - v.normalized()).cwiseAbs().maxCoeff() == 0.0);
        CHECK(over_norm(7.0, v) == 7.0 / v.norm());
    }
    // Past 1.3e154 the squares overflow (normalized() gives 0), below 1.5e-154 they underflow.
    for (const double scale : {1e154, 1e200, 1e300, std::numeric_limits<double>::max() / 16, 1e-160, 1e-300,
                               std::numeric_limits<double>::denorm_min()}) {
        INFO(scale);
        const Vec3 v = Vec3(3, -4, 12) * scale;
        REQUIRE(unit_vector(v));
        CHECK((*unit_vector(v) - Vec3(3, -4, 12) / 13.0).cwiseAbs().maxCoeff() < 1e-15);
        CHECK(over_norm(13.0 * scale, v) == Approx(1.0).epsilon(1e-15));
    }
    CHECK_FALSE(unit_vector(Vec3(0, 0, 0)));
    CHECK_FALSE(unit_vector(Vec3(std::numeric_limits<double>::infinity(), 0, 0)));
    CHECK_FALSE(unit_vector(Vec3(std::nan(""), 0, 0)));
}

TEST_CASE("User vectors of 1e200 keep their direction: sky, plane and polyhedron normals, a light's direction, an "
          "optic axis, a polarisation reference, a traced ray, a far-field axis", "[scene][limits]") {
    json j = scene_with({{"type", "uniaxial"}, {"crystal", "calcite"}, {"optic_axis", {0, 0, 1e300}}});
    j["camera"]["sky"] = {0, 1e200, 0};
    j["objects"][1]["normal"] = {0, 1e300, 0};
    j["objects"].push_back({{"type", "polyhedron"}, {"material", "floor"},
                            {"planes", {{1e300, 0, 0, 2e300}, {-1e-200, 0, 0, 1e-200}, {0, 1e200, 0, 1e200},
                                        {0, -1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}}}});
    j["lights"] = {{{"type", "directional"}, {"direction", {0, -1e200, 0}},
                    {"polarisation", {{"type", "linear"}, {"reference", {1e300, 0, 0}}}}}};
    const Scene s = parse_scene(j, "big.json");
    Camera plain = s.camera;
    plain.sky = Vec3(0, 1, 0);
    const Camera::Basis b = s.camera.basis(), p = plain.basis();
    CHECK((b.R - p.R).cwiseAbs().maxCoeff() < 1e-15);  // was (0, 0, 0): the sky's square overflowed
    CHECK((b.U - p.U).cwiseAbs().maxCoeff() < 1e-15);
    CHECK(std::get<Plane>(s.objects[1].shape).normal == Vec3(0, 1, 0));
    const auto& planes = std::get<ConvexPolyhedron>(s.objects[2].shape).planes;
    CHECK(planes[0].normal == Vec3(1, 0, 0));
    CHECK(planes[0].offset == 2.0);
    CHECK(planes[1].normal == Vec3(-1, 0, 0));
    CHECK(planes[1].offset == 1.0);
    CHECK(planes[2].offset == 1.0);
    CHECK(s.lights[0].direction == Vec3(0, -1, 0));
    CHECK(s.lights[0].polarisation.reference == Vec3(1, 0, 0));
    CHECK(s.materials[1].as<material::Uniaxial>()->optic_axis == Vec3(0, 0, 1));
    // A traced ray's direction, and a far field's axis.
    const Ray unit{Vec3(0, 1, -6), Vec3(0, 0, 1)};
    const TraceRecord a = trace_ray(s, unit), huge = trace_ray(s, Ray{unit.origin, Vec3(0, 0, 1e200)});
    REQUIRE(a.segments.size() == huge.segments.size());
    CHECK((a.radiance - huge.radiance).cwiseAbs().maxCoeff() == 0.0);
    CHECK(huge.segments[0].ray.dir == Vec3(0, 0, 1));
    CHECK_THROWS_WITH(trace_ray(s, Ray{unit.origin, Vec3(0, 0, 0)}), Contains("non-zero direction"));
    json drop = scene_with({{"type", "dielectric"}});
    drop["lights"] = {{{"type", "beam"}, {"position", {0, 1, -3}}, {"direction", {0, 0, 1}}, {"radius", 1}}};
    FarFieldSettings f;
    f.axis = Vec3(0, 0, 1e300);
    f.photons = 100;
    CHECK(far_field(parse_scene(drop, "drop.json"), f, 1).settings.axis == Vec3(0, 0, 1));
    // Zero is still refused, naming the field.
    json zero = scene_with({{"type", "uniaxial"}, {"crystal", "calcite"}, {"optic_axis", {0, 0, 0}}});
    CHECK_THAT(error_of(zero), Contains("/materials/m/optic_axis: must be a non-zero vector"));
    zero = scene_with({{"type", "diffuse"}});
    zero["camera"]["sky"] = {0, 0, 0};
    CHECK_THAT(error_of(zero), Contains("/camera/sky"));
}

TEST_CASE("Dispersion: a model that goes <= 0 between whole nanometres is refused, for a dielectric and for both rays "
          "of a crystal", "[scene][limits][spectral]") {
    // Sampled at whole nanometres its smallest value is +6.2e-5 (at 501 nm): it passed.
    CHECK_THROWS_WITH(spectrum::parse_dispersion(cauchy_dip(-1e-6), "s.json: /d"),
                      Contains("s.json: /d: the model gives n = -") && Contains(" at 500.") &&
                          Contains("must be finite and > 0 over 360–830 nm"));
    CHECK_THAT(error_of(scene_with({{"type", "dielectric"}, {"dispersion", cauchy_dip(-1e-6)}})),
               Contains("s.json: /materials/m/dispersion: the model gives n = -"));
    CHECK_THAT(error_of(scene_with({{"type", "uniaxial"}, {"ordinary", cauchy_dip(-1e-6)}, {"extraordinary", 1.5}})),
               Contains("s.json: /materials/m/ordinary: the model gives n = -"));
    CHECK_THAT(error_of(scene_with({{"type", "uniaxial"}, {"ordinary", 1.5}, {"extraordinary", cauchy_dip(-1e-6)}})),
               Contains("s.json: /materials/m/extraordinary: the model gives n = -"));
    // The same curve lifted to a minimum of +1e-4 is accepted, and is that small there.
    const spectrum::Dispersion ok = spectrum::parse_dispersion(cauchy_dip(1e-4), "s.json: /d");
    CHECK(ok.n(500.5) == Approx(1e-4).epsilon(1e-6));
    // The Moissanite form's pole inside the range is refused, as Sellmeier's.
    CHECK_THROWS_WITH(spectrum::parse_dispersion(json{{"model", "moissanite-form"}, {"A", 6.5}, {"B", 0.14},
                                                      {"C", 0.6005 * 0.6005}, {"D", 0.02}},
                                                 "s.json: /d"),
                      Contains("s.json: /d/C") && Contains("600.5 nm"));
    // Every catalogue model and crystal passes the continuous check.
    for (const std::string& name : spectrum::catalogue_names()) CHECK_NOTHROW(spectrum::parse_dispersion(name, "/d"));
    for (const std::string& name : spectrum::uniaxial_crystal_names()) {
        json u = scene_with({{"type", "uniaxial"}, {"crystal", name}});
        CHECK(error_of(u).empty());
    }
}

TEST_CASE("Image files: a value not finite as stored, or negative where it cannot be, is an internal error naming "
          "the pixel, and nothing is written", "[image][limits]") {
    const std::filesystem::path dir = test::fresh_dir("values", "image");
    const auto files = [&] {
        int n = 0;
        for (const auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file();
        return n;
    };
    Image img(3, 2);
    img.set(2, 1, Vec3(0.5, 1e300, 0.5));  // finite as a double, infinite as a float
    const std::string exr = (dir / "x.exr").string();
    CHECK_THROWS_WITH(write_image(exr, img),
                      Contains("internal error: ") && Contains("x.exr: pixel (2, 1) channel G is 1e+300") &&
                          Contains("not finite as stored") && Contains("nothing was written"));
    img.set(2, 1, Vec3(0.5, -1, 0.5));
    CHECK_THROWS_WITH(write_image(exr, img), Contains("pixel (2, 1) channel G is -1, negative"));
    CHECK(files() == 0);
    // A signed image (the xyz-srgb pipeline) keeps its negative value; the integer formats
    // clamp it to 0, but a value that is not finite is refused there too.
    write_image(exr, img, {false, true});
    CHECK(read_image(exr).at(2, 1).y() == -1.0);
    write_image((dir / "x.png").string(), img);
    img.set(0, 0, Vec3(std::nan(""), 0, 0));
    CHECK_THROWS_WITH(write_image((dir / "y.png").string(), img), Contains("y.png: pixel (0, 0) channel R"));
    CHECK(files() == 2);
    // Named channels: negative only in those that may be.
    const std::vector<double> data{0.5, -0.25, 1.0, 2.0};
    CHECK_THROWS_WITH(write_channels((dir / "c.exr").string(), 2, 1, {"S0", "S1"}, data),
                      Contains("c.exr: pixel (0, 0) channel S1 is -0.25, negative"));
    write_channels((dir / "c.exr").string(), 2, 1, {"S0", "S1"}, data, {}, {"S1"});
    CHECK(read_channels((dir / "c.exr").string()).data == data);
    CHECK_THROWS_WITH(write_channels((dir / "d.exr").string(), 2, 1, {"S0", "S1"}, {0.5, -0.25, 1e39, 2.0}, {}, {"S1"}),
                      Contains("d.exr: pixel (1, 0) channel S0 is 1e+39, not finite as stored"));
    CHECK(files() == 3);
    std::filesystem::remove_all(dir);
}
