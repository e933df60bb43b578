// Wavelength sampling and light-source spectra (see wavelengths.h, docs/spectra.md).
#include <refract/core/spectrum/wavelengths.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include <refract/geometry/error.h>

namespace refract::spectrum {

namespace {

// CIE standard illuminant D65, relative spectral power, 300–830 nm every 5 nm (107 values),
// normalised to 1.0 at 560 nm. Source: CIE 15:2004 "Colorimetry", table T.1 (values / 100),
// as distributed in colord's data files (illuminant/CIE-D65.sp, colord-data 1.4.6).
constexpr double kD65Start = 300.0;
constexpr double kD65Step = 5.0;
constexpr std::array<double, 107> kD65 = {
    0.000341, 0.016643, 0.032945, 0.117652, 0.20236, 0.286447, 0.370535, 0.385011,  // 300
    0.399488, 0.424302, 0.449117, 0.45775, 0.466383, 0.493637, 0.520891, 0.510323,  // 340
    0.499755, 0.523118, 0.546482, 0.687015, 0.827549, 0.871204, 0.91486, 0.924589,  // 380
    0.934318, 0.90057, 0.866823, 0.957736, 1.04865, 1.10936, 1.17008, 1.1741,  // 420
    1.17812, 1.16336, 1.14861, 1.15392, 1.15923, 1.12367, 1.08811, 1.09082,  // 460
    1.09354, 1.08578, 1.07802, 1.06296, 1.0479, 1.06239, 1.07689, 1.06047,  // 500
    1.04405, 1.04225, 1.04046, 1.02023, 1.0, 0.981671, 0.963342, 0.960611,  // 540
    0.95788, 0.922368, 0.886856, 0.893459, 0.900062, 0.898026, 0.895991, 0.886489,  // 580
    0.876987, 0.854936, 0.832886, 0.834939, 0.836992, 0.81863, 0.800268, 0.801207,  // 620
    0.802146, 0.812462, 0.822778, 0.80281, 0.782842, 0.740027, 0.697213, 0.706652,  // 660
    0.716091, 0.72979, 0.74349, 0.679765, 0.61604, 0.657448, 0.698856, 0.724863,  // 700
    0.75087, 0.693398, 0.635927, 0.550054, 0.464182, 0.566118, 0.668054, 0.650941,  // 740
    0.633828, 0.638434, 0.64304, 0.618779, 0.594519, 0.557054, 0.51959, 0.546998,  // 780
    0.574406, 0.588765, 0.603125,  // 820
};

}  // namespace

void validate(const WavelengthSampling& s, const std::string& where) {
    if (!std::isfinite(s.min_nm) || s.min_nm < kMinWavelength || s.min_nm > kMaxWavelength)
        throw InputError(where + "/min: " + format_value(s.min_nm) + " nm is outside the allowed range [" +
                         format_value(kMinWavelength) + ", " + format_value(kMaxWavelength) + "] nm");
    if (!std::isfinite(s.max_nm) || s.max_nm < s.min_nm || s.max_nm > kMaxWavelength)
        throw InputError(where + "/max: " + format_value(s.max_nm) + " nm is outside the allowed range [" +
                         format_value(s.min_nm) + " (min), " + format_value(kMaxWavelength) + "] nm");
    if (!std::isfinite(s.step_nm) || s.step_nm < 0.1 || s.step_nm > kMaxWavelength - kMinWavelength)
        throw InputError(where + "/step: " + format_value(s.step_nm) +
                         " nm is outside the allowed range [0.1, 470] nm");
    const double steps = (s.max_nm - s.min_nm) / s.step_nm;
    if (std::abs(steps - std::round(steps)) > 1e-9 * std::max(1.0, steps))
        throw InputError(where + "/step: " + format_value(s.step_nm) + " nm does not divide the range " +
                         format_value(s.min_nm) + "–" + format_value(s.max_nm) + " nm into whole steps");
}

std::vector<double> sample_wavelengths(const WavelengthSampling& s, const std::string& where) {
    validate(s, where);
    const int n = static_cast<int>(std::lround((s.max_nm - s.min_nm) / s.step_nm)) + 1;
    std::vector<double> w(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) w[static_cast<size_t>(i)] = s.min_nm + i * s.step_nm;
    w.back() = s.max_nm;
    return w;
}

std::vector<double> band_widths(const std::vector<double>& wl) {
    const size_t n = wl.size();
    if (n == 0) throw InputError("wavelengths: the set is empty");
    for (size_t i = 1; i < n; ++i)
        if (!(wl[i] > wl[i - 1]))
            throw InputError("wavelengths: not strictly increasing at index " + std::to_string(i) +
                             " (" + format_value(wl[i - 1]) + " then " + format_value(wl[i]) + " nm)");
    std::vector<double> d(n, 1.0);
    if (n == 1) return d;
    for (size_t i = 0; i < n; ++i) {
        const double lo = i == 0 ? wl[0] - 0.5 * (wl[1] - wl[0]) : 0.5 * (wl[i - 1] + wl[i]);
        const double hi = i + 1 == n ? wl[n - 1] + 0.5 * (wl[n - 1] - wl[n - 2])
                                     : 0.5 * (wl[i] + wl[i + 1]);
        d[i] = hi - lo;
    }
    return d;
}

double cie_d65(double lambda_nm) {
    const double x = (lambda_nm - kD65Start) / kD65Step;
    if (!(x >= 0.0) || x > static_cast<double>(kD65.size() - 1)) return 0.0;
    const size_t i = std::min(static_cast<size_t>(x), kD65.size() - 2);
    const double t = x - static_cast<double>(i);
    return (1.0 - t) * kD65[i] + t * kD65[i + 1];
}

double planck_radiance(double lambda_nm, double T) {
    // SI 2019 exact constants.
    constexpr double h = 6.62607015e-34;  // J·s
    constexpr double c = 299792458.0;     // m/s
    constexpr double k = 1.380649e-23;    // J/K
    const double lam = lambda_nm * 1e-9;  // m
    const double per_m = 2.0 * h * c * c / std::pow(lam, 5) / std::expm1(h * c / (lam * k * T));
    return per_m * 1e-9;  // per nm
}

double blackbody_relative(double lambda_nm, double T) {
    return planck_radiance(lambda_nm, T) / planck_radiance(560.0, T);
}

double LightSpectrum::operator()(double lambda_nm) const {
    switch (kind) {
        case Illuminant::EqualEnergy: return equal_energy(lambda_nm);
        case Illuminant::D65: return cie_d65(lambda_nm);
        case Illuminant::Blackbody: return blackbody_relative(lambda_nm, temperature_K);
    }
    return 1.0;
}

std::vector<double> LightSpectrum::sample(const std::vector<double>& wl) const {
    std::vector<double> s(wl.size());
    for (size_t i = 0; i < wl.size(); ++i) s[i] = (*this)(wl[i]);
    return s;
}

std::string LightSpectrum::name() const {
    switch (kind) {
        case Illuminant::EqualEnergy: return "equal-energy";
        case Illuminant::D65: return "D65";
        case Illuminant::Blackbody: return "blackbody " + format_value(temperature_K) + " K";
    }
    return "?";
}

LightSpectrum blackbody(double T, const std::string& where) {
    if (!std::isfinite(T) || T < 100.0 || T > 100000.0)
        throw InputError(where + ": " + format_value(T) + " K is outside the allowed range [100, 100000] K");
    LightSpectrum s;
    s.kind = Illuminant::Blackbody;
    s.temperature_K = T;
    return s;
}

LightSpectrum parse_light_spectrum(const nlohmann::json& j, const std::string& path) {
    if (j.is_string()) {
        const std::string s = j.get<std::string>();
        if (s == "E" || s == "equal-energy") return LightSpectrum{};
        if (s == "D65" || s == "d65") return LightSpectrum{Illuminant::D65, 6504.0};
        throw InputError(path + ": unknown light spectrum \"" + clip_echo(s) +
                         "\"; known: \"equal-energy\" (or \"E\"), \"D65\", {\"blackbody\": kelvin}");
    }
    if (j.is_object() && j.size() == 1 && j.contains("blackbody")) {
        const auto& t = j.at("blackbody");
        if (!t.is_number())
            throw InputError(path + "/blackbody: expected a temperature in kelvin, got " + clip_echo(t.dump()));
        return blackbody(t.get<double>(), path + "/blackbody");
    }
    throw InputError(path + ": expected \"equal-energy\", \"D65\" or {\"blackbody\": kelvin}, got " +
                     j.dump());
}

}  // namespace refract::spectrum
