// Dispersion laws, material catalogue and POV-Ray's bands (see dispersion.h, docs/spectra.md).
#include <refract/core/spectrum/dispersion.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

#include <nlohmann/json.hpp>

#include <refract/core/spectrum/refractiveindex_info.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/error.h>

namespace refract::spectrum {

namespace {

// POV-Ray 3.7's cumulative hue table, "SpectralHueIntegral" Variant 3 (the one compiled in),
// 375–740 nm every 5 nm: the integral of its fitted band-colour spectrum. Numeric data from
// POV-Ray 3.7.0.10, source/backend/colour/spectral.cpp (POV-Ray's data; the code is ours).
constexpr double kHueStart = 375.0;
constexpr double kHueStep = 5.0;
constexpr double kHueTable[74][3] = {
    {0.0000, 0.0000, 0.0000},  // 375
    {0.0009, 0.0000, 0.0038},  // 380
    {0.0029, 0.0000, 0.0113},  // 385
    {0.0058, 0.0000, 0.0222},  // 390
    {0.0094, 0.0000, 0.0363},  // 395
    {0.0135, 0.0000, 0.0534},  // 400
    {0.0178, 0.0000, 0.0734},  // 405
    {0.0223, 0.0000, 0.0960},  // 410
    {0.0267, 0.0000, 0.1210},  // 415
    {0.0308, 0.0000, 0.1482},  // 420
    {0.0344, 0.0000, 0.1775},  // 425
    {0.0374, 0.0000, 0.2085},  // 430
    {0.0394, 0.0000, 0.2412},  // 435
    {0.0404, 0.0000, 0.2753},  // 440
    {0.0404, 0.0000, 0.3106},  // 445
    {0.0404, 0.0000, 0.3470},  // 450
    {0.0404, 0.0000, 0.3841},  // 455
    {0.0404, 0.0000, 0.4219},  // 460
    {0.0404, 0.0000, 0.4600},  // 465
    {0.0404, 0.0000, 0.4984},  // 470
    {0.0404, 0.0000, 0.5368},  // 475
    {0.0404, 0.0000, 0.5750},  // 480
    {0.0404, 0.0000, 0.6128},  // 485
    {0.0404, 0.0000, 0.6500},  // 490
    {0.0404, 0.0000, 0.6864},  // 495
    {0.0404, 0.0045, 0.7218},  // 500
    {0.0404, 0.0131, 0.7560},  // 505
    {0.0404, 0.0256, 0.7888},  // 510
    {0.0404, 0.0417, 0.8200},  // 515
    {0.0404, 0.0612, 0.8494},  // 520
    {0.0404, 0.0839, 0.8768},  // 525
    {0.0404, 0.1095, 0.9020},  // 530
    {0.0404, 0.1378, 0.9248},  // 535
    {0.0404, 0.1684, 0.9449},  // 540
    {0.0404, 0.2013, 0.9623},  // 545
    {0.0404, 0.2360, 0.9767},  // 550
    {0.0404, 0.2724, 0.9878},  // 555
    {0.0404, 0.3102, 0.9956},  // 560
    {0.0404, 0.3492, 0.9997},  // 565
    {0.0404, 0.3891, 1.0000},  // 570
    {0.0429, 0.4297, 1.0000},  // 575
    {0.0502, 0.4707, 1.0000},  // 580
    {0.0620, 0.5119, 1.0000},  // 585
    {0.0780, 0.5530, 1.0000},  // 590
    {0.0979, 0.5937, 1.0000},  // 595
    {0.1215, 0.6340, 1.0000},  // 600
    {0.1483, 0.6733, 1.0000},  // 605
    {0.1781, 0.7117, 1.0000},  // 610
    {0.2105, 0.7487, 1.0000},  // 615
    {0.2454, 0.7841, 1.0000},  // 620
    {0.2823, 0.8178, 1.0000},  // 625
    {0.3210, 0.8494, 1.0000},  // 630
    {0.3611, 0.8786, 1.0000},  // 635
    {0.4024, 0.9054, 1.0000},  // 640
    {0.4446, 0.9293, 1.0000},  // 645
    {0.4873, 0.9501, 1.0000},  // 650
    {0.5302, 0.9677, 1.0000},  // 655
    {0.5731, 0.9817, 1.0000},  // 660
    {0.6155, 0.9919, 1.0000},  // 665
    {0.6573, 0.9981, 1.0000},  // 670
    {0.6982, 1.0000, 1.0000},  // 675
    {0.7377, 1.0000, 1.0000},  // 680
    {0.7756, 1.0000, 1.0000},  // 685
    {0.8116, 1.0000, 1.0000},  // 690
    {0.8454, 1.0000, 1.0000},  // 695
    {0.8767, 1.0000, 1.0000},  // 700
    {0.9052, 1.0000, 1.0000},  // 705
    {0.9306, 1.0000, 1.0000},  // 710
    {0.9525, 1.0000, 1.0000},  // 715
    {0.9707, 1.0000, 1.0000},  // 720
    {0.9849, 1.0000, 1.0000},  // 725
    {0.9947, 1.0000, 1.0000},  // 730
    {0.9998, 1.0000, 1.0000},  // 735
    {1.0000, 1.0000, 1.0000},  // 740
};

// POV-Ray's band geometry (colour/spectral.h): violet end, width of the visible band.
constexpr double kPovViolet = 380.0;
constexpr double kPovBandwidth = 350.0;
constexpr double kPovCentre = 555.0;

}  // namespace

// ---------------------------------------------------------------------------------------
// The laws.

double LawTerms::sum() const {
    double q = 0.0;
    for (int k = 0; k < count; ++k) q = k == 0 ? t[0] : q + t[static_cast<size_t>(k)];
    return q;
}

double LawTerms::index() const {
    if (lorentz_lorenz) {
        const double R = sum();  // (n² − 1)/(n² + 2) = R  ⇔  n² = (1 + 2R)/(1 − R)
        return std::sqrt((1.0 + 2.0 * R) / (1.0 - R));
    }
    return squared ? std::sqrt(sum()) : sum();
}

LawTerms cauchy_terms(double l, double A, double B, double C) {
    const double l2 = l * l;
    LawTerms r;  // Cauchy: n = A + B/λ² + C/λ⁴
    r.add(A);
    r.add(B / l2);
    r.add(C / (l2 * l2));
    return r;
}

LawTerms sellmeier_terms(double l, const double* B, const double* C, int terms) {
    const double l2 = l * l;
    LawTerms r;  // Sellmeier: n² = 1 + Σ B_i λ²/(λ² − C_i)
    r.squared = true;
    r.add(1.0);
    for (int i = 0; i < terms; ++i) r.add(sellmeier_term(l2, B[i], C[i]));
    return r;
}

LawTerms moissanite_form_terms(double l, double A, double B, double C, double D) {
    const double l2 = l * l;
    LawTerms r;  // Wang 2013: n² = A + B/(λ² − C) − Dλ²
    r.squared = true;
    r.add(A);
    r.add(B / (l2 - C));
    r.add(-D * l2);
    return r;
}

double cauchy_index(double l, double A, double B, double C) { return cauchy_terms(l, A, B, C).index(); }

double sellmeier_index(double l, const double* B, const double* C, int terms) {
    return sellmeier_terms(l, B, C, terms).index();
}

double moissanite_form_index(double l, double A, double B, double C, double D) {
    return moissanite_form_terms(l, A, B, C, D).index();
}

double povray_index(double ior, double dispersion, double lambda_nm) {
    // POV-Ray: n(λ) = n · D^((555 − λ)/350)
    return ior * std::pow(dispersion, (kPovCentre - lambda_nm) / kPovBandwidth);
}

AbbeModel abbe_model(double nd, double Vd) {
    // Two-term Cauchy through n_d with n_F − n_C = (n_d − 1)/V_d (λ in µm).
    AbbeModel m;
    m.nd = nd;
    m.Vd = Vd;
    const double iF = 1.0 / std::pow(fraunhofer::F * 1e-3, 2);
    const double iC = 1.0 / std::pow(fraunhofer::C * 1e-3, 2);
    const double id = 1.0 / std::pow(fraunhofer::d * 1e-3, 2);
    m.B = (nd - 1.0) / Vd / (iF - iC);
    m.A = nd - m.B * id;
    return m;
}

// ---------------------------------------------------------------------------------------
// Dispersion.

double Dispersion::n(double lambda_nm) const {
    const double l = lambda_nm * 1e-3;
    struct Eval {
        double l, nm;
        double operator()(const ConstantIndex& m) const { return m.n; }
        double operator()(const CauchyModel& m) const { return cauchy_index(l, m.A, m.B, m.C); }
        double operator()(const SellmeierModel& m) const {
            return sellmeier_index(l, m.B.data(), m.C.data(), m.terms);
        }
        double operator()(const AbbeModel& m) const { return cauchy_index(l, m.A, m.B, 0.0); }
        double operator()(const MoissaniteFormModel& m) const {
            return moissanite_form_index(l, m.A, m.B, m.C, m.D);
        }
        double operator()(const PovRayModel& m) const {
            return povray_index(m.ior, m.dispersion, nm);
        }
        double operator()(const FormulaModel& m) const { return formula_terms(m, l).index(); }
        double operator()(const TabulatedModel& m) const { return tabulated_at(m.um, m.n, l); }
    };
    return std::visit(Eval{l, lambda_nm}, model);
}

std::vector<double> Dispersion::indices(const std::vector<double>& wl) const {
    std::vector<double> r(wl.size());
    for (size_t i = 0; i < wl.size(); ++i) r[i] = n(wl[i]);
    return r;
}

// Per model: the index where one index is needed, and whether it disperses — one overload
// each, so a model that lacks one does not compile.
namespace {
struct NominalOf {
    const Dispersion& d;
    double operator()(const ConstantIndex& c) const { return c.n; }
    double operator()(const PovRayModel& p) const { return p.ior; }  // POV-Ray's Fresnel uses it
    double operator()(const CauchyModel&) const { return at_d(); }
    double operator()(const SellmeierModel&) const { return at_d(); }
    double operator()(const AbbeModel&) const { return at_d(); }
    double operator()(const MoissaniteFormModel&) const { return at_d(); }
    double operator()(const FormulaModel&) const { return at_d(); }
    double operator()(const TabulatedModel&) const { return at_d(); }
    double at_d() const { return d.n(fraunhofer::d); }
};
struct DispersiveOf {
    bool operator()(const ConstantIndex&) const { return false; }
    bool operator()(const PovRayModel& p) const { return p.dispersion != 1.0; }
    bool operator()(const CauchyModel&) const { return true; }
    bool operator()(const SellmeierModel&) const { return true; }
    bool operator()(const AbbeModel&) const { return true; }
    bool operator()(const MoissaniteFormModel&) const { return true; }
    bool operator()(const FormulaModel&) const { return true; }
    bool operator()(const TabulatedModel&) const { return true; }
};
}  // namespace

double Dispersion::nominal() const { return std::visit(NominalOf{*this}, model); }

bool Dispersion::dispersive() const { return std::visit(DispersiveOf{}, model); }

double Dispersion::abbe_number() const {
    return (n(fraunhofer::d) - 1.0) / (n(fraunhofer::F) - n(fraunhofer::C));
}

// ---------------------------------------------------------------------------------------
// Catalogue (coefficients from the refractiveindex.info database; λ in µm).

namespace {

Dispersion sellmeier(std::vector<double> B, std::vector<double> C, std::string label) {
    SellmeierModel m;
    m.terms = static_cast<int>(B.size());
    for (size_t i = 0; i < B.size(); ++i) {
        m.B[i] = B[i];
        m.C[i] = C[i];
    }
    return {m, std::move(label)};
}

const std::map<std::string, Dispersion>& table() {
    static const std::map<std::string, Dispersion> t = [] {
        std::map<std::string, Dispersion> m;
        // F. Peter, Z. Physik 15, 358 (1923): n² − 1 = 4.3356λ²/(λ² − 0.1060²)
        //                                           + 0.3306λ²/(λ² − 0.1750²)
        m.emplace("diamond", sellmeier({4.3356, 0.3306}, {0.1060 * 0.1060, 0.1750 * 0.1750},
                                       "diamond (Peter 1923)"));
        // SCHOTT optical glass data sheet, N-BK7 (C in µm² as given).
        m.emplace("n-bk7", sellmeier({1.03961212, 0.231792344, 1.01046945},
                                     {0.00600069867, 0.0200179144, 103.560653},
                                     "N-BK7 (SCHOTT)"));
        // I. H. Malitson, JOSA 55, 1205 (1965): C_i = (0.0684043, 0.1162414, 9.896161 µm)².
        m.emplace("fused-silica",
                  sellmeier({0.6961663, 0.4079426, 0.8974794},
                            {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161},
                            "fused silica (Malitson 1965)"));
        // M. Daimon & A. Masumura, Appl. Opt. 46, 3811 (2007), water at 20 °C.
        m.emplace("water",
                  sellmeier({0.5684027565, 0.1726177391, 0.02086189578, 0.1130748688},
                            {0.005101829712, 0.01821153936, 0.02620722293, 10.69792721},
                            "water 20 °C (Daimon & Masumura 2007)"));
        // D. L. Wood & K. Nassau, Appl. Opt. 21, 2978 (1982): C_i = (0.062543, 0.166739,
        // 24.320570 µm)².
        m.emplace("cubic-zirconia",
                  sellmeier({1.347091, 2.117788, 9.452943},
                            {0.062543 * 0.062543, 0.166739 * 0.166739, 24.320570 * 24.320570},
                            "cubic zirconia (Wood & Nassau 1982)"));
        // S. Wang et al., Mater. Sci. Forum 740–742 (2013), 6H-SiC ordinary ray:
        // n² = 6.57232 + 0.1401/(λ² − 0.03178) − 0.02153λ².
        m.emplace("moissanite", Dispersion{MoissaniteFormModel{6.57232, 0.1401, 0.03178, 0.02153},
                                           "moissanite 6H-SiC, ordinary ray (Wang 2013)"});
        // The other rays of the uniaxial crystals (uniaxial_crystal): "<crystal>-o"/"-e".
        // S. Wang et al., Laser Photonics Rev. 7, 831 (2013), 6H-SiC extraordinary ray:
        // n² = 6.7452 + 0.15352/(λ² − 0.03597) − 0.02249λ².
        m.emplace("moissanite-e", Dispersion{MoissaniteFormModel{6.7452, 0.15352, 0.03597, 0.02249},
                                             "moissanite 6H-SiC, extraordinary ray (Wang 2013)"});
        // G. Ghosh, Opt. Commun. 163, 95 (1999): n² = A + Bλ²/(λ² − C) + Dλ²/(λ² − E), written as
        // a Sellmeier sum with the constant A − 1 as a term of pole 0.
        const auto ghosh = [](double A, double B, double C, double D, double E, std::string label) {
            return sellmeier({A - 1.0, B, D}, {0.0, C, E}, std::move(label));
        };
        m.emplace("calcite-o", ghosh(1.73358749, 0.96464345, 1.94325203e-2, 1.82831454, 120,
                                     "calcite, ordinary ray (Ghosh 1999)"));
        m.emplace("calcite-e", ghosh(1.35859695, 0.82427830, 1.06689543e-2, 0.14429128, 120,
                                     "calcite, extraordinary ray (Ghosh 1999)"));
        m.emplace("quartz-o", ghosh(1.28604141, 1.07044083, 1.00585997e-2, 1.10202242, 100,
                                    "crystalline quartz, ordinary ray (Ghosh 1999)"));
        m.emplace("quartz-e", ghosh(1.28851804, 1.09509924, 1.02101864e-2, 1.15662475, 100,
                                    "crystalline quartz, extraordinary ray (Ghosh 1999)"));
        // I. H. Malitson & M. J. Dodge, JOSA 62, 1405 (1972), as given by M. J. Dodge, Handbook
        // of Laser Science and Technology IV (1986): C_i = (pole in µm)².
        m.emplace("sapphire-o", sellmeier({1.4313493, 0.65054713, 5.3414021},
                                          {0.0726631 * 0.0726631, 0.1193242 * 0.1193242, 18.028251 * 18.028251},
                                          "sapphire, ordinary ray (Malitson & Dodge 1972)"));
        m.emplace("sapphire-e", sellmeier({1.5039759, 0.55069141, 6.5927379},
                                          {0.0740288 * 0.0740288, 0.1216529 * 0.1216529, 20.072248 * 20.072248},
                                          "sapphire, extraordinary ray (Malitson & Dodge 1972)"));
        return m;
    }();
    return t;
}

std::string normalise_name(const std::string& s) {
    std::string r;
    for (char ch : s) {
        const unsigned char c = static_cast<unsigned char>(ch);
        r += (c == ' ' || c == '_') ? '-' : static_cast<char>(std::tolower(c));
    }
    if (r == "bk7") return "n-bk7";
    if (r == "cz") return "cubic-zirconia";
    return r;
}

std::string known_names() {
    std::string s;
    for (const auto& n : catalogue_names()) s += (s.empty() ? "" : ", ") + n;
    return s;
}

}  // namespace

std::vector<std::string> uniaxial_crystal_names() { return {"calcite", "quartz", "sapphire", "moissanite"}; }

std::optional<UniaxialCrystal> uniaxial_crystal(const std::string& name) {
    const std::string n = normalise_name(name);
    for (const auto& c : uniaxial_crystal_names())
        if (n == c) {
            const auto& t = table();
            return UniaxialCrystal{c == "moissanite" ? t.at("moissanite") : t.at(c + "-o"), t.at(c + "-e")};
        }
    return std::nullopt;
}

std::vector<std::string> catalogue_names() {
    return {"diamond", "n-bk7", "fused-silica", "water", "cubic-zirconia", "moissanite"};
}

const Dispersion& catalogue(const std::string& name) {
    const auto it = table().find(normalise_name(name));
    if (it == table().end())
        throw InputError("material \"" + clip_echo(name) + "\" is not in the catalogue; known: " +
                         known_names());
    return it->second;
}

// ---------------------------------------------------------------------------------------
// Parsing.

namespace {

double number(const nlohmann::json& o, const char* key, const std::string& path) {
    if (!o.contains(key)) throw InputError(path + ": missing \"" + key + "\"");
    const auto& v = o.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw InputError(path + "/" + key + ": expected a finite number, got " + clip_echo(v.dump()));
    return v.get<double>();
}

double number_or(const nlohmann::json& o, const char* key, double def, const std::string& path) {
    return o.contains(key) ? number(o, key, path) : def;
}

std::vector<double> numbers(const nlohmann::json& o, const char* key, const std::string& path) {
    if (!o.contains(key)) throw InputError(path + ": missing \"" + key + "\"");
    const auto& v = o.at(key);
    if (!v.is_array() || v.empty() || v.size() > 4)
        throw InputError(path + "/" + key + ": expected an array of 1–4 numbers, got " + clip_echo(v.dump()));
    std::vector<double> r;
    for (size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
            throw InputError(path + "/" + key + "/" + std::to_string(i) +
                             ": expected a finite number, got " + v[i].dump());
        r.push_back(v[i].get<double>());
    }
    return r;
}

void only_keys(const nlohmann::json& o, std::initializer_list<const char*> keys,
               const std::string& path) {
    for (const auto& item : o.items()) {
        if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return item.key() == k; })) {
            std::string allowed;
            for (const char* k : keys) allowed += (allowed.empty() ? "" : ", ") + std::string(k);
            throw InputError(path + "/" + clip_echo(item.key()) + ": unknown key for this model; allowed: " +
                             allowed);
        }
    }
}

