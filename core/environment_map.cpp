#include <refract/core/environment_map.h>

#include <algorithm>
#include <cmath>

#include <refract/core/image.h>
#include <refract/geometry/error.h>

namespace refract {
namespace {

// POV-Ray's wrap into [0, limit): fmod, plus the limit when negative, and a result that
// rounds up to the limit becomes 0.
double wrap(double v, double limit) {
    double w = std::fmod(v, limit);
    if (w < 0) w += limit;
    return w >= limit ? 0.0 : w;
}

int wrap_index(int k, int n) { return ((k % n) + n) % n; }

// The angle of (x, z) about +y from +x towards +z, in [0, 2π); 0 at the poles.
double azimuth(double x, double z) {
    double theta = std::atan2(z, x);
    if (theta < 0) theta += 2.0 * M_PI;
    return theta;
}

// One line, whatever OpenImageIO's message holds.
std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

void check_pixels(const EnvironmentMap& m) {
    for (int j = 0; j < m.height; ++j)
        for (int i = 0; i < m.width; ++i) {
            const Vec3 p = m.pixel(i, j);
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(p[c]))
                    throw InputError(m.path + ": pixel (" + std::to_string(i) + ", " + std::to_string(j) +
                                     ") is not finite (an environment map needs finite values >= 0)");
                if (!(p[c] >= 0 && p[c] <= 1e30))  // as light colours: sums must not overflow
                    throw InputError(m.path + ": pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") is " +
                                     format_value(p[c]) + " (an environment map needs values in [0, 1e30])");
            }
        }
}

}  // namespace

MapPoint spherical_map_point(const Vec3& dir, int width, int height) {
    const Vec3 d = dir.normalized();
    const double u = azimuth(d.x(), d.z()) / (2.0 * M_PI) * width;
    const double v = (0.5 + std::asin(std::clamp(d.y(), -1.0, 1.0)) / M_PI) * height;  // from the bottom
    const double nudge = 1e-10;  // POV-Ray's EPSILON, added before the wrap
    return {wrap(u + nudge, width), wrap(-(v + nudge), height)};
}

Vec3 EnvironmentMap::bilinear(double x, double y) const {
    // The four pixel centres around (x, y): columns i − 1 and i, rows j − 1 and j, with
    // (x, y) at fraction (p, q) of the way from the first to the second.
    const double xs = x + 0.5, ys = y + 0.5;
    const int i = static_cast<int>(xs), j = static_cast<int>(ys);
    const double p = xs - i, q = ys - j;
    const int i0 = wrap_index(i - 1, width), i1 = wrap_index(i, width);
    const int j0 = wrap_index(j - 1, height), j1 = wrap_index(j, height);
    return (1 - p) * (1 - q) * pixel(i0, j0) + p * (1 - q) * pixel(i1, j0) + (1 - p) * q * pixel(i0, j1) +
           p * q * pixel(i1, j1);
}

Vec3 EnvironmentMap::lookup(const Vec3& dir) const {
    const MapPoint m = spherical_map_point(dir, width, height);
    return bilinear(m.x, m.y);
}

Vec3 rotate_about_y(const Vec3& d, double deg) {
    const double a = deg * (M_PI / 180.0);
    const double c = std::cos(a), s = std::sin(a);
    return {c * d.x() + s * d.z(), d.y(), -s * d.x() + c * d.z()};
}

EnvironmentMap load_environment_map(const std::string& path) {
    Image img;  // a missing file, a directory or a device each get their own message (core/image.h)
    try {
        img = read_image(path);
    } catch (const InputError& e) {
        throw InputError(one_line(e.what()));
    }
    if (img.width <= 0 || img.height <= 0) throw InputError(path + ": the image is empty");
    EnvironmentMap m;
    m.path = path;
    m.width = img.width;
    m.height = img.height;
    m.rgb = std::move(img.rgb);
    check_pixels(m);
    return m;
}

}  // namespace refract
