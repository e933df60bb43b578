// GemCad .asc designs: the reader, the writer and the brilliant as a design (gemcad.h).
// No CGAL here; the exact construction is gemcad_build.cpp.
#include <cerrno>

#include <refract/geometry/constants.h>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/gem/gemcad.h>
#include <refract/geometry/gem/gemcad_names.h>
#include <refract/geometry/input_file.h>

namespace refract {
namespace {

constexpr std::uintmax_t kMaxDesignBytes = std::uintmax_t{1} << 20;
constexpr int kMaxGear = 1000;
constexpr std::size_t kMaxFacets = 4096;

struct Line {
    const std::string& source;
    int number;
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(source + ": line " + std::to_string(number) + ": " + what);
    }
};

std::vector<std::string> tokens(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string t;
    while (in >> t) out.push_back(t);
    return out;
}

// The whole token as a number; nothing when it is not one. Non-finite numbers are refused.
bool number(const std::string& t, double& v, const Line& line, const char* what) {
    if (t.empty()) return false;
    errno = 0;
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) return false;
    if (!std::isfinite(x) || errno == ERANGE)
        line.fail(std::string(what) + " '" + clip_echo(t) + "' is not a finite number");
    v = x;
    return true;
}

double required_number(const std::vector<std::string>& f, std::size_t k, const Line& line, const char* what,
                       const char* keyword) {
    double v = 0;
    if (k >= f.size()) line.fail(std::string("truncated '") + keyword + "' line: the " + what + " is missing");
    if (!number(f[k], v, line, what)) line.fail(std::string(what) + " '" + clip_echo(f[k]) + "' is not a number");
    return v;
}

std::string rest_after(const std::string& s, std::size_t first_chars) {
    std::string r = s.size() > first_chars ? s.substr(first_chars) : std::string();
    const auto b = r.find_first_not_of(" \t");
    return b == std::string::npos ? std::string() : r.substr(b);
}

void parse_tier(const std::vector<std::string>& f, const Line& line, GemcadDesign& d) {
    GemcadTier t;
    t.line = line.number;
    t.angle = required_number(f, 0, line, "angle", "a");
    t.distance = required_number(f, 1, line, "distance", "a");
    if (!(std::fabs(t.angle) <= 90))
        line.fail("angle " + format_value(t.angle) + " is outside -90 to 90 degrees");
    t.pavilion = std::signbit(t.angle);
    t.angle = std::fabs(t.angle);
    if (!(std::fabs(t.distance) <= 1e9)) line.fail("distance " + format_value(t.distance) + " is outside -1e9 to 1e9");
    std::size_t k = 2;
    for (; k < f.size(); ++k) {
        if (f[k] == "n") {
            if (t.indices.empty()) line.fail("a facet name 'n' before any gear index");
            if (k + 1 >= f.size()) line.fail("truncated 'a' line: 'n' without a facet name");
            t.names.back() = f[++k];
            continue;
        }
        double i = 0;
        if (!number(f[k], i, line, "gear index")) break;  // cutting instructions from here
        const int g = std::abs(d.gear);
        if (!(i >= 0 && i <= g))
            line.fail("gear index " + format_value(i) + " is outside 0 to " + std::to_string(g) + " (gear " +
                      std::to_string(d.gear) + ")");
        t.indices.push_back(i);
        t.names.emplace_back();
    }
    if (t.indices.empty()) line.fail("truncated 'a' line: a tier needs angle, distance and at least one gear index");
    for (; k < f.size(); ++k) t.instructions += (t.instructions.empty() ? "" : " ") + f[k];
    d.tiers.push_back(std::move(t));
}

std::string shortest_number(double v) { return format_shortest(v == 0 ? 0.0 : v); }

}  // namespace

std::string GemcadTier::name(int tier_number) const {
    for (const std::string& n : names)
        if (!n.empty()) return n;
    return "tier " + std::to_string(tier_number);
}

