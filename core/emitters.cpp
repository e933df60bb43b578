#include <refract/core/emitters.h>

#include <algorithm>
#include <cmath>

#include <refract/core/area_light.h>
#include <refract/core/environment_map.h>
#include <refract/geometry/error.h>

namespace refract {

namespace {

// A direction uniform in solid angle in the cone of cos θ >= cos_max about `axis`, from
// two uniform numbers: cos θ = 1 − xi (1 − cos_max), azimuth phi in the frame across it.
Vec3 in_cone(const Vec3& axis, const Frame& f, double cos_max, double xi, double phi) {
    const double cos_t = 1.0 - xi * (1.0 - cos_max);
    const double sin_t = std::sqrt(std::fmax(0.0, 1.0 - cos_t * cos_t));
    return (cos_t * axis + sin_t * (std::cos(phi) * f.u + std::sin(phi) * f.v)).normalized();
}

// Refuses an emitter whose photon power overflowed (a light or objects too far away).
void check_power(const Scene& scene, const Emitter& em, const std::string& where) {
    if (em.power.allFinite()) return;
    throw InputError((scene.source.empty() ? std::string("scene") : scene.source) + ": " + where +
                     ": the light pass's photon power overflows (lights and objects must lie within about 1e150 of "
                     "each other)");
}

}  // namespace

Frame frame_across(const Vec3& axis) {
    const Vec3 a = std::abs(axis.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 u = axis.cross(a).normalized();
    return {u, axis.cross(u)};
}

std::vector<BoundingSphere> transparent_targets(const Scene& scene) {
    std::vector<BoundingSphere> targets;
    for (const Object& o : scene.objects)
        if (transparent(scene.materials[static_cast<size_t>(o.material)]))
            if (auto b = bounding_sphere(o.shape)) targets.push_back(*b);
    return targets;
}

std::vector<Emitter> make_emitters(const Scene& scene, const std::vector<BoundingSphere>& targets, const Vec3& centre,
                                   std::uint64_t photons) {
    std::vector<Emitter> out;
    const std::uint64_t per_target = targets.empty() ? 0 : std::max<std::uint64_t>(1, photons / targets.size());
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& L = scene.lights[l];
        switch (L.kind) {
            case Light::Kind::Beam: {
                Emitter em;
                em.kind = Emitter::Kind::Disk;
                em.origin = L.position;
                em.axis = L.direction;
                em.radius = L.radius;
                em.photons = std::max<std::uint64_t>(1, photons);
                em.power = L.color * (M_PI * L.radius * L.radius / static_cast<double>(em.photons));  // irradiance × area
                em.stream = (std::uint64_t{1} << 40) + l;  // apart from the (light, target) streams
                em.light = l;
                em.frame = frame_across(em.axis);
                check_power(scene, em, "/lights/" + std::to_string(l));
                out.push_back(em);
                continue;
            }
            case Light::Kind::Point:
            case Light::Kind::Directional:
            case Light::Kind::Rectangle:
            case Light::Kind::Disk: break;
        }
        for (size_t t = 0; t < targets.size(); ++t) {
            const double R = targets[t].radius;
            Emitter em;
            em.photons = per_target;
            em.stream = l * targets.size() + t;
            em.light = l;
            switch (L.kind) {
                case Light::Kind::Directional: {
                    em.kind = Emitter::Kind::Disk;
                    em.axis = L.direction;
                    em.cos_max = std::cos(0.5 * L.angular_diameter_deg * M_PI / 180.0);
                    const double back = R * 1.01 + 1e-6;  // the disk stands just outside the sphere
                    em.origin = targets[t].centre - back * L.direction;
                    // A tilted ray from the disk must still reach every point of the sphere.
                    const double tan_max = std::sqrt(std::fmax(0.0, 1.0 - em.cos_max * em.cos_max)) / em.cos_max;
                    em.radius = R + (back + R) * tan_max;
                    em.power = L.color * (M_PI * em.radius * em.radius / static_cast<double>(per_target));
                    break;
                }
                case Light::Kind::Point: {
                    const Vec3 to = targets[t].centre - L.position;
                    const double d = to.norm();
                    if (d <= R) continue;  // light inside the bounds
                    const double sin_max = R / d;
                    em.cos_max = std::sqrt(1.0 - sin_max * sin_max);
                    em.dref = (centre - L.position).norm();
                    // It cancels (the power grows with dref², the deposit's falloff divides by
                    // it): any positive value does, when the light sits at the targets' centre.
                    if (!(em.dref > 0)) em.dref = 1.0;
                    em.origin = L.position;
                    em.axis = to / d;
                    const double omega = 2.0 * M_PI * (1.0 - em.cos_max);
                    em.power = L.color * (em.dref * em.dref * omega / static_cast<double>(per_target));
                    break;
                }
                case Light::Kind::Rectangle:
                case Light::Kind::Disk: {
                    // Each point of the area emits as a point light does (isotropically, no
                    // falloff): a photon starts at a uniform point of the grid's continuum
                    // (core/area_light.h) into the cone about the target that covers it from
                    // every point of the area (the whole sphere when the area comes within R).
                    em.kind = Emitter::Kind::Area;
                    em.area = &L;
                    em.origin = targets[t].centre;
                    // The farthest point of the area from its centre (the disk's grid reaches 0.501 of
                    // its axes: POV-Ray's 0.001 offset).
                    const double reach = L.kind == Light::Kind::Disk ? 0.502 * L.axis1.norm()
                                                                     : 0.5 * (L.axis1.norm() + L.axis2.norm());
                    const double d = (targets[t].centre - L.position).norm() - reach;
                    em.cos_max = d > R ? std::sqrt(1.0 - (R / d) * (R / d)) : -1.0;
                    em.dref = (centre - L.position).norm();
                    if (!(em.dref > 0)) em.dref = 1.0;
                    const double omega = 2.0 * M_PI * (1.0 - em.cos_max);
                    em.power = L.color * (em.dref * em.dref * omega / static_cast<double>(per_target));
                    break;
                }
                case Light::Kind::Beam: continue;
            }
            em.frame = frame_across(em.axis);
            check_power(scene, em, "/lights/" + std::to_string(l));
            out.push_back(em);
        }
    }
    if (scene.background.kind == Background::Kind::Environment) {
        const Background& bg = scene.background;
        // The brightest radiance bounds a photon's power (the light pass's fixed point).
        Vec3 max_l = bg.color;
        if (bg.map) {
            max_l = Vec3::Zero();
            for (int j = 0; j < bg.map->height; ++j)
                for (int i = 0; i < bg.map->width; ++i) max_l = max_l.cwiseMax(bg.map->pixel(i, j));
        }
        max_l *= bg.scale;
        for (size_t t = 0; t < targets.size(); ++t) {
            const double R = targets[t].radius;
            Emitter em;
            em.kind = Emitter::Kind::Environment;
            em.origin = targets[t].centre;
            em.axis = Vec3(0, 0, 1);
            em.radius = R * 1.01 + 1e-6;
            em.photons = per_target;
            em.stream = (std::uint64_t{1} << 41) + t;
            em.environment = &bg;
            em.geometry = M_PI * em.radius * em.radius * 4.0 * M_PI / static_cast<double>(per_target);
            em.power = max_l * em.geometry;
            check_power(scene, em, "/background");
            if (max_l.maxCoeff() > 0) out.push_back(em);
        }
    }
    return out;
}

const PolarisationState& emitter_polarisation(const Scene& scene, const Emitter& em) {
    static const PolarisationState unpolarised;
    return em.kind == Emitter::Kind::Environment ? unpolarised : scene.lights[em.light].polarisation;
}

PhotonRay sample_photon(const Emitter& em, std::uint64_t seed, std::uint64_t p) {
    Rng rng(seed, em.stream, p);
    if (em.kind == Emitter::Kind::Environment) {
        // A direction of travel d uniform on the sphere, from the environment at −d, through
        // the disk across d that covers the target.
        const Vec3 d = rng.unit_vector();
        const Frame f = frame_across(d);
        const double r = em.radius * std::sqrt(rng.uniform()), phi = 2.0 * M_PI * rng.uniform();
        const Vec3 origin = em.origin - em.radius * d + r * (std::cos(phi) * f.u + std::sin(phi) * f.v);
        return {Ray{origin, d}, em.environment->radiance(-d) * em.geometry};
    }
    if (em.kind == Emitter::Kind::Area) {
        const double a = rng.uniform(), b = rng.uniform();
        const Vec3 origin = area_light_point(*em.area, a, b);
        const Vec3 axis = (em.origin - origin).normalized();
        const double xi = rng.uniform(), phi = 2.0 * M_PI * rng.uniform();
        return {Ray{origin, in_cone(axis, frame_across(axis), em.cos_max, xi, phi)}, em.power};
    }
    const double xi = rng.uniform();
    const double phi = 2.0 * M_PI * rng.uniform();
    if (em.kind == Emitter::Kind::Cone)  // uniform in the cone's solid angle
        return {Ray{em.origin, in_cone(em.axis, em.frame, em.cos_max, xi, phi)}, em.power};
    // Uniform over the disk's area.
    const Vec3 origin = em.origin + em.radius * std::sqrt(xi) * (std::cos(phi) * em.frame.u + std::sin(phi) * em.frame.v);
    if (em.cos_max >= 1.0) return {Ray{origin, em.axis}, em.power};
    // A sun's disk: a direction uniform in its cone, weighted by its cosine across the disk
    // (radiance E / (π sin²α) over the cone's solid angle 2π(1 − cos α)).
    const double eta = rng.uniform();
    const Vec3 dir = in_cone(em.axis, em.frame, em.cos_max, eta, 2.0 * M_PI * rng.uniform());
    const double cos_t = 1.0 - eta * (1.0 - em.cos_max);
    const double weight = cos_t * 2.0 * (1.0 - em.cos_max) / (1.0 - em.cos_max * em.cos_max);
    return {Ray{origin, dir}, em.power * weight};
}

LightStokes emitted(const PolarisationState& p, const Vec3& dir) {
    Vec3 ref = p.reference - p.reference.dot(dir) * dir;
    if (ref.norm() < 1e-9) ref = Vec3(1, 0, 0) - dir.x() * dir;  // the beam runs along the reference
    LightStokes s;
    s.x = ref.normalized();
    switch (p.kind) {
        case PolarisationState::Kind::Unpolarised: s.S = polar::unpolarised(1.0); break;
        case PolarisationState::Kind::Linear: s.S = polar::linear(1.0, p.angle_deg * M_PI / 180.0); break;
        case PolarisationState::Kind::Circular: s.S = polar::circular(1.0, p.handedness); break;
    }
    return s;
}

}  // namespace refract
