// gem-cuts: the write step of the observer maps, the detectors and the literature table
// (experiments/gem_cuts.h); reads only the Result.
#include <cmath>
#include <sstream>

#include <refract/core/image.h>
#include <refract/experiments/common.h>
#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_detectors.h>
#include <refract/experiments/gem_observation.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::gem_cuts {

namespace sw = gem_sweep;

namespace {

std::string num_or_none(double v) { return std::isnan(v) ? std::string("none") : fmt(v, 4); }

// The crown × pavilion rows as gnuplot grid blocks: crown pavilion then one column per
// observer from `cell` (NaN for an impossible cut).
template <class Cell>
std::string grid_text(const std::vector<ObserverMap>& obs, const std::vector<sw::Row> ObserverMap::*rows, Cell cell) {
    std::ostringstream t;
    t << "# crown_angle pavilion_angle";
    for (const auto& o : obs) t << " " << o.observer;
    t << "\n";
    const auto& first = obs.front().*rows;
    double last = std::nan("");
    for (size_t i = 0; i < first.size(); ++i) {
        const auto& row = first[i];
        if (!std::isnan(last) && row.cut.crown_angle != last) t << "\n";
        last = row.cut.crown_angle;
        t << sw::number(row.cut.crown_angle) << " " << sw::number(row.cut.pavilion_angle);
        for (const auto& o : obs) {
            const auto& x = (o.*rows)[i];
            t << " " << (x.possible ? sw::number(cell(x)) : std::string("NaN"));
        }
        t << "\n";
    }
    return t.str();
}

double half_step(const sw::Axis& a) { return a.count > 1 ? 0.5 * (a.value(1) - a.value(0)) : 0.5; }

std::string frame_text(const sw::Grid& g) {
    const sw::Axis &ax = g.axes[1], &ay = g.axes[2];
    std::ostringstream b;
    b << "set xrange [" << sw::number(ax.value(0) - half_step(ax)) << ":" << sw::number(ax.value(ax.count - 1) + half_step(ax))
      << "]\nset yrange [" << sw::number(ay.value(0) - half_step(ay)) << ":"
      << sw::number(ay.value(ay.count - 1) + half_step(ay)) << "]\n"
      << "set xlabel 'crown angle (deg)'\nset ylabel 'pavilion angle (deg)'\nunset key\n";
    return b.str();
}

std::string cells(const std::string& file, const sw::Grid& g, const std::string& col, const std::string& colour) {
    const sw::Axis &ax = g.axes[1], &ay = g.axes[2];
    return "'" + file + "' using 1:2:(" + sw::number(1.02 * half_step(ax)) + "):(" + sw::number(1.02 * half_step(ay)) +
           "):" + col + " with boxxyerror fs solid 1.0 noborder " + colour;
}

// One observer's light-return map: viridis cells, Tolkowsky a circle, the best a star.
std::string light_return_body(const Result& r, size_t k) {
    const ObserverMap& o = r.observers[k];
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& row : o.rows)
        if (row.possible) {
            lo = std::fmin(lo, row.metrics.light_return.value);
            hi = std::fmax(hi, row.metrics.light_return.value);
        }
    if (!(lo < hi)) {
        lo = (std::isfinite(lo) ? lo : 0.5) - 1e-3;
        hi = lo + 2e-3;
    }
    std::ostringstream b;
    b << viridis_palette() << "\nset cbrange [" << sw::number(lo) << ":" << sw::number(hi) << "]\n"
      << "set cblabel 'light return'\n"
      << frame_text(r.main.grid) << "set title \"light return, observer " << o.observer
      << "\\n{/=9 circle: Tolkowsky 1919, star: best in the grid}\"\n"
      << "plot " << cells("gem_cuts_observers_map.dat", r.main.grid, std::to_string(3 + k), "fc palette")
      << ", \\\n     'gem_cuts_observer_marks.dat' index " << 2 * k
      << " using 1:2 with points pt 6 ps 2.2 lw 2 lc rgb 'black', \\\n"
      << "     'gem_cuts_observer_marks.dat' index " << 2 * k + 1
      << " using 1:2 with points pt 3 ps 2 lw 2 lc rgb 'white'\n";
    return b.str();
}

