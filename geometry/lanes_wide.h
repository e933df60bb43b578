#pragma once
// Whole-packet operations run on the widest vector instructions the CPU has (AVX-512F,
// AVX2 or the baseline, chosen once at run time), for the packet steps where the baseline
// lane operations of geometry/lanes.h (two lanes an instruction) are the cost. Each lane's
// result is the lane operation's, bit for bit.
#include <refract/geometry/lanes.h>
#include <refract/geometry/plane_set.h>

namespace refract {

// v.normalized() (Eigen's v / |v|) in the lanes of m whose squared norm is positive; the
// other lanes unchanged.
void normalize_lanes(LaneVec3& v, const LaneMask& m);

// Every packet operation of this file from now on runs this variant (an unsupported one:
// the baseline); by default the best the CPU runs (tests compare the variants).
void use_wide_isa(SlabIsa isa);

}  // namespace refract
