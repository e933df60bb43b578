#include <refract/core/polarisation_state.h>

#include <cmath>

#include <refract/core/scene.h>

namespace refract {

namespace {

// The frame x̂ of light reaching the camera along the primary ray, and +1 when the
// frame's ŷ = k̂ × x̂ points to the image's top, −1 when to its bottom.
std::pair<Vec3, double> camera_frame(const Scene& scene, const Ray& primary) {
    const Camera::Basis b = scene.camera.basis();
    const Vec3 k = -primary.dir;
    const Vec3 x = (b.R - b.R.dot(k) * k).normalized();
    return {x, k.cross(x).dot(b.U) >= 0 ? 1.0 : -1.0};
}

}  // namespace

EyeStokes camera_stokes(const Scene& scene, const Ray& primary) {
    const auto [x, up] = camera_frame(scene, primary);
    EyeStokes s;
    s.x = x;
    if (const auto& a = scene.settings.analyser) {
        switch (a->kind) {
            case PolarisationState::Kind::Unpolarised: break;
            case PolarisationState::Kind::Linear: s.C = polar::linear_polariser(up * a->angle_deg * M_PI / 180.0); break;
            case PolarisationState::Kind::Circular: s.C = polar::circular_polariser(a->handedness); break;
        }
    }
    return s;
}

LinearPolarisation linear_polarisation(const StokesRGB& s, const Scene& scene, const Ray& primary) {
    const polar::Stokes S = s.rowwise().sum();
    const double up = camera_frame(scene, primary).second;
    // Colour-matching weights have negative lobes, so a channel sum can have |S1, S2| > S0
    // in spectral renders: the degree is clamped to 1.
    return {std::fmin(1.0, polar::degree_of_linear_polarisation(S)), up * polar::angle_of_linear_polarisation(S)};
}

}  // namespace refract
