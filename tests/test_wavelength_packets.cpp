// Packets of rays: the bands of a spectral split walked eight at a time in the eye pass and
// the light pass (RayTreeWalkerT::walk_lanes), and the samples of a pixel in the stochastic
// integrator (stochastic_radiance_samples), give the images, the lost light and the
// illumination maps of the rays walked one by one, to the last bit. (The packet tests of
// spheres, planes and a plane set's facets: test_facet_graph.cpp.)
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/light_pass.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/tracer.h>
#include <refract/experiments/ohtsuka1998.h>
#include "tests/hit_bits.h"

using namespace refract;

namespace {

using test::bits;

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
    o.trace.packets = false;
    p.one_by_one = render(s, o);
    o.trace.packets = true;
    p.lanes = render(s, o);
    for (int j = 0; j < s.camera.height; ++j)
        for (int i = 0; i < s.camera.width; ++i)
            for (int c = 0; c < 3; ++c)
                p.image_bits += bits(p.lanes.image.at(i, j)[c]) != bits(p.one_by_one.image.at(i, j)[c]);
    for (size_t k = 0; k < p.lanes.lost.size(); ++k) p.lost_bits += bits(p.lanes.lost[k]) != bits(p.one_by_one.lost[k]);
    return p;
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
    TraceOptions alone;
    alone.packets = false;
    const auto one = light_pass(s, ctx, 2, nullptr, alone);
    const auto lanes = light_pass(s, ctx, 2, nullptr, TraceOptions{});
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

TEST_CASE("Stochastic (RTIOW): the samples of a pixel walked in packets give the one-by-one image to the last bit",
          "[render][rtiow][stochastic]") {
    // The chapter's kinds (Lambertian, fuzzy metal, a hollow Schlick glass sphere) with an
    // absorbing glass, a plane, a mesh and coincident spheres: the spheres are searched as a
    // set and the plane and the mesh one by one in the same packet, exact ties included; a
    // path that ends hands its lane to the next sample.
    const Scene s = parse_scene(nlohmann::json::parse(R"({
        "camera": {"location": [0, 0.4, -3], "look_at": [0, 0.1, 0], "angle": 60, "width": 40, "height": 30},
        "materials": {
            "ground": {"type": "lambertian", "color": [0.8, 0.8, 0.0]},
            "centre": {"type": "lambertian", "color": [0.1, 0.2, 0.5]},
            "metal": {"type": "metal", "color": [0.8, 0.6, 0.2], "fuzz": 0.3},
            "glass": {"type": "dielectric", "ior": 1.5, "reflectance": "schlick"},
            "amber": {"type": "dielectric", "ior": 1.54, "absorption": {"coefficients": [0.1, 0.6, 1.5]}},
            "floor": {"type": "lambertian", "color": [0.5, 0.5, 0.5]}},
        "objects": [
            {"type": "sphere", "center": [0, -100.5, 1], "radius": 100, "material": "ground"},
            {"type": "sphere", "center": [0, 0, 1], "radius": 0.5, "material": "centre"},
            {"type": "sphere", "center": [0, 0, 1], "radius": 0.5, "material": "metal"},
            {"type": "sphere", "center": [-1, 0, 1], "radius": 0.5, "material": "glass"},
            {"type": "sphere", "center": [-1, 0, 1], "radius": -0.45, "material": "glass"},
            {"type": "sphere", "center": [1, 0, 1], "radius": 0.5, "material": "metal"},
            {"type": "plane", "normal": [0, 0, -1], "offset": -4, "material": "floor"},
            {"type": "mesh", "vertices": [[0.3, -0.5, 0], [0.9, -0.5, 0], [0.6, 0.2, 0.3], [0.6, -0.5, -0.4]],
             "triangles": [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], "material": "amber"}],
        "background": {"type": "gradient", "bottom": [1, 1, 1], "top": [0.5, 0.7, 1]},
        "render": {"integrator": "stochastic", "samples": 21, "max_depth": 12, "jitter": true, "seed": 3}})"),
                                "stochastic.json");
    const Pair p = render_both(s);
    CHECK(p.lanes.stats.primary_rays == 40 * 30 * 21);
    CHECK(p.lanes.stats.segments == p.one_by_one.stats.segments);
    CHECK(p.lanes.stats.segments > 2 * p.lanes.stats.primary_rays);
    CHECK(p.lanes.stats.depth_limited == p.one_by_one.stats.depth_limited);
    CHECK(p.image_bits == 0);
    CHECK(p.lost_bits == 0);
}
