#pragma once
// The sections of `refract bench` besides the 1998 diamond (cli/bench.cpp), each printing
// paired timings (docs/performance.md).
#include <string>

#include <refract/geometry/shapes.h>

namespace refract::cli::bench {

// The round brilliant's intersection, on the same rays: the plane-set kernel (scalar loop
// and the vectorised one) against Embree on the gem's triangles, alone and with refract's
// double-precision refinement.
void kernels(int rounds);
// Rays leaving the brilliant's facets: the full plane loop against facet-local intersection.
void facet_local(const ConvexPolyhedron& solid, int rounds);

// Triangle meshes from 80 to 327 680 triangles (icospheres): refract's mesh search
// (Embree + refinement) against Embree alone on the same rays, and the linear search
// where it finishes.
void meshes(int rounds);

// A 1.3 M-triangle mesh file (binary PLY and STL, written in a temporary directory) loaded
// as a scene object: load and BVH build times, bytes per triangle.
void mesh_file();

// Scenes of 10 to 10 000 spheres: the tracer's nearest-hit search through its object BVH
// against the linear search over the objects.
void objects(int rounds);

// The RTIOW dielectric chapter's last scene: refract's stochastic integrator against a
// build of the book's own code at `book` (an executable writing its PPM to stdout).
void rtiow(const std::string& book, int rounds);

// The proportion sweep (refract sweep brilliant): construction (CGAL) and evaluation of one cut
// timed apart, a sub-grid swept on `threads` and extrapolated to the full >= 26 000-cut grid,
// and 1 against 2 MPI ranks; `rays` > 0 replaces the documented ray count.
void sweep(int threads, int rays);

// Ray queries on the 1998 diamond: one ray's record through a TraceSession and without
// one, and trace_rays over the camera's rays that meet the diamond, one thread and all;
// `quick`: fewer calls and rays (the test of the documented figures).
void trace(int rounds, bool quick);

// Gradient-index media: each profile's index-and-gradient evaluations per second on one
// thread, alone and inside the ray equation, and adaptive against fixed steps at the same
// error (docs/grin.md).
void grin(int rounds);

}  // namespace refract::cli::bench
