#pragma once
// refract scene -> POV-Ray 3.7 scene description language, so that an independent,
// mature renderer can render the same scene (docs/validation.md). The export is exact
// or refused: every statement reproduces refract's POV-Ray-compatible mode
// ("compat": "povray"), and a scene feature POV-Ray cannot express the same way throws
// InputError naming the feature, never an approximate file.
#include <string>

#include "core/scene.h"

namespace refract::validation {

// The scene as POV-Ray SDL (`#version 3.7;` first). Throws InputError when the scene
// uses something POV-Ray 3.7 cannot express exactly: the stochastic integrator,
// jittered supersampling, lambertian or fuzzy metal materials, Schlick / s / p
// reflectance, dispersion, an index of exactly 1, max_depth beyond POV-Ray's limit,
// overlapping transparent objects or a camera inside one (POV-Ray decides entering /
// leaving by the objects a ray is inside, refract by the surface normal; the two agree
// only for disjoint solids), open meshes made of glass.
std::string export_pov(const Scene& scene);

// export_pov written to `path` through a temporary name and a rename.
void write_pov(const Scene& scene, const std::string& path);

// Formats a double so that POV-Ray's parser reads back the same value (shortest
// representation that round-trips).
std::string pov_number(double v);

}  // namespace refract::validation