Dispersion parse_model(const nlohmann::json& o, const std::string& path) {
    if (o.contains("file") && !o.contains("model"))
        throw InputError(path + "/file: a dispersion file is read relative to a scene file, in a scene's "
                         "dielectric (\"dispersion\": {\"file\": ...})");
    if (!o.contains("model") || !o.at("model").is_string())
        throw InputError(path + "/model: expected one of \"constant\", \"cauchy\", \"sellmeier\", "
                         "\"abbe\", \"moissanite-form\", \"povray\"");
    const std::string model = o.at("model").get<std::string>();
    if (model == "constant") {
        only_keys(o, {"model", "n"}, path);
        const double n = number(o, "n", path);
        if (!(n > 0.0)) throw InputError(path + "/n: " + format_value(n) + " must be > 0");
        return {ConstantIndex{n}, "constant n = " + format_value(n)};
    }
    if (model == "cauchy") {
        only_keys(o, {"model", "A", "B", "C"}, path);
        return {CauchyModel{number(o, "A", path), number_or(o, "B", 0.0, path),
                            number_or(o, "C", 0.0, path)},
                "cauchy"};
    }
    if (model == "sellmeier") {
        only_keys(o, {"model", "B", "C"}, path);
        const auto B = numbers(o, "B", path);
        const auto C = numbers(o, "C", path);
        if (B.size() != C.size())
            throw InputError(path + "/C: " + std::to_string(C.size()) +
                             " coefficients, but B has " + std::to_string(B.size()));
        return sellmeier(B, C, "sellmeier");
    }
    if (model == "abbe") {
        only_keys(o, {"model", "nd", "Vd"}, path);
        const double nd = number(o, "nd", path), Vd = number(o, "Vd", path);
        if (!(nd > 1.0)) throw InputError(path + "/nd: " + format_value(nd) + " must be > 1");
        if (!(Vd > 0.0)) throw InputError(path + "/Vd: " + format_value(Vd) + " must be > 0");
        return {abbe_model(nd, Vd), "abbe n_d = " + format_value(nd) + ", V_d = " + format_value(Vd)};
    }
    if (model == "moissanite-form") {
        only_keys(o, {"model", "A", "B", "C", "D"}, path);
        return {MoissaniteFormModel{number(o, "A", path), number(o, "B", path),
                                    number(o, "C", path), number(o, "D", path)},
                "moissanite-form"};
    }
    if (model == "povray") {
        only_keys(o, {"model", "ior", "dispersion", "samples"}, path);
        PovRayModel m;
        m.ior = number(o, "ior", path);
        m.dispersion = number_or(o, "dispersion", 1.0, path);
        const double s = number_or(o, "samples", 7.0, path);
        if (!(m.ior > 0.0)) throw InputError(path + "/ior: " + format_value(m.ior) + " must be > 0");
        if (!(m.dispersion > 0.0))
            throw InputError(path + "/dispersion: " + format_value(m.dispersion) + " must be > 0");
        if (s != std::floor(s) || s < 2 || s > 1000)
            throw InputError(path + "/samples: " + format_value(s) + " must be an integer in [2, 1000]");
        m.samples = static_cast<int>(s);
        return {m, "povray ior " + format_value(m.ior) + " dispersion " + format_value(m.dispersion)};
    }
    throw InputError(path + "/model: unknown model \"" + clip_echo(model) + "\"; allowed: constant, cauchy, "
                     "sellmeier, abbe, moissanite-form, povray");
}

