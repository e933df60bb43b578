// refract measure IMAGE (--region X0 Y0 X1 Y1 | --mask MASK | --line X0 Y0 X1 Y1 | --radial CX CY R |
//                        --angle-histogram [--axis X Y Z]) [-o CSV]
// Image measurements as CSV (validation/measure.h), on standard output or into a file.
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include <filesystem>

#include "cli/commands.h"
#include <refract/core/provenance.h>
#include <refract/core/image.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/validation/compare.h>
#include <refract/validation/files.h>
#include <refract/validation/measure.h>

namespace measure_command {

struct MeasureArgs {
    std::string image, mask, output;
    std::vector<int> region, line;
    std::vector<double> radial, axis;
    bool angles = false;
    int bins = 32;
};

// The CSV and its settings beside it, OUT.json (core/provenance.h); neither without the other.
void write_csv_with_sidecar(const std::string& out, const std::string& csv) {
    refract::validation::write_text_file(out, csv);
    try {
        refract::write_csv_sidecar(out);
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(out, ec);
        throw;
    }
}

std::string csv_number(double v) { return refract::format_significant(v, 10); }

// --region and --line take pixels of the image: corners inside it, in order (a region's
// first corner its top left). InputError naming the option and the image's size.
void check_pixels(const MeasureArgs& a, const refract::Image& img) {
    const auto refuse = [&](const char* option, const std::vector<int>& v, const std::string& rule) {
        throw refract::InputError(std::string(option) + " " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " +
                                  std::to_string(v[2]) + " " + std::to_string(v[3]) + ": " + rule + " (the image is " +
                                  std::to_string(img.width) + "x" + std::to_string(img.height) + ")");
    };
    const auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < img.width && y < img.height; };
    const std::string w = std::to_string(img.width - 1), h = std::to_string(img.height - 1);
    if (!a.region.empty()) {
        const auto& r = a.region;
        if (!inside(r[0], r[1]) || !inside(r[2], r[3]) || r[0] > r[2] || r[1] > r[3])
            refuse("--region", r, "needs 0 <= X0 <= X1 <= " + w + " and 0 <= Y0 <= Y1 <= " + h);
    }
    if (!a.line.empty() && (!inside(a.line[0], a.line[1]) || !inside(a.line[2], a.line[3])))
        refuse("--line", a.line, "both ends must be pixels of the image, X in [0, " + w + "], Y in [0, " + h + "]");
}

// The measurement the options ask for, as CSV text.
std::string measure_csv(const MeasureArgs& a, const refract::Image& img) {
    using namespace refract;
    namespace v = refract::validation;
    check_pixels(a, img);
    std::ostringstream csv;
    if (!a.line.empty()) {
        const auto pixels = v::line_pixels(a.line[0], a.line[1], a.line[2], a.line[3]);
        const auto values = v::values_at(img, pixels);
        csv << "x,y,distance,r,g,b\n";
        for (size_t k = 0; k < pixels.size(); ++k)
            csv << pixels[k].first << "," << pixels[k].second << ","
                << csv_number(std::hypot(pixels[k].first - a.line[0], pixels[k].second - a.line[1])) << ","
                << csv_number(values[k].x()) << "," << csv_number(values[k].y()) << "," << csv_number(values[k].z()) << "\n";
    } else if (!a.radial.empty()) {
        csv << "r0,r1,pixels,r,g,b\n";
        for (const auto& b : v::radial_profile(img, a.radial[0], a.radial[1], a.bins, a.radial[2]))
            csv << csv_number(b.r0) << "," << csv_number(b.r1) << "," << b.pixels << "," << csv_number(b.mean.x()) << ","
                << csv_number(b.mean.y()) << "," << csv_number(b.mean.z()) << "\n";
    } else {
        v::PixelRect rect{0, 0, img.width - 1, img.height - 1};
        if (!a.region.empty()) rect = {a.region[0], a.region[1], a.region[2], a.region[3]};
        std::optional<Image> m;
        if (!a.mask.empty()) m = read_image(a.mask);
        const v::RegionStats s = v::region_stats(img, rect, m ? &*m : nullptr);
        csv << "channel,pixels,mean,sum,min,max\n";
        const char* names[3] = {"r", "g", "b"};
        for (int c = 0; c < 3; ++c) {
            const auto& ch = s.channel[static_cast<size_t>(c)];
            csv << names[c] << "," << s.pixels << "," << csv_number(ch.mean) << "," << csv_number(ch.sum) << ","
                << csv_number(ch.min) << "," << csv_number(ch.max) << "\n";
        }
    }
    return csv.str();
}

refract::cli::Registrar reg{55, [](CLI::App& app) {
    auto a = std::make_shared<MeasureArgs>();
    auto* sub = app.add_subcommand("measure", "Measure an image: region statistics, a line profile or a radial profile, as CSV");
    sub->add_option("image", a->image, "Image (any format OpenImageIO reads; linear values as stored)")->required();
    auto* reg = sub->add_option("--region", a->region, "Rectangle X0 Y0 X1 Y1 (pixels, inclusive): mean, sum, min, max")->expected(4);
    auto* mask = sub->add_option("--mask", a->mask, "Statistics over the pixels where this image's first channel > 0.5");
    auto* line = sub->add_option("--line", a->line, "Profile along the pixels from X0 Y0 to X1 Y1")->expected(4);
    auto* rad = sub->add_option("--radial", a->radial, "Radial profile about CX CY out to radius R (pixels)")->expected(3);
    auto* ang = sub->add_flag("--angle-histogram", a->angles,
                              "A far-field sphere map (refract farfield's far_field.exr) binned by angle to --axis: "
                              "power and intensity of every channel");
    sub->add_option("--axis", a->axis, "Angle histogram: the axis X Y Z (default: the map's own)")->expected(3);
    sub->add_option("--bins", a->bins, "Radial profile: rings (32); angle histogram: bins over 0-180 degrees (32)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("-o,--output", a->output, "Write the CSV here instead of standard output");
    line->excludes(reg)->excludes(mask)->excludes(rad);
    rad->excludes(reg)->excludes(mask);
    ang->excludes(reg)->excludes(mask)->excludes(line)->excludes(rad);
    sub->callback([a] {
        using namespace refract;
        namespace v = refract::validation;
        if (a->angles) {
            const Channels map = read_channels(a->image);
            std::optional<Vec3> axis;
            if (!a->axis.empty()) axis = Vec3(a->axis[0], a->axis[1], a->axis[2]);
            std::ostringstream csv;
            csv << "theta0_deg,theta1_deg,solid_angle_sr,pixels";
            for (const auto& n : map.names) csv << ",power_" << n;
            for (const auto& n : map.names) csv << ",intensity_" << n;
            csv << "\n";
            for (const auto& b : v::angle_histogram(map, a->image, a->bins, axis)) {
                csv << csv_number(b.theta0_deg) << "," << csv_number(b.theta1_deg) << "," << csv_number(b.solid_angle) << ","
                    << b.pixels;
                for (double p : b.power) csv << "," << csv_number(p);
                for (double i : b.intensity) csv << "," << csv_number(i);
                csv << "\n";
            }
            if (a->output.empty()) std::cout << csv.str();
            else write_csv_with_sidecar(a->output, csv.str());
            return;
        }
        const Image img = read_image(a->image);
        std::string csv;
        try {
            csv = measure_csv(*a, img);
        } catch (const InputError& e) {
            throw InputError(a->image + ": " + e.what());  // name the image measured
        }
        if (a->output.empty()) std::cout << csv;
        else write_csv_with_sidecar(a->output, csv);
    });
}};

}  // namespace measure_command
using namespace measure_command;
