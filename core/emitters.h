#pragma once
// Where the light pass and the far-field detector start their photons: each light
// becomes one or more emitters, each a way of drawing a photon's ray and its power.
//   point light        photons into the cone around each target's bounding sphere,
//                      uniform in solid angle (no distance falloff: a photon's power is
//                      that at the reference distance `dref`, see core/light_pass.h)
//   directional (sun)  parallel photons through the disk of each target's radius across
//                      the light; a sun of angular diameter α draws each direction
//                      uniformly in its cone, of radiance E / (π sin²(α/2))
//   beam               parallel photons uniform over its disk (whatever they hit)
//   area (rectangle,   from a uniform point of the grid's continuum (core/area_light.h),
//   disk)              isotropic as each grid point's point light, into the cone about
//                      each target that covers it from anywhere on the area; power as a
//                      point light's of the whole colour
//   environment        (a background of type environment) directions uniform over the
//                      sphere, each a parallel photon through the disk of each target's
//                      radius across it, of power L(−d) · πR² · 4π / N (unpolarised)
// Targets are the transparent objects' bounding spheres; a light's photons are split
// evenly over them (a beam's are its own).
#include <cstdint>
#include <vector>

#include <refract/core/polarisation_state.h>
#include <refract/core/random.h>
#include <refract/core/scene.h>

namespace refract {

// Two unit vectors across `axis`, with axis × u = v.
struct Frame {
    Vec3 u{1, 0, 0}, v{0, 1, 0};
};
Frame frame_across(const Vec3& axis);

struct Emitter {
    enum class Kind { Cone, Disk, Environment, Area };
    Kind kind = Kind::Cone;
    Vec3 origin{0, 0, 0}, axis{0, 0, 1};  // cone apex / disk centre / area: the target's centre; the central direction
    Frame frame;           // across the axis (made once, not per photon)
    Vec3 power{0, 0, 0};   // one photon's power (a cone's: at the reference distance)
    double cos_max = 1;    // cone: half-angle; disk: the sun's half-angle (1: parallel)
    double dref = 0;       // cone: the reference distance (0 for parallel light)
    double radius = 0;     // disk
    std::uint64_t photons = 0, stream = 0;
    size_t light = 0;            // index into Scene::lights (not for the environment)
    const Background* environment = nullptr;  // Environment: the radiance lookup
    double geometry = 0;         // Environment: πR² · 4π / N, times L(−d) per photon
    const Light* area = nullptr; // Area: the light (its points: area_light_point)
};

// The polarisation an emitter's photons start with (the environment's: unpolarised).
const PolarisationState& emitter_polarisation(const Scene& scene, const Emitter& em);

// The transparent (dielectric) objects' bounding spheres.
std::vector<BoundingSphere> transparent_targets(const Scene& scene);

// The emitters of every light, `photons` per light. `dref` of the cones: the distance
// from the light to `centre` (the targets' centre).
std::vector<Emitter> make_emitters(const Scene& scene, const std::vector<BoundingSphere>& targets, const Vec3& centre,
                                   std::uint64_t photons);

struct PhotonRay {
    Ray ray;
    Vec3 power;
};
// Photon p of emitter em, drawn from its own stream Rng(seed, em.stream, p).
PhotonRay sample_photon(const Emitter& em, std::uint64_t seed, std::uint64_t p);

// A light's polarisation as a photon leaving along `dir` carries it (S0 = 1).
LightStokes emitted(const PolarisationState& p, const Vec3& dir);

}  // namespace refract
