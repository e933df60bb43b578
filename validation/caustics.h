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

#include <refract/core/scene.h>
#include <refract/validation/povray_runner.h>
#include <refract/validation/suite.h>

namespace refract::validation {

struct CausticOptions {
    int width = 240, height = 180;
    std::uint64_t photons = 400000;  // refract light pass and POV-Ray `photons { count }`
    std::uint64_t seed = 7;          // refract light-pass seed
    MapFilter filter = MapFilter::Bilinear;  // refract's map reconstruction (the scene default)
    int threads = 0;
    PovrayOptions povray;
    // Measured (docs/validation.md, "Caustics"), bilinear maps, over light-pass seeds 7-9
    // and 1e5-8e5 photons: the worst caustic-core difference 1.7 %, the worst other
    // region 1.5 %, the worst profile bin 10.8 % (1e5) and 4.3 % (4e5), the worst mean
    // over the bins 3.1 % (1e5) and 1.6 % (4e5).
    double core_tolerance = 0.03;          // relative, on the caustic core's mean
    double region_tolerance = 0.05;        // relative, on each other floor-region mean
    double profile_tolerance = 0.15;       // relative, on the worst profile bin
    double profile_mean_tolerance = 0.05;  // relative, mean over the profile bins
};

// The caustic scene (refract JSON semantics, physical mode with a light pass).
Scene caustic_scene(const CausticOptions& opt);

// Renders both and compares: metrics "caustic core mean" (relative difference POV-Ray vs
// refract, against core_tolerance), "ring mean", "shadow edge mean", "lit floor mean"
// (each against region_tolerance), and the profile through the caustic centre (max and
// mean relative bin difference). Throws PovrayError when POV-Ray cannot run.
CaseResult run_caustics(const CausticOptions& opt);

}  // namespace refract::validation
