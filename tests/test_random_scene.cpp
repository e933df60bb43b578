// Random compat scenes (validation/random_scene.h): deterministic, always accepted by the
// POV-Ray exporter, and covering every feature the search for disagreements needs.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include <refract/core/scene_json.h>
#include <refract/validation/pov_export.h>
#include <refract/validation/random_scene.h>

using namespace refract;
using namespace refract::validation;
using nlohmann::json;

namespace {

constexpr int kSeeds = 300;

Vec3 vec(const json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

// Signed volume of a closed mesh: positive when its triangles are counter-clockwise seen
// from outside.
double signed_volume(const json& mesh) {
    double v = 0;
    for (const auto& t : mesh["triangles"]) {
        const Vec3 a = vec(mesh["vertices"][t[0].get<int>()]), b = vec(mesh["vertices"][t[1].get<int>()]),
                   c = vec(mesh["vertices"][t[2].get<int>()]);
        v += a.dot(b.cross(c)) / 6;
    }
    return v;
}

// Every directed edge once, its reverse once.
bool closed_oriented(const json& mesh) {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : mesh["triangles"])
        for (int k = 0; k < 3; ++k) ++edges[{t[k].get<int>(), t[(k + 1) % 3].get<int>()}];
    for (const auto& [e, n] : edges)
        if (n != 1 || !edges.count({e.second, e.first})) return false;
    return true;
}

// A polyhedron labelled like a brilliant whose girdle planes are all perpendicular to its table.
bool vertical_girdle(const json& poly) {
    if (!poly.contains("labels")) return false;
    Vec3 table(0, 0, 0);
    std::vector<Vec3> girdle;
    for (size_t k = 0; k < poly["labels"].size(); ++k) {
        const std::string label = poly["labels"][k];
        const json& p = poly["planes"][k];
        const Vec3 n = Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()).normalized();
        if (label == "table") table = n;
        if (label.rfind("girdle", 0) == 0) girdle.push_back(n);
    }
    if (girdle.size() < 8 || table.norm() == 0) return false;
    for (const Vec3& n : girdle)
        if (std::abs(n.dot(table)) > 1e-5) return false;
    return true;
}

}  // namespace

TEST_CASE("Random scene: the same seed gives byte-identical JSON, different seeds different scenes", "[random]") {
    for (std::uint64_t seed : {0ull, 1ull, 17ull, 123456789ull, 0xFFFFFFFFFFFFFFFFull})
        CHECK(random_scene(seed).dump() == random_scene(seed).dump());
    std::set<std::string> dumps;
    for (std::uint64_t seed = 0; seed < 50; ++seed) dumps.insert(random_scene(seed).dump());
    CHECK(dumps.size() == 50);
    const json j = random_scene(17);
    CHECK(j["description"].get<std::string>().rfind("random seed 17: ", 0) == 0);
    CHECK(j["render"]["compat"] == "povray");
}

TEST_CASE("Random scene: the image size follows the options", "[random]") {
    RandomSceneOptions opt;
    opt.width = 33;
    opt.height = 21;
    const json j = random_scene(5, opt);
    CHECK(j["camera"]["width"] == 33);
    CHECK(j["camera"]["height"] == 21);
    CHECK(random_scene(5)["camera"]["width"] == 80);
    CHECK(random_scene(5)["camera"]["height"] == 60);
}

