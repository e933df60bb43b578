#pragma once
// An environment light's map: an equirectangular (latitude-longitude) RGB image held in
// memory, looked up as POV-Ray 3.7 looks up `image_map { … map_type 1 interpolate 2 }`
// on a sky_sphere (docs/scene-format.md, "background"):
//   column coordinate u = W·θ/2π, θ the angle about +y from +x towards +z in [0, 2π):
//     the left edge of the image looks along +x, u = W/4 along +z, the centre along −x;
//   row coordinate from the top, H·(1/2 − asin(dir.y)/π): the top row is at +y, the
//     bottom row at −y;
//   bilinear between pixel centres (pixel i's centre at i + 1/2), wrapping around in both
//   directions, rows too: within half a row of either pole the top and the bottom rows
//   blend, as in POV-Ray.
#include <string>
#include <vector>

#include <refract/geometry/ray.h>

namespace refract {

struct EnvironmentMap {
    std::string path;         // the file it was read from (for messages and the export)
    int width = 0;
    int height = 0;
    std::vector<double> rgb;  // row-major, 3 per pixel, row 0 at the top (+y)

    Vec3 pixel(int i, int j) const {
        const size_t k = (static_cast<size_t>(j) * width + i) * 3;
        return {rgb[k], rgb[k + 1], rgb[k + 2]};
    }
    // The map's value for a direction (any length but zero), unrotated and unscaled.
    Vec3 lookup(const Vec3& dir) const;
    // Bilinear between pixel centres at continuous pixel coordinates (x, y) ∈ [0, W) ×
    // [0, H), y from the top; neighbours wrap around in both directions.
    Vec3 bilinear(double x, double y) const;
};

// Continuous pixel coordinates of a direction on a W × H map, in [0, W) × [0, H), with
// POV-Ray's 1e-10 nudge before the wrap (imageutil.cpp map_pos).
struct MapPoint {
    double x, y;
};
MapPoint spherical_map_point(const Vec3& dir, int width, int height);

// Reads the map: any image OpenImageIO reads, values as stored (no transfer function),
// RGB (one channel: grey; alpha ignored). Throws InputError with one line naming `path`
// when the file is missing or unreadable, the image is empty, or a value is negative or
// not finite (naming the first such pixel).
EnvironmentMap load_environment_map(const std::string& path);

// The direction turned by `deg` degrees about +y, right-handed (+z towards +x): the
// matrix of POV-Ray's `rotate y*deg`.
Vec3 rotate_about_y(const Vec3& dir, double deg);

}  // namespace refract
