#pragma once
// An object's "transform" in a scene file (docs/scene-format.md):
//   {"translate": [x, y, z], "rotate": [ax, ay, az] (degrees), "scale": s | [sx, sy, sz],
//    "matrix": 4×4, row-major, acting on column vectors, last row [0, 0, 0, 1]}
// composed as x ↦ translate · rotate · scale · matrix · x: the matrix first, then the scale,
// the rotation (about x, then y, then z; right-handed) and the translation last, whatever
// order the fields are written in.
#include <refract/core/json_reader.h>
#include <refract/geometry/transform.h>

namespace refract {

Transform parse_transform(const JsonReader& r);

}  // namespace refract