// One observer's detector map: each cut coloured by what it shows.
std::string phenomena_body(const Result& r, size_t k, const sw::Grid& g) {
    const ObserverMap& o = r.observers[k];
    std::ostringstream b;
    b << frame_text(g) << "set title \"nail-head and fish-eye, observer " << o.observer
      << "\\n{/=9 dark red: nail-head, blue: fish-eye, purple: both, orange: nail-head undecided at 2σ, grey: "
         "neither; circle: Tolkowsky 1919}\"\n"
      << "rgb(c) = c == 1 ? 0x8b1a1a : c == 2 ? 0x2060c0 : c == 3 ? 0x7a3d9a : c == 4 ? 0xe08a1e : 0xd8d8d8\n"
      << "plot " << cells("gem_cuts_phenomena.dat", g, "(rgb($" + std::to_string(3 + k) + "))", "lc rgb variable")
      << ", \\\n     'gem_cuts_observer_marks.dat' index " << 2 * k
      << " using 1:2 with points pt 6 ps 2.2 lw 2 lc rgb 'black'\n";
    return b.str();
}

// One observer's obstruction map: viridis cells of the value, a cross where it fires.
std::string obstruction_body(const Result& r, size_t k, const sw::Grid& g) {
    const ObserverMap& o = r.observers[k];
    const double lo = o.obstruction.lo, hi = o.obstruction.hi > lo ? o.obstruction.hi : lo + 1e-3;
    std::ostringstream b;
    b << viridis_palette() << "\nset cbrange [" << sw::number(lo) << ":" << sw::number(hi) << "]\n"
      << "set cblabel 'obstruction (share of the light from the head)'\n"
      << frame_text(g) << "set title \"obstruction, observer " << o.observer << "\\n{/=9 cross: shows obstruction (>= "
      << fmt(gem_metrics::kObstructionThreshold, 3) << "); circle: Tolkowsky 1919}\"\n"
      << "plot " << cells("gem_cuts_obstruction.dat", g, std::to_string(3 + k), "fc palette")
      << ", \\\n     'gem_cuts_obstruction_marks.dat' index " << k
      << " using 1:2 with points pt 2 ps 1.4 lw 2 lc rgb 'white', \\\n     'gem_cuts_observer_marks.dat' index " << 2 * k
      << " using 1:2 with points pt 6 ps 2.2 lw 2 lc rgb 'black'\n";
    return b.str();
}

}  // namespace

std::string edge_text(const Edge& e, const sw::Grid& grid, const Edge& limit) {
    const sw::Axis &c = grid.axes[1], &p = grid.axes[2];
    std::string s;
    auto add = [&](bool on, bool at_limit, const std::string& what) {
        if (on) s += (s.empty() ? "" : " and ") + what + (at_limit ? ", the cut builder's limit" : "");
    };
    add(e.crown_low, limit.crown_low, "crown " + num_or_none(c.value(0)) + "°, the grid's shallowest");
    add(e.crown_high, limit.crown_high, "crown " + num_or_none(c.value(c.count - 1)) + "°, the grid's steepest");
    add(e.pavilion_low, limit.pavilion_low, "pavilion " + num_or_none(p.value(0)) + "°, the grid's shallowest");
    add(e.pavilion_high, limit.pavilion_high, "pavilion " + num_or_none(p.value(p.count - 1)) + "°, the grid's steepest");
    return s;
}

std::string optimum_sentence(const Optimum& o, const sw::Grid& grid) {
    const std::string where = "crown " + num_or_none(o.best.cut.crown_angle) + "°, pavilion " + num_or_none(o.best.cut.pavilion_angle) + "°";
    const Edge &e = o.edge, &l = o.builder_limit;
    // Every edge the optimum lies on is one where the builder's range ends.
    const bool all_limits = e.crown_low == l.crown_low && e.crown_high == l.crown_high &&
                            e.pavilion_low == l.pavilion_low && e.pavilion_high == l.pavilion_high;
    if (e.any() && all_limits)
        return "Under " + o.observer + " the best " + o.metric + " (" + where + ") lies on the grid's edge (" +
               edge_text(e, grid, l) + "): the grid ends there because the cut builder accepts no cut a grid step "
                                       "beyond, so the best buildable cut is at the builder's limit, and its distance "
                                       "from Tolkowsky's is that of the limit.";
    if (e.any())
        return "Under " + o.observer + " the best " + o.metric + " (" + where + ") lies on the grid's edge (" +
               edge_text(e, grid, l) + "): the optimum may lie outside the grid, and its distance from Tolkowsky's is "
                                       "a lower bound.";
    return "Under " + o.observer + " the best " + o.metric + " (" + where + ") lies inside the grid.";
}

