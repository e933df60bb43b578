#pragma once
// A surface colour: plain, or a 3D checker of `color` and `checker->color2` (POV-Ray's
// `checker`), and its scene-file form.
#include <optional>

#include <refract/core/json_reader.h>
#include <refract/geometry/ray.h>

namespace refract {

struct Checker {
    Vec3 color2{0, 0, 0};  // the second colour; the first is the pigment's `color`
    double size = 1;       // edge of one square (3D checker as in POV-Ray)
};

struct Pigment {
    Vec3 color{1, 1, 1};
    std::optional<Checker> checker;
};

// {"color": [r, g, b], "checker": {"color2": [r, g, b], "size": s}} (colours: components
// in [0, 1e30], JsonReader::colour).
inline Pigment read_pigment(const JsonReader& r) {
    Pigment p;
    p.color = r.colour("color", p.color);
    if (r.has("checker")) {
        const JsonReader c = r.child("checker");
        c.only({"color2", "size"});
        p.checker = Checker{c.colour("color2", Vec3(0, 0, 0)), c.positive("size", 1.0)};
    }
    return p;
}

}  // namespace refract
