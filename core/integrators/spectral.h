#pragma once
// Spectral eye pass (Ohtsuka & Kawai 1998, §3.2–3.3). A ray is one RGB ray until its
// first hit on a dispersive dielectric; there it splits into one ray per sampled
// wavelength, each refracted with that wavelength's index, and every wavelength is then
// traced alone (the Fresnel-tree walk of Yasuda 1984 with the branch's own index), with
// the cumulative-attenuation threshold, max_depth and, when the scene sets them, the
// paper's separate limits on reflections and transmissions per path. Wavelength i's RGB result is weighted by
// the colour converter's weight(i) (core/spectrum/cie.h, white balanced so the weights
// sum to (1, 1, 1)) and summed; the pixel is finished (clipped for cie-rgb) at the end.
//
// The shortcut (§3.3): first only three wavelengths (610/545/445 nm); when their
// contributions lie within `shortcut_threshold` of each other in RGB, their mean stands
// for the split and the full split is skipped.
//
// POV-Ray compat mode (the policy's rules, core/compat/):
// the split happens at the first refraction only, into POV-Ray's own bands per material. A
// band ray keeps its wavelength: at another dispersive material it refracts with that
// material's index at the band's wavelength, without splitting again.
#include <memory>
#include <vector>

#include <refract/core/ray_tree.h>

namespace refract {

struct IlluminationMaps;

struct SpectralContext {
    // The bands, one flat list. Physical mode: the sampled wavelengths. POV-Ray mode: the
    // band sets of every distinct `samples` among the dispersive materials, one after
    // another (a set's weights sum to POV-Ray's mean hue, about (1, 1, 1)).
    std::vector<double> wavelengths;        // nm, per band
    std::vector<Vec3> weights;              // RGB weight of each band in its split
    std::vector<double> all_wavelengths;    // nm, per band of `index` (the bands, then the shortcut's)
    // index[b][material]: the material's index at band b's wavelength (0: not dispersive,
    // use `ior`); bands 0..n−1 are `wavelengths`, n..n+2 the shortcut wavelengths.
    std::vector<std::vector<double>> index;
    std::vector<char> dispersive;           // per material: splits an RGB ray
    // split_bands[material]: the bands an RGB ray splits into there. Physical mode: 0..n−1
    // for every material; POV-Ray mode: the material's own band set (empty when it does
    // not split).
    std::vector<std::vector<int>> split_bands;
    // Where an RGB ray splits (the policy's, CompatRules::spectral_bands): its whole subtree
    // below the first dispersive hit, every branch walked per band (physical); or only its
    // refracted ray, the reflection staying RGB (POV-Ray, core/compat/refraction_split.h).
    enum class Split { Subtree, Refraction };
    Split split = Split::Subtree;
    bool clip = true;                       // cie-rgb: clip negatives at the end
    bool shortcut = false;
    double shortcut_threshold = 0.01;
    static constexpr int kUnlimited = TreeLimits::kUnlimited;
    int max_reflections = kUnlimited, max_transmissions = kUnlimited;  // unset: no limit
    const IlluminationMaps* maps = nullptr; // light pass result, read at diffuse hits

    size_t bands() const { return wavelengths.size(); }  // n
    Vec3 finish(const Vec3& rgb) const;
    // The walker's limits: the render's, with the separate reflection/transmission limits.
    TreeLimits limits(const RenderSettings& s) const;

    // Throws InputError when the spectral settings are invalid.
    static SpectralContext build(const Scene& scene);
};

// Radiance (RGB, not yet finished) along a primary ray. `band_light` (size bands(), when
// given): adds each wavelength's light, the mean of its channels before the band's RGB
// weight: a band walk's light to its band, light that never split (an RGB ray's) to every
// band, a taken shortcut's mean to every band. Exact for colour-neutral scenes, whose
// channels are equal at every wavelength; physical mode only.
Vec3 spectral_radiance(const SceneTracer& tracer, const SpectralContext& ctx, const Ray& primary,
                       RenderStats& stats, std::vector<double>* band_light = nullptr);
// The same with exact polarisation: Stokes vectors per colour channel (not yet finished).
StokesRGB spectral_stokes(const SceneTracer& tracer, const SpectralContext& ctx, const Ray& primary,
                          const EyeStokes& start, RenderStats& stats);

}  // namespace refract
