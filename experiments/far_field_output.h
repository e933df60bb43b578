#pragma once
// Writing a far-field detector's result (core/far_field.h): the numbers, a map and a plot.
//   DIR/far_field.csv          per wavelength, class and θ bin (the sphere binning summed
//                              over φ): solid angle, power fraction, intensity (fraction
//                              per steradian) and, with exact polarisation, S1..S3 and the
//                              degree of polarisation
//   DIR/far_field_summary.csv  per wavelength: each class's total, unscattered, absorbed,
//                              dropped by the limits, and their sum (1 when nothing else
//                              was lost)
//   DIR/far_field.exr          the map of intensity per bin (sphere: φ across, θ down,
//                              equal solid angle per pixel; axis: one row of θ bins):
//                              channels R, G, B (the spectrum's colour, xyz-srgb, white =
//                              a wavelength-independent fraction), total, one per class,
//                              one per wavelength, and S1..S3 with exact polarisation; the
//                              binning in the header (refract:far_field_*)
//   DIR/far_field.png/.pdf/.gp intensity against θ per class (gnuplot; skipped without it)
#include <string>
#include <utility>
#include <vector>

#include <refract/core/far_field.h>
#include <refract/experiments/plot.h>

namespace refract::experiments {

struct FarFieldFiles {
    bool plot = true;  // false: no gnuplot figure
};

// Refuses (InputError naming it) a directory at the name of a file write_far_field would
// write into `dir`: before the work.
void check_far_field_outputs(const std::string& dir, const FarFieldFiles& opt);

// Everything the files above hold, computed from a FarFieldResult (the θ profiles, the
// balance, the map's channels and colour, the figure's data), so that writing is formatting.
struct FarFieldTables {
    Csv profile;  // far_field.csv
    Csv balance;  // far_field_summary.csv
    int map_width = 0, map_height = 0;
    std::vector<std::string> channels;  // far_field.exr
    std::vector<double> map;
    std::vector<std::pair<std::string, std::string>> attributes;
    Csv plot;                                // far_field_plot.csv: θ bin centre, intensity per class
    std::vector<std::string> class_names;    // the figure's curves
};
FarFieldTables far_field_tables(const FarFieldResult& r);

// Writes the files above into `dir` (created); returns the names written.
std::vector<std::string> write_far_field(const std::string& dir, const FarFieldTables& t, const std::string& title,
                                         const FarFieldFiles& opt = {});

// Intensity (fraction per sr) against θ: the sphere binning summed over φ, per
// wavelength w and class c (component s); axis binning as is.
std::vector<double> theta_profile(const FarFieldResult& r, int w, int c, int s = 0);
// The θ bins' edges (degrees) of theta_profile.
std::vector<double> theta_edges_deg(const FarFieldResult& r);

}  // namespace refract::experiments
