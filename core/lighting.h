#pragma once
// The lights and shadows of a scene: direct lighting of a lit surface by the point,
// directional and beam lights, POV-Ray's convention (ambient·pigment + Σ diffuse·pigment·
// light·max(0, N·L)·shadow), with shadow rays by the policy's rule
// (CompatRules::light_transmittance).
#include <refract/core/compat.h>
#include <refract/core/hit_search.h>
#include <refract/core/render_stats.h>
#include <refract/core/scene.h>

namespace refract {

class Lighting {
public:
    // The scene, the rules and the search must outlive the lighting.
    Lighting(const Scene& scene, const CompatRules& rules, const HitSearch& search)
        : scene_(scene), rules_(rules), search_(search) {}

    // Direct lighting at hit h of a surface of pigment `pigment`, `diffuse` and `ambient`.
    Vec3 shade(const SurfaceHit& h, const Pigment& pigment, double diffuse, double ambient, RenderStats& stats) const;
    // The light a leaf sends back: a lit surface's direct lighting, an emitter's colour,
    // none where the kind is not a leaf.
    Vec3 leaf(const SurfaceHit& h, const LeafLight& l, RenderStats& stats) const;

private:
    const Scene& scene_;
    const CompatRules& rules_;
    const HitSearch& search_;
};

}  // namespace refract
