// The integrator measured on a ray with a known exit (step_study.h).
#include <refract/core/grin/step_study.h>

namespace refract::grin {

namespace {
StepPoint measure(const KnownRay& ray, const Settings& s, double setting) {
    const Result r = advance(ray.profile, ray.region, ray.x0, ray.dir, ray.lambda_um, s);
    StepPoint p;
    p.setting = setting;
    p.left = r.status == Status::left_region;
    p.error = p.left ? (r.exit_point - ray.exit).norm() : 1.0;
    p.evaluations = r.evaluations;
    p.steps = r.steps;
    return p;
}
}  // namespace

StepPoint adaptive_point(const KnownRay& ray, double tol, int max_steps) {
    Settings s;
    s.abs_tol = s.rel_tol = tol;
    s.max_steps = max_steps;
    return measure(ray, s, tol);
}

StepPoint fixed_point(const KnownRay& ray, double step, int max_steps) {
    Settings s;
    s.fixed_step = step;
    s.max_steps = max_steps;
    return measure(ray, s, step);
}

StepPoint fixed_steps_to_match(const KnownRay& ray, double target, double first_step, double smallest) {
    StepPoint p;
    for (double step = first_step; step >= smallest; step /= 2) {
        p = fixed_point(ray, step);
        if (p.error <= target) break;
    }
    return p;
}

}  // namespace refract::grin
