#pragma once
// The chromaticities of a rendered RGB image (OpenEXR's `chromaticities` attribute): the
// CIE 1931 xy of its red, green and blue primaries and of its white, RGB = (1, 1, 1).
#include <array>
#include <vector>

#include <refract/core/spectrum/cie.h>

namespace refract::spectrum {

// {red x, red y, green x, green y, blue x, blue y, white x, white y}. The primaries are
// the columns of the pipeline's RGB → XYZ matrix (cie-rgb: CIE 1931 RGB, Wright–Guild;
// xyz-srgb: IEC 61966-2-1); per-channel white balance scales the channels, which moves
// the white, not the primaries: the white is the xy of Σ x̄ȳz̄(λ_i)·S(λ_i)·Δλ_i over the
// render's wavelengths, the colour SpectrumToRGB maps to (1, 1, 1).
using Chromaticities = std::array<double, 8>;
Chromaticities chromaticities(ColourPipeline pipeline, const std::vector<double>& wavelengths_nm,
                              const LightSpectrum& white);

}  // namespace refract::spectrum
