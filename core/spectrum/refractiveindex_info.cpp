// refractiveindex.info database entries (see refractiveindex_info.h for the formulas).
#include <refract/core/spectrum/refractiveindex_info.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <refract/core/optics.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/error.h>
#include <refract/geometry/input_file.h>

namespace refract::spectrum {

namespace {

// C_i, 1-based as the database numbers them; 0 past the end.
struct Coefficients {
    const std::vector<double>& c;
    double operator()(size_t i) const { return i <= c.size() ? c[i - 1] : 0.0; }
    size_t size() const { return c.size(); }
};

constexpr double kHerzbergerPole = 0.028;  // µm², formula 7

}  // namespace

LawTerms formula_terms(const FormulaModel& m, double l) {
    const Coefficients C{m.c};
    const size_t n = C.size();
    const double l2 = l * l;
    LawTerms r;
    switch (m.formula) {
        case 1:  // n² − 1 = C1 + Σ C_i λ²/(λ² − C_{i+1}²)
        case 2:  // n² − 1 = C1 + Σ C_i λ²/(λ² − C_{i+1})
            r.squared = true;
            r.add(1.0);
            r.add(C(1));
            for (size_t i = 2; i + 1 <= n; i += 2) {
                const double pole = m.formula == 1 ? C(i + 1) * C(i + 1) : C(i + 1);
                r.add(sellmeier_term(l2, C(i), pole));
            }
            break;
        case 3:  // n² = C1 + Σ C_i λ^C_{i+1}
        case 5:  // n = C1 + Σ C_i λ^C_{i+1}
            r.squared = m.formula == 3;
            r.add(C(1));
            for (size_t i = 2; i + 1 <= n; i += 2) r.add(C(i) * std::pow(l, C(i + 1)));
            break;
        case 4:  // n² = C1 + C2 λ^C3/(λ² − C4^C5) + C6 λ^C7/(λ² − C8^C9) + Σ_{i>=10} C_i λ^C_{i+1}
            r.squared = true;
            r.add(C(1));
            for (size_t i = 2; i <= 6 && i + 3 <= n; i += 4)
                r.add(C(i) * std::pow(l, C(i + 1)) / (l2 - std::pow(C(i + 2), C(i + 3))));
            for (size_t i = 10; i + 1 <= n; i += 2) r.add(C(i) * std::pow(l, C(i + 1)));
            break;
        case 6:  // n − 1 = C1 + Σ C_i/(C_{i+1} − λ^−2)
            r.add(1.0);
            r.add(C(1));
            for (size_t i = 2; i + 1 <= n; i += 2) r.add(C(i) / (C(i + 1) - 1.0 / l2));
            break;
        case 7: {  // n = C1 + C2/(λ² − 0.028) + C3/(λ² − 0.028)² + C4 λ² + C5 λ⁴ + C6 λ⁶
            const double L = 1.0 / (l2 - kHerzbergerPole);
            r.add(C(1));
            r.add(C(2) * L);
            r.add(C(3) * L * L);
            r.add(C(4) * l2);
            r.add(C(5) * l2 * l2);
            r.add(C(6) * l2 * l2 * l2);
            break;
        }
        case 8:  // (n² − 1)/(n² + 2) = C1 + C2 λ²/(λ² − C3) + C4 λ²
            r.lorentz_lorenz = true;
            r.add(C(1));
            r.add(sellmeier_term(l2, C(2), C(3)));
            r.add(C(4) * l2);
            break;
        case 9: {  // n² = C1 + C2/(λ² − C3) + C4 (λ − C5)/((λ − C5)² + C6)
            const double x = l - C(5);
            r.squared = true;
            r.add(C(1));
            r.add(C(2) / (l2 - C(3)));
            r.add(C(4) * x / (x * x + C(6)));
            break;
        }
        default:
            r.add(std::nan(""));
    }
    return r;
}

std::vector<std::pair<double, std::string>> formula_poles(const FormulaModel& m) {
    const Coefficients C{m.c};
    const size_t n = C.size();
    std::vector<std::pair<double, std::string>> r;
    const auto name = [](size_t i) { return "/coefficients: C" + std::to_string(i); };
    switch (m.formula) {
        case 1:
        case 2:
            for (size_t i = 2; i + 1 <= n; i += 2)
                r.emplace_back(m.formula == 1 ? C(i + 1) * C(i + 1) : C(i + 1), name(i + 1));
            break;
        case 4:
            for (size_t i = 2; i <= 6 && i + 3 <= n; i += 4)
                r.emplace_back(std::pow(C(i + 2), C(i + 3)), name(i + 2) + "^C" + std::to_string(i + 3));
            break;
        case 6:  // C_{i+1} − λ^−2 = 0 at λ² = 1/C_{i+1}
            for (size_t i = 2; i + 1 <= n; i += 2)
                if (C(i + 1) > 0) r.emplace_back(1.0 / C(i + 1), name(i + 1));
            break;
        case 7:
            r.emplace_back(kHerzbergerPole, "/coefficients: the term C2/(λ² − 0.028)");
            break;
        case 8:
            r.emplace_back(C(3), name(3));
            break;
        case 9:
            r.emplace_back(C(3), name(3));
            if (C(6) <= 0)  // (λ − C5)² + C6 = 0 at λ = C5 ± √(−C6)
                for (double s : {-1.0, 1.0}) {
                    const double l = C(5) + s * std::sqrt(-C(6));
                    if (l > 0) r.emplace_back(l * l, name(5) + ", C6");
                }
            break;
        default:
            break;
    }
    return r;
}

std::vector<double> formula_turns(const FormulaModel& m) {
    const Coefficients C{m.c};
    std::vector<double> r;
    if (m.formula == 4) {
        // d/dλ [λ^p/(λ² − q)] has the sign of (p − 2)λ² − pq: it turns at λ² = pq/(p − 2).
        for (size_t i = 2; i <= 6 && i + 3 <= C.size(); i += 4) {
            const double p = C(i + 1), q = std::pow(C(i + 2), C(i + 3));
            if (p != 2.0) {
                const double l2 = p * q / (p - 2.0);
                if (l2 > 0 && std::isfinite(l2)) r.push_back(std::sqrt(l2));
            }
        }
    } else if (m.formula == 9 && C(6) > 0) {
        // x/(x² + C6) turns at x = ±√C6, x = λ − C5.
        for (double s : {-1.0, 1.0}) {
            const double l = C(5) + s * std::sqrt(C(6));
            if (l > 0) r.push_back(l);
        }
    }
    return r;
}

double tabulated_at(const std::vector<double>& x, const std::vector<double>& y, double xq) {
    if (x.empty()) return std::nan("");
    if (xq <= x.front()) return y.front();
    if (xq >= x.back()) return y.back();
    const size_t i = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), xq) - x.begin());
    const double t = (xq - x[i - 1]) / (x[i] - x[i - 1]);
    return (1.0 - t) * y[i - 1] + t * y[i];
}

