#include <refract/core/spectrum/absorption.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include <refract/core/optics.h>
#include <refract/geometry/error.h>

namespace refract::spectrum {

namespace {

constexpr double kRed = 610.0, kGreen = 545.0, kBlue = 445.0;

// A Gaussian absorption band: peak α (1/cm) at centre (nm) with full width at half maximum.
struct Band {
    double centre, fwhm, peak;
};

Absorption from_bands(const std::vector<Band>& bands, double floor, const std::string& label, double unit_cm) {
    std::vector<double> nm, alpha;
    for (double l = 380.0; l <= 780.0; l += 5.0) {
        double a = floor;
        for (const Band& b : bands) {
            const double s = b.fwhm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
            a += b.peak * std::exp(-0.5 * std::pow((l - b.centre) / s, 2));
        }
        nm.push_back(l);
        alpha.push_back(a * unit_cm);
    }
    return Absorption::from_spectrum(std::move(nm), std::move(alpha), label);
}

}  // namespace

double Absorption::at(double lambda_nm) const {
    if (nm.empty()) return 0.0;
    if (lambda_nm <= nm.front()) return alpha.front();
    if (lambda_nm >= nm.back()) return alpha.back();
    const size_t i = static_cast<size_t>(std::upper_bound(nm.begin(), nm.end(), lambda_nm) - nm.begin());
    const double t = (lambda_nm - nm[i - 1]) / (nm[i] - nm[i - 1]);
    return (1.0 - t) * alpha[i - 1] + t * alpha[i];
}

Absorption Absorption::from_rgb(const Vec3& a, std::string label) {
    Absorption r;
    r.rgb = a;
    r.nm = {kBlue, kGreen, kRed};
    r.alpha = {a.z(), a.y(), a.x()};
    r.label = std::move(label);
    return r;
}

Absorption Absorption::from_spectrum(std::vector<double> nm, std::vector<double> alpha, std::string label) {
    Absorption r;
    r.nm = std::move(nm);
    r.alpha = std::move(alpha);
    r.rgb = Vec3(r.at(kRed), r.at(kGreen), r.at(kBlue));
    r.label = std::move(label);
    return r;
}

Absorption absorption_catalogue(const std::string& name, double unit_cm) {
    std::string key = name;
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return c == '_' || c == ' ' ? '-' : std::tolower(c); });
    // Band positions: Nassau, The Physics and Chemistry of Color (2nd ed., 2001), ch. 5
    // (ligand-field colours: Cr3+ in corundum and in beryl) and ch. 7 (Fe2+–Ti4+ charge
    // transfer in blue sapphire); Fe3+/Fe2+ in glass: Bamford, Colour Generation and
    // Control in Glass (1977). Strengths: models for a medium colour through about 5 mm.
    if (key == "ruby")  // Cr3+ in Al2O3: 4A2 → 4T2 (~555 nm) and 4A2 → 4T1 (~405 nm)
        return from_bands({{405, 50, 4.0}, {555, 60, 5.0}}, 0.05, "ruby (model: Cr3+ bands at 405, 555 nm)", unit_cm);
    if (key == "blue-sapphire")  // Fe2+–Ti4+ intervalence charge transfer, broad, ~565 and ~700 nm
        return from_bands({{565, 160, 3.0}, {700, 200, 2.0}}, 0.05,
                          "blue sapphire (model: Fe2+-Ti4+ bands at 565, 700 nm)", unit_cm);
    if (key == "emerald")  // Cr3+ in beryl: ~430 and ~610 nm
        return from_bands({{430, 60, 3.0}, {610, 80, 3.5}}, 0.05, "emerald (model: Cr3+ bands at 430, 610 nm)", unit_cm);
    if (key == "green-glass")  // Fe3+ near 380 nm, the short-wave tail of the Fe2+ band at 1050 nm
        return from_bands({{380, 150, 2.0}, {1050, 600, 3.0}}, 0.02,
                          "green glass (model: Fe3+ at 380 nm, Fe2+ at 1050 nm)", unit_cm);
    std::string names;
    for (const auto& n : absorption_catalogue_names()) names += (names.empty() ? "" : ", ") + n;
    throw InputError("unknown absorbing material '" + clip_echo(name) + "' (" + names + ")");
}

