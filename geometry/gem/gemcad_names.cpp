// The trade's tier names of a design (gemcad_names.h).
#include <algorithm>
#include <cmath>

#include <refract/geometry/gem/gemcad_names.h>

namespace refract {
namespace {

constexpr double kSameAngle = 1e-9;  // degrees

// The distinct angles of one side's rows (0 < angle < 90), descending.
std::vector<double> row_angles(const GemcadDesign& d, bool pavilion) {
    std::vector<double> a;
    for (const GemcadTier& t : d.tiers)
        if (t.pavilion == pavilion && t.angle > 0 && t.angle < 90) a.push_back(t.angle);
    std::sort(a.begin(), a.end(), [](double x, double y) { return x > y; });
    std::vector<double> out;
    for (double v : a)
        if (out.empty() || out.back() - v > kSameAngle) out.push_back(v);
    return out;
}

}  // namespace

std::vector<std::string> trade_tier_names(const GemcadDesign& d) {
    const std::vector<double> crown = row_angles(d, false), pavilion = row_angles(d, true);
    std::vector<std::string> names;
    for (const GemcadTier& t : d.tiers) {
        if (t.angle >= 90) {
            names.push_back("G");
        } else if (t.angle <= 0) {
            names.push_back(t.pavilion ? "CU" : "T");
        } else {
            const std::vector<double>& rows = t.pavilion ? pavilion : crown;
            std::size_t k = 0;
            while (k + 1 < rows.size() && rows[k] - t.angle > kSameAngle) ++k;
            names.push_back((t.pavilion ? "P" : "C") + std::to_string(k + 1));
        }
    }
    return names;
}

std::vector<std::size_t> tiers_of_trade_name(const GemcadDesign& d, const std::string& name) {
    const std::vector<std::string> names = trade_tier_names(d);
    std::vector<std::size_t> out;
    for (std::size_t k = 0; k < names.size(); ++k)
        if (names[k] == name) out.push_back(k);
    return out;
}

}  // namespace refract
