#pragma once
// Deterministic random numbers: one independent stream per (seed, pixel, sample), so an
// image does not depend on the thread count or the order tiles are rendered in.
#include <cmath>
#include <cstdint>

#include "geometry/ray.h"

namespace refract {

class Rng {
public:
    Rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t sub = 0)
        : state_(mix(seed ^ mix(stream + 0x9E3779B97F4A7C15ull) ^ mix(sub * 0xD1B54A32D192ED03ull + 1))) {}

    std::uint64_t next() {  // splitmix64
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        return mix(z);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

    Vec3 unit_vector() {  // uniform on the sphere
        const double z = 2.0 * uniform() - 1.0;
        const double phi = 2.0 * M_PI * uniform();
        const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    Vec3 in_unit_sphere() { return unit_vector() * std::cbrt(uniform()); }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::uint64_t state_;
};

}  // namespace refract