// The quantity whose sign decides, q(λ), as the law's terms (LawTerms); a constant and
// POV-Ray's law (monotone in λ) as one term. Poles: the C of each term B/(λ² − C).
struct TermsAt {
    double l, nm;
    LawTerms one(double v) const {
        LawTerms r;
        r.add(v);
        return r;
    }
    LawTerms operator()(const ConstantIndex& m) const { return one(m.n); }
    LawTerms operator()(const CauchyModel& m) const { return cauchy_terms(l, m.A, m.B, m.C); }
    LawTerms operator()(const SellmeierModel& m) const { return sellmeier_terms(l, m.B.data(), m.C.data(), m.terms); }
    LawTerms operator()(const AbbeModel& m) const { return cauchy_terms(l, m.A, m.B, 0.0); }
    LawTerms operator()(const MoissaniteFormModel& m) const { return moissanite_form_terms(l, m.A, m.B, m.C, m.D); }
    LawTerms operator()(const PovRayModel& m) const { return one(povray_index(m.ior, m.dispersion, nm)); }
    LawTerms operator()(const FormulaModel& m) const { return formula_terms(m, l); }
    // Linear between samples: monotone between the samples, which Turns lists.
    LawTerms operator()(const TabulatedModel& m) const { return one(tabulated_at(m.um, m.n, l)); }
};

