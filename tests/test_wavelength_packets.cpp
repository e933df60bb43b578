// Wavelength packets (RayTreeWalkerT::walk_lanes): the bands of a spectral split walked
// eight at a time in the eye pass and the light pass give the images, the lost light and the
// illumination maps of the bands walked one by one, to the last bit; and the packet tests of
// planes and of a plane set's facets give the one-ray answers in every lane.
#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "core/light_pass.h"
#include "core/render.h"
#include "core/scene_json.h"
#include "core/tracer.h"
#include "experiments/ohtsuka1998.h"
#include "geometry/facet_graph.h"
#include "geometry/gem/brilliant.h"
#include "geometry/shapes.h"
#include "tests/hit_bits.h"

using namespace refract;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using test::bits;
using test::identical;

Vec3 random_direction(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    for (;;) {
        const Vec3 v(n(rng), n(rng), n(rng));
        if (v.norm() > 1e-6) return v.normalized();
    }
}

// Renders s with the bands in packets and one by one; the number of differing values of
// the image and of the lost-light image.
struct Pair {
    RenderResult lanes, one_by_one;
    long image_bits = 0, lost_bits = 0;
};
Pair render_both(const Scene& s) {
    RenderOptions o;
    o.threads = 2;
    o.lost_energy = true;
    Pair p;
    SceneTracer::set_wavelength_lanes(false);
    p.one_by_one = render(s, o);
    SceneTracer::set_wavelength_lanes(true);
    p.lanes = render(s, o);
    for (int j = 0; j < s.camera.height; ++j)
        for (int i = 0; i < s.camera.width; ++i)
            for (int c = 0; c < 3; ++c)
                p.image_bits += bits(p.lanes.image.at(i, j)[c]) != bits(p.one_by_one.image.at(i, j)[c]);
    for (size_t k = 0; k < p.lanes.lost.size(); ++k) p.lost_bits += bits(p.lanes.lost[k]) != bits(p.one_by_one.lost[k]);
    return p;
}

ConvexPolyhedron brilliant() {
    const Gem gem = build_brilliant(BrilliantCut{});
    ConvexPolyhedron c = gem.solid;
    set_bound(c, gem.mesh.vertices);
    return c;
}

}  // namespace

TEST_CASE("Ohtsuka & Kawai 1998 diamond: light pass and eye pass with the wavelengths in packets give the one-by-one "
          "image and lost light to the last bit",
          "[render]") {
    Scene s = load_scene(std::string(REFRACT_SOURCE_DIR) + "/scenes/examples/ohtsuka1998-diamond.json");
    s.camera.width = 96;
    s.camera.height = 72;
    s.settings.light_pass.photons = 3000;
    const Pair p = render_both(s);
    CHECK(p.lanes.stats.spectral_splits > 1000);
    CHECK(p.lanes.stats.segments == p.one_by_one.stats.segments);
    CHECK(p.lanes.stats.tree_nodes == p.one_by_one.stats.tree_nodes);
    CHECK(p.lanes.stats.photon_segments == p.one_by_one.stats.photon_segments);
    CHECK(p.image_bits == 0);
    CHECK(p.lost_bits == 0);
    CHECK(bits(p.lanes.stats.lost_limits) == bits(p.one_by_one.stats.lost_limits));

    // The illumination maps themselves.
    const SpectralContext ctx = SpectralContext::build(s);
    SceneTracer::set_wavelength_lanes(false);
    const auto one = light_pass(s, ctx, 2);
    SceneTracer::set_wavelength_lanes(true);
    const auto lanes = light_pass(s, ctx, 2);
    long elements = 0, differing = 0;
    for (size_t k = 0; k < one->by_object.size(); ++k) {
        if (!one->by_object[k]) continue;
        for (int e = 0; e < one->by_object[k]->elements(); ++e)
            for (int c = 0; c < 3; ++c) {
                ++elements;
                differing += bits(one->by_object[k]->irradiance[static_cast<size_t>(e)][c]) !=
                             bits(lanes->by_object[k]->irradiance[static_cast<size_t>(e)][c]);
            }
    }
    CHECK(one->deposits > 1000);
    CHECK(elements > 1000);
    CHECK(differing == 0);
}

