#pragma once
// Gems in scenes (docs/scene-format.md): the placement shared by "brilliant" and "gem", and
// the "gem" object, a GemCad design file (geometry/gem/gemcad.h) read relative to the scene.
#include <refract/core/json_reader.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/shapes.h>

namespace refract {

// A built gem placed in the scene: its axis (its own z, table up) becomes the scene's +y,
// then `rotation` (degrees about x, y, z, in that order), scaled by `scale`, moved to
// `position`. A convex gem is its plane set, a stone with a cleft (gemcad.h) its closed mesh.
Shape place_gem(const Gem& gem, double scale, const JsonReader& o);

// {"type": "gem", "design": "x.asc", "material", "name", "position", "diameter", "rotation"}:
// without "diameter" the design keeps its own unit; with it, its width W becomes the diameter.
Shape parse_gem_design(const JsonReader& o);

}  // namespace refract
