#include <refract/core/trace_rays.h>

#include <algorithm>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/threads.h>
#include <refract/core/trace_walk.h>
#include <refract/geometry/error.h>

namespace refract {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// What one ray's tree sums to (RayBatch's row), summed in the order its record holds the
// segments (the walk's: RecordingEnds in trace_record.cpp).
struct Sums {
    int segments = 0;
    Vec3 point{kNaN, kNaN, kNaN};
    int object = -1, facet = -1;
    Vec3 radiance{0, 0, 0}, escaped{0, 0, 0}, exit{kNaN, kNaN, kNaN};
    double strongest = -std::numeric_limits<double>::infinity();
    double Rs = 0, Rp = 0;
};

// The ends of one ray's walk that sum what its record would hold.
template <class P>
class SummingEnds {
public:
    using Entry = TreeEntryT<P>;
    using Walker = RayTreeWalkerT<P>;

    SummingEnds(const SceneTracer& t, double nm, Sums& sums, RenderStats& st)
        : tracer_(t), nm_(nm), sums_(sums), stats_(st) {}

    void background(const Entry& e) {
        const Vec3 w = start(e);
        sums_.radiance += trace_walk::light(e, w, tracer_.background(e.ray.dir));
        sums_.escaped += w;
        if (const double s = w.sum(); s > sums_.strongest) {
            sums_.strongest = s;
            sums_.exit = e.ray.dir;
        }
    }

    void leaf(const Entry& e, const SurfaceHit& h) {
        sums_.radiance += trace_walk::light(e, weight_, tracer_.local_light(h, stats_));
    }

    bool intercept(Walker& walker, const Entry& e, const SurfaceHit& h, typename Walker::List& list) {
        weight_ = start(e);
        if (sums_.segments == 1) {
            sums_.point = h.hit.point;
            sums_.object = static_cast<int>(h.object - tracer_.scene().objects.data());
            sums_.facet = h.hit.facet;
        }
        const Interaction in = trace_walk::interact(tracer_, e, h, *this, stats_);
        if (!in.leaf) {
            const NodeRecord r = describe(*h.material, in, h, e.ray, band_ior(e, h));
            if (r.dielectric) {
                sums_.Rs += r.Rs;
                sums_.Rp += r.Rp;
            }
        }
        trace_walk::expand(walker, e, h, in, list, *this, [](int) {});
        return true;
    }

    double band_ior(const Entry&, const SurfaceHit& h) const {
        if (nm_ <= 0 || !dispersive(*h.material)) return 0.0;
        return band_index(*h.material, nm_, tracer_.rules());
    }
    double wavelength(const Entry&) const { return nm_; }

private:
    // A new segment: counted (and refused past the record's bound), its weight.
    Vec3 start(const Entry& e) {
        if (static_cast<std::size_t>(sums_.segments) >= kMaxTraceSegments)
            tree_too_large(tracer_.scene(), "took more than " + std::to_string(kMaxTraceSegments) +
                                                " segments, the most a trace records");
        ++sums_.segments;
        return trace_walk::weight(e);
    }

    const SceneTracer& tracer_;
    double nm_;
    Sums& sums_;
    RenderStats& stats_;
    Vec3 weight_{0, 0, 0};  // the current node's segment's
};

void store(RayBatch& b, std::size_t i, const Sums& s) {
    const auto put3 = [i](std::vector<double>& v, const Vec3& x) {
        v[3 * i] = x.x();
        v[3 * i + 1] = x.y();
        v[3 * i + 2] = x.z();
    };
    put3(b.point, s.point);
    put3(b.radiance, s.radiance);
    put3(b.escaped, s.escaped);
    put3(b.exit_direction, s.exit);
    b.object[i] = s.object;
    b.facet[i] = s.facet;
    b.Rs[i] = s.Rs;
    b.Rp[i] = s.Rp;
    b.segments[i] = s.segments;
}

}  // namespace

RayBatch trace_rays(const TraceSession& session, const Vec3* origins, const Vec3* directions,
                    const double* wavelengths_nm, std::size_t n, int threads) {
    const int nthreads = worker_threads(threads);
    const Scene& named = session.scene();
    const auto name = [&] { return named.source.empty() ? std::string("scene") : named.source; };
    std::vector<Vec3> dirs(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double nm = wavelengths_nm ? wavelengths_nm[i] : 0.0;
        if (!trace_walk::wavelength_ok(nm))
            throw InputError(name() + ": trace_rays: ray " + std::to_string(i) + ": wavelength " + format_value(nm) +
                             " nm is outside [" + std::to_string(static_cast<int>(spectrum::kMinWavelength)) + ", " +
                             std::to_string(static_cast<int>(spectrum::kMaxWavelength)) + "] nm");
        const auto d = trace_walk::direction(Ray{origins[i], directions[i]});
        if (!d)
            throw InputError(name() + ": trace_rays: ray " + std::to_string(i) +
                             " needs a finite origin and a finite, non-zero direction");
        dirs[i] = *d;
    }
    RayBatch b;
    b.n = n;
    b.point.resize(3 * n);
    b.radiance.resize(3 * n);
    b.escaped.resize(3 * n);
    b.exit_direction.resize(3 * n);
    b.object.resize(n);
    b.facet.resize(n);
    b.Rs.resize(n);
    b.Rp.resize(n);
    b.segments.resize(n);
    if (n == 0) return b;

    const SceneTracer& tracer = session.tracer();
    const Scene& scene = tracer.scene();
    const TreeLimits limits = trace_walk::limits(scene);
    // Rays [i0, i1) with one walker and one list, reused from ray to ray.
    const auto run = [&](std::size_t i0, std::size_t i1) {
        RenderStats stats;
        const auto walk = [&](auto payload) {
            using P = decltype(payload);
            RayTreeWalkerT<P> walker(tracer, limits, stats);
            typename RayTreeWalkerT<P>::List list;
            for (std::size_t i = i0; i < i1; ++i) {
                const double nm = wavelengths_nm ? wavelengths_nm[i] : 0.0;
                Sums sums;
                SummingEnds<P> ends(tracer, nm, sums, stats);
                list.push_back(trace_walk::root<P>(scene, Ray{origins[i], dirs[i]}, dirs[i], nullptr));
                walker.walk(list, ends);
                store(b, i, sums);
            }
        };
        if (tracer.exact()) walk(EyeStokes{});
        else walk(NaturalLight{});
    };
    constexpr std::size_t kChunk = 256;
    if (nthreads == 1 || n <= kChunk) {
        run(0, n);
        return b;
    }
    tbb::task_arena arena(nthreads);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kChunk),
                          [&](const tbb::blocked_range<std::size_t>& r) { run(r.begin(), r.end()); });
    });
    return b;
}

}  // namespace refract
