// gem-cuts under several observer models (issue 31; experiments/gem_cuts.h): the light
// return's map and table scan per observer, the nail-head and fish-eye detectors over a
// wider pavilion range, and the comparison with the published results.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_detectors.h>
#include <refract/experiments/gem_observation.h>

namespace refract::experiments::gem_cuts {

namespace sw = gem_sweep;

namespace {

// The light return only: fire and scintillation at their fewest pixels (their values are
// not used), every other setting as the map's.
gem_metrics::MetricOptions light_return_only(gem_metrics::MetricOptions m, const std::string& observer) {
    m.observer = observer;
    m.fire_divisor = m.rays;
    m.scintillation_divisor = m.rays;
    m.spot_rotations = 1;
    return m;
}

constexpr int kPhenomenaRays = 1024, kQuickPhenomenaRays = 64;
// The detector grid's and the renders' central-zone rays: four per light-return ray (4096
// at 1024 rays; the nail-head error, about 0.010, is then the rest of the face's; gem_detectors.h).
constexpr double kCentreShare = 4.0;

const MetricInfo kLightReturn{"light_return", "light return (brilliance)", true};

}  // namespace

const std::vector<std::string>& map_observers() {
    static const std::vector<std::string> o{"aset", "sasian", "hemisphere"};
    return o;
}

sw::Sweep phenomena_sweep(bool quick) {
    sw::Sweep s = crown_pavilion_sweep(quick);
    s.metric = light_return_only(s.metric, "aset");
    s.metric.rays = quick ? kQuickPhenomenaRays : kPhenomenaRays;
    s.metric.fire_divisor = s.metric.scintillation_divisor = s.metric.rays;
    s.metric.centre_share = kCentreShare;
    sw::set_axis(s.grid, sw::parse_axis("crown_angle", quick ? "29.5:34.5:5" : "24.5:39.5:2.5"));
    sw::set_axis(s.grid, sw::parse_axis("pavilion_angle", quick ? "37.75:43.75:3" : "37.25:43.75:0.5"));
    return s;
}

sw::Sweep table_sweep(bool quick) {
    sw::Sweep s = crown_pavilion_sweep(quick);
    sw::set_axis(s.grid, sw::parse_axis("crown_angle", sw::number(s.grid.base.crown_angle)));
    sw::set_axis(s.grid, sw::parse_axis("pavilion_angle", sw::number(s.grid.base.pavilion_angle)));
    sw::set_axis(s.grid, sw::parse_axis("table", quick ? "53:61:8" : "52:66:2"));
    return s;
}

const std::vector<std::string>& render_views() {
    static const std::vector<std::string> v{"aset", "ideal-scope", "brilliance"};
    return v;
}

std::vector<double> render_pavilions() { return {37.25, 40.75, 43.75}; }

std::vector<double> render_tilts() { return {0.0, 10.0, 20.0, 30.0}; }

const std::vector<std::string>& render_tilt_views() {
    static const std::vector<std::string> v{"aset", "ideal-scope"};
    return v;
}

BrilliantCut tolkowsky_with_girdle(double pavilion) {
    BrilliantCut c = brilliant_preset("tolkowsky");
    c.girdle = brilliant_preset("gia-default").girdle;
    c.pavilion_angle = pavilion;
    return c;
}

namespace {

void add_renders(Result& r) {
    r.render_size = r.quick ? 40 : 160;
    gem_metrics::MetricOptions m = light_return_only(r.main.metric, "aset");
    m.also_observers = other_observers();
    m.centre_share = kCentreShare;
    const auto pav = render_pavilions();
    for (size_t i = 0; i < pav.size(); ++i) {
        RenderedCut c;
        const BrilliantCut cut = tolkowsky_with_girdle(pav[i]);
        c.label = "pavilion " + sw::number(pav[i]) + "°";
        c.row = sw::evaluate_cut(cut, m);
        if (c.row.possible) {
            const Gem gem = build_brilliant(cut);
            for (const std::string& v : render_views())
                c.views.emplace_back(v, gem_metrics::render_view(gem, v, r.render_size, 1, m));
            for (const std::string& v : render_tilt_views()) {
                // Tilt 0 is the face-up image already rendered (render_view: to the bit).
                const Image* up = nullptr;
                for (const auto& [name, img] : c.views)
                    if (name == v) up = &img;
                std::vector<std::pair<double, Image>> series;
                for (const double tilt : render_tilts())
                    series.emplace_back(tilt, tilt == 0.0 && up ? *up
                                                                : gem_metrics::render_view(gem, v, r.render_size, 1, m, tilt));
                c.tilts.emplace_back(v, std::move(series));
            }
        }
        r.renders.push_back(std::move(c));
    }
}

}  // namespace

std::vector<std::string> other_observers() {
    return {map_observers().begin() + 1, map_observers().end()};
}

namespace {

// A row as the observer model `k` of map_observers() saw it: k > 0 takes the light return
// and nail-head measured on the same rays under the further model (MetricOptions::also_observers).
sw::Row under(sw::Row row, size_t k) {
    if (k == 0 || !row.possible) {
        if (k > 0) row.metrics.observer = map_observers()[k];
        return row;
    }
    const auto& a = row.metrics.also.at(k - 1);
    row.metrics.light_return = a.light_return;
    row.metrics.nail_head = a.nail_head;
    row.metrics.obstruction = a.obstruction;
    row.metrics.observer = a.observer;
    return row;
}

std::vector<sw::Row> under(const std::vector<sw::Row>& rows, size_t k) {
    std::vector<sw::Row> out;
    out.reserve(rows.size());
    for (const auto& row : rows) out.push_back(under(row, k));
    return out;
}

}  // namespace

void add_observer_maps(Result& r, int threads) {
    add_renders(r);
    sw::Sweep table = table_sweep(r.quick);
    table.metric.also_observers = other_observers();
    const std::vector<sw::Row> table_rows = sw::run(table, sw::all_indices(table), threads);
    sw::Sweep p = phenomena_sweep(r.quick);
    p.metric.also_observers = other_observers();
    const std::vector<sw::Row> phenomena = sw::run(p, sw::all_indices(p), threads);
    for (size_t k = 0; k < map_observers().size(); ++k) {
        ObserverMap m;
        m.observer = map_observers()[k];
        m.rows = under(r.main_rows, k);
        m.table_rows = under(table_rows, k);
        m.tolkowsky = under(r.presets.at(0).second, k);
        m.phenomena = under(phenomena, k);
        m.light_return = optimum_of(kLightReturn, m.rows, m.tolkowsky, r.main.grid);
        m.obstruction = obstruction_count(m.phenomena);
        for (const auto& x : m.phenomena) m.nail_head_undecided += x.possible && !gem_metrics::nail_head_decided(x.metrics.nail_head);
        r.nail_head_onset.push_back(nail_head_onsets(p, m.phenomena));
        r.fish_eye_limit.push_back(fish_eye_limits(p, m.phenomena));
        r.observers.push_back(std::move(m));
    }
}

namespace {

// The detector's firing along the pavilion axis at each crown of the grid: fires[c][p].
std::vector<std::vector<bool>> firing(const sw::Sweep& s, const std::vector<sw::Row>& rows, bool nail) {
    const sw::Axis &ac = s.grid.axes[1], &ap = s.grid.axes[2];
    std::vector<std::vector<bool>> f(static_cast<size_t>(ac.count), std::vector<bool>(static_cast<size_t>(ap.count), false));
    for (const auto& row : rows) {
        if (!row.possible) continue;
        const std::int64_t i = row.index % (static_cast<std::int64_t>(ac.count) * ap.count);
        const size_t c = static_cast<size_t>(i / ap.count), p = static_cast<size_t>(i % ap.count);
        f[c][p] = nail ? gem_metrics::shows_nail_head(row.metrics.nail_head) : gem_metrics::shows_fish_eye(row.metrics.fish_eye);
    }
    return f;
}

}  // namespace

ObstructionCount obstruction_count(const std::vector<sw::Row>& rows) {
    ObstructionCount c;
    for (const auto& row : rows) {
        if (!row.possible) continue;
        const double v = row.metrics.obstruction.value;
        if (c.cuts == 0) c.lo = c.hi = v;
        c.lo = std::min(c.lo, v);
        c.hi = std::max(c.hi, v);
        ++c.cuts;
        c.firing += gem_metrics::shows_obstruction(row.metrics.obstruction);
        c.near += std::fabs(v - gem_metrics::kObstructionThreshold) < 2 * row.metrics.obstruction.error;
    }
    return c;
}

std::vector<Onset> nail_head_onsets(const sw::Sweep& s, const std::vector<sw::Row>& rows) {
    const auto f = firing(s, rows, true);
    const sw::Axis &ac = s.grid.axes[1], &ap = s.grid.axes[2];
    std::vector<Onset> out;
    for (int c = 0; c < ac.count; ++c) {
        Onset o{ac.value(c), std::nan("")};
        for (int p = ap.count - 1; p >= 0 && f[static_cast<size_t>(c)][static_cast<size_t>(p)]; --p) o.pavilion = ap.value(p);
        out.push_back(o);
    }
    return out;
}

std::vector<Onset> fish_eye_limits(const sw::Sweep& s, const std::vector<sw::Row>& rows) {
    const auto f = firing(s, rows, false);
    const sw::Axis &ac = s.grid.axes[1], &ap = s.grid.axes[2];
    std::vector<Onset> out;
    for (int c = 0; c < ac.count; ++c) {
        Onset o{ac.value(c), std::nan("")};
        for (int p = 0; p < ap.count && f[static_cast<size_t>(c)][static_cast<size_t>(p)]; ++p) o.pavilion = ap.value(p);
        out.push_back(o);
    }
    return out;
}

std::pair<Slope, Slope> crown_pavilion_slopes(const std::vector<sw::Row>& rows, const std::string& metric) {
    std::vector<const sw::Row*> ok;
    for (const auto& row : rows)
        if (row.possible) ok.push_back(&row);
    const int n = static_cast<int>(ok.size());
    if (n < 4) return {};
    Eigen::MatrixXd X(n, 3);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) {
        X(i, 0) = 1;
        X(i, 1) = ok[static_cast<size_t>(i)]->cut.crown_angle;
        X(i, 2) = ok[static_cast<size_t>(i)]->cut.pavilion_angle;
        y(i) = metric_of(ok[static_cast<size_t>(i)]->metrics, metric).value;
    }
    const Eigen::Matrix3d A = X.transpose() * X;
    if (std::fabs(A.determinant()) < 1e-12) return {};
    const Eigen::Matrix3d Ai = A.inverse();
    const Eigen::Vector3d b = Ai * (X.transpose() * y);
    const double s2 = (y - X * b).squaredNorm() / (n - 3);
    return {{b(1), std::sqrt(s2 * Ai(1, 1))}, {b(2), std::sqrt(s2 * Ai(2, 2))}};
}

Slope table_slope(const std::vector<sw::Row>& rows, const std::string& metric) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (const auto& row : rows)
        if (row.possible) {
            const double x = row.cut.table, y = metric_of(row.metrics, metric).value;
            sx += x;
            sy += y;
            sxx += x * x;
            sxy += x * y;
            ++n;
        }
    if (n < 2) return {};
    const double d = n * sxx - sx * sx;
    if (!(d > 0)) return {};
    const double b = (n * sxy - sx * sy) / d, a = (sy - b * sx) / n;
    if (n < 3) return {b, 0};
    double rss = 0;
    for (const auto& row : rows)
        if (row.possible) {
            const double e = metric_of(row.metrics, metric).value - a - b * row.cut.table;
            rss += e * e;
        }
    return {b, std::sqrt(rss / (n - 2) * n / d)};
}

}  // namespace refract::experiments::gem_cuts
