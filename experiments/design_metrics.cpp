#include <refract/experiments/design_metrics.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/threads.h>
#include <refract/geometry/gem/gemcad_names.h>
#include <refract/experiments/gem_observation.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>

namespace refract::experiments::design_metrics {

namespace {

// The unit outward normal of index i of tier t at angle `angle` (gemcad.h's frame; doubles:
// the pivot's plane, not the exact build, needs it).
Vec3 tier_normal(const GemcadDesign& d, const GemcadTier& t, double angle, double index) {
    const double a = angle * M_PI / 180, phi = (360.0 * (index - d.location) / d.gear - 90.0) * M_PI / 180;
    return Vec3(std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), t.pavilion ? -std::cos(a) : std::cos(a));
}

// Each swept facet's outermost point on the design's own stone (NaN: not on the stone).
std::vector<std::vector<Vec3>> pivots_of(const GemcadDesign& d, const std::vector<std::size_t>& tiers) {
    const DesignGem own = build_design(d);
    double size = 0;
    for (const Vec3& v : own.gem.mesh.vertices) size = std::max(size, v.norm());
    std::vector<std::vector<Vec3>> out;
    for (std::size_t k : tiers) {
        const GemcadTier& t = d.tiers[k];
        out.emplace_back();
        for (const double index : t.indices) {
            const Vec3 n = tier_normal(d, t, std::fabs(t.angle), index);
            Vec3 pivot = Vec3::Constant(std::nan(""));
            for (const GemFacet& f : own.gem.facets) {
                if ((f.plane.normal - n).norm() > 1e-9 || std::fabs(f.plane.offset - t.distance) > 1e-9 * size) continue;
                pivot = f.polygon.front();
                for (const Vec3& p : f.polygon)
                    if (t.pavilion ? p.z() > pivot.z() : p.z() < pivot.z()) pivot = p;
                break;
            }
            out.back().push_back(pivot);
        }
    }
    return out;
}

}  // namespace

DesignGem build_at_width_2(const GemcadDesign& design) {
    const DesignGem own = build_design(design);
    GemcadDesign scaled = design;
    const double s = 2.0 / own.width;
    for (GemcadTier& t : scaled.tiers) t.distance *= s;
    return build_design(scaled);
}

gem_metrics::MetricOptions options_for(const Gem& gem, gem_metrics::MetricOptions o) {
    double r = 0;
    for (const Vec3& v : gem.mesh.vertices) r = std::max(r, v.norm());
    o.frame = r;
    return o;
}

gem_metrics::GemMetrics measure(const DesignGem& stone, const gem_metrics::MetricOptions& options) {
    return gem_metrics::measure(stone.gem, options_for(stone.gem, options));
}

Image render_view(const DesignGem& stone, const std::string& view, int size, int samples,
                  const gem_metrics::MetricOptions& options) {
    return gem_metrics::render_view(stone.gem, view, size, samples, options_for(stone.gem, options));
}

TierSweep parse_tier_sweep(const GemcadDesign& design, const std::string& text, const gem_metrics::MetricOptions& metric) {
    const auto refuse = [&](const std::string& why) {
        throw InputError("--tier '" + clip_echo(text) + "': " + why);
    };
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) refuse("expected NAME:FROM:TO:STEP (a tier's name and its angles, e.g. P1:38:43:0.1)");
    const std::string name = text.substr(0, colon);
    TierSweep s;
    s.design = design;
    s.metric = metric;
    s.name = name;
    std::vector<std::string> names;  // each once, in file order
    for (std::size_t k = 0; k < design.tiers.size(); ++k) {
        const std::string n = design.tiers[k].name(static_cast<int>(k) + 1);
        if (n == name) s.tiers.push_back(k);
        if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    }
    for (std::size_t k = 0; k < design.tiers.size() && s.tiers.empty(); ++k)
        if (name == "tier " + std::to_string(k + 1)) s.tiers = {k};  // by its place in the file
    if (s.tiers.empty()) s.tiers = tiers_of_trade_name(design, name);  // P1, C2, T, G, CU by side and angle
    const auto listed = [](const std::vector<std::string>& all) {
        std::vector<std::string> once;
        for (const std::string& n : all)
            if (std::find(once.begin(), once.end(), n) == once.end()) once.push_back(n);
        std::string list;
        for (const std::string& n : once) list += (list.empty() ? "" : ", ") + clip_echo(n);
        return list;
    };
    std::string list = listed(names);
    const std::string trade = listed(trade_tier_names(design));
    if (trade != list) list += "; by side and angle: " + trade;
    if (s.tiers.empty()) refuse(design.source + " has no tier named '" + clip_echo(name) + "' (its tiers: " + list + ")");
    for (std::size_t k : s.tiers)
        if (design.tiers[k].pavilion != design.tiers[s.tiers[0]].pavilion) {
            refuse(design.source + ": tiers named '" + clip_echo(name) + "' lie on the crown and on the pavilion (lines " +
                   std::to_string(design.tiers[s.tiers[0]].line) + " and " + std::to_string(design.tiers[k].line) +
                   "): name one as 'tier N', N its place in the file");
        }
    s.angles = gem_sweep::parse_axis("tier", text.substr(colon + 1));
    s.pivots = pivots_of(design, s.tiers);
    for (const int i : {0, s.angles.count - 1})
        if (!(s.angles.value(i) >= 0 && s.angles.value(i) <= 90))
            refuse("the angles run from 0 to 90 degrees (the tier keeps its side, " +
                   std::string(design.tiers[s.tiers[0]].pavilion ? "pavilion" : "crown") + ")");
    gem_metrics::validate(metric);
    return s;
}

