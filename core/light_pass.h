#pragma once
// Light pass of bidirectional ray tracing (Chattopadhyay & Fujimoto 1987, as Ohtsuka &
// Kawai 1998 use it). From each point light, photons are shot into the cone around each
// transparent object's bounding sphere (uniform in solid angle); a photon is one RGB ray
// until its first hit on a dispersive dielectric, where it splits into one ray per band
// carrying the band's RGB weight; each is traced with its own index through reflections
// and refractions (both branches, Fresnel-weighted, the paper's 8/8 limits and the
// threshold), and what reaches a diffuse surface after at least one specular interaction
// is deposited in that surface's illumination map (core/illumination_map.h).
//
// Units: point lights have no falloff (the POV-Ray convention of the direct lighting):
// a photon's power is scaled by the square of the path length it travelled, so that
// light crossing an index-1 object lands as the direct irradiance c·cosθ would.
// Deterministic for any thread count: photon p draws from its own stream
// Rng(seed, light·objects + object, p), and deposits are summed in 64-bit fixed point.
#include <atomic>
#include <memory>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/trace_options.h>

namespace refract {

// Runs the light pass with scene.settings.light_pass on `threads` threads (0: all), searching
// and walking as `options` say. `cancel`, when given and set, stops the pass early (its maps
// are then incomplete; the caller discards them).
std::shared_ptr<IlluminationMaps> light_pass(const Scene& scene, const SpectralContext& ctx, int threads = 0,
                                             const std::atomic<bool>* cancel = nullptr, const TraceOptions& options = {});

// The elements its illumination maps would hold, computed without allocating.
double illumination_elements(const Scene& scene);

}  // namespace refract
