// Round brilliant parameters: presets, domain and feasibility checks, closed forms.
// (No CGAL here; the exact construction is brilliant.cpp.)
#include <algorithm>

#include <refract/geometry/constants.h>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/gem/brilliant.h>

namespace refract {
namespace {

double rad(double deg) { return deg * kPi / 180.0; }

std::string num(double v) { return format_significant(v, 6); }

[[noreturn]] void fail(const std::string& what) { throw InputError("brilliant cut: " + what); }

void check_range(const char* name, double v, double lo, double hi, const char* unit,
                 const char* source) {
    if (!std::isfinite(v) || v < lo || v > hi)
        fail(std::string(name) + " = " + num(v) + unit + " is outside the allowed range " + num(lo) +
             " to " + num(hi) + unit + " (" + source + ")");
}

// The documented domain (GIA Facetware input ranges, see docs/gems.md).
struct Domain {
    double lo, hi;
};
constexpr Domain kTable{44, 72}, kCrown{20, 41.5}, kPavilion{37.2, 43.8}, kStar{35, 75},
    kLowerHalf{60, 95}, kGirdle{1.5, 11}, kCulet{0, 10};

const double kC225 = std::cos(rad(22.5));

// Star tip below the table: the bezel ridge at azimuth 22.5° crosses the table plane at
// horizontal distance t / cos 22.5°, so the tip ρS = ρe + s(1 − ρe) must lie beyond it.
double min_star_fraction(double t) {
    const double rho_e = t * kC225;
    return (t / kC225 - rho_e) / (1 - rho_e);
}

// Height above z = 0 of the plane through a, b, c at horizontal point (x, y).
double plane_z(const Vec3& a, const Vec3& b, const Vec3& c, double x, double y) {
    const Vec3 n = (b - a).cross(c - a);
    return a.z() - (n.x() * (x - a.x()) + n.y() * (y - a.y())) / n.z();
}

}  // namespace

std::vector<std::string> brilliant_preset_names() { return {"tolkowsky", "gia-default"}; }

BrilliantCut brilliant_preset(const std::string& name) {
    BrilliantCut c;
    if (name == "tolkowsky") {
        // Tolkowsky (1919): table 53 %, crown 34.5°, pavilion 40.75°, knife-edge girdle, no
        // culet. He gives no star or lower-half lengths: 50 % and 75 % are our choice.
        c.table = 53;
        c.crown_angle = 34.5;
        c.pavilion_angle = 40.75;
        c.star = 50;
        c.lower_half = 75;
        c.girdle = 0;
        c.culet = 0;
        return c;
    }
    if (name == "gia-default") {
        // GIA default proportion chart: table 57 %, crown 34.5°, pavilion 40.75°, star 55 %,
        // lower half 80 %, girdle 3 %, no culet; the girdle is bruted.
        c.table = 57;
        c.crown_angle = 34.5;
        c.pavilion_angle = 40.75;
        c.star = 55;
        c.lower_half = 80;
        c.girdle = 3.0;
        c.culet = 0;
        return c;
    }
    std::string names;
    for (const auto& n : brilliant_preset_names()) names += (names.empty() ? "" : ", ") + n;
    throw InputError("brilliant cut: preset '" + name + "' is unknown (known presets: " + names + ")");
}

int girdle_plane_count(const BrilliantCut& cut) {
    return cut.girdle_facets > 0 ? cut.girdle_facets : cut.bruted_planes;
}

std::string girdle_description(const BrilliantCut& cut) {
    if (cut.girdle == 0) return "knife edge (no girdle facets)";
    return cut.girdle_facets > 0 ? std::to_string(cut.girdle_facets) + " girdle facets"
                                 : "bruted (round girdle approximated by " + std::to_string(cut.bruted_planes) +
                                       " vertical planes)";
}

double min_girdle_percent(const BrilliantCut& cut) {
    // With the girdle half-thickness g, the upper halves are the g = 0 planes lifted by g and
    // the lower halves lowered by g. Between a bezel (azimuth 0) and the next half junction
    // (22.5°) the upper half dips below z = g and the lower half rises above z = −g at the
    // girdle polygon's corners; every girdle facet survives iff 2g exceeds dip + rise there.
    const double t = cut.table / 100, s = cut.star / 100, l = cut.lower_half / 100;
    const double tb = std::tan(rad(cut.crown_angle)), ta = std::tan(rad(cut.pavilion_angle));
    const double psi = rad(22.5);
    const Vec3 G(1, 0, 0), V(std::cos(psi), std::sin(psi), 0);
    const double rho_e = t * kC225, rho_s = rho_e + s * (1 - rho_e), rho_l = 1 - l;
    const Vec3 S(rho_s * std::cos(psi), rho_s * std::sin(psi), tb * (1 - rho_s * kC225));
    const Vec3 L(rho_l * std::cos(psi), rho_l * std::sin(psi), -ta * (1 - rho_l * kC225));
    const int n = girdle_plane_count(cut);
    const double half = kPi / n, rc = 1 / std::cos(half);
    double worst = 0;
    for (int j = 0; j < n / 16; ++j) {
        const double th = 2 * kPi * j / n + half;
        const double x = rc * std::cos(th), y = rc * std::sin(th);
        const double dip = -plane_z(S, G, V, x, y), rise = plane_z(L, G, V, x, y);
        worst = std::max(worst, dip + rise);
    }
    return 100 * worst / 2;  // thickness 2g over D = 2, in %
}

void validate(const BrilliantCut& cut) {
    check_range("table", cut.table, kTable.lo, kTable.hi, " %", "GIA Facetware");
    check_range("crown angle", cut.crown_angle, kCrown.lo, kCrown.hi, " deg", "GIA Facetware");
    check_range("pavilion angle", cut.pavilion_angle, kPavilion.lo, kPavilion.hi, " deg",
                "GIA Facetware");
    check_range("star length", cut.star, kStar.lo, kStar.hi, " %", "GIA Facetware");
    check_range("lower-half length", cut.lower_half, kLowerHalf.lo, kLowerHalf.hi, " %",
                "GIA Facetware");
    if (!std::isfinite(cut.girdle) || (cut.girdle != 0 && (cut.girdle < kGirdle.lo || cut.girdle > kGirdle.hi)))
        fail("girdle thickness = " + num(cut.girdle) + " % is outside the allowed range: 0 (knife edge) or " +
             num(kGirdle.lo) + " to " + num(kGirdle.hi) + " % (GIA Facetware)");
    check_range("culet", cut.culet, kCulet.lo, kCulet.hi, " %", "refract's limit for a small culet");
    const auto girdle_count_ok = [](int n, int hi) { return n >= 16 && n <= hi && n % 16 == 0; };
    if (cut.girdle_facets != 0 && !girdle_count_ok(cut.girdle_facets, 192))
        fail("girdle facets = " + std::to_string(cut.girdle_facets) +
             " is not allowed: 0 (bruted) or a multiple of 16 from 16 to 192");
    if (!girdle_count_ok(cut.bruted_planes, 512))
        fail("bruted planes = " + std::to_string(cut.bruted_planes) +
             " is not allowed: a multiple of 16 from 16 to 512");

    // Feasibility.
    const double t = cut.table / 100;
    const double s_min = 100 * min_star_fraction(t);
    if (!(cut.star > s_min))
        fail("star length = " + num(cut.star) + " % puts the star tip above the table for table " +
             num(cut.table) + " %: allowed range " + num(std::ceil(s_min * 100) / 100) + " to " +
             num(kStar.hi) + " %");
    if (cut.culet > 0) {
        // The culet's corners lie on the main ridges at horizontal distance c / cos 22.5°;
        // the lower-half points ρL = 1 − l must stay above them.
        const double l_max = 100 * (1 - cut.culet / 100 / kC225);
        if (!(cut.lower_half < l_max))
            fail("lower-half length = " + num(cut.lower_half) + " % reaches the culet (culet " +
                 num(cut.culet) + " %): allowed range " + num(kLowerHalf.lo) + " to " +
                 num(std::floor(l_max * 100) / 100) + " %");
    }
    if (cut.girdle > 0) {
        const double g_min = min_girdle_percent(cut);
        if (!(cut.girdle > g_min))
            fail("girdle thickness = " + num(cut.girdle) +
                 " % is too thin: the upper and lower halves would meet across the girdle; allowed 0 (knife "
                 "edge) or " + num(std::ceil(std::max(g_min, kGirdle.lo) * 100) / 100) + " to " +
                 num(kGirdle.hi) + " % for these crown and pavilion facets and girdle (" +
                 girdle_description(cut) + ")");
    }
}

BrilliantProportions closed_form_proportions(const BrilliantCut& cut) {
    BrilliantProportions p;
    p.table = cut.table;
    p.crown_angle = cut.crown_angle;
    p.pavilion_angle = cut.pavilion_angle;
    p.star = cut.star;
    p.lower_half = cut.lower_half;
    p.girdle = cut.girdle;
    p.culet = cut.culet;
    p.crown_height = 100 * 0.5 * (1 - cut.table / 100) * std::tan(rad(cut.crown_angle));
    p.pavilion_depth = 100 * 0.5 * (1 - cut.culet / 100) * std::tan(rad(cut.pavilion_angle));
    p.total_depth = p.crown_height + p.girdle + p.pavilion_depth;
    return p;
}

std::string facet_kind(const std::string& label) {
    const auto pos = label.find_last_of(' ');
    if (pos == std::string::npos) return label;
    const std::string tail = label.substr(pos + 1);
    if (!tail.empty() && std::isdigit(static_cast<unsigned char>(tail[0]))) return label.substr(0, pos);
    return label;
}

std::vector<std::pair<std::string, int>> facet_counts(const Gem& gem) {
    static const char* const kOrder[] = {"table", "star", "bezel", "upper half",
                                         "girdle", "lower half", "pavilion main", "culet"};
    std::map<std::string, int> n;
    for (const auto& f : gem.facets) ++n[facet_kind(f.label)];
    std::vector<std::pair<std::string, int>> out;
    for (const char* k : kOrder)
        if (n.count(k)) out.emplace_back(k, n[k]);
    return out;
}

}  // namespace refract
