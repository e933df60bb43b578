#pragma once
// Many rays at once (trace_rays): per ray what its tree sums to, without the record. The
// same walk as TraceSession::ray (core/trace_walk.h), so each value is what that ray's
// TraceRecord gives to the last bit (tested); threads share the rays, each ray's values
// do not depend on them.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <refract/core/trace_record.h>

namespace refract {

// Row-major arrays, one row per ray (n rays: vectors of 3n or n values).
struct RayBatch {
    std::size_t n = 0;
    // The first segment's hit: its point (NaN without one), the object's index in
    // scene.objects (−1: none) and the facet or triangle (−1 for smooth shapes or none).
    std::vector<double> point;
    std::vector<std::int32_t> object, facet;
    // The radiance the ray brings back: the record's `radiance` (the sum of its segments' light).
    std::vector<double> radiance;
    // The segments that leave the scene (event "background"): the sum of their weights,
    // and the direction of the one of largest weight (R + G + B; the first on a tie; NaN
    // when none leaves).
    std::vector<double> escaped, exit_direction;
    // The sums over the tree's dielectric nodes of their Rs and Rp (the record's fields).
    std::vector<double> Rs, Rp;
    std::vector<std::int32_t> segments;  // the record's segment count
};

// Traces rays (origins[i], directions[i]) at wavelengths_nm[i] (null: all RGB rays, 0 for
// one ray: an RGB ray) as session.ray() with no polarisation state does, on `threads`
// threads (0: all cores). Every ray is checked before any is traced: InputError naming
// the scene and the ray's index for a non-finite ray or a wavelength outside the range;
// a tree of more than kMaxTraceSegments segments is refused as in trace_ray().
RayBatch trace_rays(const TraceSession& session, const Vec3* origins, const Vec3* directions,
                    const double* wavelengths_nm, std::size_t n, int threads = 0);

}  // namespace refract