std::vector<std::string> absorption_catalogue_names() { return {"ruby", "blue-sapphire", "emerald", "green-glass"}; }

namespace {

double finite_nonneg(const nlohmann::json& v, const std::string& where) {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
        throw InputError(where + ": must be a finite number >= 0, got " + clip_echo(v.dump()));
    return v.get<double>();
}

Vec3 triple(const nlohmann::json& j, const std::string& where) {
    if (!j.is_array() || j.size() != 3) throw InputError(where + ": must be an array of 3 numbers");
    return {finite_nonneg(j[0], where + "/0"), finite_nonneg(j[1], where + "/1"), finite_nonneg(j[2], where + "/2")};
}

}  // namespace

Absorption parse_absorption(const nlohmann::json& j, const std::string& path) {
    if (j.is_string()) {
        try {
            return absorption_catalogue(j.get<std::string>());
        } catch (const InputError& e) {
            throw InputError(path + ": " + e.what());
        }
    }
    if (!j.is_object()) throw InputError(path + ": expected a material name or an object, got " + clip_echo(j.dump()));
    auto only = [&](std::initializer_list<const char*> keys) {
        for (const auto& [k, v] : j.items()) {
            bool ok = false;
            for (const char* a : keys) ok = ok || k == a;
            if (!ok) throw InputError(path + "/" + clip_echo(k) + ": unknown field");
        }
    };
    if (j.contains("model")) {
        only({"model", "unit_cm"});
        if (!j["model"].is_string()) throw InputError(path + "/model: must be a catalogue name");
        double unit = 1.0;
        if (j.contains("unit_cm")) {
            unit = finite_nonneg(j["unit_cm"], path + "/unit_cm");
            if (!(unit > 0)) throw InputError(path + "/unit_cm: must be > 0");
        }
        try {
            return absorption_catalogue(j["model"].get<std::string>(), unit);
        } catch (const InputError& e) {
            throw InputError(path + "/model: " + e.what());
        }
    }
    if (j.contains("coefficients")) {
        only({"coefficients"});
        return Absorption::from_rgb(triple(j["coefficients"], path + "/coefficients"), "RGB coefficients");
    }
    if (j.contains("transmittance")) {
        only({"transmittance", "thickness"});
        if (!j.contains("thickness")) throw InputError(path + "/thickness: required with a transmittance");
        const Vec3 t = triple(j["transmittance"], path + "/transmittance");
        const double d = finite_nonneg(j["thickness"], path + "/thickness");
        Vec3 a;
        for (int c = 0; c < 3; ++c) {
            const auto alpha = optics::absorption_coefficient(t[c], d);
            if (!alpha)
                throw InputError(path + "/transmittance/" + std::to_string(c) +
                                 ": needs 0 < transmittance <= 1 and a thickness > 0");
            a[c] = *alpha;
        }
        return Absorption::from_rgb(a, "transmittance colour");
    }
    if (j.contains("spectrum")) {
        only({"spectrum"});
        const auto& s = j["spectrum"];
        if (!s.is_array() || s.size() < 2) throw InputError(path + "/spectrum: needs at least two [nm, alpha] pairs");
        std::vector<double> nm, alpha;
        for (size_t k = 0; k < s.size(); ++k) {
            const std::string w = path + "/spectrum/" + std::to_string(k);
            if (!s[k].is_array() || s[k].size() != 2) throw InputError(w + ": must be [nm, alpha]");
            const double l = finite_nonneg(s[k][0], w + "/0");
            if (!nm.empty() && !(l > nm.back())) throw InputError(w + ": wavelengths must increase");
            nm.push_back(l);
            alpha.push_back(finite_nonneg(s[k][1], w + "/1"));
        }
        return Absorption::from_spectrum(std::move(nm), std::move(alpha), "tabulated spectrum");
    }
    throw InputError(path + ": give a catalogue name, \"model\", \"coefficients\", \"transmittance\" or \"spectrum\"");
}

}  // namespace refract::spectrum
