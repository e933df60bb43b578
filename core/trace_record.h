#pragma once
// Path record: every segment of one ray's tree, walked by the one ray-tree walker with
// the scene's threshold, limits and polarisation model, with what happened at its end: the
// point, object and facet, the event, the cosines, Rs and Rp, the weight, the wavelength;
// inside a uniaxial crystal the wave (o or e) and its index.
// `refract trace` writes it as JSON (docs/scene-format.md, "Tracing one ray").
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <refract/core/scene.h>

namespace refract {

class SceneTracer;

struct TraceSegment {
    int id = 0;
    int parent = -1;     // the segment whose end this one starts from; −1: the primary ray
    int depth = 0, reflections = 0, transmissions = 0;
    Ray ray;
    // Cumulative attenuation along the segment (after its absorption); under exact
    // polarisation that of unpolarised light arriving along it (the colour weight times the
    // first element of its Mueller matrix to the camera).
    Vec3 weight{1, 1, 1};
    // What ends it: "background", or at a hit "diffuse", "emissive", "mirror",
    // "reflection and refraction", "reflection only" (the refracted branch too weak or
    // absent), "total internal reflection".
    std::string event;
    bool hit = false;
    double length = 0;  // to the hit (inside a gradient-index medium: along the curved ray)
    // Inside a gradient-index medium: the curved ray's points, from the origin to the hit
    // (the start, each step's end, the exit); `ray.dir` is then the direction it arrives in.
    std::vector<Vec3> path;
    Vec3 point{0, 0, 0};
    Vec3 normal{0, 0, 0};  // unit surface normal at the hit, on the incident side
    std::string object;
    int facet = -1;            // facet or triangle index, −1 for smooth shapes
    std::string facet_label;   // the polyhedron's facet name, when it has one
    bool entering = false;
    // Dielectric hits: cos θi, cos θt (0 on total internal reflection), Rs, Rp and the R
    // the node used; the relative index η = n_t / n_i.
    double cos_i = 0, cos_t = 0, Rs = 0, Rp = 0, R = 0, eta = 0;
    Vec3 light{0, 0, 0};  // what this segment brings to the root: weight × the light at its end (leaves)
    // A polarised trace (trace_ray with a polarisation state): the Stokes vector of the
    // light along the segment, as a fraction of the root's power (colour filters aside:
    // `weight` is the colour weight times S0), in the frame x̂ = stokes_x (across the
    // segment), ŷ = direction × x̂ (docs/polarisation.md).
    bool polarised = false;
    Eigen::Vector4d stokes = Eigen::Vector4d::Zero();
    Vec3 stokes_x{0, 0, 0};
    // Inside a uniaxial crystal: the wave the segment travels as (Ordinary, Extraordinary;
    // Isotropic elsewhere), its refractive index there (n_o; for the e wave the index of its
    // wave normal, biref::extraordinary_index) and its unit wave normal (the segment's
    // direction is the ray's, which the e wave's walk-off turns away from it).
    biref::Wave wave = biref::Wave::Isotropic;
    double index = 0;
    Vec3 wave_normal{0, 0, 0};
};

// The most segments one record holds (docs/limits.md): a tree with more is refused as
// /render, naming max_depth and threshold, before its record (a few hundred bytes a
// segment, and its JSON) outgrows the memory. The walk's own bounds are far larger.
constexpr std::size_t kMaxTraceSegments = std::size_t{1} << 16;

struct TraceRecord {
    double wavelength_nm = 0;  // 0: an RGB ray with each material's nominal index
    std::vector<TraceSegment> segments;
    Vec3 radiance{0, 0, 0};    // the sum of the segments' light: the ray's value
};

// The tree of `ray` (at `wavelength_nm` when > 0: every dielectric with a dispersion
// takes its index there). Throws InputError for an invalid scene or wavelength, or a tree
// of more than kMaxTraceSegments segments.
// With `polarisation`: the ray is light of that state travelling along it (a linear
// state's angle measured from its reference as for a light), walked with exact
// polarisation whatever the scene's model, each segment carrying its Stokes vector.
// Without: the camera's walk under the scene's model (polarisation_model()), so that a
// pixel's record sums to its rendered value.
TraceRecord trace_ray(const Scene& scene, const Ray& ray, double wavelength_nm = 0,
                      const PolarisationState* polarisation = nullptr);

// The same for the centre of pixel (i, j).
TraceRecord trace_pixel(const Scene& scene, int i, int j, double wavelength_nm = 0,
                        const PolarisationState* polarisation = nullptr);

// One scene's tracers, built once and kept for many queries: trace_ray() and trace_pixel()
// build the tracer (its acceleration structures, a gem's facet graphs) for every call, a
// session on its first query in each walk (the scene's own model, and the exact one for a
// polarised trace). The same records as those functions; queries may run from several
// threads at once.
class TraceSession {
public:
    explicit TraceSession(std::shared_ptr<const Scene> scene);
    ~TraceSession();
    TraceSession(const TraceSession&) = delete;
    TraceSession& operator=(const TraceSession&) = delete;

    TraceRecord ray(const Ray& ray, double wavelength_nm = 0, const PolarisationState* polarisation = nullptr) const;
    TraceRecord pixel(int i, int j, double wavelength_nm = 0, const PolarisationState* polarisation = nullptr) const;
    const Scene& scene() const { return *scene_; }
    // The tracer of the camera's walk under the scene's model (`polarised`: of the exact
    // model's walk), built on first use; its scene() is the one it walks.
    const SceneTracer& tracer(bool polarised = false) const;

    struct Walk;  // a scene as walked (its own model, or the exact one) and its tracer

private:
    const Walk& walk(bool polarised) const;

    std::shared_ptr<const Scene> scene_;
    mutable std::once_flag once_[2];
    mutable std::unique_ptr<Walk> walks_[2];
};

}  // namespace refract
