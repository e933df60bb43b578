#pragma once
// Where to write the level of each contour line on a map, so that no label covers a marker,
// another label, another level's line or the plot's border.
#include <string>
#include <vector>

namespace refract::experiments {

// A map sampled on a regular grid: value(i, j) at x[i], y[j] (NaN: no value).
struct GridMap {
    std::vector<double> x, y;
    std::vector<double> values;  // x-major: values[i * y.size() + j]
    double value(size_t i, size_t j) const { return values[i * y.size() + j]; }
};

struct PlotFrame {  // the data range shown and the label size, as fractions of the plot area
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    double char_width = 0.015, label_height = 0.06, padding = 0.012;  // per character; box
    double marker_half_width = 0.035, marker_half_height = 0.05;
};

struct ContourLabel {
    double level = 0, x = 0, y = 0;  // centre, in data coordinates, on the level's line
    std::string text;
};

// One label per level at most, each at a point where the level crosses a grid edge (where
// any linear-interpolating contourer such as gnuplot's draws the line), chosen greedily
// (levels in order) as far as possible from the markers and the labels already placed,
// among the points whose label box stays inside the frame and clear of the markers, of the
// other labels and of every other level's crossings. A level without such a point gets no
// label. `format` is a printf format for one double ("%.2f").
std::vector<ContourLabel> place_contour_labels(const GridMap& map, const std::vector<double>& levels,
                                               const std::string& format, const PlotFrame& frame,
                                               const std::vector<std::pair<double, double>>& markers);

}  // namespace refract::experiments
