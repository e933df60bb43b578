#include <refract/core/compat/povray.h>

#include <cmath>
#include <map>

#include <refract/core/hit_search.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/scene.h>

namespace refract::povray {

Vec3 fade(const Vec3& alpha, double distance) {
    Vec3 f;
    for (int c = 0; c < 3; ++c) {
        const float colour = static_cast<float>(1.0 - alpha[c]);  // fade_color, stored as float
        const float x = static_cast<float>(static_cast<float>(1.0f - colour) * distance);  // D = 1
        f[c] = static_cast<double>(static_cast<float>(std::exp(-static_cast<double>(x))));
    }
    return f;
}

Vec3 light_transmittance(const HitSearch& search, const Vec3& from, const Vec3& to, RenderStats& stats) {
    const Scene& scene = search.scene();
    Vec3 origin = from;
    double remaining = (to - from).norm();
    const Vec3 dir = (to - from) / remaining;
    Vec3 t(1, 1, 1);
    RayOrigin leaving;  // after the first crossing: the object and facet the ray leaves
    while (true) {
        const auto n = search.shadow_blocker(Ray{origin, dir}, kShadowTolerance, remaining, leaving, &stats);
        if (!n || n->hit.t >= remaining - kShadowTolerance) return t;
        const Material& m = scene.materials[static_cast<size_t>(n->object->material)];
        const Vec3* filter = shadow_filter(m);
        if (!filter) return Vec3(0, 0, 0);
        t = t.cwiseProduct(*filter);
        if (const spectrum::Absorption* a = absorption(m); a && n->hit.normal.dot(dir) > 0)
            t = t.cwiseProduct(fade(a->rgb, n->hit.t));
        origin = n->hit.point;
        remaining -= n->hit.t;
        leaving = RayOrigin{static_cast<std::int32_t>(n->object - scene.objects.data()), n->hit.facet};
    }
}

namespace {

// The POV-Ray law of a dielectric that splits (|D − 1| >= EPSILON in single precision), or null.
const spectrum::PovRayModel* splitting_model(const Material& m) {
    constexpr double kEpsilon = 1e-10;
    const auto* d = m.dielectric();
    if (!d || !d->dispersion || !d->dispersion->is_povray()) return nullptr;
    const auto& p = std::get<spectrum::PovRayModel>(d->dispersion->model);
    return std::fabs(stored_index(p.dispersion) - 1.0) >= kEpsilon ? &p : nullptr;
}

}  // namespace

void spectral_bands(const Scene& scene, SpectralContext& c) {
    std::map<int, std::vector<int>> sets;  // samples → its bands
    for (size_t mi = 0; mi < scene.materials.size(); ++mi) {
        const spectrum::PovRayModel* p = splitting_model(scene.materials[mi]);
        if (!p) continue;
        const auto [set, added] = sets.try_emplace(p->samples);
        if (added)
            for (const auto& b : spectrum::povray_bands(p->samples)) {
                set->second.push_back(static_cast<int>(c.wavelengths.size()));
                c.wavelengths.push_back(b.wavelength_nm);
                c.weights.push_back(b.hue / p->samples);
            }
        c.dispersive[mi] = 1;
        c.split_bands[mi] = set->second;
    }
    c.clip = false;  // POV-Ray keeps the band sums as they are
    c.split = SpectralContext::Split::Refraction;
}

}  // namespace refract::povray
