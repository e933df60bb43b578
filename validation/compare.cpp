#include "validation/compare.h"
#include "validation/measure.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "geometry/atomic_file.h"
#include "geometry/error.h"

namespace refract::validation {
namespace {

namespace IBA = OIIO::ImageBufAlgo;

OIIO::ImageBuf to_buf(const Image& img) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT));
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::DOUBLE, img.rgb.data());
    return buf;
}

Image from_buf(const OIIO::ImageBuf& buf) {
    const OIIO::ImageSpec& s = buf.spec();
    Image img(s.width, s.height);
    OIIO::ROI roi = buf.roi();
    roi.chend = 3;
    buf.get_pixels(roi, OIIO::TypeDesc::DOUBLE, img.rgb.data());
    return img;
}

void same_size(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw InputError("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) + " image with a " +
                         std::to_string(b.width) + "x" + std::to_string(b.height) + " one");
}

}  // namespace

ImageDifference compare_images(const Image& a, const Image& b, double tolerance) {
    same_size(a, b);
    const auto r = IBA::compare(to_buf(a), to_buf(b), static_cast<float>(tolerance), static_cast<float>(tolerance));
    // (r.error is also set when any pixel fails the threshold: not an error here.)
    ImageDifference d;
    d.rmse = r.rms_error;
    d.max_error = r.maxerror;
    d.mean_error = r.meanerror;
    d.psnr = r.rms_error > 0 ? 20.0 * std::log10(1.0 / r.rms_error) : INFINITY;
    d.max_x = r.maxx;
    d.max_y = r.maxy;
    d.pixels = static_cast<long long>(a.width) * a.height;
    d.pixels_over = static_cast<long long>(r.nfail);
    d.fraction_over = d.pixels > 0 ? static_cast<double>(d.pixels_over) / d.pixels : 0.0;
    return d;
}

Image clamp01(const Image& img) {
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    return from_buf(IBA::clamp(to_buf(img), lo, hi));
}

void write_heatmap(const std::string& path, const Image& a, const Image& b) {
    same_size(a, b);
    OIIO::ImageBuf diff = IBA::maxchan(IBA::absdiff(to_buf(a), to_buf(b)));
    // Log scale (OpenImageIO has no log operator): 1e-6 -> 0, 1e-1 -> 1.
    for (OIIO::ImageBuf::Iterator<float> it(diff); !it.done(); ++it) {
        const float v = it[0];
        it[0] = v <= 1e-6f ? 0.0f : std::clamp((std::log10(v) + 6.0f) / 5.0f, 0.0f, 1.0f);
    }
    OIIO::ImageBuf heat = IBA::color_map(diff, 0, "inferno");
    if (heat.has_error()) throw InputError(path + ": cannot build heat map: " + heat.geterror());
    TempFile tmp(path, true);  // the extension picks the writer
    heat.set_write_format(OIIO::TypeDesc::UINT8);
    if (!heat.write(tmp.path())) throw InputError(path + ": cannot write heat map: " + heat.geterror());
    tmp.commit();
}

std::vector<std::pair<int, int>> line_pixels(int x0, int y0, int x1, int y1) {
    const int n = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
    std::vector<std::pair<int, int>> px;
    for (int k = 0; k <= n; ++k) {
        const double t = n == 0 ? 0.0 : static_cast<double>(k) / n;
        px.emplace_back(static_cast<int>(std::lround(x0 + t * (x1 - x0))), static_cast<int>(std::lround(y0 + t * (y1 - y0))));
    }
    return px;
}

ProfileComparison compare_profile(const Image& img, const std::vector<std::pair<int, int>>& pixels, int channel,
                                  const std::function<std::optional<double>(int, int)>& expected) {
    if (channel < 0 || channel > 2) throw InputError("profile channel must be 0, 1 or 2 (got " + std::to_string(channel) + ")");
    ProfileComparison p;
    double sq = 0;
    std::vector<Vec3> values;
    try {
        values = values_at(img, pixels);  // validation/measure.h
    } catch (const InputError& e) {
        throw InputError(std::string("profile ") + e.what());
    }
    for (size_t k = 0; k < pixels.size(); ++k) {
        const auto [x, y] = pixels[k];
        const auto e = expected(x, y);
        if (!e) continue;
        const double v = values[k][channel];
        p.points.push_back({x, y, v, *e});
        const double err = std::abs(v - *e);
        p.max_error = std::max(p.max_error, err);
        sq += err * err;
    }
    if (!p.points.empty()) p.rmse = std::sqrt(sq / static_cast<double>(p.points.size()));
    return p;
}

}  // namespace refract::validation