TEST_CASE("Ohtsuka & Kawai 1998 diamond in POV-Ray mode: the bands of each split in packets give the one-by-one image "
          "to the last bit",
          "[render]") {
    experiments::ohtsuka1998::SceneParams p;
    p.width = 96;
    p.height = 72;
    const Scene s = parse_scene(experiments::ohtsuka1998::povray_scene_json(p, 31), "povray diamond");
    REQUIRE(s.settings.compat == Compat::PovRay);
    const Pair r = render_both(s);
    CHECK(r.lanes.stats.spectral_splits > 1000);
    CHECK(r.lanes.stats.segments == r.one_by_one.stats.segments);
    CHECK(r.image_bits == 0);
    CHECK(r.lost_bits == 0);
}

TEST_CASE("Dispersive spheres, a mesh, absorbing glass, a mirror and a Schlick drop: packets give the one-by-one image "
          "to the last bit",
          "[render]") {
    // Lanes that meet different objects and kinds in one packet: the mixed nodes go lane by
    // lane, Beer–Lambert per wavelength, the floor's leaves per lane.
    const Scene s = parse_scene(nlohmann::json::parse(R"({
        "camera": {"location": [0, 1.5, -5], "look_at": [0, 0.5, 0], "angle": 40, "width": 48, "height": 36},
        "materials": {
            "flint": {"type": "dielectric", "dispersion": "n-bk7", "absorption": {"coefficients": [0.2, 0.05, 0.4]}},
            "water": {"type": "dielectric", "dispersion": "water", "reflectance": "schlick"},
            "diamond": {"type": "dielectric", "dispersion": "diamond"},
            "mirror": {"type": "mirror", "color": [0.9, 0.9, 0.9]},
            "floor": {"type": "diffuse", "color": [0.7, 0.7, 0.7], "checker": {"color2": [0.2, 0.2, 0.2], "size": 0.5}}},
        "objects": [
            {"type": "plane", "normal": [0, 1, 0], "offset": 0, "material": "floor"},
            {"type": "sphere", "center": [-0.9, 0.6, 0], "radius": 0.6, "material": "flint"},
            {"type": "sphere", "center": [0.5, 0.5, 0.2], "radius": 0.5, "material": "water"},
            {"type": "sphere", "center": [0.5, 0.5, 0.2], "radius": -0.2, "material": "water"},
            {"type": "sphere", "center": [0.1, 0.3, -1], "radius": 0.3, "material": "diamond"},
            {"type": "mesh", "vertices": [[1.2, 0, 1], [2.2, 0, 1], [1.7, 1.2, 1.6], [1.7, 0, 0.4]],
             "triangles": [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], "material": "diamond"},
            {"type": "sphere", "center": [0, 1, 2.5], "radius": 1, "material": "mirror"}],
        "lights": [{"position": [3, 6, -2], "color": [1, 1, 1]}],
        "render": {"max_depth": 10, "threshold": 0.001, "light_pass": {"photons": 2000, "element_size": 0.05}}})"),
                                "mixed.json");
    const Pair p = render_both(s);
    CHECK(p.lanes.stats.spectral_splits > 100);
    CHECK(p.lanes.stats.segments == p.one_by_one.stats.segments);
    CHECK(p.image_bits == 0);
    CHECK(p.lost_bits == 0);
}