bool is_cleft_tier(const GemcadTier& tier, int tier_number) {
    const std::string n = tier.name(tier_number);
    if (n.size() < 2 || n.compare(0, 2, "CL") != 0) return false;
    for (std::size_t i = 2; i < n.size(); ++i)
        if (n[i] < '0' || n[i] > '9') return false;
    return true;
}

GemcadDesign parse_gemcad(const std::string& text, const std::string& source) {
    GemcadDesign d;
    d.source = source;
    d.gear = 0;  // required before the first tier
    std::istringstream in(text);
    std::string s;
    int number = 0;
    bool gear_seen = false;
    std::size_t facets = 0;
    while (std::getline(in, s)) {
        ++number;
        const Line line{source, number};
        if (!s.empty() && s.back() == '\r') s.pop_back();
        if (number == 1 && s.rfind("\xEF\xBB\xBF", 0) == 0) s.erase(0, 3);  // UTF-8 byte-order mark
        const auto first = s.find_first_not_of(" \t");
        if (first == std::string::npos) continue;
        s.erase(0, first);
        if (s.rfind("GemCad", 0) == 0) {
            d.version = s;
            continue;
        }
        const char key = s[0];
        const std::vector<std::string> f = tokens(s.substr(1));
        switch (key) {
            case 'g': {
                const double g = required_number(f, 0, line, "gear", "g");
                if (!(g == std::floor(g) && g != 0 && std::fabs(g) <= kMaxGear))
                    line.fail("gear " + format_value(g) + " must be a non-zero whole number of teeth within -" +
                              std::to_string(kMaxGear) + " to " + std::to_string(kMaxGear));
                d.gear = static_cast<int>(g);
                d.location = f.size() > 1 ? required_number(f, 1, line, "location", "g") : 0.0;
                if (!(std::fabs(d.location) <= kMaxGear))
                    line.fail("location " + format_value(d.location) + " is outside -1000 to 1000");
                gear_seen = true;
                break;
            }
            case 'y': {
                const double folds = required_number(f, 0, line, "symmetry", "y");
                if (!(folds == std::floor(folds) && folds >= 1 && folds <= kMaxGear))
                    line.fail("symmetry " + format_value(folds) + " must be a whole number from 1 to 1000");
                d.symmetry = static_cast<int>(folds);
                if (f.size() < 2) line.fail("truncated 'y' line: the mirror flag (y or n) is missing");
                if (f[1] != "y" && f[1] != "n") line.fail("mirror flag '" + clip_echo(f[1]) + "' must be y or n");
                d.mirror = f[1] == "y";
                break;
            }
            case 'I':
                d.index = required_number(f, 0, line, "refractive index", "I");
                if (!(d.index >= 1 && d.index <= 10))
                    line.fail("refractive index " + format_value(d.index) + " is outside 1 to 10");
                break;
            case 'H': d.headings.push_back(rest_after(s, 1)); break;
            case 'F': d.footnotes.push_back(rest_after(s, 1)); break;
            case 'G':
                if (d.tiers.empty()) line.fail("cutting instructions 'G' before any tier");
                d.tiers.back().instructions += (d.tiers.back().instructions.empty() ? "" : " ") + rest_after(s, 1);
                break;
            case 'a':
                if (!gear_seen) line.fail("a tier before the gear line 'g'");
                parse_tier(f, line, d);
                facets += d.tiers.back().indices.size();
                if (facets > kMaxFacets)
                    line.fail("more than " + std::to_string(kMaxFacets) + " facets (refract's limit for a design)");
                break;
            default:
                line.fail("unknown keyword '" + clip_echo(std::string(1, key)) +
                          "' (GemCad .asc records: GemCad, g, y, I, H, F, a, G)");
        }
    }
    if (d.tiers.empty())
        throw InputError(source + (number == 0 ? std::string(": the file is empty: the design has no tier ('a' line)")
                                               : ": line " + std::to_string(number) +
                                                     ": the design has no tier ('a' line): truncated file?"));
    return d;
}

