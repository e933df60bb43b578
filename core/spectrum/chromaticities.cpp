#include <refract/core/spectrum/chromaticities.h>

namespace refract::spectrum {
namespace {

void put_xy(const Vec3& xyz, double* out) {
    const double s = xyz.sum();
    out[0] = xyz.x() / s;
    out[1] = xyz.y() / s;
}

}  // namespace

Chromaticities chromaticities(ColourPipeline pipeline, const std::vector<double>& wavelengths_nm,
                              const LightSpectrum& white) {
    const Eigen::Matrix3d& M = pipeline == ColourPipeline::CieRgb ? cie_rgb_to_xyz() : linear_srgb_to_xyz();
    Chromaticities c{};
    for (int k = 0; k < 3; ++k) put_xy(M.col(k), &c[static_cast<size_t>(2 * k)]);
    const std::vector<double> dl = band_widths(wavelengths_nm);
    Vec3 w = Vec3::Zero();
    for (size_t i = 0; i < wavelengths_nm.size(); ++i)
        w += cie_xyz_cmf(wavelengths_nm[i]) * (white(wavelengths_nm[i]) * dl[i]);
    put_xy(w, &c[6]);
    return c;
}

}  // namespace refract::spectrum