LawTerms terms_at(const Dispersion& d, double nm) { return std::visit(TermsAt{nm * 1e-3, nm}, d.model); }

// Each pole C (µm²) with the field it comes from.
struct Poles {
    using List = std::vector<std::pair<double, std::string>>;
    List operator()(const ConstantIndex&) const { return {}; }
    List operator()(const CauchyModel&) const { return {}; }
    List operator()(const SellmeierModel& m) const {
        List r;
        for (int k = 0; k < m.terms; ++k) r.emplace_back(m.C[static_cast<size_t>(k)], "/C: term " + std::to_string(k + 1));
        return r;
    }
    List operator()(const AbbeModel&) const { return {}; }
    List operator()(const MoissaniteFormModel& m) const { return {{m.C, "/C: the term B/(λ² − C)"}}; }
    List operator()(const PovRayModel&) const { return {}; }
    List operator()(const FormulaModel& m) const { return formula_poles(m); }
    List operator()(const TabulatedModel&) const { return {}; }
};

// Where a term turns (nm): the range check splits the range there, so that each term is
// monotone on every piece it bounds.
struct Turns {
    using List = std::vector<double>;
    List operator()(const ConstantIndex&) const { return {}; }
    List operator()(const CauchyModel&) const { return {}; }
    List operator()(const SellmeierModel&) const { return {}; }
    List operator()(const AbbeModel&) const { return {}; }
    List operator()(const MoissaniteFormModel&) const { return {}; }
    List operator()(const PovRayModel&) const { return {}; }
    List operator()(const FormulaModel& m) const { return in_nm(formula_turns(m)); }
    List operator()(const TabulatedModel& m) const { return in_nm(m.um); }
    static List in_nm(List um) {
        for (double& x : um) x *= 1000.0;
        return um;
    }
};

