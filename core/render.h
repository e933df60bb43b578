#pragma once
// Rendering a scene: tiles over oneTBB, deterministic whatever the thread count.
#include <cstdint>
#include <string>

#include "core/image.h"
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
    std::uint64_t peak_list = 0;       // fresnel-tree: longest FIFO list; whitted: largest stored tree
    double seconds = 0;                // wall time of the render

    void merge(const RenderStats& o);
    std::string summary() const;       // multi-line text for --stats
};

struct RenderOptions {
    int threads = 0;        // 0: all cores
    bool progress = false;  // progress bar on stderr (callers pass isatty(2))
};

struct RenderResult {
    Image image;
    RenderStats stats;
};

// Validates the scene (throws InputError) and renders it.
RenderResult render(const Scene& scene, const RenderOptions& opt = {});

// Radiance along the primary ray(s) of pixel (i, j) alone, with the scene's settings.
Vec3 render_pixel(const Scene& scene, int i, int j, RenderStats* stats = nullptr);

}  // namespace refract
