#pragma once
// Transparent spheres nested inside one another, as POV-Ray 3.7 expresses them
// (docs/validation.md, "Nested spheres"). refract gives every surface its own relative
// index (the material's `ior`: the inside over the outside, whatever the outside is) and
// decides entering by the normal; POV-Ray gives every object an absolute index and
// takes the ratio from the ray's list of interiors (trace.cpp ComputeRefraction: entering
// B inside A refracts with n_B / n_A, leaving it with n_A / n_B). The two agree on the
// directions when POV-Ray's index of a nested sphere is the product of the `ior`s of it
// and of every sphere around it. They do not agree on Fresnel reflection: POV-Ray 3.7's
// ComputeRelativeIOR takes the ratio of the sphere being left to itself (1) at an exit
// into a container, so it reflects nothing there. Nesting is therefore exported only for
// a constant reflectivity (which no ratio changes), without dispersion or absorption.
#include <string>
#include <vector>

#include <refract/core/scene.h>

namespace refract::validation {

// `inner` lies strictly inside `outer` (both of positive radius).
bool sphere_strictly_inside(const Sphere& inner, const Sphere& outer);

// Why a transparent sphere of this material cannot take part in a nest ("" when it can).
std::string nesting_refusal(const Material& m);

struct SphereNesting {
    std::vector<int> container;        // per object: the smallest transparent sphere strictly around it, or -1
    std::vector<double> absolute_ior;  // per object: POV-Ray's index (the product of the ior along the chain)
    bool any = false;                  // some transparent sphere has a container
};

// The nest of the transparent solids `solids` (object indices; spheres of positive radius
// take part, other shapes never contain or are contained).
SphereNesting sphere_nesting(const Scene& s, const std::vector<size_t>& solids);

}  // namespace refract::validation
