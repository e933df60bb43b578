#pragma once
// What a rendered image says about itself (its OpenEXR header): the chromaticities of its
// RGB (core/spectrum/chromaticities.h) and the run that made it (docs/limits.md, "Outputs").
#include <string>
#include <utility>
#include <vector>

namespace refract {

struct Scene;

// Header attributes of a render of `scene` (read from `scene_path`, hashed as read now):
// chromaticities; Software "refract VERSION"; refract:version, refract:scene (the path as
// given), refract:scene_fnv1a64, refract:integrator, refract:samples, refract:seed,
// refract:colour_pipeline, and refract:command_line when the program set one.
std::vector<std::pair<std::string, std::string>> render_attributes(const Scene& scene, const std::string& scene_path);

}  // namespace refract
