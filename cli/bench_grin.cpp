// refract bench --grin: the gradient-index profiles' index-and-gradient evaluations per
// second on one core, and the ray equation's adaptive steps against fixed steps at the
// same error (docs/grin.md).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/bench_sections.h"
#include "cli/bench_timing.h"
#include <refract/core/grin/atmosphere.h>
#include <refract/core/grin/grid.h>
#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/grin/step_study.h>

namespace refract::cli::bench {

namespace bench_grin_command {
using namespace refract::grin;
constexpr double kPi = 3.14159265358979323846;
constexpr double kLambda = 0.5876;

struct Case {
    std::string name;
    Profile profile;
};

// A field sampled on 65³ points over [−1.1, 1.1]³: the Luneburg index, or as a temperature
// grid 300 K + 30 K·(2 − r²) (a warm core), each interpolated by the tricubic spline.
Profile sampled_luneburg(GridQuantity q) {
    GridSamples s;
    const int m = 65;
    s.dims = {m, m, m};
    s.origin = Vec3::Constant(-1.1);
    s.spacing = Vec3::Constant(2.2 / (m - 1));
    for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
                const Vec3 x = s.origin + Vec3(i, j, k).cwiseProduct(s.spacing);
                const double r2 = std::min(x.squaredNorm(), 1.2);
                s.values.push_back(q == GridQuantity::index ? std::sqrt(2 - r2) : 300.0 + 30.0 * (2 - r2));
            }
    return sampled_grid(std::move(s), q, 288.15, 101325.0, "values", "bench");
}

std::vector<Case> profiles() {
    std::vector<double> r, n;
    for (int i = 0; i <= 200; ++i) {
        r.push_back(1.5 * i / 200);
        n.push_back(1.0 + 0.5 * std::exp(-r.back() * r.back()));
    }
    return {{"linear in height", LinearHeight{{1.5, 0.004}, -0.2, 0.0, Vec3::UnitZ()}},
            {"exponential in height", ExponentialHeight{{1.6, 0.004}, 0.5, 0.0, Vec3::UnitZ()}},
            {"Luneburg", Luneburg{}},
            {"Maxwell fish-eye", MaxwellFishEye{Vec3::Zero(), {2.0, 0.004}, 1.0}},
            {"sech rod", SechRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.004}, 1.0}},
            {"parabolic rod", ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.004}, 0.5}},
            {"tabulated radial (201 radii)", tabulated_radial(Vec3::Zero(), r, n, "bench")},
            {"sampled index grid (65^3)", sampled_luneburg(GridQuantity::index)},
            {"sampled temperature grid (65^3)", sampled_luneburg(GridQuantity::temperature)},
            // The unit ball 0 to 2 m above the ground.
            {"Earth's air (1976 standard)", EarthAtmosphere{Vec3(0, 0, -1 - kEarthRadius_m), Atmosphere{}}}};
}

// Points in the unit ball from a fixed linear congruential sequence.
std::vector<Vec3> points(int count) {
    std::vector<Vec3> p;
    std::uint64_t s = 12345;
    auto u = [&s] {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) * 0x1.0p-53 * 2.0 - 1.0;
    };
    while (static_cast<int>(p.size()) < count) {
        const Vec3 v(u(), u(), u());
        if (v.squaredNorm() <= 1.0) p.push_back(v);
    }
    return p;
}
}  // namespace bench_grin_command
using namespace bench_grin_command;

void grin(int rounds) {
    std::printf("GRIN index-and-gradient evaluations, one thread per second of this thread's CPU time (median of %d rounds of 4 M calls)\n", rounds);
    const std::vector<Vec3> xs = points(1 << 16);
    for (const Case& c : profiles()) {
        std::vector<double> rate;
        double sink = 0;
        for (int k = 0; k < rounds; ++k) {
            const double t0 = thread_cpu_seconds();
            const int calls = 1 << 22;
            for (int i = 0; i < calls; ++i) {
                const IndexGradient g = index_and_gradient(c.profile, xs[static_cast<size_t>(i) & 0xffff], kLambda);
                sink += g.n + g.grad.x();
            }
            rate.push_back(calls / (thread_cpu_seconds() - t0));
        }
        // Inside the integrator: Luneburg-sized rays through the unit ball, tolerance 1e-10.
        std::vector<double> ray_rate;
        for (int k = 0; k < rounds; ++k) {
            long evaluations = 0;
            const double t0 = thread_cpu_seconds();
            for (int i = 0; i < 200; ++i) {
                const double rho = 0.9 * i / 200;
                Settings s;
                s.max_steps = 20000;
                const Result r = advance(c.profile, grin::Sphere{}, Vec3(rho, 0, -std::sqrt(1 - rho * rho)),
                                         Vec3(0.1, 0, 1).normalized(), kLambda, s);
                evaluations += r.evaluations;
                sink += r.exit_point.x();
            }
            ray_rate.push_back(static_cast<double>(evaluations) / (thread_cpu_seconds() - t0));
        }
        std::printf("  %-30s %6.1f M/s alone, %6.1f M/s in the ray equation%s\n", c.name.c_str(), median(rate) / 1e6,
                    median(ray_rate) / 1e6, sink == 12345.678 ? " " : "");
    }

    std::printf("Adaptive Dormand-Prince 5(4) against fixed steps of the same method, same error at the exit\n");
    struct Ray {
        std::string name;
        KnownRay ray;
        double tol;
    };
    const double rho = 0.7;
    const Vec3 r0(0, 0, 0.5), image = -r0 / r0.squaredNorm();
    const std::vector<Ray> rays = {
        {"Luneburg, impact 0.7",
         {Luneburg{}, grin::Sphere{}, Vec3(rho, 0, -std::sqrt(1 - rho * rho)), Vec3::UnitZ(), Vec3::UnitZ(), kLambda},
         1e-11},
        {"sech rod, one pitch, 0.3 rad",
         {SechRod{Vec3::Zero(), Vec3::UnitZ(), {1.5, 0.0}, 0.8}, grin::Slab{Vec3::UnitZ(), 0.0, 2 * kPi / 0.8},
          Vec3(0.3, 0, 0), Vec3(std::sin(0.3), 0, std::cos(0.3)), Vec3(0.3, 0, 2 * kPi / 0.8), kLambda},
         1e-11},
        {"fish-eye, 20 deg off the axis",
         {MaxwellFishEye{Vec3::Zero(), {2.0, 0.0}, 1.0}, grin::HalfSpace{-Vec3::UnitX(), 0.0}, r0,
          Vec3(std::sin(20 * kPi / 180), 0, std::cos(20 * kPi / 180)), image, kLambda},
         1e-11},
    };
    for (const Ray& ray : rays) {
        const StepPoint a = adaptive_point(ray.ray, ray.tol);
        const StepPoint f = fixed_steps_to_match(ray.ray, a.error);  // core/grin/step_study.h
        std::printf("  %-30s tol %.0e: adaptive %6ld evaluations (error %.2e), fixed step %.3g: %8ld (error %.2e), "
                    "ratio %.1f\n",
                    ray.name.c_str(), ray.tol, a.evaluations, a.error, f.setting, f.evaluations, f.error,
                    static_cast<double>(f.evaluations) / static_cast<double>(a.evaluations));
    }
}

}  // namespace refract::cli::bench
