#include <refract/experiments/gem_sweep.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/threads.h>
#include <refract/geometry/error.h>

namespace refract::experiments::gem_sweep {

namespace {

constexpr int kMaxDecimals = 6;
constexpr std::int64_t kMaxValues = 1000000;
constexpr std::int64_t kMaxCuts = 100000000;
constexpr std::int64_t kMaxUnits = 1000000000000000;  // 10^15: a value's magnitude in units of 10^-decimals

std::int64_t pow10(int d) {
    std::int64_t p = 1;
    for (int i = 0; i < d; ++i) p *= 10;
    return p;
}

// "-12.345" -> (-12345, 3); nullopt-like failure as ok = false.
struct Decimal {
    std::int64_t units = 0;
    int decimals = 0;
    bool ok = false;
};
Decimal parse_decimal(const std::string& s) {
    Decimal d;
    size_t i = 0;
    bool negative = false;
    if (i < s.size() && (s[i] == '-' || s[i] == '+')) negative = s[i++] == '-';
    std::int64_t units = 0;
    int digits = 0, decimals = 0;
    bool point = false;
    for (; i < s.size(); ++i) {
        const char c = s[i];
        if (c == '.' && !point) {
            point = true;
            continue;
        }
        if (c < '0' || c > '9') return d;
        if (++digits > 15) return d;
        units = units * 10 + (c - '0');
        if (point) ++decimals;
    }
    if (digits == 0 || decimals > kMaxDecimals) return d;
    d.units = negative ? -units : units;
    d.decimals = decimals;
    d.ok = true;
    return d;
}

double& field(BrilliantCut& cut, const std::string& name) {
    if (name == "table") return cut.table;
    if (name == "crown_angle") return cut.crown_angle;
    if (name == "pavilion_angle") return cut.pavilion_angle;
    if (name == "star") return cut.star;
    if (name == "lower_half") return cut.lower_half;
    return cut.girdle;
}

std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}


}  // namespace

double Axis::value(int i) const {
    return static_cast<double>(start + step * i) / static_cast<double>(pow10(decimals));
}

std::string Axis::text() const {
    const auto show = [&](std::int64_t u) {
        const std::int64_t p = pow10(decimals);
        std::string s = (u < 0 ? "-" : "") + std::to_string(std::abs(u) / p);
        if (decimals > 0) {
            std::string frac = std::to_string(std::abs(u) % p);
            frac = std::string(decimals - frac.size(), '0') + frac;
            while (!frac.empty() && frac.back() == '0') frac.pop_back();
            if (!frac.empty()) s += "." + frac;
        }
        return s;
    };
    if (count == 1) return show(start);
    return show(start) + ":" + show(start + step * (count - 1)) + ":" + show(step);
}

const std::vector<std::string>& parameter_names() {
    static const std::vector<std::string> names{"table", "crown_angle", "pavilion_angle", "star", "lower_half", "girdle"};
    return names;
}

std::string option_name(const std::string& parameter) {
    std::string o = "--" + parameter;
    std::replace(o.begin(), o.end(), '_', '-');
    return o;
}

Axis parse_axis(const std::string& parameter, const std::string& text) {
    const std::string opt = option_name(parameter);
    const auto fail = [&](const std::string& why) {
        throw InputError(opt + " '" + text + "': " + why + " (expected START:STOP:STEP or a single value, e.g. 38:43:0.1)");
    };
    std::vector<std::string> parts;
    size_t b = 0;
    for (size_t i = 0; i <= text.size(); ++i)
        if (i == text.size() || text[i] == ':') {
            parts.push_back(text.substr(b, i - b));
            b = i + 1;
        }
    if (parts.size() != 1 && parts.size() != 3) fail("wrong number of fields");
    std::vector<Decimal> d;
    for (const auto& p : parts) {
        d.push_back(parse_decimal(p));
        if (!d.back().ok) fail("'" + p + "' is not a decimal number with at most " + std::to_string(kMaxDecimals) + " decimals");
    }
    Axis a;
    a.name = parameter;
    for (const auto& x : d) a.decimals = std::max(a.decimals, x.decimals);
    // Each value in units of 10^-decimals must stay within ±10^15 (so that STOP − START and
    // START + STEP·i fit an int64): checked before the multiplication that could overflow.
    for (size_t k = 0; k < d.size(); ++k)
        if (std::abs(d[k].units) > kMaxUnits / pow10(a.decimals - d[k].decimals))
            fail("'" + parts[k] + "' is too large: with " + std::to_string(a.decimals) +
                 " decimals a value stays below 1e" + std::to_string(15 - a.decimals));
    const auto units = [&](const Decimal& x) { return x.units * pow10(a.decimals - x.decimals); };
    a.start = units(d[0]);
    if (parts.size() == 1) return a;
    const std::int64_t stop = units(d[1]);
    a.step = units(d[2]);
    if (a.step <= 0) fail("STEP must be positive");
    if (stop < a.start) fail("STOP is below START");
    const std::int64_t n = (stop - a.start) / a.step + 1;
    if (n > kMaxValues) fail("more than " + std::to_string(kMaxValues) + " values");
    a.count = static_cast<int>(n);
    if (a.count == 1) a.step = 0;
    return a;
}

