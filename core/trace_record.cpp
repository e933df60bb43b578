#include <refract/core/trace_record.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <tuple>
#include <vector>

#include <refract/core/emitters.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/optics.h>
#include <refract/core/ray_tree.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/core/trace_walk.h>
#include <refract/geometry/error.h>

namespace refract {

namespace {

// Records every entry the walker pops; a segment's parent is the node that pushed it (the
// list is FIFO: the entries come back in the order their parents' nodes pushed them). Its
// intercept() expands every node itself (trace_walk::expand), with one interaction.
template <class P>
class RecordingEnds {
public:
    using Entry = TreeEntryT<P>;
    using Walker = RayTreeWalkerT<P>;

    RecordingEnds(const SceneTracer& t, double nm, TraceRecord& r, RenderStats& st)
        : tracer_(t), nm_(nm), rec_(r), stats_(st) {}

    void background(const Entry& e) {
        TraceSegment& s = start(e);
        s.event = "background";
        s.light = trace_walk::light(e, s.weight, tracer_.background(e.ray.dir));
        rec_.radiance += s.light;
    }

    void leaf(const Entry& e, const SurfaceHit& h) {
        TraceSegment& s = rec_.segments[static_cast<size_t>(current_)];
        s.event = describe(*h.material, Interaction{}, h, e.ray, 0.0).event;
        s.light = trace_walk::light(e, s.weight, tracer_.local_light(h, stats_));
        rec_.radiance += s.light;
    }

    bool intercept(Walker& walker, const Entry& e, const SurfaceHit& h, typename Walker::List& list) {
        TraceSegment& s = start(e);
        current_ = s.id;
        s.hit = true;
        s.length = h.hit.t;
        s.point = h.hit.point;
        s.normal = h.normal;
        s.object = h.object->name;
        s.facet = h.hit.facet;
        if (const auto* c = std::get_if<ConvexPolyhedron>(&h.object->shape))
            if (h.hit.facet >= 0 && static_cast<size_t>(h.hit.facet) < c->labels.size())
                s.facet_label = c->labels[static_cast<size_t>(h.hit.facet)];
        s.entering = h.entering;
        hit_material_[static_cast<size_t>(s.id)] = h.material;
        const Interaction in = trace_walk::interact(tracer_, e, h, *this, stats_);
        if (!in.leaf) {  // leaf() names a leaf's event
            const NodeRecord r = describe(*h.material, in, h, e.ray, band_ior(e, h));
            s.event = r.event;
            s.R = r.R;
            if (r.dielectric) {
                s.eta = r.eta;
                s.cos_i = r.cos_i;
                s.cos_t = r.cos_t;
                s.Rs = r.Rs;
                s.Rp = r.Rp;
            }
        }
        const int id = s.id;  // `s` moves as the children's segments are added later
        trace_walk::expand(walker, e, h, in, list, *this, [&](int b) {
            parents_.push_back(id);
            departures_.push_back(in.branch[static_cast<size_t>(b)].ray.dir);
        });
        return true;
    }

    double band_ior(const Entry&, const SurfaceHit& h) const {
        if (nm_ <= 0 || !dispersive(*h.material)) return 0.0;
        return band_index(*h.material, nm_, tracer_.rules());
    }
    double wavelength(const Entry&) const { return nm_; }

private:
    TraceSegment& start(const Entry& e) {
        if (rec_.segments.size() >= kMaxTraceSegments)
            tree_too_large(tracer_.scene(), "took more than " + std::to_string(kMaxTraceSegments) +
                                                " segments, the most a trace records");
        TraceSegment& s = rec_.segments.emplace_back();
        s.id = static_cast<int>(rec_.segments.size() - 1);
        const Vec3 departure = s.id == 0 ? root_dir_ : departures_[next_parent_];
        s.parent = s.id == 0 ? -1 : parents_[next_parent_++];
        curved_path(s, e, departure);
        s.depth = e.depth;
        s.reflections = e.reflections;
        s.transmissions = e.transmissions;
        s.ray = e.ray;
        s.weight = trace_walk::weight(e);
        if constexpr (std::is_same_v<P, LightStokes>) {
            s.polarised = true;
            s.stokes = e.pol.S;
            s.stokes_x = e.pol.x;
        }
        s.wave = e.wave;
        if (e.wave != biref::Wave::Isotropic && s.parent >= 0) {
            // A crystal's wave starts at the crystal's own surface: the parent's hit.
            const Material* m = hit_material_[static_cast<size_t>(s.parent)];
            if (const auto* u = m ? m->as<material::Uniaxial>() : nullptr) {
                const Vec3 k = biref::wave_vector_of_ray(u->medium(nm_), e.wave, e.ray.dir);
                s.index = k.norm();
                s.wave_normal = k / s.index;
            }
        }
        hit_material_.push_back(nullptr);
        return s;
    }

