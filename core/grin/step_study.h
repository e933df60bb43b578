#pragma once
// The integrator measured on one ray with a known exit point (docs/grin.md, "The
// integrator"): the exit error against the tolerance, and fixed steps of the same method
// against the adaptive ones at the same error. Used by `refract bench --grin` and by the
// `grin` experiment's convergence figure.
#include <vector>

#include <refract/core/grin/ray_equation.h>

namespace refract::grin {

// One ray through a validated profile and region whose exact exit point is known.
struct KnownRay {
    Profile profile;
    Region region;
    Vec3 x0, dir, exit;
    double lambda_um = 0.55;
};

struct StepPoint {
    double setting = 0;     // the tolerance (adaptive) or the step in t (fixed)
    bool left = true;       // the ray left the region (else it ran out of its step budget)
    double error = 0;       // |exit point − the exact one|; 1 when the ray did not leave
    long evaluations = 0;   // index-and-gradient evaluations
    int steps = 0;          // accepted
};

// The ray at abs_tol = rel_tol = `tol` (budget `max_steps`).
StepPoint adaptive_point(const KnownRay& ray, double tol, int max_steps = 100000);
// The ray at fixed steps of `step` in t (budget `max_steps`).
StepPoint fixed_point(const KnownRay& ray, double step, int max_steps = 4000000);

// Fixed steps from `first_step`, halved until the exit error is ≤ `target` or the step is
// below `smallest`: the last one tried.
StepPoint fixed_steps_to_match(const KnownRay& ray, double target, double first_step = 0.4, double smallest = 1e-5);

}  // namespace refract::grin
