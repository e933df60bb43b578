#pragma once
#include <functional>
#include <vector>

#include <refract/core/random.h>
#include <refract/core/tracer.h>

namespace refract {

// "Ray Tracing in One Weekend", dielectric chapter: one scattered ray per hit. At a
// dielectric the ray reflects with probability R and refracts otherwise (attenuation 1,
// or the filter colour); Lambertian surfaces bounce randomly, metals reflect with fuzz.
// Many samples per pixel average to the tree's value. Seeded and deterministic.
Vec3 stochastic_radiance(const SceneTracer& tracer, const Ray& primary, Rng& rng, RenderStats& stats);

// The same for the n samples of a pixel, by the one path loop: kLanes paths at a time where
// the tracer walks packets (one at a time otherwise): each bounce searches the paths' rays
// together, then each path takes its own bounce, so that the paths' dependency chains
// overlap; a lane whose path ends takes the next sample. `start(k, rng)` sets rng to sample k's stream and gives its primary ray. out[k] is
// stochastic_radiance(tracer, that ray, rng k, stats) to the last bit.
void stochastic_radiance_samples(const SceneTracer& tracer, int n, const std::function<Ray(int, Rng&)>& start,
                                 std::vector<Vec3>& out, RenderStats& stats);

}  // namespace refract