// The quantity that must be > 0: the law's sum itself, or for the Lorentz–Lorenz form
// 1 + 2R (condition 1) and 1 − R (condition 2); each linear in the terms.
LawTerms condition(const LawTerms& t, int which) {
    if (which == 0) return t;
    LawTerms r;
    r.add(1.0);
    for (int k = 0; k < t.count; ++k) r.add((which == 1 ? 2.0 : -1.0) * t.t[static_cast<size_t>(k)]);
    return r;
}

}  // namespace

void check_range(const Dispersion& d, const std::string& path) {
    // A pole λ = √C (µm², so × 1000 for nm) inside the range: the index is infinite there.
    const auto pole_check = [&](double C, const std::string& field) {
        const double pole = std::sqrt(std::fmax(C, 0.0)) * 1000.0;
        if (pole >= kMinWavelength && pole <= kMaxWavelength)
            throw InputError(path + field + " has its pole at " + format_value(pole) + " nm, inside 360–830 nm");
    };
    for (const auto& [C, field] : std::visit(Poles{}, d.model)) pole_check(C, field);
    const auto refuse = [&](const LawTerms& t, double nm, const std::string& what) {
        if (t.lorentz_lorenz)
            throw InputError(path + ": the model gives (n² − 1)/(n² + 2) = " + what + " at " + format_value(nm) +
                             " nm; it must be finite and in (−1/2, 1) over 360–830 nm");
        throw InputError(path + ": the model gives " + (t.squared ? "n² = " : "n = ") + what + " at " +
                         format_value(nm) + " nm; it must be finite and > 0 over 360–830 nm");
    };
    // The minimum over the whole continuous range, not at whole nanometres: on [a, b] each
    // term lies between its values at the ends (monotone: no pole and no turn inside), so
    // the sum of their smaller ends bounds q from below. An interval whose bound is not > 0
    // is halved until the bound is > 0 or a point with q <= 0 is found. The range is first
    // cut where a term turns (Turns).
    std::vector<double> cuts{kMinWavelength};
    for (double x : std::visit(Turns{}, d.model))
        if (x > kMinWavelength && x < kMaxWavelength) cuts.push_back(x);
    cuts.push_back(kMaxWavelength);
    std::sort(cuts.begin(), cuts.end());
    const int conditions = terms_at(d, kMinWavelength).lorentz_lorenz ? 2 : 1;
    for (int which = conditions == 1 ? 0 : 1; which <= conditions; ++which) {
        const auto at = [&](double nm) { return condition(terms_at(d, nm), which); };
        const auto check_point = [&](const LawTerms& t, double nm) {
            const double q = t.sum();
            if (!std::isfinite(q) || !(q > 0)) {
                const LawTerms law = terms_at(d, nm);
                refuse(law, nm, format_value(law.sum()));
            }
        };
        const LawTerms lo = at(kMinWavelength), hi = at(kMaxWavelength);
        check_point(lo, kMinWavelength);
        check_point(hi, kMaxWavelength);
        double largest = 0;  // every value of every term is within its ends: the sum cannot overflow
        for (int k = 0; k < lo.count; ++k)
            largest += std::fmax(std::fabs(lo.t[static_cast<size_t>(k)]), std::fabs(hi.t[static_cast<size_t>(k)]));
        if (!std::isfinite(largest)) refuse(terms_at(d, kMinWavelength), kMinWavelength, "a value past the range of a double");
        struct Interval {
            double a, b;
            LawTerms ta, tb;
        };
        std::vector<Interval> todo;
        for (size_t i = 0; i + 1 < cuts.size(); ++i) {
            const LawTerms ta = at(cuts[i]), tb = at(cuts[i + 1]);
            check_point(ta, cuts[i]);
            todo.push_back({cuts[i], cuts[i + 1], ta, tb});
        }
        for (int steps = 0; !todo.empty(); ++steps) {
            const Interval iv = todo.back();
            todo.pop_back();
            double bound = 0;
            for (int k = 0; k < iv.ta.count; ++k)
                bound += std::fmin(iv.ta.t[static_cast<size_t>(k)], iv.tb.t[static_cast<size_t>(k)]);
            if (bound > 0) continue;
            const double m = 0.5 * (iv.a + iv.b);
            const LawTerms tm = at(m);
            check_point(tm, m);
            // Still not shown > 0 on an interval of 1e-9 nm (39 halvings), or after 100 000
            // intervals: a minimum that is zero to rounding.
            if (iv.b - iv.a < 1e-9 || steps > 100000) refuse(terms_at(d, m), m, "0 to within rounding");
            todo.push_back({iv.a, m, iv.ta, tm});
            todo.push_back({m, iv.b, tm, iv.tb});
        }
    }
}

