#include <refract/core/trace_rays.h>

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
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
constexpr std::size_t kBlock = 4096;  // rays walked in packets with one walker

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

    // A hit of the ray's walk, before its node: a new segment (its weight kept for a leaf's
    // light), the first hit noted, a dielectric's Rs and Rp summed (its record's describe():
    // node_fresnel, 1 and 1 on total internal reflection).
    void arrive(const Entry& e, const SurfaceHit& h) {
        weight_ = start(e);
        if (sums_.segments == 1) {
            sums_.point = h.hit.point;
            sums_.object = static_cast<int>(h.object - tracer_.scene().objects.data());
            sums_.facet = h.hit.facet;
        }
        if (const material::Dielectric* d = h.material->dielectric()) {
            const material::NodeFresnel n = material::node_fresnel(*d, h, e.ray.dir, band_ior(e, h));
            sums_.Rs += n.terms ? n.terms->Rs : 1.0;
            sums_.Rp += n.terms ? n.terms->Rp : 1.0;
        }
    }

    bool intercept(Walker& walker, const Entry& e, const SurfaceHit& h, typename Walker::List& list) {
        arrive(e, h);
        const Interaction in = trace_walk::interact(tracer_, e, h, *this, stats_);
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

// The ends of up to kLanes rays walked as one packet (natural light): lane l's are ray l's,
// each lane's branches ended in the order of its own walk.
struct LaneSums {
    static constexpr bool kInOrder = true;
    const SceneTracer& tracer;
    std::array<std::optional<SummingEnds<NaturalLight>>, kLanes> ends;

    SummingEnds<NaturalLight>& lane(int l) { return *ends[static_cast<std::size_t>(l)]; }
    void intercept_lanes(const LaneEntry& p, const LaneMask& m, const SceneTracer::LaneHits& h) {
        for_each_lane(m, [&](int l) { lane(l).arrive(p.lane(l), tracer.surface_hit(h, l)); });
    }
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
    // Rays [i0, i1) kLanes at a time in packets, with one walker and one list (the walker keeps
    // each packet's indices by its lanes' bands: a band here is a wavelength of the block).
    const auto packets = [&](std::size_t i0, std::size_t i1) {
        RenderStats stats;
        RayTreeWalkerT<NaturalLight> walker(tracer, limits, stats);
        FifoList<LaneEntry> list;
        const auto nm_of = [&](std::size_t i) { return wavelengths_nm ? wavelengths_nm[i] : 0.0; };
        std::vector<double> bands;
        for (std::size_t i = i0; i < i1; ++i) bands.push_back(nm_of(i));
        std::sort(bands.begin(), bands.end());
        bands.erase(std::unique(bands.begin(), bands.end()), bands.end());
        std::array<Sums, kLanes> sums;
        for (std::size_t j0 = i0; j0 < i1; j0 += kLanes) {
            const int m = static_cast<int>(std::min<std::size_t>(kLanes, i1 - j0));
            LaneSums ends{tracer, {}};
            LaneEntry p;
            for (int l = 0; l < kLanes; ++l) {
                const std::size_t i = j0 + static_cast<std::size_t>(std::min(l, m - 1));
                const double nm = nm_of(i);
                sums[static_cast<std::size_t>(l)] = Sums{};
                ends.ends[static_cast<std::size_t>(l)].emplace(tracer, nm, sums[static_cast<std::size_t>(l)], stats);
                TreeEntry e = trace_walk::root<NaturalLight>(scene, Ray{origins[i], dirs[i]}, dirs[i], nullptr);
                e.band = static_cast<std::int16_t>(std::lower_bound(bands.begin(), bands.end(), nm) - bands.begin());
                if (l == 0) p.fill(e);
                if (l < m) p.set(l, e);
            }
            list.push_back(p);
            walker.walk(list, ends);
            for (int l = 0; l < m; ++l) store(b, j0 + static_cast<std::size_t>(l), sums[static_cast<std::size_t>(l)]);
        }
    };
    // Rays [i0, i1) one by one, with one walker and one list, reused from ray to ray.
    const auto run = [&](std::size_t i0, std::size_t i1) {
        if (tracer.packets()) {  // blocks of few enough wavelengths for the bands' 16 bits
            for (std::size_t k = i0; k < i1; k += kBlock) packets(k, std::min(i1, k + kBlock));
            return;
        }
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
