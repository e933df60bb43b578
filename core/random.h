#pragma once
// Deterministic random numbers: one independent stream per (seed, pixel, sample), so an
// image does not depend on the thread count or the order tiles are rendered in.
#include <cmath>
#include <cstdint>

#include <refract/geometry/ray.h>

namespace refract {

class Rng {
public:
    Rng() = default;  // a placeholder, to be assigned a stream (arrays of generators)
    Rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t sub = 0)
        : state_(mix(seed ^ mix(stream + 0x9E3779B97F4A7C15ull) ^ mix(sub * 0xD1B54A32D192ED03ull + 1))) {}

    std::uint64_t next() {  // splitmix64
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        return mix(z);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

    // Uniform on the unit sphere (Marsaglia 1972): (u, v) uniform in the unit disk by
    // rejection from the square, then (2u√(1−s), 2v√(1−s), 1 − 2s) with s = u² + v²; no
    // trigonometry.
    Vec3 unit_vector() {
        for (;;) {
            const double u = 2.0 * uniform() - 1.0, v = 2.0 * uniform() - 1.0;
            const double s = u * u + v * v;
            if (s >= 1.0 || s == 0.0) continue;
            const double w = 2.0 * std::sqrt(1.0 - s);
            return {u * w, v * w, 1.0 - 2.0 * s};
        }
    }
    // Uniform in the unit ball: by rejection from the cube [−1, 1)³ (RTIOW's
    // random_in_unit_sphere).
    Vec3 in_unit_sphere() {
        for (;;) {
            const Vec3 p(2.0 * uniform() - 1.0, 2.0 * uniform() - 1.0, 2.0 * uniform() - 1.0);
            if (p.squaredNorm() < 1.0) return p;
        }
    }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::uint64_t state_ = 0;
};

}  // namespace refract
