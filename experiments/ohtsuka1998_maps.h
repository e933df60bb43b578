#pragma once
// The ohtsuka1998 experiment's illumination-map studies: how the caustic on the floor
// converges with the photon count and the element size, for the box and the bilinear
// reconstruction (core/illumination_map.h).
//
// Error measure. The floor map's irradiance (RGB) is reconstructed at the points of a
// fixed grid (2×2 per reference element, over the whole map square) and compared with a
// reference map: ε = √(Σ|E − E_ref|²) / √(Σ|E_ref|²), Σ over the points and channels.
// Every configuration is run with two photon seeds A and B, which separates
//   noise  σ² = Σ|A − B|² / 2 / Σ|E_ref|²                  (one run's)
//   bias   β² = Σ|(A + B)/2 − E_ref|² / Σ|E_ref|² − σ²/2 − σ_ref²
// where σ_ref is the reference's own noise: the reference is the mean of two light
// passes R1, R2 with other seeds (R1 may be the main image's), σ_ref² = Σ|R1 − R2|² / 4 /
// Σ|E_ref|². β is the bias against the reference's own (the reference's elements are half
// the finest studied, read bilinearly); `error` is run A's ε, which contains σ_ref.
#include <cstdint>
#include <memory>
#include <vector>

#include <refract/core/illumination_map.h>
#include <refract/core/scene.h>
#include <refract/experiments/ohtsuka1998.h>

namespace refract::experiments::ohtsuka1998 {

struct MapError {
    double error = 0, noise = 0, bias = 0;  // relative RMS (see above)
};

struct MapStudyRow {
    double element_size = 0;
    std::uint64_t photons = 0;
    MapFilter filter = MapFilter::Bilinear;
    int elements = 0;                  // in the floor map
    double deposits_per_element = 0;   // run A's deposits over the elements that received any
    MapError e;
    double light_s = 0;                // light-pass wall time of run A
};

struct MapStudyPlan {
    double reference_element = 0.0125;
    std::uint64_t reference_photons = 1000000;  // per half
    std::uint64_t reference_seeds[2] = {7, 8};
    std::uint64_t seeds[2] = {11, 12};          // runs A and B of every configuration
    // Photon-count study: element `photon_element`, these photon counts.
    double photon_element = 0.025;
    std::vector<std::uint64_t> photons{7500, 30000, 120000};
    // Element-size study at a fixed photon density: `density_photons` photons on elements
    // of `density_element`, scaled by (density_element / h)² for element h.
    std::vector<double> elements{0.2, 0.1, 0.05, 0.025};
    double density_element = 0.025;
    std::uint64_t density_photons = 120000;
};

struct MapStudies {
    double reference_element = 0;
    std::uint64_t reference_photons = 0;
    double reference_noise = 0;    // σ_ref
    double reference_light_s = 0;  // both halves
    std::vector<MapStudyRow> by_photons;  // box and bilinear per photon count
    std::vector<MapStudyRow> by_element;  // box and bilinear per element size
    std::uint64_t photons_traced = 0;     // every light pass of the studies
    double seconds = 0;                   // the studies' wall time
};

// Runs the studies on the experiment's scene `base` (its light pass's element size,
// photons and seed replaced per run; the image size does not matter). `known`: the maps
// of `base`'s own light pass when already run (reused where the plan asks for them).
MapStudies run_map_studies(const SceneParams& base, const MapStudyPlan& plan, int threads,
                           std::shared_ptr<const IlluminationMaps> known = nullptr);

}  // namespace refract::experiments::ohtsuka1998
