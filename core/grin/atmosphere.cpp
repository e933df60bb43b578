// The U.S. Standard Atmosphere 1976 to 84.852 km geopotential, with humidity and a surface
// layer, and its refractive index (atmosphere.h).
#include <refract/core/grin/atmosphere.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/quadrature/gauss.hpp>

#include <refract/core/grin/check_range.h>
#include <refract/geometry/error.h>

namespace refract::grin {

namespace {
constexpr double kHydrostatic = kStandardGravity * kStandardAirMolarMass / kStandardGasConstant;  // K/m
constexpr int kSurfaceSteps = 400;       // steps of the surface layer's table
constexpr double kSurfaceExtent = 40.0;  // e-folding heights it covers (e⁻⁴⁰ ≈ 4·10⁻¹⁸)


// The 1976 standard's layers below 84.852 km: base geopotential height (m) and lapse rate
// dT/dH (K/m); the last entry starts the isothermal continuation.
struct LayerDef {
    double base_H, lapse;
};
constexpr LayerDef kLayers[] = {{0.0, -6.5e-3},     {11000.0, 0.0},     {20000.0, 1.0e-3},  {32000.0, 2.8e-3},
                                {47000.0, 0.0},     {51000.0, -2.8e-3}, {71000.0, -2.0e-3}, {kStandardTopGeopotential_m, 0.0}};

// Pressure at the top of a layer of lapse rate L from its base (hydrostatic equilibrium with
// T linear in geopotential height).
double layer_pressure(double base_p, double base_T, double lapse, double dH) {
    if (lapse == 0.0) return base_p * std::exp(-kHydrostatic * dH / base_T);
    return base_p * std::pow(base_T / (base_T + lapse * dH), kHydrostatic / lapse);
}
}  // namespace

double geopotential_height(double z) { return kStandardEarthRadius_m * z / (kStandardEarthRadius_m + z); }
double geometric_height(double H) { return kStandardEarthRadius_m * H / (kStandardEarthRadius_m - H); }

Atmosphere::Atmosphere(const AtmosphereSpec& spec, const std::string& where) : spec_(spec), where_(where) {
    check_range(spec.sea_level_temperature_K, 233.15, 323.15, where, "sea_level_temperature", " K");
    check_range(spec.sea_level_pressure_Pa, 80000.0, 120000.0, where, "sea_level_pressure", " Pa");
    check_range(spec.relative_humidity, 0.0, 1.0, where, "relative_humidity", "");
    check_range(spec.humidity_scale_height_m, 100.0, 1e5, where, "humidity_scale_height", " m");
    check_range(spec.co2_ppm, 0.0, air_limits::kMaxCO2_ppm, where, "co2", " ppm");
    check_range(spec.surface_delta_T_K, -50.0, 50.0, where, "surface_delta_T", " K");
    check_range(spec.surface_height_m, 0.01, 100.0, where, "surface_height", " m");

    double T = spec.sea_level_temperature_K, p = spec.sea_level_pressure_Pa;
    for (size_t i = 0; i < std::size(kLayers); ++i) {
        if (i > 0) {
            const double dH = kLayers[i].base_H - kLayers[i - 1].base_H;
            p = layer_pressure(p, T, kLayers[i - 1].lapse, dH);
            T += kLayers[i - 1].lapse * dH;
        }
        layers_.push_back({kLayers[i].base_H, T, p, kLayers[i].lapse});
    }

    if (spec.surface_delta_T_K != 0.0) {
        // C(h) = ∫₀ʰ (1/T − 1/T_std) dH/dh' dh', each step by 7-point Gauss–Legendre.
        surface_step_ = kSurfaceExtent * spec.surface_height_m / kSurfaceSteps;
        surface_integral_.assign(kSurfaceSteps + 1, 0.0);
        for (int k = 0; k < kSurfaceSteps; ++k) {
            const double a = k * surface_step_;
            surface_integral_[k + 1] =
                surface_integral_[k] + boost::math::quadrature::gauss<double, 7>::integrate(
                                           [&](double h) { return surface_integrand(h); },
                                           a, a + surface_step_);
        }
    }
}

const Atmosphere::Layer& Atmosphere::layer_at(double H) const {
    const Layer* L = &layers_.front();
    for (const Layer& l : layers_)
        if (H >= l.base_H) L = &l;
    return *L;
}

double Atmosphere::surface_integrand(double h) const {
    const double R = kStandardEarthRadius_m / (kStandardEarthRadius_m + h);
    const double H = geopotential_height(h);
    const Layer& L = layer_at(H);
    const double T_std = L.base_T + L.lapse * (H - L.base_H);
    const double T = T_std + spec_.surface_delta_T_K * std::exp(-h / spec_.surface_height_m);
    return (1.0 / T - 1.0 / T_std) * R * R;
}

double Atmosphere::surface_correction(double h) const {
    const double x = h / surface_step_;
    if (x >= kSurfaceSteps) return surface_integral_.back();
    const int k = static_cast<int>(x);
    const double t = x - k, t2 = t * t, t3 = t2 * t;
    const double s0 = surface_integrand(k * surface_step_), s1 = surface_integrand((k + 1) * surface_step_);
    return (2 * t3 - 3 * t2 + 1) * surface_integral_[k] + (t3 - 2 * t2 + t) * surface_step_ * s0 +
           (-2 * t3 + 3 * t2) * surface_integral_[k + 1] + (t3 - t2) * surface_step_ * s1;
}

std::vector<double> Atmosphere::kink_heights() const {
    std::vector<double> h;
    for (size_t i = 1; i < layers_.size(); ++i) h.push_back(geometric_height(layers_[i].base_H));
    return h;
}

AirProfilePoint Atmosphere::state(double h) const {
    if (!(h >= 0.0 && h <= 1e7)) throw InputError(where_ + "/height: must be in [0, 1e7] m, got " + format_value(h));
    const double R = kStandardEarthRadius_m / (kStandardEarthRadius_m + h);
    const double dH_dh = R * R;
    const double H = geopotential_height(h);
    const Layer& L = layer_at(H);
    AirProfilePoint s;
    s.temperature_K = L.base_T + L.lapse * (H - L.base_H);
    s.dT_dh = L.lapse * dH_dh;
    double log_p = std::log(layer_pressure(L.base_p, L.base_T, L.lapse, H - L.base_H));
    if (!surface_integral_.empty()) {
        const double e = spec_.surface_delta_T_K * std::exp(-h / spec_.surface_height_m);
        s.temperature_K += e;
        s.dT_dh -= e / spec_.surface_height_m;
        log_p -= kHydrostatic * surface_correction(h);
    }
    s.pressure_Pa = std::exp(log_p);
    s.dp_dh = -s.pressure_Pa * kHydrostatic / s.temperature_K * dH_dh;
    if (spec_.relative_humidity > 0.0) {
        const double rh = spec_.relative_humidity * std::exp(-h / spec_.humidity_scale_height_m);
        const double svp = saturation_vapour_pressure(s.temperature_K);
        s.vapour_pressure_Pa = std::min(rh * svp, s.pressure_Pa);
        s.dpw_dh = s.vapour_pressure_Pa < s.pressure_Pa
                       ? -s.vapour_pressure_Pa / spec_.humidity_scale_height_m +
                             rh * saturation_vapour_pressure_slope(s.temperature_K) * s.dT_dh
                       : s.dp_dh;
    }
    return s;
}

Atmosphere::Index Atmosphere::index(double h, double lambda_um) const {
    return index(h, ciddor_reference(lambda_um, spec_.co2_ppm, where_));
}

Atmosphere::Index Atmosphere::index(double h, const CiddorReference& ref) const {
    const AirProfilePoint s = state(h);
    const double T = s.temperature_K, p = s.pressure_Pa, pw = s.vapour_pressure_Pa;
    auto f = [&](double pp, double TT, double ww) { return ciddor_refractivity(ref, pp, TT, ww); };
    // dn/dh by the chain rule; the partial derivatives of Ciddor's refractivity by central
    // differences (relative steps 10⁻⁵: truncation and rounding both near 10⁻¹⁰ relative).
    const double dT = 1e-5 * T;
    double dn = (f(p, T + dT, pw) - f(p, T - dT, pw)) / (2 * dT) * s.dT_dh;
    if (p > 0.0) {
        const double dp = 1e-5 * p;
        dn += (f(p + dp, T, pw) - f(p - dp, T, pw)) / (2 * dp) * s.dp_dh;
    }
    if (s.dpw_dh != 0.0) {
        const double dw = std::max(1e-5 * pw, 1e-9);
        dn += (f(p, T, pw + dw) - f(p, T, pw - dw)) / (2 * dw) * s.dpw_dh;
    }
    return {1.0 + f(p, T, pw), dn};
}

IndexSamples sample_index(const Atmosphere& atm, double lambda_um, double h_min, double h_max, int count) {
    if (!(count >= 2 && count <= (1 << 24)))
        throw InputError("sample_index/count: must be in [2, 16777216], got " + std::to_string(count));
    if (!(h_min >= 0.0 && h_max > h_min && h_max <= 1e7))
        throw InputError("sample_index/height: needs 0 <= min < max <= 1e7 m, got " + format_value(h_min) + " to " +
                         format_value(h_max));
    const CiddorReference ref = ciddor_reference(lambda_um, atm.spec().co2_ppm, "sample_index");
    IndexSamples out;
    for (int i = 0; i < count; ++i) {
        const double h = i + 1 == count ? h_max : h_min + (h_max - h_min) * i / (count - 1);
        const Atmosphere::Index x = atm.index(h, ref);
        out.height_m.push_back(h);
        out.n.push_back(x.n);
        out.dn_dh.push_back(x.dn_dh);
    }
    return out;
}

}  // namespace refract::grin
