#pragma once
// A ray through a gradient-index medium (docs/grin.md): the ray equation
// d/ds (n dr/ds) = ∇n (Born & Wolf, Principles of Optics, §3.2) in the form of Sharma,
// Kumar & Ghatak (Applied Optics 21(6), 984–987, 1982): with dt = ds/n and T = dr/dt =
// n·(unit direction), d²r/dt² = ∇(n²/2) = n∇n. Integrated by Dormand & Prince's embedded
// Runge–Kutta 5(4) pair (J. Comput. Appl. Math. 6, 19–26, 1980) with its FSAL stage and
// its dense output (Hairer, Nørsett & Wanner, Solving ODEs I, §II.6), the optical path
// ∫n ds = ∫n² dt and the length ∫ds = ∫n dt integrated with it.
//
// advance() is what a walker calls for a ray inside a GRIN object: from a point and a
// direction until the ray leaves the region (the crossing found by root finding on the
// step's dense output, then polished on the true step) or the step budget runs out. With
// Settings::frame it also carries a polarisation frame along the ray (Rytov's law).
#include <optional>
#include <vector>

#include <Eigen/Core>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/region.h>

namespace refract::grin {

// Surfaces inside the medium (the leaf objects a scene places in it, core/grin/media.h):
// the first crossing of the straight segment from a to b, as the fraction of the way along
// it (in [0, 1]) and the caller's id of the surface; none when the segment meets none.
struct ObstacleHit {
    double fraction = 0;
    int id = -1;
};
class Obstacles {
public:
    virtual ~Obstacles() = default;
    virtual std::optional<ObstacleHit> first(const Vec3& a, const Vec3& b) const = 0;
};

struct Settings {
    // Each step's error estimate e_i of each component y_i of (r, T, optical path,
    // length) must satisfy |e_i| ≤ abs_tol + rel_tol·max(|y_i| before, |y_i| after).
    double abs_tol = 1e-10, rel_tol = 1e-10;
    // Steps tried (accepted and rejected) before the ray ends as budget_exhausted.
    int max_steps = 100000;
    // > 0: fixed steps of this size in t (no error control; for comparisons only).
    double fixed_step = 0.0;
    // Record the points and directions along the ray (the start, every step's end, the exit).
    bool record_path = false;
    // Non-zero: a polarisation frame vector at the start, parallel-transported along the ray
    // (Rytov's law, core/grin/rytov.h) in the same steps, with the same error test, and
    // returned as Result::exit_frame. Its component along dir0 is removed and it is
    // normalised; one parallel to dir0 or not finite is a std::invalid_argument. Zero: off
    // (the integrator then runs as without it, to the bit).
    Vec3 frame = Vec3::Zero();
    // Non-null: surfaces inside the region that end the ray where it first meets one
    // (Status::met_obstacle). Each accepted step's dense output is tested as a polyline of
    // kObstacleChords chords, in order; in the first chord that meets a surface the crossing
    // is found by bisection on the dense output (each half tested as a chord, 40 halvings).
    // The last first() call that returns a hit is the crossing reported (its caller may
    // keep what it found there). Null: the integrator runs as without it, to the bit.
    const Obstacles* obstacles = nullptr;
};
inline constexpr int kObstacleChords = 4;

enum class Status {
    left_region,       // the exit point is on the region's boundary
    budget_exhausted,  // max_steps tried: the ray ends where it is (lost light)
    met_obstacle       // the exit point is on a surface inside (Settings::obstacles), Result::obstacle
};

struct PathSample {
    Vec3 x;
    Vec3 dir;                   // unit
    Vec3 frame = Vec3::Zero();  // with Settings::frame: the transported vector, unit, ⟂ dir
};

struct Result {
    Status status = Status::left_region;
    Vec3 exit_point = Vec3::Zero();
    Vec3 exit_dir = Vec3::Zero();  // unit
    double exit_index = 1.0;       // n at the exit point
    double optical_path = 0.0;     // ∫ n ds
    double length = 0.0;           // ∫ ds
    int steps = 0;                 // accepted
    int rejected = 0;
    long evaluations = 0;          // index-and-gradient evaluations
    // With Settings::frame: the frame vector transported to the exit point, unit and ⟂
    // exit_dir (a Stokes vector in the start's frame (frame, dir0 × frame) is the same in
    // (exit_frame, exit_dir × exit_frame)); zero otherwise.
    Vec3 exit_frame = Vec3::Zero();
    int obstacle = -1;  // met_obstacle: the surface's id (ObstacleHit::id)
    std::vector<PathSample> path;  // with Settings::record_path
};

// The ray from x0 (inside the region or on its boundary) in the unit direction dir0 at
// wavelength lambda_um through `profile` until it leaves `region`. The profile and the
// region must have been validated (validate() in profile.h and region.h).
Result advance(const Profile& profile, const Region& region, const Vec3& x0, const Vec3& dir0, double lambda_um,
               const Settings& settings = {});

}  // namespace refract::grin
