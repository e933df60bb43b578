#pragma once
// The walk behind a traced ray, shared by its whole record (trace_record.cpp) and by the
// batched sums (trace_rays.cpp), so that both see the same tree to the last bit: the
// scene's limits, the root entry of the scene's payload, a segment's weight and the light
// it brings to the root, and a node expanded by its ends (one interaction per node).
#include <cmath>
#include <optional>
#include <type_traits>

#include <refract/core/emitters.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/ray_tree.h>
#include <refract/core/scene.h>
#include <refract/core/spectrum/wavelengths.h>

namespace refract::trace_walk {

// A query's wavelength: 0 (an RGB ray) or within the spectral range.
inline bool wavelength_ok(double nm) {
    return nm == 0 || (nm >= spectrum::kMinWavelength && nm <= spectrum::kMaxWavelength);
}

// The unit direction a ray is walked along (a unit direction kept as it is: a camera ray
// traces as it renders); none without a finite origin and a finite, non-zero direction.
inline std::optional<Vec3> direction(const Ray& ray) {
    const auto unit = unit_vector(ray.dir);
    if (!ray.origin.allFinite() || !unit) return std::nullopt;
    return std::abs(ray.dir.squaredNorm() - 1.0) < 1e-15 ? ray.dir : *unit;
}

// The limits of a traced ray: the render's, with the spectral walk's reflection and
// transmission limits.
inline TreeLimits limits(const Scene& scene) {
    TreeLimits l = tree_limits(scene.settings);
    l.max_reflections = scene.settings.spectral.max_reflections.value_or(TreeLimits::kUnlimited);
    l.max_transmissions = scene.settings.spectral.max_transmissions.value_or(TreeLimits::kUnlimited);
    return l;
}

// The root entry of `ray` (unit direction `dir`): light of state `polarisation` along it
// (LightStokes), or the camera's side of it (EyeStokes).
template <class P>
TreeEntryT<P> root(const Scene& scene, const Ray& ray, const Vec3& dir, const PolarisationState* polarisation) {
    TreeEntryT<P> e{Ray{ray.origin, dir}, Vec3(1, 1, 1)};
    if constexpr (std::is_same_v<P, LightStokes>) e.pol = emitted(*polarisation, dir);
    if constexpr (std::is_same_v<P, EyeStokes>) e.pol = camera_stokes(scene, e.ray);
    return e;
}

// A segment's weight: the colour weight times the payload's throughput.
template <class P>
Vec3 weight(const TreeEntryT<P>& e) {
    if constexpr (std::is_same_v<P, NaturalLight>) return e.weight;
    else return e.weight * throughput(e.pol);
}

// What a segment of weight w brings to the root: the light L at its end as the walk sums
// it (under exact polarisation the camera's walk adds the S0 row of C·(L, 0, 0, 0)).
template <class P>
Vec3 light(const TreeEntryT<P>& e, const Vec3& w, const Vec3& L) {
    if constexpr (std::is_same_v<P, EyeStokes>) return rgb_of(seen(e.pol, e.weight, L));
    else return w.cwiseProduct(L);
}

// The node of entry e at hit h expanded as the walker expands it (RayTreeWalkerT::expand),
// its interaction `in` already computed: a leaf to ends.leaf(), the branches to the list;
// `pushed(b)` after each branch kept. For ends whose intercept() takes every hit over.
template <class P, class Ends, class Pushed>
void expand(RayTreeWalkerT<P>& walker, const TreeEntryT<P>& e, const SurfaceHit& h, const Interaction& in,
            FifoList<TreeEntryT<P>>& list, Ends& ends, Pushed&& pushed) {
    if (in.leaf) {
        ends.leaf(e, h);
        return;
    }
    for (int b = 0; b < in.branches; ++b)
        if (walker.push(e, h, in, b, in.transmitted[static_cast<size_t>(b)], list)) pushed(b);
}

// The interaction at hit h as the walker computes it for entry e at the ends' index.
template <class P, class Ends>
Interaction interact(const SceneTracer& tracer, const TreeEntryT<P>& e, const SurfaceHit& h, Ends& ends,
                     RenderStats& stats) {
    return tracer.interact(h, e.ray, stats, ends.band_ior(e, h), false, e.wave, ends.wavelength(e),
                           std::is_same_v<P, EyeStokes>);
}

}  // namespace refract::trace_walk
