// Background::radiance (core/scene.h): what a ray that leaves the scene sees.
#include <refract/core/environment_map.h>
#include <refract/core/scene.h>

namespace refract {

Vec3 Background::radiance(const Vec3& dir) const {
    switch (kind) {
        case Kind::Solid:
            return color;
        case Kind::Gradient: {
            const double a = 0.5 * (dir.normalized().y() + 1.0);  // RTIOW ray_color sky
            return (1.0 - a) * bottom + a * top;
        }
        case Kind::Environment:
            // A map turned by rotation_deg shows in direction R·d what the unturned map
            // shows in d: look up R⁻¹·dir (POV-Ray: the sky_sphere's inverse transform).
            if (!map) return scale * color;
            return scale * map->lookup(rotation_deg == 0 ? dir : rotate_about_y(dir, -rotation_deg));
    }
    return color;
}

}  // namespace refract
