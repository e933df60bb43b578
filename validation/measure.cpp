#include <refract/validation/measure.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <refract/core/far_field.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <refract/geometry/error.h>

namespace refract::validation {

RegionStats region_stats(const Image& img, const PixelRect& rect, const Image* mask) {
    if (mask && (mask->width != img.width || mask->height != img.height))
        throw InputError("mask is " + std::to_string(mask->width) + "x" + std::to_string(mask->height) +
                         ", the image " + std::to_string(img.width) + "x" + std::to_string(img.height));
    RegionStats s;
    for (auto& c : s.channel) {
        c.min = std::numeric_limits<double>::infinity();
        c.max = -std::numeric_limits<double>::infinity();
    }
    const int x0 = std::max(0, std::min(rect.x0, rect.x1)), x1 = std::min(img.width - 1, std::max(rect.x0, rect.x1));
    const int y0 = std::max(0, std::min(rect.y0, rect.y1)), y1 = std::min(img.height - 1, std::max(rect.y0, rect.y1));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            if (mask && !(mask->at(x, y).x() > 0.5)) continue;
            const Vec3 v = img.at(x, y);
            ++s.pixels;
            for (int c = 0; c < 3; ++c) {
                s.channel[static_cast<size_t>(c)].sum += v[c];
                s.channel[static_cast<size_t>(c)].min = std::min(s.channel[static_cast<size_t>(c)].min, v[c]);
                s.channel[static_cast<size_t>(c)].max = std::max(s.channel[static_cast<size_t>(c)].max, v[c]);
            }
        }
    if (s.pixels == 0) throw InputError("the region selects no pixel");
    for (auto& c : s.channel) c.mean = c.sum / static_cast<double>(s.pixels);
    return s;
}

std::vector<Vec3> values_at(const Image& img, const std::vector<std::pair<int, int>>& pixels) {
    std::vector<Vec3> v;
    v.reserve(pixels.size());
    for (const auto& [x, y] : pixels) {
        if (x < 0 || y < 0 || x >= img.width || y >= img.height)
            throw InputError("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the image");
        v.push_back(img.at(x, y));
    }
    return v;
}

std::vector<RadialBin> radial_profile(const Image& img, double cx, double cy, int bins, double max_radius) {
    if (bins < 1 || !(max_radius > 0) || !std::isfinite(max_radius) || !std::isfinite(cx) || !std::isfinite(cy))
        throw InputError("radial profile: needs bins >= 1, a finite centre and a finite radius > 0");
    std::vector<RadialBin> out(static_cast<size_t>(bins));
    const double w = max_radius / bins;
    for (int k = 0; k < bins; ++k) out[static_cast<size_t>(k)].r0 = k * w, out[static_cast<size_t>(k)].r1 = (k + 1) * w;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            if (r >= max_radius) continue;
            RadialBin& b = out[static_cast<size_t>(std::min(bins - 1, static_cast<int>(r / w)))];
            b.mean += img.at(x, y);
            ++b.pixels;
        }
    for (auto& b : out)
        if (b.pixels > 0) b.mean /= static_cast<double>(b.pixels);
    return out;
}

namespace {

Vec3 parse_vec3(const Channels& map, const std::string& name, const std::string& key) {
    const std::string* v = map.attribute(key);
    if (!v) throw InputError(name + ": not a far-field sphere map (no " + key + " in its header)");
    std::istringstream in(*v);
    double x, y, z;
    if (!(in >> x >> y >> z)) throw InputError(name + ": " + key + " '" + clip_echo(*v) + "' is not three numbers");
    return {x, y, z};
}

}  // namespace

std::vector<AngleBin> angle_histogram(const Channels& map, const std::string& name, int bins,
                                      const std::optional<Vec3>& axis) {
    const std::string* kind = map.attribute("refract:far_field");
    if (!kind || *kind != "sphere")
        throw InputError(name + ": not a far-field sphere map (refract farfield --binning sphere writes one)");
    if (bins < 1 || bins > (1 << 20)) throw InputError(name + ": --bins must be in [1, 2^20]");
    FarFieldSettings s;
    s.binning = FarFieldSettings::Binning::Sphere;
    s.axis = parse_vec3(map, name, "refract:far_field_axis");
    s.reference = parse_vec3(map, name, "refract:far_field_reference");
    s.azimuth_bins = map.width;
    s.polar_bins = map.height;
    const auto unit = unit_vector(axis.value_or(s.axis));
    if (!unit) throw InputError(name + ": the axis must be a finite, non-zero vector");
    const Vec3 a = *unit;
    const size_t nc = map.names.size();
    const double pixel_omega = 4.0 * M_PI / (static_cast<double>(map.width) * map.height);
    std::vector<AngleBin> out(static_cast<size_t>(bins));
    for (int b = 0; b < bins; ++b) {
        AngleBin& bin = out[static_cast<size_t>(b)];
        bin.theta0_deg = 180.0 * b / bins;
        bin.theta1_deg = 180.0 * (b + 1) / bins;
        bin.solid_angle = 2.0 * M_PI * (std::cos(bin.theta0_deg * M_PI / 180) - std::cos(bin.theta1_deg * M_PI / 180));
        bin.power.assign(nc, 0.0);
    }
    for (int p = 0; p < map.width * map.height; ++p) {
        const Vec3 d = bin_direction(s, p);
        const double theta = std::acos(std::clamp(d.dot(a), -1.0, 1.0));
        const int b = std::min(bins - 1, static_cast<int>(theta / M_PI * bins));
        AngleBin& bin = out[static_cast<size_t>(b)];
        ++bin.pixels;
        for (size_t c = 0; c < nc; ++c) bin.power[c] += map.data[static_cast<size_t>(p) * nc + c] * pixel_omega;
    }
    for (AngleBin& bin : out) {
        bin.intensity.resize(nc);
        for (size_t c = 0; c < nc; ++c) bin.intensity[c] = bin.power[c] / bin.solid_angle;
    }
    return out;
}

}  // namespace refract::validation
