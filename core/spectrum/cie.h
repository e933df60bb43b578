#pragma once
// CIE 1931 colorimetry: colour-matching functions, the two spectrum → RGB pipelines
// (Ohtsuka & Kawai 1998's CIE RGB, and modern CIE XYZ → linear sRGB), CIE Lab and
// CIEDE2000. See docs/spectra.md for the normalisation.
#include <string>
#include <vector>

#include <Eigen/Core>

#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/ray.h>

namespace refract::spectrum {

// CIE 1931 2° standard observer x̄, ȳ, z̄ (CIE 15:2004, 5 nm table 360–830 nm),
// linearly interpolated; 0 outside the table.
Vec3 cie_xyz_cmf(double lambda_nm);

// CIE 1931 RGB colour-matching functions r̄, ḡ, b̄ (Wright–Guild primaries 700 / 546.1 /
// 435.8 nm, with negative lobes): r̄ḡb̄ = xyz_to_cie_rgb() · x̄ȳz̄.
Vec3 cie_rgb_cmf(double lambda_nm);

// CIE 1931: XYZ = (1/0.17697) [[0.49, 0.31, 0.20], [0.17697, 0.81240, 0.01063],
// [0, 0.01, 0.99]] · RGB. Every row sums to 1 (times 1/0.17697), so equal-energy white
// has R = G = B and X = Y = Z.
const Eigen::Matrix3d& cie_rgb_to_xyz();
const Eigen::Matrix3d& xyz_to_cie_rgb();  // its inverse
// IEC 61966-2-1 (sRGB, D65), the 4-digit matrix; and its inverse.
const Eigen::Matrix3d& xyz_to_linear_srgb();
const Eigen::Matrix3d& linear_srgb_to_xyz();

// Peak wavelengths (nm) of r̄, ḡ, b̄ measured on the table: the largest 5 nm node refined
// by the vertex of the parabola through it and its two neighbours.
struct RGBPeaks {
    double r, g, b;
};
RGBPeaks cie_rgb_peaks();

// ---------------------------------------------------------------------------------------
// Spectrum → RGB.

enum class ColourPipeline {
    CieRgb,   // "cie-rgb": Σ radiance·(r̄, ḡ, b̄); negative final values clipped to 0 (1998 paper)
    XyzSrgb,  // "xyz-srgb": Σ radiance·(x̄, ȳ, z̄), then XYZ → linear sRGB; not clipped
};
std::string to_string(ColourPipeline p);
// "cie-rgb" or "xyz-srgb"; InputError naming `path` otherwise.
ColourPipeline parse_colour_pipeline(const std::string& s, const std::string& path);

enum class WhiteBalance {
    PerChannel,  // each channel divided by the white's: the white maps to exactly (1, 1, 1)
    Luminance,   // one factor: the white has luminance 1; it maps to (1, 1, 1) only as far
                 // as its chromaticity is the pipeline's white (E for cie-rgb, D65 for sRGB)
};

// Per-wavelength RGB weights for a fixed wavelength set, so that a renderer computes a
// colour as Σ_i v_i · weight(i). v_i is the radiance at λ_i *relative to the white
// spectrum* S (a spectral throughput: 1 = the illuminant unattenuated). The raw weight is
//   T · x̄ȳz̄(λ_i) · S(λ_i) · Δλ_i   (T = xyz_to_cie_rgb or xyz_to_linear_srgb,
//                                     Δλ_i from band_widths: the midpoint rule)
// scaled by the white balance, so v_i = 1 for all i gives (1, 1, 1) (PerChannel).
// Default white: equal energy for cie-rgb (CIE RGB's own white), D65 for xyz-srgb.
class SpectrumToRGB {
public:
    explicit SpectrumToRGB(std::vector<double> wavelengths_nm,
                           ColourPipeline pipeline = ColourPipeline::CieRgb,
                           WhiteBalance balance = WhiteBalance::PerChannel);
    SpectrumToRGB(std::vector<double> wavelengths_nm, ColourPipeline pipeline,
                  WhiteBalance balance, const LightSpectrum& white);

    ColourPipeline pipeline() const { return pipeline_; }
    WhiteBalance balance() const { return balance_; }
    const LightSpectrum& white() const { return white_; }
    size_t size() const { return wavelengths_.size(); }
    const std::vector<double>& wavelengths() const { return wavelengths_; }
    // rgb_weight(λ_i), already normalised.
    const std::vector<Vec3>& weights() const { return weights_; }
    const Vec3& weight(size_t i) const { return weights_[i]; }

    // Σ v_i · weight(i) (v has size() entries), no clipping: sum per-ray contributions
    // with this, and call finish() once on the final pixel value.
    Vec3 accumulate(const double* v) const;
    Vec3 accumulate(const std::vector<double>& v) const { return accumulate(v.data()); }
    // cie-rgb: negative components clipped to 0 (the paper, at the end); xyz-srgb: as is.
    Vec3 finish(const Vec3& rgb) const;
    // finish(accumulate(v)).
    Vec3 to_rgb(const std::vector<double>& v) const { return finish(accumulate(v)); }

private:
    std::vector<double> wavelengths_;
    ColourPipeline pipeline_;
    WhiteBalance balance_;
    LightSpectrum white_;
    std::vector<Vec3> weights_;
};

// ---------------------------------------------------------------------------------------
// CIE Lab and CIEDE2000.

// CIE 1976 L*a*b* of XYZ against the white `white_xyz` (CIE 15:2004 eq. 8.1–8.3).
Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white_xyz);
// Linear sRGB → XYZ (linear_srgb_to_xyz) → Lab with the D65 white linear_srgb_to_xyz·(1,1,1),
// so (1, 1, 1) is L* = 100, a* = b* = 0.
Vec3 linear_srgb_to_lab(const Vec3& rgb);
// CIEDE2000 colour difference ΔE00 of two Lab colours, k_L = k_C = k_H = 1
// (Sharma, Wu & Dalal 2005, eq. 1–22).
double ciede2000(const Vec3& lab1, const Vec3& lab2);
// ΔE00 of two linear-sRGB colours: ciede2000(linear_srgb_to_lab(a), linear_srgb_to_lab(b)).
double delta_e2000(const Vec3& linear_srgb1, const Vec3& linear_srgb2);

}  // namespace refract::spectrum
