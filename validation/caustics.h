#pragma once
// Caustics against POV-Ray photons, statistically (docs/validation.md, "Caustics"): a
// glass sphere (n = 1.5, no dispersion) above a diffuse floor, one point light, the
// camera looking down at the floor from the side away from the light. refract renders it
// in physical mode with a light pass (glass blocks the straight shadow ray, the light
// through the sphere arrives as the caustic in the illumination map); POV-Ray renders the
// export with photons (photon targets block the straight light as well). Both therefore
// compute floor = direct light outside the sphere's shadow + caustic. Photons are
// jittered and gathered over a radius, so only floor-region means and a binned profile
// are compared, never pixels.
#include <string>
#include <vector>

#include "core/scene.h"
#include "validation/povray_runner.h"
#include "validation/suite.h"

namespace refract::validation {

struct CausticOptions {
    int width = 240, height = 180;
    std::uint64_t photons = 400000;  // refract light pass and POV-Ray `photons { count }`
    std::uint64_t seed = 7;          // refract light-pass seed
    int threads = 0;
    PovrayOptions povray;
    // Measured (docs/validation.md, "Caustics"): over light-pass seeds 7-9 and 1e5-8e5
    // photons the worst region difference was 2.2 %, the worst profile bin 15.5 % (1e5)
    // and 11.0 % (4e5), the worst mean over the bins 4.2 % (1e5) and 2.6 % (4e5).
    double region_tolerance = 0.05;        // relative, on each floor-region mean
    double profile_tolerance = 0.15;       // relative, on the worst profile bin
    double profile_mean_tolerance = 0.05;  // relative, mean over the profile bins
};

// The caustic scene (refract JSON semantics, physical mode with a light pass).
Scene caustic_scene(const CausticOptions& opt);

// Renders both and compares: metrics "caustic core mean", "ring mean", "shadow edge mean",
// "lit floor mean" (relative difference POV-Ray vs refract, each against
// region_tolerance), and the profile through the caustic centre (max and mean relative
// bin difference). Throws PovrayError when POV-Ray cannot run.
CaseResult run_caustics(const CausticOptions& opt);

}  // namespace refract::validation