GemcadDesign read_gemcad(const std::string& path) {
    return parse_gemcad(read_input_file(path, "design file", kMaxDesignBytes), path);
}

std::string gemcad_text(const GemcadDesign& d) {
    std::ostringstream s;
    s << (d.version.empty() ? "GemCad 5.0" : d.version) << "\n";
    s << "g " << d.gear << " " << shortest_number(d.location) << "\n";
    s << "y " << d.symmetry << " " << (d.mirror ? "y" : "n") << "\n";
    if (d.index > 0) s << "I " << shortest_number(d.index) << "\n";
    for (const std::string& h : d.headings) s << "H " << h << "\n";
    for (const GemcadTier& t : d.tiers) {
        s << "a " << (t.pavilion ? "-" : "") << shortest_number(t.angle) << " " << shortest_number(t.distance);
        for (std::size_t k = 0; k < t.indices.size(); ++k) {
            s << " " << shortest_number(t.indices[k]);
            if (k < t.names.size() && !t.names[k].empty()) s << " n " << t.names[k];
        }
        if (!t.instructions.empty()) s << " " << t.instructions;
        s << "\n";
    }
    for (const std::string& f : d.footnotes) s << "F " << f << "\n";
    return s.str();
}

GemcadDesign brilliant_design(const Gem& gem) {
    GemcadDesign d;
    d.version = "GemCad 5.0";
    d.gear = 96;
    d.symmetry = 8;
    d.mirror = true;
    const BrilliantCut& c = gem.cut;
    std::ostringstream h;
    h << "round brilliant by refract: table " << c.table << " %, crown " << c.crown_angle << " deg, pavilion "
      << c.pavilion_angle << " deg, star " << c.star << " %, lower half " << c.lower_half << " %, girdle " << c.girdle
      << " %, culet " << c.culet << " %";
    d.headings = {h.str(), "girdle radius 1; gear 96, index 24 along the bezel 0 (+x); fractional indices where "
                           "the facet's azimuth falls between teeth"};
    std::string last_kind;
    for (const GemFacet& f : gem.facets) {
        const Vec3& n = f.plane.normal;
        const double h_len = std::hypot(n.x(), n.y());
        const double angle = std::atan2(h_len, std::fabs(n.z())) * 180 / kPi;
        const bool pavilion = !(n.z() > 0);
        double index = 0;
        if (h_len > 0) {
            index = std::fmod((std::atan2(n.y(), n.x()) * 180 / kPi + 90) / 360 * d.gear, d.gear);
            if (index < 0) index += d.gear;
            if (std::fabs(index - std::round(index)) < 1e-9) index = std::round(index);  // on a tooth
            if (index >= d.gear) index -= d.gear;
        }
        std::string kind = facet_kind(f.label);
        for (char& ch : kind)
            if (ch == ' ') ch = '_';
        GemcadTier* t = d.tiers.empty() ? nullptr : &d.tiers.back();
        // One tier per kind while angle and distance agree to 1e-12 (symmetric facets differ
        // in their last bits; the tier's values move a plane by far less than the 1e-9 the
        // design reads back within).
        if (!t || kind != last_kind || std::fabs(t->angle - angle) > 1e-12 || t->pavilion != pavilion ||
            std::fabs(t->distance - f.plane.offset) > 1e-12) {
            d.tiers.emplace_back();
            t = &d.tiers.back();
            t->angle = angle;
            t->pavilion = pavilion;
            t->distance = f.plane.offset;
        }
        t->indices.push_back(index);
        t->names.push_back(kind != last_kind || t->indices.size() == 1 ? kind : std::string());
        last_kind = kind;
    }
    // The tiers named as the trade names them (G, T, C1…, P1…, CU), by side and angle.
    const std::vector<std::string> trade = trade_tier_names(d);
    for (std::size_t k = 0; k < d.tiers.size(); ++k)
        for (std::string& n : d.tiers[k].names)
            if (!n.empty()) n = trade[k];
    return d;
}

}  // namespace refract
