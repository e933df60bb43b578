#pragma once
// Random scenes for the search for disagreements between refract and POV-Ray: each is a
// refract scene file in "compat": "povray" that export_pov can express exactly (disjoint
// closed transparent solids, the camera outside them, no refused feature), drawn
// deterministically from a seed.
#include <cstdint>

#include <nlohmann/json.hpp>

namespace refract::validation {

struct RandomSceneOptions {
    int width = 80, height = 60;  // image size (validation-sized)
    bool dispersion = true;       // allow dispersive materials (POV-Ray's law)
    // Objects written untransformed plus a random "transform" that puts them back where the
    // generator placed them (a stream of their own: off, the scene is the same as before).
    bool transforms = false;
};

// A refract scene file (docs/scene-format.md) as JSON, "compat": "povray", deterministic
// from the seed (the same JSON for the same seed on any IEEE-754 platform: std::mt19937_64
// mapped to doubles by hand, no std distributions, own sin/cos, numbers rounded to ~6
// significant digits; geometry checks are made on the rounded values), with a
// "description" summarising what it holds. Covers spheres (also hollow), closed meshes,
// random and brilliant-like convex polyhedra, exact brilliants, checker planes,
// dielectrics (Fresnel or constant ks, filters, POV-Ray dispersion), diffuse, mirror and
// emissive materials, 0–3 point lights, solid or gradient backgrounds, perspective and
// orthographic cameras (sometimes far, sometimes inside an opaque sphere), max_depth
// 1–24, adc thresholds, and the fresnel-tree or Whitted integrator.
nlohmann::json random_scene(std::uint64_t seed, const RandomSceneOptions& opt = {});

}  // namespace refract::validation
