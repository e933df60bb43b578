#pragma once
// Area lights (docs/scene-format.md): a rectangle, or a disk as POV-Ray 3.7's `circular`
// area_light, each the grid of size[0] × size[1] point lights of colour
// color / (size[0]·size[1]) (POV-Ray's area_light without jitter or adaptive sampling).
//   rectangle  point (i, j) at position + (i/(n1−1) − ½)·axis1 + (j/(n2−1) − ½)·axis2
//              (a side of one point: its centre), so the grid spans the rectangle's edges
//   disk       s = i/(n1−1) − ½ + 0.001, t = j/(n2−1) − ½ + 0.001 (POV-Ray's offset),
//              scaled by max(|s|, |t|) / √(s² + t²): each square shell of the grid onto
//              the circle of its half-width; point at position + s·axis1 + t·axis2
// The light pass draws (i/(n1−1), j/(n2−1)) uniformly in [0, 1]² instead: the grid's
// continuum (uniform on the rectangle; on the disk as dense as the mapping makes it).
#include <array>

#include <nlohmann/json.hpp>

#include <refract/core/json_reader.h>
#include <refract/core/scene.h>

namespace refract {

constexpr int kMaxAreaLightGrid = 64;  // each of size[0], size[1]

// The point of an area light at grid coordinates (a, b) in [0, 1]².
Vec3 area_light_point(const Light& l, double a, double b);

// Reads the fields of a light of type "rectangle" or "disk" (the kind already set);
// InputError naming the field.
void parse_area_light(const JsonReader& r, Light& light);

}  // namespace refract
