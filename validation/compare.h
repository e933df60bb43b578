#pragma once
// Image comparison for validation, on OpenImageIO's ImageBufAlgo: per-channel error
// statistics, the fraction of pixels over a tolerance, a difference heat map, and
// profiles (values along a line of pixels against an analytic curve).
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <refract/core/image.h>

namespace refract::validation {

struct ImageDifference {
    double rmse = 0;        // root mean square over every channel value of every pixel
    double max_error = 0;   // largest |a − b| over channels and pixels
    double mean_error = 0;  // mean |a − b| over channel values
    double psnr = 0;        // 20 log10(1 / rmse), peak 1 (infinite when identical)
    int max_x = -1, max_y = -1;  // where max_error is
    long long pixels = 0;
    long long pixels_over = 0;   // pixels with any channel |a − b| > tolerance
    double fraction_over = 0;    // pixels_over / pixels
};

// Compares two images of the same size (InputError otherwise) on float buffers
// (errors resolved to ~1e-7).
ImageDifference compare_images(const Image& a, const Image& b, double tolerance);

// The suite's rule for refract against POV-Ray (docs/validation.md), the one every such
// comparison uses: at most `max_fraction_over` of the pixels differ by more than
// `pixel_tolerance` in a channel, AND the RMSE is at most `rmse`. The RMSE part catches what
// a per-pixel count alone (idiff -fail 1e-3 -failpercent 0.1) passes: one pixel off by 0.12
// in 4 800 is 0.02 % of the pixels but an RMSE of 1e-3.
struct Targets {
    double pixel_tolerance = 1e-3;
    double max_fraction_over = 1e-3;
    double rmse = 2e-4;
    bool met_by(const ImageDifference& d) const { return d.fraction_over <= max_fraction_over && d.rmse <= rmse; }
};

// refract's image against POV-Ray's 16-bit PNG, which holds [0, 1]: refract clipped the same
// way first, then compare_images at the targets' pixel tolerance.
ImageDifference compare_with_povray_image(const Image& refract, const Image& povray, const Targets& targets);

// Every channel clamped to [0, 1]: what a 16-bit PNG can hold.
Image clamp01(const Image& img);

// The means of `block`×`block` squares of pixels (the last row and column of squares
// cover what is left): the statistical comparison of images whose pixels are each a mean
// of random samples (a thin lens against POV-Ray's focal blur, docs/validation.md).
Image block_means(const Image& img, int block);

// Difference heat map: per pixel max over channels of |a − b| on a log scale, 1e-6 and
// below black, 1e-1 and above the top of OpenImageIO's "inferno" map (1e-3 is 60 %).
// Written as an 8-bit PNG through a temporary name.
void write_heatmap(const std::string& path, const Image& a, const Image& b);

// Pixels on the segment (x0, y0)–(x1, y1), both ends included, one per step of the
// longer axis.
std::vector<std::pair<int, int>> line_pixels(int x0, int y0, int x1, int y1);

struct ProfilePoint {
    int x = 0, y = 0;
    double value = 0;     // the image, channel `channel`
    double expected = 0;  // the analytic curve
};
struct ProfileComparison {
    std::vector<ProfilePoint> points;
    double max_error = 0;
    double rmse = 0;
};

// Values of `img` along `pixels` against `expected(x, y)`; pixels where `expected` is
// empty are left out.
ProfileComparison compare_profile(const Image& img, const std::vector<std::pair<int, int>>& pixels, int channel,
                                  const std::function<std::optional<double>(int, int)>& expected);

}  // namespace refract::validation
