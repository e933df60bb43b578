#pragma once
// refract scene -> POV-Ray 3.7 scene description language, so that an independent,
// mature renderer can render the same scene (docs/validation.md). The export is exact
// or refused: every statement reproduces refract's POV-Ray-compatible mode
// ("compat": "povray"), and a scene feature POV-Ray cannot express the same way throws
// InputError naming the feature, never an approximate file.
#include <cstdint>
#include <string>

#include <refract/core/scene.h>

namespace refract::validation {

// The scene as POV-Ray SDL (`#version 3.7;` first). Throws InputError when the scene
// uses something POV-Ray 3.7 cannot express exactly: the stochastic integrator,
// jittered supersampling, lambertian or fuzzy metal materials, Schlick / s / p
// reflectance, dispersion, an index of exactly 1, max_depth beyond POV-Ray's limit,
// overlapping transparent objects or a camera inside one (POV-Ray decides entering /
// leaving by the objects a ray is inside, refract by the surface normal; the two agree
// only for disjoint solids; transparent spheres strictly nested with a constant
// reflectivity are exported, validation/pov_nesting.h), open meshes made of glass.
std::string export_pov(const Scene& scene);

// Opt-in statistical export (docs/validation.md, "Caustics"): with `photons`, a scene
// with a light pass is accepted and exported with POV-Ray photons instead: `photons {
// count N }` in global_settings (N = photon_count, or the scene's light_pass.photons
// when 0) and `photons { target refraction on reflection on }` on every transparent
// object. POV-Ray then blocks the straight light through those objects (the caustic
// replaces it), as refract's physical shadow rays do. Photons are jittered: compare such
// renders statistically, never per pixel. With photons off the output is export_pov's.
// `environment_map`: the file name by which the SDL refers to an environment light's map
// (a sky_sphere image map, looked for beside the .pov); write_environment_map writes it.
struct ExportOptions {
    bool photons = false;
    std::uint64_t photon_count = 0;
    std::string environment_map = "environment.exr";
};
std::string export_pov(const Scene& scene, const ExportOptions& options);

// Whether the scene's background is an environment light with a map, i.e. whether the
// exported SDL refers to a map file.
bool has_environment_map(const Scene& scene);

// Writes that map to `path` (a float OpenEXR file of the values refract looks up; the
// export refuses a map whose values are not exactly half-precision, the precision in
// which POV-Ray reads OpenEXR). Nothing without a map. Throws InputError naming the path.
void write_environment_map(const Scene& scene, const std::string& path);

// export_pov written to `path` through a temporary name and a rename; an environment
// map beside it as STEM-environment.exr.
void write_pov(const Scene& scene, const std::string& path);

// Formats a double so that POV-Ray's parser reads back the same value (shortest
// representation that round-trips).
std::string pov_number(double v);

}  // namespace refract::validation
