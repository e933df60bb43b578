#pragma once
// Image measurements (`refract measure`, and the validation comparisons' profiles):
// statistics over a rectangle or a mask, the values along a line of pixels, and a radial
// profile about a point. Pure functions returning structures; writing CSV is the caller's.
#include <array>
#include <string>
#include <optional>
#include <utility>
#include <vector>

#include <refract/core/image.h>

namespace refract::validation {

struct ChannelStats {
    double mean = 0, sum = 0, min = 0, max = 0;
};
struct RegionStats {
    long long pixels = 0;
    std::array<ChannelStats, 3> channel{};
};
// Pixel rectangle, both corners included.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Statistics of the pixels of `rect` (clipped to the image) where `mask` (same size,
// when given) has channel 0 above 0.5. InputError when no pixel is selected or the mask's
// size differs.
RegionStats region_stats(const Image& img, const PixelRect& rect, const Image* mask = nullptr);

// The pixels' values at the given pixels, in order; InputError naming a pixel outside.
std::vector<Vec3> values_at(const Image& img, const std::vector<std::pair<int, int>>& pixels);

struct RadialBin {
    double r0 = 0, r1 = 0;  // pixel distances from the centre (pixel centres at +0.5)
    long long pixels = 0;
    Vec3 mean{0, 0, 0};
};
// Mean per ring of width max_radius / bins about (cx, cy) in pixel coordinates (x to the
// right, y down, the top-left corner at 0).
std::vector<RadialBin> radial_profile(const Image& img, double cx, double cy, int bins, double max_radius);

// A far-field detector's sphere map (refract farfield: far_field.exr, equal solid angle
// per pixel, intensities per steradian) re-binned by the angle θ of each pixel's centre
// direction to `axis` (default: the map's own axis): per bin of width 180°/bins, the
// pixels, the power (Σ intensity × pixel solid angle) and the mean intensity
// (power / the bin's solid angle) of every channel. InputError naming the image when it
// is not a sphere far-field map.
struct AngleBin {
    double theta0_deg = 0, theta1_deg = 0, solid_angle = 0;
    long long pixels = 0;
    std::vector<double> power, intensity;  // per channel of the map
};
std::vector<AngleBin> angle_histogram(const Channels& map, const std::string& name, int bins,
                                      const std::optional<Vec3>& axis = std::nullopt);

}  // namespace refract::validation