void write_observers(const Result& r, const std::string& dir, std::ostream& s) {
    if (r.observers.empty()) return;
    const sw::Sweep ph = phenomena_sweep(r.quick);
    write_text_atomic(dir + "/gem_cuts_observers_map.dat",
                      grid_text(r.observers, &ObserverMap::rows, [](const sw::Row& x) { return x.metrics.light_return.value; }));
    write_text_atomic(dir + "/gem_cuts_phenomena.dat", grid_text(r.observers, &ObserverMap::phenomena, [](const sw::Row& x) {
                          // 4: the nail-head undecided at 2σ (drawn apart whatever the fish-eye).
                          if (!gem_metrics::nail_head_decided(x.metrics.nail_head)) return 4.0;
                          return static_cast<double>(gem_metrics::shows_nail_head(x.metrics.nail_head) +
                                                     2 * gem_metrics::shows_fish_eye(x.metrics.fish_eye));
                      }));
    write_text_atomic(dir + "/gem_cuts_obstruction.dat",
                      grid_text(r.observers, &ObserverMap::phenomena, [](const sw::Row& x) { return x.metrics.obstruction.value; }));
    std::ostringstream firing;  // index k: the cells where obstruction fires under observer k
    for (const auto& o : r.observers) {
        firing << "# " << o.observer << " shows obstruction\n";
        int n = 0;
        for (const auto& x : o.phenomena)
            if (x.possible && gem_metrics::shows_obstruction(x.metrics.obstruction)) {
                firing << sw::number(x.cut.crown_angle) << " " << sw::number(x.cut.pavilion_angle) << "\n";
                ++n;
            }
        if (n == 0) firing << "NaN NaN\n";  // an empty block would shift the indices
        firing << "\n\n";
    }
    write_text_atomic(dir + "/gem_cuts_obstruction_marks.dat", firing.str());
    std::ostringstream marks;  // index 2k: Tolkowsky, 2k + 1: observer k's best light return
    for (const auto& o : r.observers)
        marks << "# " << o.observer << " tolkowsky\n" << sw::number(o.tolkowsky.cut.crown_angle) << " "
              << sw::number(o.tolkowsky.cut.pavilion_angle) << "\n\n\n# " << o.observer << " best\n"
              << sw::number(o.light_return.best.cut.crown_angle) << " "
              << sw::number(o.light_return.best.cut.pavilion_angle) << "\n\n\n";
    write_text_atomic(dir + "/gem_cuts_observer_marks.dat", marks.str());
    Csv obs, phen, lit;
    obs.header = {"observer", "crown_angle", "pavilion_angle", "light_return", "light_return_error"};
    phen.header = {"observer",       "crown_angle",   "pavilion_angle",   "nail_head",       "nail_head_error",
                   "fish_eye",       "fish_eye_error", "obstruction",      "obstruction_error", "shows_nail_head",
                   "shows_fish_eye", "shows_obstruction"};
    for (const auto& o : r.observers) {
        for (const auto& x : o.rows)
            if (x.possible)
                obs.add({o.observer, fmt(x.cut.crown_angle), fmt(x.cut.pavilion_angle), fmt(x.metrics.light_return.value),
                         fmt(x.metrics.light_return.error)});
        for (const auto& x : o.phenomena)
            if (x.possible)
                phen.add({o.observer, fmt(x.cut.crown_angle), fmt(x.cut.pavilion_angle), fmt(x.metrics.nail_head.value),
                          fmt(x.metrics.nail_head.error), fmt(x.metrics.fish_eye.value), fmt(x.metrics.fish_eye.error),
                          fmt(x.metrics.obstruction.value), fmt(x.metrics.obstruction.error),
                          gem_metrics::shows_nail_head(x.metrics.nail_head) ? "1" : "0",
                          gem_metrics::shows_fish_eye(x.metrics.fish_eye) ? "1" : "0",
                          gem_metrics::shows_obstruction(x.metrics.obstruction) ? "1" : "0"});
    }
    write_csv(dir + "/gem_cuts_observers.csv", obs);
    write_csv(dir + "/gem_cuts_phenomena.csv", phen);
    lit.header = {"result", "observer", "agrees", "numbers"};
    for (const auto& x : r.literature)
        for (size_t k = 0; k < x.agrees.size(); ++k)
            lit.add({x.key, r.observers[k].observer, x.agrees[k] ? "1" : "0", x.numbers[k]});
    write_csv(dir + "/gem_cuts_literature.csv", lit);
    for (size_t k = 0; k < r.observers.size(); ++k) {
        gnuplot_figure(dir, "gem_cuts_light_return_" + r.observers[k].observer, light_return_body(r, k));
        gnuplot_figure(dir, "gem_cuts_phenomena_" + r.observers[k].observer, phenomena_body(r, k, ph.grid));
        gnuplot_figure(dir, "gem_cuts_obstruction_" + r.observers[k].observer, obstruction_body(r, k, ph.grid));
    }

    s << "\n## Light return under three observer models\n\n"
      << "The light return depends on who looks (docs/gem-metrics.md, \"Observer models\"): the crown × pavilion map "
         "measured again under each model (the light return only; fire, leakage and scintillation do not depend on "
         "the model). Maps `gem_cuts_light_return_OBSERVER.png`, data `gem_cuts_observers.csv`.\n\n"
      << "| observer | best crown | best pavilion | best ± error | Tolkowsky ± error | Δcrown | Δpavilion | "
         "difference / σ | on the grid's edge |\n|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const auto& o : r.observers) {
        const Optimum& p = o.light_return;
        const auto& b = p.best.metrics.light_return;
        s << "| " << o.observer << " | " << num_or_none(p.best.cut.crown_angle) << " | " << num_or_none(p.best.cut.pavilion_angle) << " | "
          << num_or_none(b.value) << " ± " << fmt(b.error, 2) << " | " << num_or_none(p.tolkowsky.value) << " ± " << fmt(p.tolkowsky.error, 2)
          << " | " << num_or_none(p.d_crown) << " | " << num_or_none(p.d_pavilion) << " | " << fmt(p.sigmas, 3) << " | "
          << (p.edge.any() ? edge_text(p.edge, r.main.grid, p.builder_limit) : std::string("no")) << " |\n";
    }
    s << "\n";
    for (const auto& o : r.observers) s << "- " << optimum_sentence(o.light_return, r.main.grid) << "\n";
    s << "\nBetween the observer models the best light return moves by up to " << fmt(r.findings.optimum_spread_deg, 3)
      << "° in crown × pavilion.\n";

    s << "\n## Nail-head and fish-eye\n\n"
      << "The detectors (docs/gem-metrics.md, \"Nail-head and fish-eye\"): nail-head = the share of the light of the "
         "table's central zone (within "
      << fmt(gem_metrics::kNailHeadZone, 2)
      << " of its radius) that comes from the observer's head, less that share over the rest of the face, shown at ≥ "
      << fmt(gem_metrics::kNailHeadThreshold, 3) << "; fish-eye = the share of the table's light that leaves through "
         "the girdle, shown at ≥ "
      << fmt(gem_metrics::kFishEyeThreshold, 3) << ". Grid crown " << ph.grid.axes[1].text() << " × pavilion "
      << ph.grid.axes[2].text() << ", " << ph.metric.rays << " rays per cut and "
      << static_cast<int>(ph.metric.rays * ph.metric.centre_share) << " in the table's central zone; maps `gem_cuts_phenomena_OBSERVER.png`, "
      << "data `gem_cuts_phenomena.csv`.\n\n| crown |";
    for (const auto& o : r.observers) s << " nail-head from (" << o.observer << ") |";
    s << " fish-eye up to |\n|---:|";
    for (size_t k = 0; k <= r.observers.size(); ++k) s << "---:|";
    s << "\n";
    for (size_t c = 0; c < r.nail_head_onset.front().size(); ++c) {
        s << "| " << num_or_none(r.nail_head_onset.front()[c].crown) << " |";
        for (size_t k = 0; k < r.observers.size(); ++k) s << " " << num_or_none(r.nail_head_onset[k][c].pavilion) << " |";
        s << " " << num_or_none(r.fish_eye_limit.front()[c].pavilion) << " |\n";
    }
    for (const auto& o : r.observers)
            s << "- Under " << o.observer << " "
              << (o.nail_head_undecided == 0
                      ? std::string("every cut of the detector grid is decided at 2σ: none lies within two standard "
                                    "errors of the nail-head threshold.")
                      : std::to_string(o.nail_head_undecided) +
                            (o.nail_head_undecided == 1 ? " cut of the detector grid lies" : " cuts of the detector grid lie") +
                            " within two standard errors of the nail-head threshold (orange in the map): undecided at "
                            "this ray count.")
              << "\n";
    s << "\n(\"none\": the detector does not fire at the grid's steepest, or shallowest, pavilion. The fish-eye does "
         "not depend on the observer: the same eye rays, the same exits.) Tolkowsky's own cut has a knife-edge girdle "
         "and so no fish-eye by definition; the detector grid's cut at his angles has the GIA default's girdle (the "
         "literature table's last row).\n";

    s << "\n### Obstruction\n\n"
      << "The obstruction detector (docs/gem-metrics.md, \"Obstruction\"): the share of the whole face's light that "
         "comes from the observer's head (ASET's blue), shown at ≥ "
      << fmt(gem_metrics::kObstructionThreshold, 3)
      << "; the same detector grid, maps `gem_cuts_obstruction_OBSERVER.png` (a cross where it fires), the columns "
         "`obstruction` of `gem_cuts_phenomena.csv`.\n\n";
    for (const auto& o : r.observers) {
        const ObstructionCount& c = o.obstruction;
        const std::string range = " (values " + fmt(c.lo, 3) + " to " + fmt(c.hi, 3) + ")";
        s << "- Under " << o.observer << " ";
        if (c.cuts == 0) s << "the detector grid has no possible cut.";
        else if (c.firing == 0) s << "no cut of the detector grid shows obstruction" << range << ".";
        else if (c.firing == c.cuts) s << "every cut of the detector grid shows obstruction" << range << ": the head hides a large share of every face.";
        else s << c.firing << " of " << c.cuts << " cuts of the detector grid show obstruction" << range << ".";
        if (c.near > 0)
            s << " " << c.near << " of the " << c.cuts << (c.near == 1 ? " lies" : " lie")
              << " within two standard errors of the threshold, undecided at this ray count (the threshold is a "
                 "convention on a smoothly varying share: read the map's values).";
        for (const auto& x : o.phenomena)
            if (x.possible && std::fabs(x.cut.crown_angle - 34.5) < 1e-9 && std::fabs(x.cut.pavilion_angle - 40.75) < 1e-9)
                s << " At Tolkowsky's angles " << fmt(x.metrics.obstruction.value, 3) << " ± "
                  << fmt(x.metrics.obstruction.error, 2)
                  << (gem_metrics::shows_obstruction(x.metrics.obstruction) ? ": it shows obstruction." : ": it does not.");
        s << "\n";
    }

    if (!r.renders.empty() && !r.renders.front().views.empty()) {
        std::vector<Panel> panels;
        s << "\n## A fish-eye, Tolkowsky's cut and a nail-head in the viewers\n\n"
          << "`gem_cuts_renders.png` / `.pdf`: Tolkowsky's crown and table with the pavilion at ";
        for (size_t i = 0; i < r.renders.size(); ++i) {
            const RenderedCut& c = r.renders[i];
            const std::string base = "gem_cuts_render_" + sw::number(c.row.cut.pavilion_angle);
            for (const auto& [view, img] : c.views) {
                write_image(dir + "/" + base + "_" + view + ".png", img);
                panels.push_back({base + "_" + view + ".png", sw::number(c.row.cut.pavilion_angle) + "°, " + view});
            }
            const auto& m = c.row.metrics;
            // The nail-head under each observer the row carries (the main one and `also`).
            std::vector<std::pair<std::string, gem_metrics::Metric>> nails{{m.observer, m.nail_head}};
            for (const auto& a : m.also) nails.emplace_back(a.observer, a.nail_head);
            std::string firing;
            for (const auto& [name, v] : nails)
                if (gem_metrics::shows_nail_head(v)) firing += (firing.empty() ? "" : ", ") + name;
            const bool fish = gem_metrics::shows_fish_eye(m.fish_eye);
            s << (i == 0 ? "" : i + 1 == r.renders.size() ? " and " : ", ") << num_or_none(c.row.cut.pavilion_angle) << "° ("
              << (firing.empty() ? std::string("no nail-head under any observer")
                                 : "a nail-head under " + firing)
              << (fish ? ", a fish-eye" : ", no fish-eye") << ": nail-head";
            for (const auto& [name, v] : nails) s << " " << name << " " << fmt(v.value, 2) << " ± " << fmt(v.error, 1) << ";";
            s << " fish-eye " << fmt(m.fish_eye.value, 2) << " ± " << fmt(m.fish_eye.error, 1) << ")";
        }
        s << ", each in the ASET, ideal-scope and brilliance viewers (" << r.render_size << "² pixels, one eye ray each, "
          << "the band nearest 560 nm). A nail-head shows as a central zone in the viewer's own colour (ASET blue, dark "
             "in brilliance; the ideal-scope's black hole only when the centre's light leaves within 10° of the "
             "axis), a fish-eye as a ring in the table of light that left through the girdle.\n";
        image_grid_figure(dir, "gem_cuts_renders", static_cast<int>(r.renders.size()),
                          static_cast<int>(render_views().size()), panels,
                          "Tolkowsky's crown and table, three pavilion angles, in the viewers", 1.0, r.quick ? 120 : 200);
        for (const std::string& view : render_tilt_views()) {
            std::vector<Panel> tilt_panels;
            for (const RenderedCut& c : r.renders)
                for (const auto& [v, series] : c.tilts)
                    if (v == view)
                        for (const auto& [tilt, img] : series) {
                            const std::string f = "gem_cuts_render_" + sw::number(c.row.cut.pavilion_angle) + "_" + view +
                                                  "_tilt" + sw::number(tilt) + ".png";
                            write_image(dir + "/" + f, img);
                            tilt_panels.push_back({f, sw::number(c.row.cut.pavilion_angle) + "°, tilt " + sw::number(tilt) + "°"});
                        }
            if (tilt_panels.empty()) continue;
            // The ASET series keeps its name (gem_cuts_tilts), the others carry the view's.
            const std::string name = view == "aset" ? std::string("gem_cuts_tilts") : "gem_cuts_tilts_" + view;
            image_grid_figure(dir, name, static_cast<int>(r.renders.size()), static_cast<int>(render_tilts().size()),
                              tilt_panels, "The same cuts in " + view + ", the stone tilted 0, 10, 20 and 30 degrees", 1.0,
                              r.quick ? 120 : 200);
            s << "\nThe " << view << " tilt series `" << name << ".png` / `.pdf`: the same three cuts in " << view
              << ", the stone tilted by 0°, 10°, 20° and 30° about the image's horizontal axis (the viewer fixed).\n";
        }
    }

    s << "\n## The literature side by side\n\n"
      << "Each published qualitative result, marked by a test on this run's numbers (docs/gem-metrics.md explains "
         "every row and the reason for each disagreement); `gem_cuts_literature.csv`.\n\n| result | test |";
    for (const auto& o : r.observers) s << " " << o.observer << " |";
    s << "\n|---|---|";
    for (size_t k = 0; k < r.observers.size(); ++k) s << "---|";
    s << "\n";
    int agree = 0, total = 0;
    for (const auto& x : r.literature) {
        s << "| " << x.claim << " | " << x.measure << " |";
        for (size_t k = 0; k < x.agrees.size(); ++k) {
            s << " " << (x.agrees[k] ? "agrees" : "disagrees") << " (" << x.numbers[k] << ") |";
            agree += x.agrees[k];
            ++total;
        }
        s << "\n";
    }
    s << "\n" << agree << " of " << total << " marks agree.\n";
}

}  // namespace refract::experiments::gem_cuts
