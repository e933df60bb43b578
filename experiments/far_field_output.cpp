#include <refract/experiments/common.h>
#include <refract/experiments/far_field_output.h>

#include <cmath>
#include <filesystem>

#include <refract/core/image.h>
#include <refract/core/spectrum/cie.h>
#include <refract/geometry/error.h>
#include <refract/experiments/plot.h>

namespace refract::experiments {

namespace {

int theta_bins(const FarFieldResult& r) {
    return r.settings.binning == FarFieldSettings::Binning::Sphere ? r.settings.polar_bins : r.bins;
}

std::string binning_text(const FarFieldResult& r) {
    const Vec3& a = r.settings.axis;
    const std::string axis = "(" + fmt(a.x()) + ", " + fmt(a.y()) + ", " + fmt(a.z()) + ")";
    if (r.settings.binning == FarFieldSettings::Binning::Axis)
        return "axis " + axis + ", " + std::to_string(r.bins) + " bins uniform in angle 0-180 deg";
    return "sphere about " + axis + ", " + std::to_string(r.settings.azimuth_bins) + " azimuth x " +
           std::to_string(r.settings.polar_bins) + " polar bins uniform in cos theta (equal solid angle)";
}

}  // namespace

std::vector<double> theta_edges_deg(const FarFieldResult& r) {
    const int n = theta_bins(r);
    std::vector<double> e(static_cast<size_t>(n) + 1);
    for (int k = 0; k <= n; ++k)
        e[static_cast<size_t>(k)] = r.settings.binning == FarFieldSettings::Binning::Axis
                                        ? 180.0 * k / n
                                        : std::acos(std::clamp(1.0 - 2.0 * k / n, -1.0, 1.0)) * 180.0 / M_PI;
    return e;
}

std::vector<double> theta_profile(const FarFieldResult& r, int w, int c, int s) {
    const int n = theta_bins(r);
    std::vector<double> out(static_cast<size_t>(n), 0.0);
    const auto edges = theta_edges_deg(r);
    const int per_row = r.settings.binning == FarFieldSettings::Binning::Sphere ? r.settings.azimuth_bins : 1;
    for (int row = 0; row < n; ++row) {
        double sum = 0;
        for (int k = 0; k < per_row; ++k) sum += r.at(w, c, s, row * per_row + k);
        const double t0 = edges[static_cast<size_t>(row)] * M_PI / 180.0, t1 = edges[static_cast<size_t>(row) + 1] * M_PI / 180.0;
        out[static_cast<size_t>(row)] = sum / (2.0 * M_PI * (std::cos(t0) - std::cos(t1)));
    }
    return out;
}

FarFieldTables far_field_tables(const FarFieldResult& r) {
    FarFieldTables t;
    const int nw = static_cast<int>(r.wavelengths.size());
    const auto edges = theta_edges_deg(r);
    const int nt = theta_bins(r);
    // The θ profile.
    Csv& csv = t.profile;
    csv.header = {"wavelength_nm", "class", "class_name", "theta0_deg", "theta1_deg", "solid_angle_sr", "power", "intensity_per_sr"};
    if (r.components == 4)
        for (const char* h : {"S1", "S2", "S3", "degree_of_polarisation"}) csv.header.push_back(h);
    for (int w = 0; w < nw; ++w)
        for (int c = 0; c < r.classes; ++c) {
            std::vector<std::vector<double>> prof;
            for (int s = 0; s < r.components; ++s) prof.push_back(theta_profile(r, w, c, s));
            for (int b = 0; b < nt; ++b) {
                const double t0 = edges[static_cast<size_t>(b)] * M_PI / 180.0, t1 = edges[static_cast<size_t>(b) + 1] * M_PI / 180.0;
                const double omega = 2.0 * M_PI * (std::cos(t0) - std::cos(t1));
                const double I = prof[0][static_cast<size_t>(b)];
                std::vector<std::string> row{fmt(r.wavelengths[static_cast<size_t>(w)]), std::to_string(c), r.class_name(c),
                                             fmt(edges[static_cast<size_t>(b)], 12), fmt(edges[static_cast<size_t>(b) + 1], 12),
                                             fmt(omega, 12), fmt(I * omega, 12), fmt(I, 12)};
                if (r.components == 4) {
                    double pol2 = 0;
                    for (int s = 1; s < 4; ++s) {
                        row.push_back(fmt(prof[static_cast<size_t>(s)][static_cast<size_t>(b)] * omega, 12));
                        pol2 += prof[static_cast<size_t>(s)][static_cast<size_t>(b)] * prof[static_cast<size_t>(s)][static_cast<size_t>(b)];
                    }
                    row.push_back(I > 0 ? fmt(std::sqrt(pol2) / I, 8) : "0");
                }
                csv.add(std::move(row));
            }
        }
    // The balance per wavelength.
    Csv& sum = t.balance;
    sum.header = {"wavelength_nm"};
    for (int c = 0; c < r.classes; ++c) sum.header.push_back("class" + std::to_string(c));
    for (const char* h : {"scattered", "unscattered", "absorbed", "dropped", "sum", "absorbed_inside"}) sum.header.push_back(h);
    for (int w = 0; w < nw; ++w) {
        std::vector<std::string> row{fmt(r.wavelengths[static_cast<size_t>(w)])};
        double scattered = 0;
        for (int c = 0; c < r.classes; ++c) {
            double v = 0;
            for (int b = 0; b < r.bins; ++b) v += r.at(w, c, 0, b);
            scattered += v;
            row.push_back(fmt(v, 12));
        }
        const size_t k = static_cast<size_t>(w);
        for (double v : {scattered, r.unscattered[k], r.absorbed[k], r.dropped[k],
                         scattered + r.unscattered[k] + r.absorbed[k] + r.dropped[k], r.absorbed_inside(w)})
            row.push_back(fmt(v, 12));
        sum.add(std::move(row));
    }
    // The map.
    const int width = r.settings.binning == FarFieldSettings::Binning::Sphere ? r.settings.azimuth_bins : r.bins;
    t.map_width = width;
    t.map_height = r.bins / width;
    std::vector<std::string>& names = t.channels;
    names = {"R", "G", "B", "total"};
    for (int c = 0; c < r.classes; ++c) names.push_back("class" + std::to_string(c));
    for (int w = 0; w < nw; ++w) names.push_back("w" + fmt(r.wavelengths[static_cast<size_t>(w)]));
    if (r.components == 4)
        for (const char* h : {"S1", "S2", "S3"}) names.push_back(h);
    std::vector<Vec3> weights;
    if (nw >= 2) {
        try {
            weights = spectrum::SpectrumToRGB(r.wavelengths, spectrum::ColourPipeline::XyzSrgb).weights();
        } catch (const std::exception&) {
            weights.clear();  // an uneven list: no colour
        }
    }
    const size_t nc = names.size();
    std::vector<double>& data = t.map;
    data.assign(static_cast<size_t>(r.bins) * nc, 0.0);
    for (int b = 0; b < r.bins; ++b) {
        double* px = &data[static_cast<size_t>(b) * nc];
        const double inv = 1.0 / r.solid_angle(b);
        for (int w = 0; w < nw; ++w) {
            double lw = 0;
            for (int c = 0; c < r.classes; ++c) {
                const double v = r.at(w, c, 0, b) * inv;
                lw += v;
                px[4 + c] += v / nw;
                if (r.components == 4)
                    for (int s = 1; s < 4; ++s) px[nc - 4 + static_cast<size_t>(s)] += r.at(w, c, s, b) * inv / nw;
            }
            px[4 + r.classes + w] = lw;
            px[3] += lw / nw;
            const Vec3 rgb = weights.empty() ? Vec3::Constant(lw / nw) : Vec3(lw * weights[static_cast<size_t>(w)]);
            for (int k = 0; k < 3; ++k) px[k] += rgb[k];
        }
    }
    t.attributes = {{"refract:far_field_binning", binning_text(r)},
                    {"refract:far_field", r.settings.binning == FarFieldSettings::Binning::Sphere ? "sphere" : "axis"},
                    {"refract:far_field_axis", fmt(r.settings.axis.x()) + " " + fmt(r.settings.axis.y()) + " " + fmt(r.settings.axis.z())},
                    {"refract:far_field_reference",
                     fmt(r.settings.reference.x()) + " " + fmt(r.settings.reference.y()) + " " + fmt(r.settings.reference.z())},
                    {"refract:far_field_units", "fraction of the emitted power per steradian"}};
    // The figure's data: intensity against θ per class, averaged over the wavelengths.
    Csv& fig = t.plot;
    fig.header = {"theta_deg"};
    for (int c = 0; c < r.classes; ++c) fig.header.push_back("class" + std::to_string(c));
    std::vector<std::vector<double>> prof(static_cast<size_t>(r.classes), std::vector<double>(static_cast<size_t>(nt), 0.0));
    for (int w = 0; w < nw; ++w)
        for (int c = 0; c < r.classes; ++c) {
            const auto p = theta_profile(r, w, c);
            for (int b = 0; b < nt; ++b) prof[static_cast<size_t>(c)][static_cast<size_t>(b)] += p[static_cast<size_t>(b)] / nw;
        }
    for (int b = 0; b < nt; ++b) {
        std::vector<std::string> row{fmt(0.5 * (edges[static_cast<size_t>(b)] + edges[static_cast<size_t>(b) + 1]), 8)};
        for (int c = 0; c < r.classes; ++c) row.push_back(fmt(prof[static_cast<size_t>(c)][static_cast<size_t>(b)], 10));
        fig.add(std::move(row));
    }
    for (int c = 0; c < r.classes; ++c) t.class_names.push_back(r.class_name(c));
    return t;
}

void check_far_field_outputs(const std::string& dir, const FarFieldFiles& opt) {
    std::vector<std::string> names{"far_field.csv", "far_field.csv.json", "far_field_summary.csv",
                                   "far_field_summary.csv.json", "far_field.exr"};
    if (opt.plot)
        for (const char* n : {"far_field_plot.csv", "far_field_plot.csv.json", "far_field.gp", "far_field.png", "far_field.pdf"})
            names.push_back(n);
    std::error_code ec;
    for (const auto& n : names)
        if (std::filesystem::is_directory(std::filesystem::path(dir) / n, ec))
            throw InputError(dir + "/" + n + ": is a directory, not a file");
}

std::vector<std::string> write_far_field(const std::string& dir, const FarFieldTables& t, const std::string& title,
                                         const FarFieldFiles& opt) {
    ensure_dir(dir);
    std::vector<std::string> written;
    write_csv(dir + "/far_field.csv", t.profile);
    written.push_back("far_field.csv");
    written.push_back("far_field.csv.json");  // its settings (write_csv, core/provenance.h)
    write_csv(dir + "/far_field_summary.csv", t.balance);
    written.push_back("far_field_summary.csv");
    written.push_back("far_field_summary.csv.json");
    // The colour (xyz-srgb, out of the sRGB gamut) and S1–S3 may be negative.
    write_channels(dir + "/far_field.exr", t.map_width, t.map_height, t.channels, t.map, t.attributes,
                   {"R", "G", "B", "S1", "S2", "S3"});
    written.push_back("far_field.exr");
    // The figure: intensity against θ per class, averaged over the wavelengths.
    if (opt.plot && gnuplot_available()) {
        write_csv(dir + "/far_field_plot.csv", t.plot);
        std::string body = "set title \"" + title + "\" noenhanced\nset xlabel \"angle from the axis (degrees)\"\n"
                           "set ylabel \"intensity (fraction of the emitted power per sr)\"\nset logscale y\nset format y \"10^{%L}\"\n"
                           "set xrange [0:180]\nset key outside right\nset datafile separator \",\"\nplot ";
        for (size_t c = 0; c < t.class_names.size(); ++c)
            body += std::string(c ? ", " : "") + "\"far_field_plot.csv\" using 1:($" + std::to_string(c + 2) + " > 0 ? $" +
                    std::to_string(c + 2) + " : NaN) skip 1 with lines title \"" + t.class_names[c] + "\"";
        body += "\n";
        FigureSize size;  // room for the classes' key beside the plot
        size.width_px = 1040;
        size.width_in = 7.8;
        gnuplot_figure(dir, "far_field", body, size);
        written.push_back("far_field.png");
    }
    return written;
}

}  // namespace refract::experiments