Dispersion parse_dispersion(const nlohmann::json& j, const std::string& path) {
    if (j.is_string()) {
        try {
            return catalogue(j.get<std::string>());
        } catch (const InputError& e) {
            throw InputError(path + ": " + e.what());
        }
    }
    Dispersion d;
    if (j.is_number()) {
        const double n = j.get<double>();
        if (!std::isfinite(n) || !(n > 0.0))
            throw InputError(path + ": index " + clip_echo(j.dump()) + " must be finite and > 0");
        d = {ConstantIndex{n}, "constant n = " + format_value(n)};
    } else if (j.is_object()) {
        d = parse_model(j, path);
    } else {
        throw InputError(path + ": expected a material name, a number or a model object, got " +
                         clip_echo(j.dump()));
    }
    check_range(d, path);
    return d;
}

Dispersion parse_dispersion_text(const std::string& text, const std::string& path) {
    const auto b = text.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) throw InputError(path + ": empty dispersion");
    const char c = text[b];
    if (c == '{' || c == '"' || c == '-' || c == '.' || std::isdigit(static_cast<unsigned char>(c))) {
        nlohmann::json j;
        try {
            j = nlohmann::json::parse(text);
        } catch (const nlohmann::json::parse_error& e) {
            throw InputError(path + ": not valid JSON (" + e.what() + ")");
        }
        return parse_dispersion(j, path);
    }
    return parse_dispersion(nlohmann::json(text.substr(b, text.find_last_not_of(" \t\r\n") - b + 1)),
                            path);
}

