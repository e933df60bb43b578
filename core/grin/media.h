#pragma once
// The gradient-index media of a scene (docs/grin.md): each object of a "grin" material
// with the region its shape bounds (a sphere, or a bounded convex polyhedron) and its
// profile checked over that region. Built once per SceneTracer.
#include <string>
#include <vector>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/grin/region.h>

namespace refract {
struct Scene;
}

namespace refract::grin {

struct Medium {
    int object = -1;  // index into Scene::objects
    Region region;
    Profile profile;  // validated over the region
    Settings settings;
    // The objects inside the region (indices into Scene::objects): lit or emitting surfaces
    // (a material whose leaf_light is not None), which end a curved ray where it meets them.
    std::vector<int> inside;
};

// The scene's media in object order. InputError, naming the file and the field, for a
// shape with no inside (a plane, an open mesh, a hollow sphere, an unbounded polyhedron),
// a profile whose index is not finite and > 0 over its region at 360–830 nm, and any
// object overlapping a medium's region that is not a lit or emitting surface (a dielectric,
// a mirror, a metal or another medium: a ray leaving it would start inside the medium
// with no index of its own there).
std::vector<Medium> media(const Scene& scene);

// The medium of `media` that a ray at `origin` along unit `dir` travels in: leaving the
// surface of object `from` (−1: a root ray) into that object's medium, or a root ray that
// starts inside one. Null: none.
const Medium* medium_of(const std::vector<Medium>& media, const Vec3& origin, const Vec3& dir, int from);

}  // namespace refract::grin
