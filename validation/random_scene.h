#pragma once
// Random scenes for the search for disagreements between refract and POV-Ray: each is a
// refract scene file in "compat": "povray" that export_pov can express exactly (disjoint
// closed transparent solids, the camera outside them, no refused feature), drawn
// deterministically from a seed.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace refract::validation {

struct RandomSceneOptions {
    int width = 80, height = 60;  // image size (validation-sized)
    bool dispersion = true;       // allow dispersive materials (POV-Ray's law)
    // Objects written untransformed plus a random "transform" that puts them back where the
    // generator placed them (a stream of their own: off, the scene is the same as before).
    bool transforms = false;
    // Point lights made, about half of the time, 2 × 2 rectangle or disk area lights about
    // the same point (a stream of their own: off, the scene is the same as before).
    bool area_lights = false;
    // Closed meshes written, about half of the time, as OBJ files beside the scene
    // (random_scene_files only; a stream of their own).
    bool mesh_files = false;
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
// Meshes stay inline here whatever opt.mesh_files says.
nlohmann::json random_scene(std::uint64_t seed, const RandomSceneOptions& opt = {});

// The scene and the files it names: with opt.mesh_files, some of its meshes become
// {"type": "mesh", "file": "mesh-K.obj"} and their OBJ text (every coordinate with 17
// significant digits, the triangles as they were) is in `files`, to be written beside the
// scene file (the case's directory) before it is read.
struct RandomSceneFiles {
    nlohmann::json scene;
    std::vector<std::pair<std::string, std::string>> files;  // (file name, text)
};
RandomSceneFiles random_scene_files(std::uint64_t seed, const RandomSceneOptions& opt = {});

}  // namespace refract::validation