    // A segment inside a gradient-index medium: its curved path, the walk's own (the same
    // integration from the same start: the walker turned e.ray to its arrival direction).
    void curved_path(TraceSegment& s, const Entry& e, const Vec3& departure) const {
        const grin::Medium* m = tracer_.medium_of(Ray{e.ray.origin, departure}, e.from);
        if (!m) return;
        grin::Settings st = m->settings;
        st.record_path = true;
        const grin::Result r = tracer_.curve(*m, Ray{e.ray.origin, departure}, nm_, st);
        for (const grin::PathSample& p : r.path) s.path.push_back(p.x);
    }

public:
    Vec3 root_dir_{0, 0, 1};  // the root ray's direction as given (the walk may turn it)

private:
    const SceneTracer& tracer_;
    double nm_;
    TraceRecord& rec_;
    RenderStats& stats_;
    std::vector<Vec3> departures_;  // the direction each entry pushed leaves its node in
    std::vector<int> parents_;  // the parent of each entry pushed, in the list's order
    size_t next_parent_ = 0;    // that of the next entry popped
    std::vector<const Material*> hit_material_;  // per segment, the material at its end
    int current_ = -1;
};

}  // namespace

namespace {

// The query's checks (the wavelength, a finite ray): the unit direction it is walked along
// (a unit direction kept as it is: a camera ray traces as it renders).
Vec3 checked_direction(const Scene& scene_in, const Ray& ray, double wavelength_nm) {
    const auto name = [&] { return scene_in.source.empty() ? std::string("scene") : scene_in.source; };
    if (!trace_walk::wavelength_ok(wavelength_nm))
        throw InputError(name() + ": --wavelength " + std::to_string(wavelength_nm) + " nm is outside [" +
                         std::to_string(static_cast<int>(spectrum::kMinWavelength)) + ", " +
                         std::to_string(static_cast<int>(spectrum::kMaxWavelength)) + "] nm");
    const auto dir = trace_walk::direction(ray);
    if (!dir) throw InputError(name() + ": the ray needs a finite origin and a finite, non-zero direction");
    return *dir;
}

// The record of `ray` (direction `dir`) walked by `tracer` over `scene`.
TraceRecord walk_record(const SceneTracer& tracer, const Scene& scene, const Ray& ray, const Vec3& dir,
                        double wavelength_nm, const PolarisationState* polarisation) {
    TraceRecord rec;
    rec.wavelength_nm = wavelength_nm;
    rec.segments.reserve(64);
    RenderStats stats;
    const TreeLimits limits = trace_walk::limits(scene);
    const auto walk = [&](auto payload) {
        using P = decltype(payload);
        RayTreeWalkerT<P> walker(tracer, limits, stats);
        RecordingEnds<P> ends(tracer, wavelength_nm, rec, stats);
        ends.root_dir_ = dir;
        typename RayTreeWalkerT<P>::List list{trace_walk::root<P>(scene, ray, dir, polarisation)};
        walker.walk(list, ends);
    };
    if (polarisation) walk(LightStokes{});
    else if (tracer.exact()) walk(EyeStokes{});
    else walk(NaturalLight{});
    return rec;
}


// The scene a polarised trace walks: the exact model (a copy when the scene's is not).
bool needs_exact_copy(const Scene& scene, const PolarisationState* polarisation) {
    return polarisation && polarisation_model(scene) != PolarisationModel::Exact;
}
Scene exact_copy(const Scene& scene) {
    Scene exact = scene;
    exact.settings.requested_polarisation = PolarisationModel::Exact;
    return exact;
}

}  // namespace

TraceRecord trace_ray(const Scene& scene_in, const Ray& ray, double wavelength_nm,
                      const PolarisationState* polarisation) {
    const Vec3 dir = checked_direction(scene_in, ray, wavelength_nm);
    std::optional<Scene> exact;
    if (needs_exact_copy(scene_in, polarisation)) exact = exact_copy(scene_in);
    const Scene& scene = exact ? *exact : scene_in;
    const SceneTracer tracer(scene);
    return walk_record(tracer, scene, ray, dir, wavelength_nm, polarisation);
}

namespace {

// Pixel (i, j)'s centre ray, the pixel checked against the image.
Ray pixel_ray(const Scene& scene, int i, int j) {
    const std::string f = scene.source.empty() ? std::string("scene") : scene.source;
    if (i < 0 || j < 0 || i >= scene.camera.width || j >= scene.camera.height)
        throw InputError(f + ": --pixel " + std::to_string(i) + " " + std::to_string(j) + " is outside the " +
                         std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height) + " image");
    return scene.camera.ray(i + 0.5, j + 0.5);
}

}  // namespace

TraceRecord trace_pixel(const Scene& scene, int i, int j, double wavelength_nm,
                        const PolarisationState* polarisation) {
    return trace_ray(scene, pixel_ray(scene, i, j), wavelength_nm, polarisation);
}

struct TraceSession::Walk {
    explicit Walk(const Scene& s) : scene(s), tracer(scene) {}     // the session's scene itself
    explicit Walk(Scene&& copy) : own(std::move(copy)), scene(*own), tracer(scene) {}  // a model's copy
    std::optional<Scene> own;
    const Scene& scene;
    const SceneTracer tracer;
};

TraceSession::TraceSession(std::shared_ptr<const Scene> scene) : scene_(std::move(scene)) {
    if (!scene_) throw std::invalid_argument("TraceSession: no scene");
}

TraceSession::~TraceSession() = default;

const TraceSession::Walk& TraceSession::walk(bool polarised) const {
    const bool exact = polarised && polarisation_model(*scene_) != PolarisationModel::Exact;
    const size_t k = exact ? 1 : 0;
    std::call_once(once_[k], [&] {
        walks_[k] = exact ? std::make_unique<Walk>(exact_copy(*scene_)) : std::make_unique<Walk>(*scene_);
    });
    return *walks_[k];
}

const SceneTracer& TraceSession::tracer(bool polarised) const { return walk(polarised).tracer; }

TraceRecord TraceSession::ray(const Ray& ray, double wavelength_nm, const PolarisationState* polarisation) const {
    const Vec3 dir = checked_direction(*scene_, ray, wavelength_nm);
    const Walk& w = walk(polarisation != nullptr);
    return walk_record(w.tracer, w.scene, ray, dir, wavelength_nm, polarisation);
}

TraceRecord TraceSession::pixel(int i, int j, double wavelength_nm, const PolarisationState* polarisation) const {
    return ray(pixel_ray(*scene_, i, j), wavelength_nm, polarisation);
}

}  // namespace refract
