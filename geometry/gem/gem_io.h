#pragma once
// Writing a built gem to disk, chosen by the file extension:
//   .obj  Wavefront OBJ, one polygon per facet, grouped by facet label ("g upper_half_2+")
//   .off  Object File Format, one polygon per facet
//   .ply  ASCII PLY, one polygon per facet
//   .pov  POV-Ray: #declare Gem = intersection { plane { <n>, d } ... }
//   .asc  GemCad design (geometry/gem/gemcad.h), the round brilliant only (no frame: angles,
//         distances and gear indices)
// Coordinates are the scene's (docs/scene-format.md, "Coordinates"): y up, the gem's axis
// (its own z, table up) along +y, its own y along −z: (x, y, z) -> (x, z, −y), exactly; the
// file loaded as a mesh is the gem a scene places at the origin with its own size (girdle
// radius 1 for the brilliant). %.17g keeps every double.
// Files are written to a temporary name beside the target and renamed: never half-written.
#include <string>

#include <refract/geometry/gem/brilliant.h>

namespace refract {

// Throws InputError for an unknown extension or a file that cannot be written.
void write_gem(const Gem& gem, const std::string& path);

// The POV-Ray declaration alone. POV-Ray's `plane { <n>, d }` is the set n·x = d with the
// inside where n·x < d, the same convention as refract's planes; POV-Ray's axes are
// left-handed but the numbers are the same. Planes in the scene's frame, like the files.
std::string pov_gem_declaration(const Gem& gem, const std::string& name = "Gem");

}  // namespace refract