TEST_CASE("Facet-local intersection of a packet of rays leaving one facet equals the one-ray answer in every lane",
          "[geometry]") {
    // Packets leaving hits on the brilliant's facets, inward and outward, each lane with the
    // right guess, a random one or none: every lane decided as FacetGraph::intersect decides
    // it, with the same hit to the last bit.
    const ConvexPolyhedron c = brilliant();
    const FacetGraph g(c);
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int> any(0, static_cast<int>(c.planes.size()) - 1);
    long lanes = 0, decided = 0, mismatches = 0;
    for (int i = 0; i < 6000; ++i) {
        const Vec3 from = c.bound_center + 3 * c.bound_radius * random_direction(rng);
        const Vec3 to = c.bound_center + 0.9 * c.bound_radius * random_direction(rng);
        const auto hit = intersect(c, Ray{from, (to - from).normalized()}, 0, kInf);
        if (!hit || !g.usable(hit->facet)) continue;
        const Vec3 n = c.planes[static_cast<size_t>(hit->facet)].normal;
        Vec3 d0 = random_direction(rng);
        if ((d0.dot(n) > 0) != (i % 4 == 0)) d0 = -d0;  // a quarter outward
        LaneVec3 o, d;
        Lanes t_max;
        LaneMask active;
        std::array<std::int32_t, kLanes> guess;
        for (int l = 0; l < kLanes; ++l) {
            // The wavelengths of a split: nearly the same direction from nearly the same point.
            const Vec3 dir = (d0 + 0.01 * random_direction(rng)).normalized();
            o.set(l, hit->point);
            d.set(l, dir);
            t_max[l] = l == 6 ? 0.05 : kInf;
            active[l] = l != 3 || i % 2 == 0;
            const auto want = intersect(c, Ray{hit->point, dir}, 1e-6, t_max[l]);
            guess[static_cast<size_t>(l)] = l % 3 == 0 ? -1 : l % 3 == 1 && want ? want->facet : any(rng);
        }
        const FacetGraph::LocalLanes loc = g.intersect_lanes(c, o, d, active, 1e-6, t_max, hit->facet, guess);
        for (int l = 0; l < kLanes; ++l) {
            if (!active[l]) continue;
            ++lanes;
            const Ray r{o.lane(l), d.lane(l)};
            const FacetGraph::Local one = g.intersect(c, r, 1e-6, t_max[l], hit->facet, guess[static_cast<size_t>(l)]);
            if (loc.decided[l] != one.decided) {
                ++mismatches;
                continue;
            }
            if (!one.decided) continue;
            ++decided;
            std::optional<Hit> got;
            if (loc.hit[l])
                got = Hit{loc.t[l], loc.point.lane(l), c.planes[static_cast<size_t>(loc.facet[static_cast<size_t>(l)])].normal,
                          loc.facet[static_cast<size_t>(l)]};
            mismatches += !identical(got, one.hit) || !identical(got, intersect(c, r, 1e-6, t_max[l]));
        }
    }
    CHECK(lanes > 20000);
    CHECK(decided > lanes / 3);
    CHECK(mismatches == 0);
}

TEST_CASE("The plane test on a packet of rays equals the one-ray test in every lane, bit for bit", "[geometry]") {
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(-2, 2);
    const Plane p{Vec3(0.3, 0.9, -0.2).normalized(), 0.4};
    long compared = 0, hits = 0, mismatches = 0;
    for (int i = 0; i < 10000; ++i) {
        LaneVec3 o, d;
        Lanes t_max;
        LaneMask active;
        for (int l = 0; l < kLanes; ++l) {
            Vec3 dir = random_direction(rng);
            if (l == 7) dir = (dir - dir.dot(p.normal) * p.normal).normalized();  // parallel to the plane
            o.set(l, Vec3(u(rng), u(rng), u(rng)));
            d.set(l, dir);
            t_max[l] = l % 4 == 3 ? 1.0 : kInf;
            active[l] = l != 2 || i % 2 == 0;
        }
        const LaneShapeHits h = intersect_lanes(p, o, d, active, 1e-6, t_max);
        for (int l = 0; l < kLanes; ++l) {
            if (!active[l]) continue;
            ++compared;
            const auto want = intersect(p, Ray{o.lane(l), d.lane(l)}, 1e-6, t_max[l]);
            std::optional<Hit> got;
            if (h.hit[l]) got = Hit{h.t[l], h.point.lane(l), h.normal.lane(l), -1};
            hits += want.has_value();
            mismatches += !identical(want, got);
        }
    }
    CHECK(compared > 70000);
    CHECK(hits > compared / 4);
    CHECK(mismatches == 0);
}