TEST_CASE("Random scenes 0-299 parse, export to POV-Ray (100 %) and cover every feature", "[random]") {
    std::map<std::string, int> count;
    int exported = 0;
    for (int seed = 0; seed < kSeeds; ++seed) {
        const json j = random_scene(static_cast<std::uint64_t>(seed));
        const std::string name = "random-" + std::to_string(seed);
        INFO(name << ": " << j["description"].get<std::string>());
        Scene scene;
        REQUIRE_NOTHROW(scene = parse_scene(j, name));
        REQUIRE_NOTHROW(export_pov(scene));
        ++exported;

        // Nothing the exporter refuses, and nothing beyond the compat subset.
        const std::string text = j.dump();
        for (const char* banned : {"jitter", "stochastic", "lambertian", "metal", "schlick", "fresnel-s", "fresnel-p",
                                   "light_pass", "spectral", "max_reflections", "max_transmissions"})
            CHECK(text.find(banned) == std::string::npos);
        CHECK(scene.settings.compat == Compat::PovRay);
        CHECK(scene.settings.max_depth >= 1);
        CHECK(scene.settings.max_depth <= 24);
        CHECK(scene.settings.threshold >= 0);
        CHECK(scene.settings.threshold <= 0.1);
        CHECK(scene.lights.size() <= 3);
        for (const Light& l : scene.lights) CHECK(l.color.minCoeff() > 0);

        int planes = 0, others = 0, dispersive = 0;
        for (const auto& o : j["objects"]) {
            const std::string type = o["type"];
            if (type == "plane") ++planes;
            else if (!(type == "sphere" && o["radius"].get<double>() < 0)) ++others;  // a hole is part of its sphere
            if (type == "mesh") {
                ++count["mesh"];
                CHECK(o["triangles"].size() <= 100);
                CHECK(closed_oriented(o));
                CHECK(signed_volume(o) > 0);
            }
            if (type == "polyhedron") {
                CHECK(o["planes"].size() <= 46);
                if (vertical_girdle(o)) ++count["brilliant-like, vertical girdle"];
                else ++count["random polyhedron"];
            }
            if (type == "brilliant") ++count["exact brilliant"];
            if (type == "sphere" && o["radius"].get<double>() < 0) ++count["hollow sphere"];
            const json& m = o["material"].is_string() ? j["materials"][o["material"].get<std::string>()] : o["material"];
            if (type == "plane") CHECK(m["type"] != "dielectric");
            if (m["type"] == "emissive") ++count["emissive"];
        }
        CHECK(planes <= 2);
        CHECK(others >= 1);
        CHECK(others <= 6);
        for (const auto& [mname, m] : j["materials"].items()) {
            if (m["type"] != "dielectric") continue;
            const double n = m["ior"];
            CHECK(n >= 0.3);
            CHECK(n <= 4);
            CHECK(std::abs(n - 1) >= 0.02);
            if (m.value("reflectance", "fresnel") == "constant") ++count["constant reflectivity"];
            if (m.contains("dispersion")) {
                const json& d = m["dispersion"];
                CHECK(d["model"] == "povray");
                CHECK(d["ior"].get<double>() == n);
                CHECK(d["samples"].get<int>() >= 2);
                CHECK(d["samples"].get<int>() <= 31);
                if (d["dispersion"].get<double>() != 1) ++dispersive;
            }
        }
        CHECK(dispersive <= 3);
        count["dispersive material"] += dispersive;
        if (scene.camera.type == Camera::Type::Orthographic) ++count["orthographic"];
        if (scene.settings.integrator == IntegratorKind::Whitted) ++count["whitted"];
        if (scene.settings.max_depth > 10) ++count["max_depth > 10"];
        if (scene.background.kind == Background::Kind::Gradient) ++count["gradient background"];
        for (const Object& o : scene.objects) {
            const auto* s = std::get_if<Sphere>(&o.shape);
            if (s && s->radius > 0 && !scene.materials[o.material].is<material::Dielectric>() &&
                (scene.camera.location - s->center).norm() < s->radius) {
                ++count["camera inside an opaque sphere"];
                break;
            }
        }
    }
    CHECK(exported == kSeeds);
    for (const auto& [feature, minimum] : std::map<std::string, int>{{"hollow sphere", 40},
                                                                     {"mesh", 80},
                                                                     {"brilliant-like, vertical girdle", 80},
                                                                     {"random polyhedron", 80},
                                                                     {"exact brilliant", 15},
                                                                     {"dispersive material", 60},
                                                                     {"constant reflectivity", 60},
                                                                     {"orthographic", 30},
                                                                     {"whitted", 30},
                                                                     {"max_depth > 10", 80},
                                                                     {"gradient background", 60},
                                                                     {"camera inside an opaque sphere", 15},
                                                                     {"emissive", 30}}) {
        INFO(feature << ": " << count[feature] << " in " << kSeeds << " scenes (at least " << minimum << " expected)");
        CHECK(count[feature] >= minimum);
    }
}

TEST_CASE("Random scene without dispersion has no dispersive material anywhere", "[random]") {
    RandomSceneOptions opt;
    opt.dispersion = false;
    for (int seed = 0; seed < kSeeds; ++seed) {
        const json j = random_scene(static_cast<std::uint64_t>(seed), opt);
        INFO("seed " << seed);
        CHECK(j.dump().find("dispersion") == std::string::npos);
        if (seed >= 100) continue;  // parsing (exact brilliants) is the slow part
        const Scene scene = parse_scene(j, "random-" + std::to_string(seed));
        CHECK_FALSE(scene.settings.spectral.enabled);
        for (const Material& m : scene.materials) CHECK_FALSE((m.dielectric() && m.dielectric()->dispersion.has_value()));
    }
}
