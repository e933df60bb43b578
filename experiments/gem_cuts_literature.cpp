// gem-cuts: the published qualitative results against the experiment's numbers (issue 31;
// experiments/gem_cuts.h, docs/gem-metrics.md "The literature side by side"). Every mark is
// a predicate on the Result; the words around it are chosen by the marks.
#include <algorithm>
#include <cmath>

#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_detectors.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::gem_cuts {

namespace sw = gem_sweep;

namespace {

std::string deg(double v) { return std::isnan(v) ? std::string("none in the grid") : fmt(v, 4) + "°"; }
std::string slope_text(const Slope& s, const std::string& unit) {
    return fmt(s.value, 3) + " ± " + fmt(s.error, 2) + " per " + unit;
}

// The onset at Tolkowsky's crown angle (34.5°), NaN when the detector grid lacks it.
double at_tolkowsky_crown(const std::vector<Onset>& onsets) {
    for (const Onset& o : onsets)
        if (std::fabs(o.crown - 34.5) < 1e-9) return o.pavilion;
    return std::nan("");
}

// Pearson correlation of crown and pavilion angle over the best tenth (at least five) of
// the map's possible cuts by light return.
double top_correlation(const std::vector<sw::Row>& rows) {
    std::vector<const sw::Row*> ok;
    for (const auto& row : rows)
        if (row.possible) ok.push_back(&row);
    std::stable_sort(ok.begin(), ok.end(), [](const sw::Row* a, const sw::Row* b) {
        return a->metrics.light_return.value > b->metrics.light_return.value;
    });
    const size_t n = std::min(ok.size(), std::max<size_t>(5, ok.size() / 10));
    if (n < 3) return 0;
    double mx = 0, my = 0;
    for (size_t i = 0; i < n; ++i) {
        mx += ok[i]->cut.crown_angle;
        my += ok[i]->cut.pavilion_angle;
    }
    mx /= n;
    my /= n;
    double sxy = 0, sxx = 0, syy = 0;
    for (size_t i = 0; i < n; ++i) {
        const double dx = ok[i]->cut.crown_angle - mx, dy = ok[i]->cut.pavilion_angle - my;
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    return sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : 0;
}

}  // namespace

// The limits the marks use (docs/gem-metrics.md, "The literature side by side").
constexpr double kBetterShare = 0.10;   // Tolkowsky among the best: < 10 % of the cuts brighter by 2σ
constexpr double kLineCorrelation = -0.3;  // the best tenth along a falling crown–pavilion line
constexpr double kNailLow = 41.5, kNailHigh = 43.5;  // "steeper than about 42–43°"
constexpr double kFishLow = 38.0, kFishHigh = 39.5;  // "shallower than about 39°"

std::vector<LiteratureRow> literature(const Result& r) {
    std::vector<LiteratureRow> out;
    const size_t K = r.observers.size();
    auto row = [&](std::string key, std::string claim, std::string measure, bool dependent) {
        LiteratureRow x;
        x.key = std::move(key);
        x.claim = std::move(claim);
        x.measure = std::move(measure);
        x.observer_dependent = dependent;
        return x;
    };

    LiteratureRow best = row("tolkowsky_among_best",
                             "Tolkowsky's cut lies among the best (Sasian et al. 2007)",
                             "fewer than 10 % of the map's cuts have a light return above Tolkowsky's by more than "
                             "2 combined standard errors",
                             true);
    LiteratureRow line = row("main_cutters_line",
                             "the best cuts lie along a \"main cutter's line\", a steeper pavilion with a shallower "
                             "crown (Sasian et al. 2007; the falling line is refract's reading)",
                             "crown and pavilion angle of the best tenth of the map's cuts (light return) correlate "
                             "below -0.3",
                             true);
    LiteratureRow crown = row("wlr_shallow_crown",
                              "light return (WLR) is highest for shallow crowns and falls as the crown angle rises "
                              "(Hemphill et al. 1998)",
                              "the least-squares slope of the light return over the crown angle (with the pavilion "
                              "angle as a second regressor) is below zero by more than 2 standard errors",
                              true);
    LiteratureRow pav = row("wlr_pavilion_38_42",
                            "the highest WLR lies at pavilion angles of 38–42° (Hemphill et al. 1998)",
                            "the map's best light return lies at a pavilion angle within 38–42°", true);
    LiteratureRow table = row("wlr_small_table",
                              "WLR is highest for small tables, below about 57 % (Hemphill et al. 1998)",
                              "the slope of the light return over the table (52–66 %, GIA default angles) is below "
                              "zero by more than 2 standard errors",
                              true);
    LiteratureRow fcrown = row("dclr_steep_crown",
                               "fire (DCLR) rises with the crown angle, so WLR and DCLR are best at different "
                               "proportions (Reinitz et al. 2001)",
                               "the slope of fire over the crown angle is above zero by more than 2 standard errors "
                               "(spot lighting: the same under every observer)",
                               false);
    LiteratureRow ftable = row("dclr_small_table", "DCLR is higher for smaller tables (Reinitz et al. 2001)",
                               "the slope of fire over the table is below zero by more than 2 standard errors (the "
                               "same under every observer)",
                               false);
    LiteratureRow nail = row("nail_head_steep",
                             "pavilions steeper than about 42–43° show a nail-head (Sasian et al. 2007; the grading "
                             "laboratories' pavilion ranges)",
                             "at Tolkowsky's crown (34.5°) the nail-head detector fires from a pavilion angle within "
                             "41.5–43.5° on",
                             true);
    LiteratureRow fish = row("fish_eye_shallow",
                             "pavilions shallower than about 39° show a fish-eye (the grading laboratories' pavilion "
                             "ranges)",
                             "at Tolkowsky's crown the fish-eye detector fires up to a pavilion angle within "
                             "38–39.5°",
                             true);
    LiteratureRow clean = row("tolkowsky_clean", "Tolkowsky's proportions show neither a nail-head nor a fish-eye",
                              "neither detector fires on the detector grid's cut at Tolkowsky's angles (crown 34.5°, "
                              "pavilion 40.75°; the GIA default's table and girdle)",
                              true);

    for (size_t k = 0; k < K; ++k) {
        const ObserverMap& om = r.observers[k];
        const gem_metrics::Metric t = om.tolkowsky.metrics.light_return;
        int brighter = 0, n = 0;
        for (const auto& x : om.rows)
            if (x.possible) {
                ++n;
                const auto& v = x.metrics.light_return;
                brighter += v.value - t.value > 2 * std::hypot(v.error, t.error);
            }
        const double share = n > 0 ? static_cast<double>(brighter) / n : 0;
        best.agrees.push_back(share < kBetterShare);
        best.numbers.push_back(std::to_string(brighter) + " of " + std::to_string(n) + " cuts (" + fmt(100 * share, 2) +
                               " %)");

        const double c = top_correlation(om.rows);
        line.agrees.push_back(c < kLineCorrelation);
        line.numbers.push_back("r = " + fmt(c, 2));

        const Slope sc = crown_pavilion_slopes(om.rows, "light_return").first;
        crown.agrees.push_back(sc.falls());
        crown.numbers.push_back(slope_text(sc, "degree"));

        const double bp = om.light_return.best.cut.pavilion_angle;
        pav.agrees.push_back(bp >= 38.0 - 1e-9 && bp <= 42.0 + 1e-9);
        pav.numbers.push_back("best at " + deg(bp));

        const Slope st = table_slope(om.table_rows, "light_return");
        table.agrees.push_back(st.falls());
        table.numbers.push_back(slope_text(st, "table %"));

        const ObserverMap& a = r.observers.front();  // fire: the aset run's full metrics
        const Slope fc = crown_pavilion_slopes(a.rows, "fire").first;
        fcrown.agrees.push_back(fc.rises());
        fcrown.numbers.push_back(slope_text(fc, "degree"));
        const Slope ft = table_slope(a.table_rows, "fire");
        ftable.agrees.push_back(ft.falls());
        ftable.numbers.push_back(slope_text(ft, "table %"));

        const double on = k < r.nail_head_onset.size() ? at_tolkowsky_crown(r.nail_head_onset[k]) : std::nan("");
        nail.agrees.push_back(on >= kNailLow - 1e-9 && on <= kNailHigh + 1e-9);
        nail.numbers.push_back("from " + deg(on));
        const double lim = k < r.fish_eye_limit.size() ? at_tolkowsky_crown(r.fish_eye_limit[k]) : std::nan("");
        fish.agrees.push_back(lim >= kFishLow - 1e-9 && lim <= kFishHigh + 1e-9);
        fish.numbers.push_back("up to " + deg(lim));

        const sw::Row* tc = nullptr;
        for (const auto& x : om.phenomena)
            if (x.possible && std::fabs(x.cut.crown_angle - 34.5) < 1e-9 && std::fabs(x.cut.pavilion_angle - 40.75) < 1e-9)
                tc = &x;
        if (tc) {
            const auto& tm = tc->metrics;
            clean.agrees.push_back(!gem_metrics::shows_nail_head(tm.nail_head) && !gem_metrics::shows_fish_eye(tm.fish_eye));
            clean.numbers.push_back("nail-head " + fmt(tm.nail_head.value, 2) + " ± " + fmt(tm.nail_head.error, 1) +
                                    ", fish-eye " + fmt(tm.fish_eye.value, 2) + " ± " + fmt(tm.fish_eye.error, 1));
        } else {
            clean.agrees.push_back(false);
            clean.numbers.push_back("not in the detector grid");
        }
    }
    for (LiteratureRow* x : {&best, &line, &crown, &pav, &table, &fcrown, &ftable, &nail, &fish, &clean})
        out.push_back(std::move(*x));
    return out;
}

}  // namespace refract::experiments::gem_cuts