// ---------------------------------------------------------------------------------------
// Reading.

namespace {

struct Reader {
    std::string file;

    [[noreturn]] void fail(const std::string& item, const std::string& what) const {
        throw InputError(file + ": " + item + ": " + what);
    }

    // Whitespace-separated finite numbers from a scalar (or a sequence of scalars).
    std::vector<double> numbers(const YAML::Node& n, const std::string& item) const {
        std::string text;
        if (n.IsScalar()) {
            text = n.Scalar();
        } else if (n.IsSequence()) {
            for (const auto& e : n) {
                if (!e.IsScalar()) fail(item, "expected numbers");
                text += " " + e.Scalar();
            }
        } else {
            fail(item, "expected numbers");
        }
        std::vector<double> r;
        const char* p = text.data();
        const char* end = p + text.size();
        while (true) {
            while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
            if (p == end) break;
            const char* q = p;
            while (q < end && !std::isspace(static_cast<unsigned char>(*q))) ++q;
            double v = 0;
            const char* start = *p == '+' ? p + 1 : p;  // from_chars takes no '+'
            const auto res = std::from_chars(start, q, v);
            if (res.ec != std::errc() || res.ptr != q || !std::isfinite(v))
                fail(item, "\"" + clip_echo(std::string(p, q)) + "\" is not a finite number");
            r.push_back(v);
            p = q;
        }
        return r;
    }

