#include <refract/experiments/contour_labels.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace refract::experiments {

namespace {

struct Box {
    double x0, x1, y0, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
    bool contains(double x, double y) const { return x > x0 && x < x1 && y > y0 && y < y1; }
};

struct Point {
    double x, y;  // fractions of the frame
};

// Where `level` crosses the grid's edges (both ends known, on either side).
std::vector<Point> crossings(const GridMap& m, double level, const PlotFrame& f) {
    std::vector<Point> v;
    auto add = [&](double xa, double ya, double va, double xb, double yb, double vb) {
        if (!std::isfinite(va) || !std::isfinite(vb) || !((va - level) * (vb - level) < 0)) return;
        const double t = (level - va) / (vb - va);
        v.push_back({(xa + t * (xb - xa) - f.x0) / (f.x1 - f.x0), (ya + t * (yb - ya) - f.y0) / (f.y1 - f.y0)});
    };
    const size_t nx = m.x.size(), ny = m.y.size();
    for (size_t i = 0; i < nx; ++i)
        for (size_t j = 0; j < ny; ++j) {
            if (i + 1 < nx) add(m.x[i], m.y[j], m.value(i, j), m.x[i + 1], m.y[j], m.value(i + 1, j));
            if (j + 1 < ny) add(m.x[i], m.y[j], m.value(i, j), m.x[i], m.y[j + 1], m.value(i, j + 1));
        }
    return v;
}

}  // namespace

std::vector<ContourLabel> place_contour_labels(const GridMap& map, const std::vector<double>& levels,
                                               const std::string& format, const PlotFrame& f,
                                               const std::vector<std::pair<double, double>>& markers) {
    std::vector<std::vector<Point>> cross;
    for (double l : levels) cross.push_back(crossings(map, l, f));
    std::vector<Box> taken;  // the markers', then the placed labels' boxes
    for (const auto& [x, y] : markers) {
        const double fx = (x - f.x0) / (f.x1 - f.x0), fy = (y - f.y0) / (f.y1 - f.y0);
        taken.push_back({fx - f.marker_half_width, fx + f.marker_half_width, fy - f.marker_half_height,
                         fy + f.marker_half_height});
    }
    std::vector<ContourLabel> labels;
    for (size_t k = 0; k < levels.size(); ++k) {
        char text[64];
        std::snprintf(text, sizeof text, format.c_str(), levels[k]);
        const double hw = 0.5 * (std::string(text).size() * f.char_width + 2 * f.padding), hh = 0.5 * f.label_height;
        double best_score = -1;
        Point best{0, 0};
        for (const Point& p : cross[k]) {
            const Box b{p.x - hw, p.x + hw, p.y - hh, p.y + hh};
            if (b.x0 < 0.01 || b.x1 > 0.99 || b.y0 < 0.01 || b.y1 > 0.99) continue;
            bool clear = true;
            for (const Box& t : taken) clear = clear && !b.overlaps(t);
            for (size_t o = 0; o < levels.size() && clear; ++o)
                if (o != k)
                    for (const Point& q : cross[o]) clear = clear && !b.contains(q.x, q.y);
            if (!clear) continue;
            double d = 0.25;  // far enough beyond this
            for (const Box& t : taken)
                d = std::min(d, std::hypot(p.x - 0.5 * (t.x0 + t.x1), p.y - 0.5 * (t.y0 + t.y1)));
            const double border = std::min({b.x0, 1 - b.x1, b.y0, 1 - b.y1, 0.1});
            const double score = d + 0.5 * border;
            if (score > best_score) {
                best_score = score;
                best = p;
            }
        }
        if (best_score < 0) continue;
        taken.push_back({best.x - hw - 0.01, best.x + hw + 0.01, best.y - hh - 0.01, best.y + hh + 0.01});
        labels.push_back({levels[k], f.x0 + best.x * (f.x1 - f.x0), f.y0 + best.y * (f.y1 - f.y0), text});
    }
    return labels;
}

}  // namespace refract::experiments