TierRow evaluate(const TierSweep& sweep, std::int64_t index) {
    TierRow r;
    r.index = index;
    r.angle = sweep.angles.value(static_cast<int>(index));
    GemcadDesign d = sweep.design;
    for (std::size_t m = 0; m < sweep.tiers.size(); ++m) {
        GemcadTier& t = d.tiers[sweep.tiers[m]];
        t.angle = r.angle;
        // One tier per facet that turns about its pivot: its own distance.
        GemcadTier one = t;
        t.indices.clear();
        t.names.clear();
        for (std::size_t j = 0; j < one.indices.size(); ++j) {
            const Vec3& p = sweep.pivots[m][j];
            if (std::isnan(p.x())) {
                t.indices.push_back(one.indices[j]);
                t.names.push_back(one.names[j]);
                continue;
            }
            GemcadTier f = one;
            f.indices = {one.indices[j]};
            f.names = {one.names[j].empty() ? one.name(static_cast<int>(sweep.tiers[m]) + 1) : one.names[j]};
            f.distance = tier_normal(d, one, r.angle, one.indices[j]).dot(p);
            d.tiers.push_back(f);
        }
    }
    // Tiers left without an index (every facet turned) go.
    d.tiers.erase(std::remove_if(d.tiers.begin(), d.tiers.end(), [](const GemcadTier& t) { return t.indices.empty(); }),
                  d.tiers.end());
    try {
        r.stone = build_at_width_2(d);
    } catch (const InputError& e) {
        r.reason = e.what();
        return r;
    }
    r.possible = true;
    r.metrics = measure(r.stone, sweep.metric);
    return r;
}

std::vector<TierRow> run(const TierSweep& sweep, int threads, const std::function<void(const TierRow&)>& done) {
    std::vector<TierRow> rows(static_cast<std::size_t>(sweep.angles.count));
    std::mutex lock;
    tbb::task_arena arena(worker_threads(threads));
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 1), [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                rows[i] = evaluate(sweep, static_cast<std::int64_t>(i));
                if (done) {
                    std::lock_guard<std::mutex> g(lock);
                    done(rows[i]);
                }
            }
        });
    });
    return rows;
}


std::string csv_text(const TierSweep& sweep, const std::vector<TierRow>& rows) {
    using gem_sweep::number;
    std::string s =
        "index,tier,angle,status,reason,facets,volume,length_over_width,height_over_width,"
        "light_return,light_return_error,fire,fire_error,leakage,leakage_error,scintillation,scintillation_error,"
        "aset_red,aset_green,aset_blue,aset_white,observer\n";
    const std::string tier = csv_quote(sweep.name);
    for (const TierRow& r : rows) {
        s += std::to_string(r.index) + "," + tier + "," + number(r.angle);
        if (!r.possible) {
            s += ",impossible," + csv_quote(r.reason) + std::string(17, ',') + "\n";
            continue;
        }
        const DesignGem& g = r.stone;
        s += ",ok,," + std::to_string(g.gem.facets.size()) + "," + number(g.volume) + "," + number(g.length / g.width) +
             "," + number(g.height / g.width);
        const auto& m = r.metrics;
        for (const auto* x : {&m.light_return, &m.fire, &m.leakage, &m.scintillation})
            s += "," + number(x->value) + "," + number(x->error);
        for (const double v : {m.aset.red, m.aset.green, m.aset.blue, m.aset.white}) s += "," + number(v);
        s += "," + csv_quote(m.observer) + "\n";
    }
    return s;
}

}  // namespace refract::experiments::design_metrics
