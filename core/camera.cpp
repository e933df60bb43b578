#include <refract/core/camera.h>

#include <cmath>

namespace refract {

Camera::Basis Camera::basis() const {
    // POV-Ray Parse_Camera with look_at: D̂ = normalize(look_at − location),
    // R = |right|·normalize(sky × D̂), U = |up|·(D̂ × R̂), right = x·W/H, up = y.
    const double aspect = static_cast<double>(width) / height;
    const Vec3 d = unit_vector(look_at - location).value_or(Vec3::Zero());
    const Vec3 r = unit_vector(sky.cross(d)).value_or(Vec3::Zero());
    const Vec3 u = d.cross(r);
    Basis b;
    if (type == Type::Perspective) {
        const double right_len = aspect;
        // |D| = |right| / tan(A·π/360) / 2.
        const double d_len = right_len / std::tan(angle_deg * M_PI / 360.0) / 2.0;
        b.D = d * d_len;
        b.R = r * right_len;
        b.U = u;
    } else {
        b.D = d;
        b.R = r * (ortho_height * aspect);
        b.U = u * ortho_height;
    }
    return b;
}

Ray Camera::ray(double x, double y) const { return ray(basis(), x, y); }

Ray Camera::ray(const Basis& b, double x, double y) const {
    const double x0 = x / width - 0.5;
    const double y0 = 0.5 - y / height;
    if (type == Type::Perspective)
        return Ray{location, (b.D + x0 * b.R + y0 * b.U).normalized()};
    return Ray{location + x0 * b.R + y0 * b.U, b.D};
}

Ray Camera::ray(const Basis& b, double x, double y, double u, double v) const {
    const Ray pin = ray(b, x, y);
    if (!thin_lens()) return pin;
    // The pinhole ray meets the plane in focus (normal D̂, at focus_distance) at P.
    const Vec3 d_hat = b.D.normalized();
    const Vec3 P = pin.origin + pin.dir * (focus_distance / pin.dir.dot(d_hat));
    const double r = 0.5 * aperture * std::sqrt(u), phi = 2.0 * M_PI * v;
    const Vec3 lens = location + r * std::cos(phi) * b.R.normalized() + r * std::sin(phi) * b.U.normalized();
    return Ray{lens, (P - lens).normalized()};
}

double thin_lens_blur_diameter(double aperture, double focus_distance, double z) {
    return aperture * std::fabs(z - focus_distance) / z;
}

}  // namespace refract
