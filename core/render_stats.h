#pragma once
// The counters of one render (RenderStats): what core/render.h's render() returns beside
// the image, summed over pixels.
#include <cstdint>
#include <string>
#include <tuple>

#include <refract/core/fields.h>

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
    double lost_limits = 0;      // the spectral pass's max_reflections / max_transmissions, a
                                 // gradient-index medium's step budget
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
    // Curved segments through gradient-index media (core/grin/): their index-and-gradient
    // evaluations, and those that ran out of steps (their light counted in lost_limits).
    std::uint64_t grin_segments = 0, grin_evaluations = 0, grin_exhausted = 0;
    // Light pass (core/light_pass.h).
    std::uint64_t photons = 0;              // photons shot
    std::uint64_t photon_segments = 0;      // their ray segments
    std::uint64_t deposits = 0;             // hits stored in an illumination map
    double light_seconds = 0;               // wall time of the light pass
    double seconds = 0;                     // wall time of the render (light + eye pass)

    void merge(const RenderStats& o);  // by the field list's rules below
    std::string summary() const;       // multi-line text for --stats, from the field list's labels
    // One line when the dropped weight exceeds `fraction` of the primary rays' (naming the
    // setting that dropped most), else empty.
    std::string lost_warning(double fraction = 0.01) const;
};

// The counters, once: the Python module's `stats` dict (python/src/module.cpp), `merge`
// (sums, except the longest list, which is a maximum, and the wall time, which the caller
// measures) and the lines of `summary` (a label; some only when not 0).
template <>
struct Fields<RenderStats> {
    static auto list() {
        using S = RenderStats;
        return std::make_tuple(
            field("primary_rays", &S::primary_rays).text("primary rays"),
            field("segments", &S::segments).text("ray segments"),
            field("shadow_rays", &S::shadow_rays).text("shadow rays"),
            field("tree_nodes", &S::tree_nodes).text("tree nodes"),
            field("pruned", &S::pruned).text("pruned branches"),
            field("depth_limited", &S::depth_limited).text("depth-limited"),
            field("lost_depth", &S::lost_depth).text("lost, depth"),
            field("lost_limits", &S::lost_limits).text("lost, limits"),
            field("lost_threshold", &S::lost_threshold).text("lost, threshold"),
            field("peak_list", &S::peak_list).merge(MergeRule::Max).text("peak list / tree"),
            field("spectral_splits", &S::spectral_splits).text("spectral splits", true),
            field("shortcut_tests", &S::shortcut_tests).text("shortcut tests", true),
            field("shortcut_taken", &S::shortcut_taken).text("shortcut taken", true),
            field("wavelength_segments", &S::wavelength_segments).text("wavelength segs", true),
            field("facet_local", &S::facet_local).text("facet segs, local", true),
            field("facet_full", &S::facet_full).text("facet segs, full", true),
            field("grin_segments", &S::grin_segments).text("GRIN segments", true),
            field("grin_evaluations", &S::grin_evaluations).text("GRIN evaluations", true),
            field("grin_exhausted", &S::grin_exhausted).text("GRIN budget runs", true),
            field("photons", &S::photons).text("photons", true),
            field("photon_segments", &S::photon_segments).text("photon segments", true),
            field("deposits", &S::deposits).text("map deposits", true),
            field("light_seconds", &S::light_seconds).text("light pass (s)", true),
            field("seconds", &S::seconds).merge(MergeRule::None).text("wall time (s)"));
    }
};

}  // namespace refract