    YAML::Node field(const YAML::Node& block, const char* key, const std::string& where) const {
        const YAML::Node n = block[key];
        if (!n) fail(where, std::string("missing \"") + key + "\"");
        return n;
    }
};

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::string range_text(double a_um, double b_um) {
    return format_value(a_um) + "–" + format_value(b_um) + " µm (" + format_value(a_um * 1000) + "–" +
           format_value(b_um * 1000) + " nm)";
}

// Allowed numbers of coefficients per formula.
bool coefficient_count_ok(int formula, size_t n) {
    switch (formula) {
        case 1: case 2: case 3: return n % 2 == 1 && n <= 17;
        case 4: return n == 1 || n == 5 || (n >= 9 && n % 2 == 1 && n <= 17);
        case 5: case 6: return n % 2 == 1 && n <= 11;
        case 7: case 9: return n == 6;
        case 8: return n == 4;
        default: return false;
    }
}

const char* coefficient_counts(int formula) {
    switch (formula) {
        case 1: case 2: case 3: return "C1 and pairs: 1, 3, …, 17";
        case 4: return "1, 5, 9, 11, …, 17";
        case 5: case 6: return "C1 and pairs: 1, 3, …, 11";
        case 7: case 9: return "6";
        default: return "4";
    }
}

}  // namespace

namespace {
CataloguedConstants read_entry(const Reader& rd, const YAML::Node& root, const std::string& file, double unit_cm);
}  // namespace

CataloguedConstants read_refractiveindex_info(const std::string& file, double unit_cm) {
    const Reader rd{file};
    const std::string text = read_input_file(file, "dispersion file");
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw InputError(file + ": malformed YAML" +
                         (e.mark.is_null() ? std::string() : " at line " + std::to_string(e.mark.line + 1)) + ": " + e.msg);
    }
    try {
        return read_entry(rd, root, file, unit_cm);
    } catch (const YAML::Exception& e) {
        throw InputError(file + ": malformed entry: " + e.msg);
    }
}

