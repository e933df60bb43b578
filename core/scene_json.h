#pragma once
// Scene files (JSON, docs/scene-format.md). Every error is an InputError whose message
// names the file and the JSON path, e.g. "scene.json: /objects/2/radius: must be a
// finite number".
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace refract {

Scene load_scene(const std::string& path);
Scene parse_scene(const nlohmann::json& j, const std::string& source_name);

}  // namespace refract
