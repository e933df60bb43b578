#pragma once
// Rendering a scene: tiles over oneTBB, deterministic whatever the thread count.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <refract/core/image.h>
#include <refract/core/polarisation_state.h>
#include <refract/core/trace_options.h>
#include <refract/core/render_stats.h>
#include <refract/core/scene.h>

namespace refract {

struct IlluminationMaps;

struct RenderOptions {
    int threads = 0;        // 0: all cores
    // How rays are searched and walked (facet-local intersection, packets): the same images
    // either way, to the last bit (core/hit_search.h).
    TraceOptions trace;
    bool progress = false;  // progress bar on stderr (callers pass isatty(2))
    // Illumination maps of an earlier light pass of the same scene (render.light_pass):
    // used instead of running the light pass again.
    std::shared_ptr<const IlluminationMaps> maps;
    // Spectral eye pass, physical mode, natural light: also the light of every wavelength
    // per pixel (RenderResult::spectral; core/integrators/spectral.h spectral_radiance). A
    // scene that does not set render.polarisation is then rendered with natural light.
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
    // The colours (the image, Stokes S0) may be negative: a spectral render's xyz-srgb
    // pipeline keeps colours out of the sRGB gamut (docs/spectra.md). Its writers allow them.
    bool signed_colours = false;
};

// Validates the scene (throws InputError) and renders it.
RenderResult render(const Scene& scene, const RenderOptions& opt = {});

// Radiance along the primary ray(s) of pixel (i, j) alone, with the scene's settings.
Vec3 render_pixel(const Scene& scene, int i, int j, RenderStats* stats = nullptr);
// The same as Stokes vectors per colour channel (exact polarisation; natural light: S0 only).
StokesRGB render_pixel_stokes(const Scene& scene, int i, int j, RenderStats* stats = nullptr);

}  // namespace refract
