#pragma once
#include "core/random.h"
#include "core/tracer.h"

namespace refract {

// "Ray Tracing in One Weekend", dielectric chapter: one scattered ray per hit. At a
// dielectric the ray reflects with probability R and refracts otherwise (attenuation 1,
// or the filter colour); Lambertian surfaces bounce randomly, metals reflect with fuzz.
// Many samples per pixel average to the tree's value. Seeded and deterministic.
Vec3 stochastic_radiance(const SceneTracer& tracer, const Ray& primary, Rng& rng, RenderStats& stats);

}  // namespace refract