// ---------------------------------------------------------------------------------------
// POV-Ray's bands.

Vec3 povray_hue_integral(double lambda_nm) {
    constexpr int size = 74;
    const double x = std::clamp((lambda_nm - kHueStart) / kHueStep, 0.0, size - 1.0);
    const int i = std::min(static_cast<int>(x), size - 2);
    const double t = x - i;
    return {(1.0 - t) * kHueTable[i][0] + t * kHueTable[i + 1][0],
            (1.0 - t) * kHueTable[i][1] + t * kHueTable[i + 1][1],
            (1.0 - t) * kHueTable[i][2] + t * kHueTable[i + 1][2]};
}

std::vector<PovBand> povray_bands(int samples) {
    if (samples < 2 || samples > 1000)
        throw InputError("dispersion samples: " + std::to_string(samples) +
                         " is outside the allowed range [2, 1000] (POV-Ray's minimum is 2)");
    std::vector<PovBand> bands(static_cast<size_t>(samples));
    for (int i = 0; i < samples; ++i) {
        // POV-Ray keeps the band wavelength and width in single precision.
        const float wl = static_cast<float>(kPovViolet + kPovBandwidth * ((i + 0.5) / samples));
        const float bw = static_cast<float>(kPovBandwidth / samples);
        const float hi = wl + bw / 2, lo = wl - bw / 2;
        PovBand& b = bands[static_cast<size_t>(i)];
        b.wavelength_nm = wl;
        b.bandwidth_nm = bw;
        b.hue = (povray_hue_integral(hi) - povray_hue_integral(lo)) * (kPovBandwidth / bw);
    }
    return bands;
}

}  // namespace refract::spectrum
