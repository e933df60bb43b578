#pragma once
// Rendering a scene: tiles over oneTBB, deterministic whatever the thread count.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/polarisation_state.h"
#include "core/scene.h"

namespace refract {

// Counters of one render; sums over pixels, so identical for any thread count.
struct RenderStats {
    std::uint64_t primary_rays = 0;
    std::uint64_t segments = 0;        // ray segments traced (intersection searches)
    std::uint64_t shadow_rays = 0;
    std::uint64_t tree_nodes = 0;      // branching nodes (surface interactions that split)
    std::uint64_t pruned = 0;          // branches dropped under the threshold
    std::uint64_t depth_limited = 0;   // branches dropped at the depth limit
    // The light the dropped branches would have carried: their weights (cumulative
    // attenuation, mean of the channels; a primary ray has weight 1), summed, by what
    // dropped them. Eye passes only (the Fresnel tree, the spectral pass, the stochastic
    // integrator's last bounce); Whitted's stored tree has no weights while it grows.
    double lost_depth = 0;       // max_depth
    double lost_limits = 0;      // the spectral pass's max_reflections / max_transmissions
    double lost_threshold = 0;   // the pruning threshold
    std::uint64_t peak_list = 0;       // fresnel-tree: longest FIFO list; whitted: largest stored tree
    // Spectral eye pass (core/integrators/spectral.h).
    std::uint64_t spectral_splits = 0;      // rays split per wavelength (first transparent hit)
    std::uint64_t shortcut_tests = 0;       // three-wavelength tests made
    std::uint64_t shortcut_taken = 0;       // ... that skipped the full split
    std::uint64_t wavelength_segments = 0;  // segments traced by single-wavelength rays
    // Segments leaving a facet of a convex plane set (core/tracer.h): decided from the planes
    // around the facet and a guessed leaving facet, or by the full plane loop.
    std::uint64_t facet_local = 0, facet_full = 0;
    // Light pass (core/light_pass.h).
    std::uint64_t photons = 0;              // photons shot
    std::uint64_t photon_segments = 0;      // their ray segments
    std::uint64_t deposits = 0;             // hits stored in an illumination map
    double light_seconds = 0;               // wall time of the light pass
    double seconds = 0;                     // wall time of the render (light + eye pass)

    void merge(const RenderStats& o);
    std::string summary() const;       // multi-line text for --stats
    // One line when the dropped weight exceeds `fraction` of the primary rays' (naming the
    // setting that dropped most), else empty.
    std::string lost_warning(double fraction = 0.01) const;
};

struct IlluminationMaps;

struct RenderOptions {
    int threads = 0;        // 0: all cores
    bool progress = false;  // progress bar on stderr (callers pass isatty(2))
    // Illumination maps of an earlier light pass of the same scene (render.light_pass):
    // used instead of running the light pass again.
    std::shared_ptr<const IlluminationMaps> maps;
    // Spectral eye pass, physical mode, natural light: also the light of every wavelength
    // per pixel (RenderResult::spectral; core/integrators/spectral.h spectral_radiance).
    bool spectral_channels = false;
    // Also the per-pixel weight the limits and the threshold dropped (RenderResult::lost).
    bool lost_energy = false;
    // Memory budget in bytes (0: default_memory_budget(), core/memory.h): the render's
    // estimate is checked against it before anything large is allocated.
    std::uint64_t max_memory = 0;
    // Cancellation (the Python module's Ctrl-C): when set and it becomes true, the eye
    // pass stops at the next tile and render() throws RenderCancelled.
    const std::atomic<bool>* cancel = nullptr;
};

// Thrown by render() when RenderOptions::cancel became true.
struct RenderCancelled : std::runtime_error {
    RenderCancelled() : std::runtime_error("render cancelled") {}
};

// Exact polarisation's images (render.polarisation "exact"): per pixel the Stokes vectors
// S0..S3 of the R, G and B channels (12 values: S0.R, S0.G, S0.B, S1.R, ..., S3.B; S0 is
// the image), and the degree and angle (radians, on the image from its right towards its
// top) of linear polarisation of the channels' sum.
struct PolarisationImages {
    std::vector<double> stokes;
    std::vector<double> dolp, aolp;
};

struct RenderResult {
    Image image;
    RenderStats stats;
    // With RenderOptions::lost_energy: per pixel the weight dropped by the depth limit, the
    // reflection/transmission limits and the threshold (RenderStats::lost_*), per primary
    // sample: 3 values per pixel.
    std::vector<double> lost;
    // With RenderOptions::spectral_channels: per pixel the light at each of `wavelengths`
    // (nm), the samples averaged; wavelengths.size() values per pixel.
    std::vector<double> wavelengths, spectral;
    std::optional<PolarisationImages> polarisation;
};

// Validates the scene (throws InputError) and renders it.
RenderResult render(const Scene& scene, const RenderOptions& opt = {});

// Radiance along the primary ray(s) of pixel (i, j) alone, with the scene's settings.
Vec3 render_pixel(const Scene& scene, int i, int j, RenderStats* stats = nullptr);
// The same as Stokes vectors per colour channel (exact polarisation; natural light: S0 only).
StokesRGB render_pixel_stokes(const Scene& scene, int i, int j, RenderStats* stats = nullptr);

}  // namespace refract
