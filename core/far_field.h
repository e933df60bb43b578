#pragma once
// The far-field detector: the radiant power leaving the scene's transparent objects,
// binned by direction. Photons start at the lights (core/emitters.h: point lights, suns,
// beams) as in the light pass, each at one wavelength from its start (every wavelength of
// the sampling is a run of its own: indices n(λ), absorption at λ), and are walked by the
// one ray-tree walker (core/ray_tree.h) with the scene's limits; a branch that leaves the
// scene after at least one interaction lands in the bin of its direction (the far field:
// the object is a point seen from infinity), in its event class, with its Stokes vector
// when the scene's polarisation model is exact.
//
// Binning (docs/far-field.md):
//   Sphere  equal solid angle: `azimuth_bins` in φ about `axis` (from `reference`
//           projected across it) × `polar_bins` uniform in cos θ (θ from `axis`, row 0 at
//           θ = 0); each bin spans 4π / (azimuth_bins · polar_bins) sr.
//   Axis    `angle_bins` uniform in θ ∈ [0°, 180°] from `axis` (a bin's solid angle
//           2π (cos θ₀ − cos θ₁)): a drop's scattering-angle histogram with `axis` the
//           beam's direction.
// Event classes: 0 reflected without entering any object (no transmission), then
// 1 + k for a branch transmitted with k reflections (inside a single convex object: k
// internal reflections, van de Hulst's p = k + 1), the last class gathering the rest.
// Stokes vectors are expressed in the frame x̂ = ⊥ the plane of `axis` and the outgoing
// direction (x̂ = axis × d, normalised): S1 > 0 is light polarised perpendicular to the
// scattering plane.
// Powers are fractions of the power the lights emitted at that wavelength. Sums are made in
// 64-bit fixed point per thread and added: the result is identical for any thread count.
#include <cstdint>
#include <string>
#include <vector>

#include <refract/core/trace_options.h>
#include <refract/core/scene.h>

namespace refract {

struct FarFieldSettings {
    enum class Binning { Sphere, Axis };
    Binning binning = Binning::Sphere;
    Vec3 axis{0, 0, 1};
    Vec3 reference{1, 0, 0};  // Sphere: where φ = 0 (projected across the axis)
    int azimuth_bins = 360, polar_bins = 180;
    int angle_bins = 180;
    int classes = 5;                 // reflected, 0, 1, 2, ≥3 internal reflections
    std::uint64_t photons = 1000000;  // per light and wavelength
    std::uint64_t seed = 7;
    // Wavelengths (nm) of the runs; empty: the scene's spectral sampling when a material is
    // dispersive or absorbs per wavelength, else the single wavelength 550 nm.
    std::vector<double> wavelengths;
    std::uint64_t max_memory = 0;  // bytes; 0: default_memory_budget() (core/memory.h)
    // How rays are searched and walked (natural light: the wavelengths of a photon walked
    // together in packets of kLanes, the same result as one by one to the last bit).
    TraceOptions trace;
    bool progress = false;  // a progress line on stderr (core/progress.h; callers pass isatty(2))
};

struct FarFieldResult {
    FarFieldSettings settings;
    std::vector<double> wavelengths;
    int bins = 0, classes = 0;
    int components = 1;            // 4 (S0..S3) with exact polarisation, else 1
    // power[((w · classes + c) · components + s) · bins + b]: the fraction of the power
    // emitted at wavelength w leaving in bin b, class c, Stokes component s.
    std::vector<double> power;
    std::vector<double> unscattered;  // per wavelength: photons that hit nothing
    std::vector<double> absorbed;     // ... ending on a diffuse surface or an emitter, or absorbed inside
    std::vector<double> dropped;      // ... dropped by the depth limit and the threshold
    double emitted_power = 0;         // per wavelength, in the lights' units
    std::uint64_t photons = 0, segments = 0;
    double seconds = 0;

    double at(int w, int c, int s, int b) const {
        return power[((static_cast<size_t>(w) * static_cast<size_t>(classes) + static_cast<size_t>(c)) *
                          static_cast<size_t>(components) + static_cast<size_t>(s)) * static_cast<size_t>(bins) +
                     static_cast<size_t>(b)];
    }
    // Of the power emitted at wavelength w: what leaves in any bin and class (S0), and the
    // rest, 1 − scattered − unscattered − absorbed − dropped: the light absorbed inside
    // the objects (Beer–Lambert), 0 below 1e-9 (the fixed-point tallies' rounding).
    double scattered(int w) const;
    double absorbed_inside(int w) const;
    // A bin's solid angle (sr), and its centre: θ (degrees from the axis) and, for the
    // sphere binning, φ (degrees).
    double solid_angle(int b) const;
    double theta_deg(int b) const;
    double phi_deg(int b) const;
    // The bin a direction falls in.
    int bin_of(const Vec3& dir) const;
    // The same for many directions (the binning built once).
    std::vector<int> bins_of(const std::vector<Vec3>& dirs) const;
    std::string class_name(int c) const;
};

// The centre direction of bin b (sphere binning: its row's mean cos θ and φ; axis
// binning: its θ in the plane of the axis and the reference).
Vec3 bin_direction(const FarFieldSettings& settings, int b);

// Checks the settings (one-line InputError naming the option) and runs the detector on
// `threads` threads (0: all).
FarFieldResult far_field(const Scene& scene, const FarFieldSettings& settings, int threads = 0);

}  // namespace refract
