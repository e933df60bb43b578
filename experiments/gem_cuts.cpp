#include <refract/experiments/gem_cuts.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <refract/geometry/error.h>

namespace refract::experiments::gem_cuts {

namespace sw = gem_sweep;

const std::vector<MetricInfo>& metrics() {
    static const std::vector<MetricInfo> m{{"light_return", "light return (brilliance)", true},
                                           {"fire", "fire (dispersed coloured light return)", true},
                                           {"leakage", "leakage through the pavilion", false},
                                           {"scintillation", "scintillation", true}};
    return m;
}

const gem_metrics::Metric& metric_of(const gem_metrics::GemMetrics& g, const std::string& key) {
    if (key == "light_return") return g.light_return;
    if (key == "fire") return g.fire;
    if (key == "leakage") return g.leakage;
    if (key == "nail_head") return g.nail_head;
    if (key == "fish_eye") return g.fish_eye;
    if (key == "obstruction") return g.obstruction;
    return g.scintillation;
}

namespace {

// Reproduce's ray count per metric, and the quick one; 31 wavelengths, exact polarisation.
constexpr int kRays = 1024, kQuickRays = 64;

sw::Sweep base_sweep(bool quick) {
    sw::Sweep s;
    s.grid = sw::single_cut_grid(brilliant_preset("gia-default"));
    s.metric.rays = quick ? kQuickRays : kRays;
    s.metric.wavelengths = quick ? 3 : 31;
    return s;
}

// True when `a` is better than `b` for the metric.
bool better(const MetricInfo& m, double a, double b) { return m.maximise ? a > b : a < b; }

}  // namespace

sw::Sweep crown_pavilion_sweep(bool quick) {
    sw::Sweep s = base_sweep(quick);
    sw::set_axis(s.grid, sw::parse_axis("crown_angle", quick ? "30:38:4" : "20:41:1"));
    sw::set_axis(s.grid, sw::parse_axis("pavilion_angle", quick ? "39:42:1.5" : "38:43.75:0.25"));
    return s;
}

sw::Sweep star_lower_half_sweep(bool quick) {
    sw::Sweep s = base_sweep(quick);
    sw::set_axis(s.grid, sw::parse_axis("star", quick ? "45:65:20" : "40:70:5"));
    sw::set_axis(s.grid, sw::parse_axis("lower_half", quick ? "70:90:20" : "65:90:5"));
    return s;
}

sw::Sweep full_sweep() {
    sw::Sweep s = base_sweep(false);
    s.metric.rays = 4096;
    sw::set_axis(s.grid, sw::parse_axis("table", "52:66:1"));
    sw::set_axis(s.grid, sw::parse_axis("crown_angle", "23:41:0.5"));
    sw::set_axis(s.grid, sw::parse_axis("pavilion_angle", "38:43:0.1"));
    return s;
}

std::string command_of(const sw::Sweep& s, const std::string& output) {
    const sw::Sweep base = base_sweep(false);
    std::string c = "refract sweep brilliant";
    for (size_t k = 0; k < s.grid.axes.size(); ++k)
        if (s.grid.axes[k].text() != base.grid.axes[k].text())
            c += " " + sw::option_name(s.grid.axes[k].name) + " " + s.grid.axes[k].text();
    c += " --rays " + std::to_string(s.metric.rays);
    if (s.metric.wavelengths != 31) c += " --wavelengths " + std::to_string(s.metric.wavelengths);
    return c + " -o " + output;
}

Edge edge_of(const sw::Grid& grid, const BrilliantCut& cut) {
    const sw::Axis &c = grid.axes[1], &p = grid.axes[2];
    auto near = [](double a, double b) { return std::fabs(a - b) <= 1e-9; };
    Edge e;
    if (c.count > 1) {
        e.crown_low = near(cut.crown_angle, c.value(0));
        e.crown_high = near(cut.crown_angle, c.value(c.count - 1));
    }
    if (p.count > 1) {
        e.pavilion_low = near(cut.pavilion_angle, p.value(0));
        e.pavilion_high = near(cut.pavilion_angle, p.value(p.count - 1));
    }
    return e;
}

Edge builder_limits(const sw::Grid& grid, const BrilliantCut& cut, const Edge& e) {
    const sw::Axis &c = grid.axes[1], &p = grid.axes[2];
    auto refused = [&](double BrilliantCut::*field, const sw::Axis& a, double sign) {
        if (a.count < 2) return false;
        BrilliantCut beyond = cut;
        beyond.*field += sign * (a.value(1) - a.value(0));
        try {
            validate(beyond);
            return false;
        } catch (const InputError&) {
            return true;
        }
    };
    Edge l;
    l.crown_low = e.crown_low && refused(&BrilliantCut::crown_angle, c, -1);
    l.crown_high = e.crown_high && refused(&BrilliantCut::crown_angle, c, 1);
    l.pavilion_low = e.pavilion_low && refused(&BrilliantCut::pavilion_angle, p, -1);
    l.pavilion_high = e.pavilion_high && refused(&BrilliantCut::pavilion_angle, p, 1);
    return l;
}

Optimum optimum_of(const MetricInfo& m, const std::vector<sw::Row>& rows, const sw::Row& tolk, const sw::Grid& grid) {
    std::vector<const sw::Row*> ok;
    for (const auto& row : rows)
        if (row.possible) ok.push_back(&row);
    // Best first; ties by index (deterministic).
    std::stable_sort(ok.begin(), ok.end(), [&](const sw::Row* a, const sw::Row* b) {
        return better(m, metric_of(a->metrics, m.key).value, metric_of(b->metrics, m.key).value);
    });
    Optimum o;
    o.metric = m.key;
    o.observer = tolk.metrics.observer;
    if (!ok.empty()) o.best = *ok.front();
    for (size_t i = 0; i < ok.size() && i < 5; ++i) o.top.push_back(*ok[i]);
    o.tolkowsky = metric_of(tolk.metrics, m.key);
    o.d_crown = o.best.cut.crown_angle - tolk.cut.crown_angle;
    o.d_pavilion = o.best.cut.pavilion_angle - tolk.cut.pavilion_angle;
    const gem_metrics::Metric& b = metric_of(o.best.metrics, m.key);
    const double se = std::hypot(b.error, o.tolkowsky.error);
    o.sigmas = se > 0 ? (b.value - o.tolkowsky.value) / se : 0;
    o.edge = edge_of(grid, o.best.cut);
    o.builder_limit = builder_limits(grid, o.best.cut, o.edge);
    return o;
}

Result compute(const ExperimentOptions& opt) {
    const auto t0 = std::chrono::steady_clock::now();
    Result r;
    r.quick = opt.quick;
    r.main = crown_pavilion_sweep(opt.quick);
    r.detail = star_lower_half_sweep(opt.quick);
    r.main.metric.also_observers = other_observers();  // the observer maps on the same rays
    r.main_rows = sw::run(r.main, sw::all_indices(r.main), opt.threads);
    r.detail_rows = sw::run(r.detail, sw::all_indices(r.detail), opt.threads);
    for (const char* p : {"tolkowsky", "gia-default"})
        r.presets.emplace_back(p, sw::evaluate_cut(brilliant_preset(p), r.main.metric));
    for (const auto& row : r.main_rows) r.impossible += !row.possible;
    const sw::Row& tolk = r.presets[0].second;

    for (const MetricInfo& m : metrics()) {
        std::vector<const sw::Row*> ok;
        for (const auto& row : r.main_rows)
            if (row.possible) ok.push_back(&row);
        r.optima.push_back(optimum_of(m, r.main_rows, tolk, r.main.grid));

        Sensitivity s;
        s.metric = m.key;
        s.min = std::numeric_limits<double>::infinity();
        s.max = -s.min;
        int n = 0;
        for (const auto& row : r.detail_rows) {
            if (!row.possible) continue;
            const auto& v = metric_of(row.metrics, m.key);
            s.min = std::min(s.min, v.value);
            s.max = std::max(s.max, v.value);
            s.mean_error += v.error;
            ++n;
        }
        if (n > 0) s.mean_error /= n;
        else s.min = s.max = 0;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const sw::Row* row : ok) {
            lo = std::min(lo, metric_of(row->metrics, m.key).value);
            hi = std::max(hi, metric_of(row->metrics, m.key).value);
        }
        s.crown_pavilion_spread = ok.empty() ? 0 : hi - lo;
        r.sensitivity.push_back(s);
    }
    const auto t1 = std::chrono::steady_clock::now();
    add_observer_maps(r, opt.threads);
    r.observer_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    r.literature = literature(r);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.findings = judge(r);
    return r;
}

Findings judge(const Result& r) {
    Findings f;
    if (r.presets.size() >= 2) {
        const BrilliantCut &a = r.presets[0].second.cut, &b = r.presets[1].second.cut;
        f.presets_share_angles = a.crown_angle == b.crown_angle && a.pavilion_angle == b.pavilion_angle;
    }
    for (const auto& x : r.observers)
        for (const auto& y : r.observers)
            f.optimum_spread_deg =
                std::max(f.optimum_spread_deg, std::hypot(x.light_return.best.cut.crown_angle - y.light_return.best.cut.crown_angle,
                                                          x.light_return.best.cut.pavilion_angle -
                                                              y.light_return.best.cut.pavilion_angle));
    return f;
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::gem_cuts