namespace {

CataloguedConstants read_entry(const Reader& rd, const YAML::Node& root, const std::string& file, double unit_cm) {
    if (!root.IsMap()) rd.fail("/", "expected a refractiveindex.info entry (a map with DATA)");
    const YAML::Node data = root["DATA"];
    if (!data || !data.IsSequence() || data.size() == 0) rd.fail("/DATA", "missing, or not a list of data blocks");

    std::optional<Dispersion> index;
    std::optional<std::pair<std::vector<double>, std::vector<double>>> k;  // λ µm, k
    std::string index_item;
    const auto covers = [&](double a, double b, const std::string& item) {
        // In nm, to within rounding (a file's 0.83 µm is 830 nm).
        if (!(a * 1000 <= kMinWavelength + 1e-9 && b * 1000 >= kMaxWavelength - 1e-9))
            rd.fail(item, "the range " + range_text(a, b) + " does not cover the rendered 360–830 nm");
    };
    const std::string name = std::filesystem::path(file).filename().string();
    for (size_t b = 0; b < data.size(); ++b) {
        const std::string where = "/DATA/" + std::to_string(b);
        const YAML::Node block = data[b];
        if (!block.IsMap()) rd.fail(where, "expected a map with \"type\"");
        const YAML::Node type_node = rd.field(block, "type", where);
        if (!type_node.IsScalar()) rd.fail(where + "/type", "expected a string");
        const std::string type = trim(type_node.Scalar());
        const auto set_index = [&](Dispersion d) {
            if (index) rd.fail(where, "a second index (the first is " + index_item + ")");
            index = std::move(d);
            index_item = where;
        };
        if (type.rfind("formula ", 0) == 0) {
            const std::string num = trim(type.substr(8));
            if (num.size() != 1 || num[0] < '1' || num[0] > '9')
                rd.fail(where + "/type", "unknown formula \"" + clip_echo(num) + "\" (formula 1–9)");
            FormulaModel m;
            m.formula = num[0] - '0';
            // The database's files name the range `wavelength_range` (older ones `range`).
            const char* range_key = block["wavelength_range"] || !block["range"] ? "wavelength_range" : "range";
            const auto range = rd.numbers(rd.field(block, range_key, where), where + "/" + range_key);
            if (range.size() != 2 || !(range[0] > 0) || !(range[1] > range[0]))
                rd.fail(where + "/" + range_key, "expected two wavelengths 0 < a < b (µm)");
            m.range_um[0] = range[0];
            m.range_um[1] = range[1];
            covers(range[0], range[1], where + "/" + range_key);
            m.c = rd.numbers(rd.field(block, "coefficients", where), where + "/coefficients");
            if (!coefficient_count_ok(m.formula, m.c.size()))
                rd.fail(where + "/coefficients", std::to_string(m.c.size()) + " coefficients; formula " + num +
                                                     " takes " + coefficient_counts(m.formula));
            set_index(Dispersion{m, name + " (refractiveindex.info formula " + num + ")"});
        } else if (type == "tabulated n" || type == "tabulated k" || type == "tabulated nk") {
            const size_t columns = type == "tabulated nk" ? 3 : 2;
            const YAML::Node d = rd.field(block, "data", where);
            if (!d.IsScalar()) rd.fail(where + "/data", "expected lines of numbers");
            std::vector<double> um, n, kk;
            size_t line = 0;
            std::string row;
            for (size_t pos = 0; pos <= d.Scalar().size(); ++pos) {
                const char ch = pos < d.Scalar().size() ? d.Scalar()[pos] : '\n';
                if (ch != '\n') {
                    row += ch;
                    continue;
                }
                ++line;
                const std::string item = where + "/data: line " + std::to_string(line);
                const auto v = rd.numbers(YAML::Node(row), item);
                row.clear();
                if (v.empty()) continue;
                if (v.size() != columns)
                    rd.fail(item, std::to_string(v.size()) + " numbers; \"" + type + "\" takes " + std::to_string(columns));
                if (!(v[0] > 0) || (!um.empty() && !(v[0] > um.back())))
                    rd.fail(item, "wavelengths must be > 0 and increase");
                um.push_back(v[0]);
                if (type == "tabulated k") {
                    kk.push_back(v[1]);
                } else {
                    n.push_back(v[1]);
                    if (columns == 3) kk.push_back(v[2]);
                }
                if (!kk.empty() && !(kk.back() >= 0)) rd.fail(item, "k must be >= 0");
            }
            if (um.size() < 2) rd.fail(where + "/data", "needs at least two lines");
            covers(um.front(), um.back(), where + "/data");
            if (!n.empty()) set_index(Dispersion{TabulatedModel{um, n}, name + " (refractiveindex.info " + type + ")"});
            if (!kk.empty()) {
                if (k) rd.fail(where, "a second k");
                k.emplace(um, kk);
            }
        } else {
            rd.fail(where + "/type", "unknown type \"" + clip_echo(type) +
                                         "\" (formula 1–9, tabulated n, tabulated k, tabulated nk)");
        }
    }
    if (!index) rd.fail("/DATA", "no index (a formula, tabulated n or tabulated nk)");
    check_range(*index, file + ": " + index_item);

    CataloguedConstants r{*index, std::nullopt};
    if (k) {
        // α per scene unit at each sample: 4πk/λ with λ in scene units (λ_µm·1e-4 cm / unit_cm).
        std::vector<double> nm, alpha;
        for (size_t i = 0; i < k->first.size(); ++i) {
            nm.push_back(k->first[i] * 1000.0);
            alpha.push_back(optics::extinction_absorption(k->second[i], k->first[i] * 1e-4 / unit_cm));
        }
        r.absorption = Absorption::from_spectrum(std::move(nm), std::move(alpha), name + " (k)");
    }
    return r;
}

}  // namespace

CataloguedConstants read_dispersion_file(const nlohmann::json& j, const std::string& scene_file,
                                         const std::string& path) {
    for (const auto& item : j.items())
        if (item.key() != "file" && item.key() != "unit_cm")
            throw InputError(path + "/" + clip_echo(item.key()) + ": unknown key for a dispersion file; allowed: file, unit_cm");
    if (!j.at("file").is_string() || j.at("file").get<std::string>().empty())
        throw InputError(path + "/file: must name a refractiveindex.info YAML file");
    double unit_cm = 1.0;
    if (j.contains("unit_cm")) {
        const auto& u = j.at("unit_cm");
        if (!u.is_number() || !std::isfinite(u.get<double>()) || !(u.get<double>() > 0))
            throw InputError(path + "/unit_cm: must be a finite number > 0, got " + clip_echo(u.dump()));
        unit_cm = u.get<double>();
    }
    const std::filesystem::path f = std::filesystem::path(scene_file).parent_path() / j.at("file").get<std::string>();
    try {
        return read_refractiveindex_info(f.lexically_normal().string(), unit_cm);
    } catch (const InputError& e) {
        throw InputError(path + "/file: " + e.what());
    }
}

}  // namespace refract::spectrum
