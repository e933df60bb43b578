#include <refract/validation/compare.h>
#include <refract/validation/measure.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unistd.h>

#include <refract/core/image_io.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace refract::validation {
namespace {

void same_size(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw InputError("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) + " image with a " +
                         std::to_string(b.width) + "x" + std::to_string(b.height) + " one");
}

}  // namespace

ImageDifference compare_images(const Image& a, const Image& b, double tolerance) {
    same_size(a, b);
    CompareStats r;  // the image module's ImageBufAlgo::compare (core/image_io.h)
    throw_if_failed(image_io().compare(a.rgb.data(), b.rgb.data(), a.width, a.height, tolerance, r), "");
    ImageDifference d;
    d.rmse = r.rms_error;
    d.max_error = r.max_error;
    d.mean_error = r.mean_error;
    d.psnr = r.rms_error > 0 ? 20.0 * std::log10(1.0 / r.rms_error) : INFINITY;
    d.max_x = r.max_x;
    d.max_y = r.max_y;
    d.pixels = static_cast<long long>(a.width) * a.height;
    d.pixels_over = r.nfail;
    d.fraction_over = d.pixels > 0 ? static_cast<double>(d.pixels_over) / d.pixels : 0.0;
    return d;
}

ImageDifference compare_with_povray_image(const Image& refract, const Image& povray, const Targets& targets) {
    return compare_images(clamp01(refract), povray, targets.pixel_tolerance);
}

Image block_means(const Image& img, int block) {
    const int w = (img.width + block - 1) / block, h = (img.height + block - 1) / block;
    Image r(w, h);
    for (int bj = 0; bj < h; ++bj)
        for (int bi = 0; bi < w; ++bi) {
            Vec3 sum = Vec3::Zero();
            int n = 0;
            for (int j = bj * block; j < std::min(img.height, (bj + 1) * block); ++j)
                for (int i = bi * block; i < std::min(img.width, (bi + 1) * block); ++i, ++n) sum += img.at(i, j);
            r.set(bi, bj, sum / n);
        }
    return r;
}

Image clamp01(const Image& img) {
    Image out(img.width, img.height);
    throw_if_failed(image_io().clamp01(img.rgb.data(), img.width, img.height, out.rgb.data()), "");
    return out;
}

void write_heatmap(const std::string& path, const Image& a, const Image& b) {
    same_size(a, b);
    const ImageIoModule& io = image_io();
    TempFile tmp(path);  // written through its descriptor; the extension of `path` picks the writer
    throw_if_failed(io.heatmap(a.rgb.data(), b.rgb.data(), a.width, a.height, tmp.fd(), path), path);
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
