// CIE 1931 colorimetry (see cie.h, docs/spectra.md).
#include <refract/core/spectrum/cie.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <Eigen/LU>

#include <refract/geometry/error.h>

namespace refract::spectrum {

namespace {

// CIE 1931 2° standard colorimetric observer x̄(λ), ȳ(λ), z̄(λ), 360–830 nm every 5 nm.
// Source: CIE 15:2004 "Colorimetry", table T.4, as distributed in colord's data files
// (cmf/CIE1931-2deg-XYZ.cmf, colord-data 1.4.6); float-printing artefacts of that file
// below 700 nm (e.g. 0.05795001) are restored to the CIE's six-digit values (0.057950).
constexpr double kCmfStart = 360.0;
constexpr double kCmfStep = 5.0;
constexpr std::array<std::array<double, 3>, 95> kCmf = {{
    {0.0001299, 0.000003917, 0.0006061},  // 360
    {0.0002321, 0.000006965, 0.001086},  // 365
    {0.0004149, 0.00001239, 0.001946},  // 370
    {0.0007416, 0.00002202, 0.003486},  // 375
    {0.001368, 0.000039, 0.00645},  // 380
    {0.002236, 0.000064, 0.01055},  // 385
    {0.004243, 0.00012, 0.02005},  // 390
    {0.00765, 0.000217, 0.03621},  // 395
    {0.01431, 0.000396, 0.06785},  // 400
    {0.02319, 0.00064, 0.1102},  // 405
    {0.04351, 0.00121, 0.2074},  // 410
    {0.07763, 0.00218, 0.3713},  // 415
    {0.13438, 0.004, 0.6456},  // 420
    {0.21477, 0.0073, 1.03905},  // 425
    {0.2839, 0.0116, 1.3856},  // 430
    {0.3285, 0.01684, 1.62296},  // 435
    {0.34828, 0.023, 1.74706},  // 440
    {0.34806, 0.0298, 1.7826},  // 445
    {0.3362, 0.038, 1.77211},  // 450
    {0.3187, 0.048, 1.7441},  // 455
    {0.2908, 0.06, 1.6692},  // 460
    {0.2511, 0.0739, 1.5281},  // 465
    {0.19536, 0.09098, 1.28764},  // 470
    {0.1421, 0.1126, 1.0419},  // 475
    {0.09564, 0.13902, 0.81295},  // 480
    {0.05795, 0.1693, 0.6162},  // 485
    {0.03201, 0.20802, 0.46518},  // 490
    {0.0147, 0.2586, 0.3533},  // 495
    {0.0049, 0.323, 0.272},  // 500
    {0.0024, 0.4073, 0.2123},  // 505
    {0.0093, 0.503, 0.1582},  // 510
    {0.0291, 0.6082, 0.1117},  // 515
    {0.06327, 0.71, 0.07825},  // 520
    {0.1096, 0.7932, 0.05725},  // 525
    {0.1655, 0.862, 0.04216},  // 530
    {0.22575, 0.91485, 0.02984},  // 535
    {0.2904, 0.954, 0.0203},  // 540
    {0.3597, 0.9803, 0.0134},  // 545
    {0.43345, 0.99495, 0.00875},  // 550
    {0.51205, 1.0, 0.00575},  // 555
    {0.5945, 0.995, 0.0039},  // 560
    {0.6784, 0.9786, 0.00275},  // 565
    {0.7621, 0.952, 0.0021},  // 570
    {0.8425, 0.9154, 0.0018},  // 575
    {0.9163, 0.87, 0.00165},  // 580
    {0.9786, 0.8163, 0.0014},  // 585
    {1.0263, 0.757, 0.0011},  // 590
    {1.0567, 0.6949, 0.001},  // 595
    {1.0622, 0.631, 0.0008},  // 600
    {1.0456, 0.5668, 0.0006},  // 605
    {1.0026, 0.503, 0.00034},  // 610
    {0.9384, 0.4412, 0.00024},  // 615
    {0.85445, 0.381, 0.00019},  // 620
    {0.7514, 0.321, 0.0001},  // 625
    {0.6424, 0.265, 0.00005},  // 630
    {0.5419, 0.217, 0.00003},  // 635
    {0.4479, 0.175, 0.00002},  // 640
    {0.3608, 0.1382, 0.00001},  // 645
    {0.2835, 0.107, 0.0},  // 650
    {0.2187, 0.0816, 0.0},  // 655
    {0.1649, 0.061, 0.0},  // 660
    {0.1212, 0.04458, 0.0},  // 665
    {0.0874, 0.032, 0.0},  // 670
    {0.0636, 0.0232, 0.0},  // 675
    {0.04677, 0.017, 0.0},  // 680
    {0.0329, 0.01192, 0.0},  // 685
    {0.0227, 0.00821, 0.0},  // 690
    {0.01584, 0.005723, 0.0},  // 695
    {0.01135916, 0.004102, 0.0},  // 700
    {0.008110916, 0.002929, 0.0},  // 705
    {0.005790346, 0.002091, 0.0},  // 710
    {0.004109457, 0.001484, 0.0},  // 715
    {0.002899327, 0.001047, 0.0},  // 720
    {0.00204919, 0.00074, 0.0},  // 725
    {0.001439971, 0.00052, 0.0},  // 730
    {0.0009999493, 0.0003611, 0.0},  // 735
    {0.0006900786, 0.0002492, 0.0},  // 740
    {0.0004760213, 0.0001719, 0.0},  // 745
    {0.0003323011, 0.00012, 0.0},  // 750
    {0.0002348261, 0.0000848, 0.0},  // 755
    {0.0001661505, 0.00006, 0.0},  // 760
    {0.000117413, 0.0000424, 0.0},  // 765
    {0.00008307527, 0.00003, 0.0},  // 770
    {0.00005870652, 0.0000212, 0.0},  // 775
    {0.00004150994, 0.00001499, 0.0},  // 780
    {0.00002935326, 0.0000106, 0.0},  // 785
    {0.00002067383, 0.0000074657, 0.0},  // 790
    {0.00001455977, 0.0000052578, 0.0},  // 795
    {0.00001025398, 0.0000037029, 0.0},  // 800
    {0.000007221456, 0.0000026078, 0.0},  // 805
    {0.000005085868, 0.0000018366, 0.0},  // 810
    {0.000003581652, 0.0000012934, 0.0},  // 815
    {0.000002522525, 0.00000091093, 0.0},  // 820
    {0.000001776509, 0.00000064153, 0.0},  // 825
    {0.000001251141, 0.00000045181, 0.0},  // 830
}};

Eigen::Matrix3d make_cie_rgb_to_xyz() {
    Eigen::Matrix3d m;
    m << 0.49, 0.31, 0.20,
         0.17697, 0.81240, 0.01063,
         0.0, 0.01, 0.99;
    return m / 0.17697;
}

Eigen::Matrix3d make_xyz_to_srgb() {
    Eigen::Matrix3d m;
    m << 3.2406, -1.5372, -0.4986,
         -0.9689, 1.8758, 0.0415,
         0.0557, -0.2040, 1.0570;
    return m;
}

// Vertex of the parabola through (−1, a), (0, b), (1, c): offset in steps from the middle.
double parabola_vertex(double a, double b, double c) {
    const double den = a - 2.0 * b + c;
    return den == 0.0 ? 0.0 : 0.5 * (a - c) / den;
}

double peak_of(int channel) {
    // r̄ḡb̄ at the table nodes.
    std::array<double, kCmf.size()> f{};
    for (size_t i = 0; i < kCmf.size(); ++i)
        f[i] = cie_rgb_cmf(kCmfStart + kCmfStep * static_cast<double>(i))[channel];
    const size_t k = static_cast<size_t>(std::max_element(f.begin(), f.end()) - f.begin());
    const double l = kCmfStart + kCmfStep * static_cast<double>(k);
    if (k == 0 || k + 1 == f.size()) return l;
    return l + kCmfStep * parabola_vertex(f[k - 1], f[k], f[k + 1]);
}

}  // namespace

Vec3 cie_xyz_cmf(double lambda_nm) {
    const double x = (lambda_nm - kCmfStart) / kCmfStep;
    if (!(x >= 0.0) || x > static_cast<double>(kCmf.size() - 1)) return Vec3::Zero();
    const size_t i = std::min(static_cast<size_t>(x), kCmf.size() - 2);
    const double t = x - static_cast<double>(i);
    const auto& a = kCmf[i];
    const auto& b = kCmf[i + 1];
    return {(1.0 - t) * a[0] + t * b[0], (1.0 - t) * a[1] + t * b[1], (1.0 - t) * a[2] + t * b[2]};
}

Vec3 cie_rgb_cmf(double lambda_nm) { return xyz_to_cie_rgb() * cie_xyz_cmf(lambda_nm); }

const Eigen::Matrix3d& cie_rgb_to_xyz() {
    static const Eigen::Matrix3d m = make_cie_rgb_to_xyz();
    return m;
}
const Eigen::Matrix3d& xyz_to_cie_rgb() {
    static const Eigen::Matrix3d m = make_cie_rgb_to_xyz().inverse();
    return m;
}
const Eigen::Matrix3d& xyz_to_linear_srgb() {
    static const Eigen::Matrix3d m = make_xyz_to_srgb();
    return m;
}
const Eigen::Matrix3d& linear_srgb_to_xyz() {
    static const Eigen::Matrix3d m = make_xyz_to_srgb().inverse();
    return m;
}

RGBPeaks cie_rgb_peaks() { return {peak_of(0), peak_of(1), peak_of(2)}; }

// ---------------------------------------------------------------------------------------

std::string to_string(ColourPipeline p) {
    return p == ColourPipeline::CieRgb ? "cie-rgb" : "xyz-srgb";
}

ColourPipeline parse_colour_pipeline(const std::string& s, const std::string& path) {
    if (s == "cie-rgb") return ColourPipeline::CieRgb;
    if (s == "xyz-srgb") return ColourPipeline::XyzSrgb;
    throw InputError(path + ": unknown colour pipeline \"" + clip_echo(s) +
                     "\"; allowed: \"cie-rgb\", \"xyz-srgb\"");
}

SpectrumToRGB::SpectrumToRGB(std::vector<double> wl, ColourPipeline p, WhiteBalance b)
    : SpectrumToRGB(std::move(wl), p, b,
                    p == ColourPipeline::CieRgb ? LightSpectrum{}
                                                : LightSpectrum{Illuminant::D65, 6504.0}) {}

SpectrumToRGB::SpectrumToRGB(std::vector<double> wl, ColourPipeline p, WhiteBalance b,
                             const LightSpectrum& white)
    : wavelengths_(std::move(wl)), pipeline_(p), balance_(b), white_(white) {
    const std::vector<double> dl = band_widths(wavelengths_);  // validates the set
    for (double l : wavelengths_)
        if (!(l >= kMinWavelength && l <= kMaxWavelength))
            throw InputError("wavelengths: " + std::to_string(l) + " nm is outside [360, 830] nm");
    const Eigen::Matrix3d& T =
        p == ColourPipeline::CieRgb ? xyz_to_cie_rgb() : xyz_to_linear_srgb();
    weights_.resize(wavelengths_.size());
    Vec3 sum = Vec3::Zero();
    double Y = 0.0;
    for (size_t i = 0; i < wavelengths_.size(); ++i) {
        const Vec3 xyz = cie_xyz_cmf(wavelengths_[i]) * (white_(wavelengths_[i]) * dl[i]);
        weights_[i] = T * xyz;
        sum += weights_[i];
        Y += xyz.y();
    }
    Vec3 scale;
    if (b == WhiteBalance::PerChannel) {
        for (int c = 0; c < 3; ++c)
            if (!(sum[c] > 1e-12 * std::abs(Y)) || !(Y > 0.0))
                throw InputError("wavelengths: this set gives the white no positive response in "
                                 "channel " + std::string(1, "RGB"[c]) +
                                 "; use a wider set or luminance white balance");
        scale = sum.cwiseInverse();
    } else {
        if (!(Y > 0.0))
            throw InputError("wavelengths: this set gives the white zero luminance");
        // The pipeline's white of luminance Y is R = G = B = k·Y, k = 0.17697 for CIE RGB
        // (the rows of cie_rgb_to_xyz sum to 1/0.17697), 1 for sRGB (D65).
        const double k = p == ColourPipeline::CieRgb ? 0.17697 : 1.0;
        scale = Vec3::Constant(1.0 / (k * Y));
    }
    for (auto& w : weights_) w = w.cwiseProduct(scale);
}

Vec3 SpectrumToRGB::accumulate(const double* v) const {
    Vec3 s = Vec3::Zero();
    for (size_t i = 0; i < weights_.size(); ++i) s += v[i] * weights_[i];
    return s;
}

Vec3 SpectrumToRGB::finish(const Vec3& rgb) const {
    return pipeline_ == ColourPipeline::CieRgb ? Vec3(rgb.cwiseMax(0.0)) : rgb;
}

// ---------------------------------------------------------------------------------------

Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white) {
    // CIE 15:2004 eq. 8.1–8.3, with the linear segment below (6/29)³.
    constexpr double d = 6.0 / 29.0;
    const auto f = [&](double t) {
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(xyz.x() / white.x());
    const double fy = f(xyz.y() / white.y());
    const double fz = f(xyz.z() / white.z());
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Vec3 linear_srgb_to_lab(const Vec3& rgb) {
    static const Vec3 white = linear_srgb_to_xyz() * Vec3::Ones();
    return xyz_to_lab(linear_srgb_to_xyz() * rgb, white);
}

double ciede2000(const Vec3& lab1, const Vec3& lab2) {
    // Sharma, Wu & Dalal, "The CIEDE2000 color-difference formula: implementation notes,
    // supplementary test data, and mathematical observations", Color Res. Appl. 30 (2005).
    constexpr double pi = 3.14159265358979323846;
    constexpr double deg = pi / 180.0;
    constexpr double p25_7 = 6103515625.0;  // 25^7
    const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2];
    const double L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
    // eq. 2–7
    const double Cab = 0.5 * (std::hypot(a1, b1) + std::hypot(a2, b2));
    const double Cab7 = std::pow(Cab, 7);
    const double G = 0.5 * (1.0 - std::sqrt(Cab7 / (Cab7 + p25_7)));
    const double ap1 = (1.0 + G) * a1, ap2 = (1.0 + G) * a2;
    const double Cp1 = std::hypot(ap1, b1), Cp2 = std::hypot(ap2, b2);
    const auto hue = [&](double b, double ap) {
        if (b == 0.0 && ap == 0.0) return 0.0;
        double h = std::atan2(b, ap) / deg;
        return h < 0.0 ? h + 360.0 : h;
    };
    const double hp1 = hue(b1, ap1), hp2 = hue(b2, ap2);
    // eq. 8–11
    const double dLp = L2 - L1;
    const double dCp = Cp2 - Cp1;
    double dhp = 0.0;
    if (Cp1 * Cp2 != 0.0) {
        dhp = hp2 - hp1;
        if (dhp > 180.0) dhp -= 360.0;
        else if (dhp < -180.0) dhp += 360.0;
    }
    const double dHp = 2.0 * std::sqrt(Cp1 * Cp2) * std::sin(0.5 * dhp * deg);
    // eq. 12–22
    const double Lbp = 0.5 * (L1 + L2);
    const double Cbp = 0.5 * (Cp1 + Cp2);
    double hbp = hp1 + hp2;
    if (Cp1 * Cp2 != 0.0) {
        if (std::abs(hp1 - hp2) <= 180.0) hbp = 0.5 * (hp1 + hp2);
        else if (hp1 + hp2 < 360.0) hbp = 0.5 * (hp1 + hp2 + 360.0);
        else hbp = 0.5 * (hp1 + hp2 - 360.0);
    }
    const double T = 1.0 - 0.17 * std::cos((hbp - 30.0) * deg) + 0.24 * std::cos(2.0 * hbp * deg) +
                     0.32 * std::cos((3.0 * hbp + 6.0) * deg) -
                     0.20 * std::cos((4.0 * hbp - 63.0) * deg);
    const double dtheta = 30.0 * std::exp(-std::pow((hbp - 275.0) / 25.0, 2));
    const double Cbp7 = std::pow(Cbp, 7);
    const double RC = 2.0 * std::sqrt(Cbp7 / (Cbp7 + p25_7));
    const double l50 = (Lbp - 50.0) * (Lbp - 50.0);
    const double SL = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
    const double SC = 1.0 + 0.045 * Cbp;
    const double SH = 1.0 + 0.015 * Cbp * T;
    const double RT = -std::sin(2.0 * dtheta * deg) * RC;
    const double tL = dLp / SL, tC = dCp / SC, tH = dHp / SH;
    return std::sqrt(tL * tL + tC * tC + tH * tH + RT * tC * tH);
}

double delta_e2000(const Vec3& c1, const Vec3& c2) {
    return ciede2000(linear_srgb_to_lab(c1), linear_srgb_to_lab(c2));
}

}  // namespace refract::spectrum
