#pragma once
// Scene files (JSON, docs/scene-format.md). Every error is an InputError whose message
// names the file and the JSON path, e.g. "scene.json: /objects/2/radius: must be a
// finite number".
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/scene.h>

namespace refract {

Scene load_scene(const std::string& path);
Scene parse_scene(const nlohmann::json& j, const std::string& source_name);
// A polarisation state from its JSON object, as a light's "polarisation" ({"type":
// "unpolarised" | "linear" | "circular", "angle", "reference", "handedness"}); errors name
// `source` and the field.
PolarisationState parse_polarisation_state(const nlohmann::json& j, const std::string& source);

}  // namespace refract
