#pragma once
// A gradient-index profile (core/grin/profile.h) as a scene file gives it
// (docs/grin.md, docs/scene-format.md): {"kind": "luneburg", "centre": [x, y, z],
// "radius": R}, and so on for each kind; a base index "n0" with an optional Cauchy
// coefficient "cauchy_b" (µm²). Unknown kinds and fields are refused naming the field.
#include <string>

#include <refract/core/grin/profile.h>
#include <refract/core/json_reader.h>

namespace refract::grin {

Profile read_profile(const JsonReader& r);
// The kind's name in scene files ("luneburg", "sech-rod", …).
std::string kind_name(const Profile& p);

}  // namespace refract::grin