std::int64_t Grid::size() const {
    std::int64_t n = 1;
    for (const Axis& a : axes) n *= a.count;
    return n;
}

BrilliantCut Grid::cut(std::int64_t index) const {
    BrilliantCut c = base;
    for (size_t k = axes.size(); k-- > 0;) {
        const Axis& a = axes[k];
        field(c, a.name) = a.value(static_cast<int>(index % a.count));
        index /= a.count;
    }
    return c;
}

Grid single_cut_grid(const BrilliantCut& base) {
    Grid g;
    g.base = base;
    for (const auto& name : parameter_names()) {
        // The base value as an exact decimal: its shortest round-trip text.
        Axis a = parse_axis(name, number(field(g.base, name)));
        g.axes.push_back(a);
    }
    return g;
}

void set_axis(Grid& grid, const Axis& axis) {
    for (Axis& a : grid.axes)
        if (a.name == axis.name) a = axis;
    if (grid.size() > kMaxCuts)
        throw InputError(option_name(axis.name) + " '" + axis.text() + "': the grid would hold " +
                         std::to_string(grid.size()) + " cuts, more than " + std::to_string(kMaxCuts));
}

std::string fingerprint(const Sweep& s) {
    std::string f = "refract sweep brilliant v5";  // v2: the ASET and balance columns; v3: the observer; v4: the detectors; v5: obstruction
    for (const Axis& a : s.grid.axes) f += " " + a.name + "=" + a.text();
    const BrilliantCut& b = s.grid.base;
    f += " culet=" + number(b.culet) + " girdle_facets=" + std::to_string(b.girdle_facets) +
         " bruted_planes=" + std::to_string(b.bruted_planes);
    f += " material=" + s.metric.material + " rays=" + std::to_string(s.metric.rays) +
         " wavelengths=" + std::to_string(s.metric.wavelengths) +
         " polarisation=" + (s.metric.exact_polarisation ? "exact" : "natural") +
         " seed=" + std::to_string(s.metric.seed) + " observer=" + s.metric.observer;
    return f;
}

std::uint64_t cut_seed(std::uint64_t base, const BrilliantCut& c) {
    std::uint64_t h = splitmix(base);
    for (const double v : {c.table, c.crown_angle, c.pavilion_angle, c.star, c.lower_half, c.girdle, c.culet}) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        h = splitmix(h ^ bits);
    }
    h = splitmix(h ^ static_cast<std::uint64_t>(c.girdle_facets) ^ (static_cast<std::uint64_t>(c.bruted_planes) << 32));
    return h;
}

Row evaluate_cut(const BrilliantCut& cut, const gem_metrics::MetricOptions& metric) {
    Row r;
    r.cut = cut;
    Gem gem;
    try {
        gem = build_brilliant(cut);  // validates first
    } catch (const InputError& e) {
        r.reason = e.what();
        return r;
    }
    r.possible = true;
    r.measured = gem.measured;
    gem_metrics::MetricOptions m = metric;
    m.seed = cut_seed(metric.seed, cut);
    r.metrics = gem_metrics::measure(gem, m);
    return r;
}

Row evaluate(const Sweep& sweep, std::int64_t index) {
    Row r = evaluate_cut(sweep.grid.cut(index), sweep.metric);
    r.index = index;
    return r;
}

std::vector<std::int64_t> all_indices(const Sweep& sweep) {
    std::vector<std::int64_t> v(static_cast<size_t>(sweep.grid.size()));
    for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<std::int64_t>(i);
    return v;
}

std::vector<Row> run(const Sweep& sweep, const std::vector<std::int64_t>& indices, int threads,
                     const std::function<void(const Row&)>& done) {
    std::vector<Row> rows(indices.size());
    std::mutex lock;
    tbb::task_arena arena(worker_threads(threads));
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, indices.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                rows[i] = evaluate(sweep, indices[i]);
                if (done) {
                    std::lock_guard<std::mutex> g(lock);
                    done(rows[i]);
                }
            }
        });
    });
    return rows;
}

std::string number(double v) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

}  // namespace refract::experiments::gem_sweep
