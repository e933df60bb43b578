#include <refract/core/far_field.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/emitters.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/ray_tree.h>
#include <refract/geometry/error.h>
#include <refract/core/memory.h>
#include <refract/core/progress.h>
#include <refract/core/threads.h>

namespace refract {

namespace {

constexpr double kFixedScale = 4503599627370496.0;  // 2^52 units for one wavelength's emitted power

// std::llround(x) (halves away from zero), inlined for |x| < 2^52, where x minus its
// truncation is exact.
inline std::int64_t fixed(double x) {
    if (!(std::abs(x) < kFixedScale)) return std::llround(x);
    const auto r = static_cast<std::int64_t>(x);
    const double frac = x - static_cast<double>(r);
    return r + (frac >= 0.5 ? 1 : 0) - (frac <= -0.5 ? 1 : 0);
}

// The detector's directions: the axis and a frame across it.
struct Geometry {
    FarFieldSettings::Binning binning;
    Vec3 w, u, v;  // axis; φ = 0 and φ = 90° across it
    int nphi, ncos, nangle;
    std::vector<double> cos_edges;  // axis binning: −cos of the bins' edges, increasing
    // Axis binning: for each of `ncells` equal cells of x = −cos θ over [−1, 1], the number
    // of edges below the cell's lower end, so that a bin is found from its cell by a step
    // or two (the cells are fine enough that few edges fall in one, even at the poles).
    std::vector<std::int32_t> cell_first;
    double cell_scale = 0;

    explicit Geometry(const FarFieldSettings& s)
        : binning(s.binning), w(unit_vector(s.axis).value_or(Vec3::Zero())), nphi(s.azimuth_bins), ncos(s.polar_bins), nangle(s.angle_bins) {
        if (binning == FarFieldSettings::Binning::Axis) {
            for (int k = 1; k < nangle; ++k) cos_edges.push_back(-std::cos(M_PI * k / nangle));
            const int ncells = std::clamp(16 * nangle, 64, 1 << 16);
            cell_scale = 0.5 * ncells;
            cell_first.resize(static_cast<size_t>(ncells) + 1);
            size_t k = 0;
            for (int i = 0; i <= ncells; ++i) {
                const double lower = -1.0 + static_cast<double>(i) / cell_scale;
                while (k < cos_edges.size() && cos_edges[k] < lower) ++k;
                cell_first[static_cast<size_t>(i)] = static_cast<std::int32_t>(k);
            }
        }
        const Vec3 ref = rescaled(s.reference);
        Vec3 r = ref - ref.dot(w) * w;
        if (r.norm() < 1e-9) r = (std::abs(w.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)) - w * (std::abs(w.x()) < 0.9 ? w.x() : w.y());
        u = r.normalized();
        v = w.cross(u);
    }
    int bins() const { return binning == FarFieldSettings::Binning::Sphere ? nphi * ncos : nangle; }
    int bin_of(const Vec3& d) const {
        const double c = std::clamp(d.dot(w), -1.0, 1.0);
        if (binning == FarFieldSettings::Binning::Axis) {  // θ = acos c, by its bins' cosines
            // The number of edges <= −c (std::upper_bound's answer): every edge below x's
            // cell is below x, so count on from the cell's first.
            const double x = -c;
            const size_t cell = std::min(cell_first.size() - 1, static_cast<size_t>((x + 1.0) * cell_scale));
            size_t k = static_cast<size_t>(cell_first[cell]);
            while (k > 0 && cos_edges[k - 1] > x) --k;  // x rounded into the next cell
            while (k < cos_edges.size() && cos_edges[k] <= x) ++k;
            return static_cast<int>(k);
        }
        const int row = std::min(ncos - 1, static_cast<int>((1.0 - c) * 0.5 * ncos));
        double phi = std::atan2(d.dot(v), d.dot(u));
        if (phi < 0) phi += 2.0 * M_PI;
        const int col = std::min(nphi - 1, static_cast<int>(phi / (2.0 * M_PI) * nphi));
        return row * nphi + col;
    }
    // The Stokes frame's x̂ for a photon leaving along d: ⊥ the plane of the axis and d.
    Vec3 stokes_x(const Vec3& d) const {
        const Vec3 x = w.cross(d);
        return x.norm() > 1e-12 ? Vec3(x.normalized()) : v;
    }
};

void check(const FarFieldSettings& s) {
    const auto positive_count = [](int n, const char* name, int max) {
        if (!(n >= 1 && n <= max))
            throw InputError(std::string("far field: ") + name + " must be in [1, " + std::to_string(max) + "], got " +
                             std::to_string(n));
    };
    if (!unit_vector(s.axis)) throw InputError("far field: the axis must be a finite, non-zero vector");
    if (!s.reference.allFinite()) throw InputError("far field: the reference must be finite");
    positive_count(s.azimuth_bins, "azimuth bins", 1 << 14);
    positive_count(s.polar_bins, "polar bins", 1 << 14);
    positive_count(s.angle_bins, "angle bins", 1 << 20);
    positive_count(s.classes, "classes", 64);
    if (s.photons < 1 || s.photons > (std::uint64_t{1} << 31))
        throw InputError("far field: photons must be in [1, 2^31], got " + std::to_string(s.photons));
    if (s.wavelengths.size() > 1001) throw InputError("far field: at most 1001 wavelengths");
    for (double l : s.wavelengths)
        if (!(l >= spectrum::kMinWavelength && l <= spectrum::kMaxWavelength))
            throw InputError("far field: wavelength " + std::to_string(l) + " nm outside [360, 830] nm");
}

// One thread's sums for a group of wavelengths (w0 onwards): the bins of each, then per
// wavelength what was not scattered.
struct Tally {
    std::vector<std::int64_t> bins;
    std::vector<std::int64_t> unscattered, absorbed, dropped;
    std::uint64_t segments = 0;
};

template <class P>
struct FarFieldEnds {
    using Entry = TreeEntryT<P>;
    const Geometry& geo;
    const SpectralContext& ctx;
    Tally& tally;
    double scale;
    int classes, components, bins;
    size_t w0, per_wavelength;

    static double amount(const Entry& e) { return e.weight.mean(); }
    size_t slot(const Entry& e) const { return static_cast<size_t>(e.band) - w0; }
    std::int64_t* bins_of(const Entry& e) { return tally.bins.data() + slot(e) * per_wavelength; }
    // Natural light of `a` (the emitted power's units) leaving at wavelength slot w in
    // class cls and bin b, or unscattered (depth 0).
    void natural(size_t w, int depth, int cls, int b, double a) {
        if (depth == 0)
            tally.unscattered[w] += fixed(a * scale);
        else
            tally.bins[w * per_wavelength + static_cast<size_t>(cls * bins + b)] += fixed(a * scale);
    }
    void deposit(const TreeEntryT<NaturalLight>& e, int cls, int b) { natural(slot(e), e.depth, cls, b, amount(e)); }
    void deposit(const TreeEntryT<LightStokes>& e, int cls, int b) {
        const Vec3& d = e.ray.dir;
        const polar::Stokes S = polar::rotator(polar::frame_angle(e.pol.x, geo.stokes_x(d), d)) * e.pol.S;
        std::int64_t* out = bins_of(e);
        for (int s = 0; s < 4; ++s)
            out[static_cast<size_t>((cls * 4 + s) * bins + b)] += fixed(amount(e) * S[s] * scale);
    }
    // The event class of a ray leaving after `reflections` internal reflections.
    int event_class(int transmissions, int reflections) const {
        const int cls = transmissions == 0 ? 0 : 1 + std::min<int>(reflections, classes - 2);
        return std::min(cls, classes - 1);
    }
    void background(const Entry& e) {
        if (e.depth == 0) {
            tally.unscattered[slot(e)] += fixed(amount(e) * scale);
            return;
        }
        deposit(e, event_class(e.transmissions, e.reflections), geo.bin_of(e.ray.dir));
    }
    // The lanes of a packet leaving the scene (natural light): background() for each.
    void background_lanes(const LaneEntry& p, const LaneMask& m) {
        const Lanes mean = mean_of(p.weight);  // amount(): Vec3::mean()
        for (int l = 0; l < kLanes; ++l) {
            if (!m[l]) continue;
            const size_t i = static_cast<size_t>(l);
            const int cls = event_class(p.transmissions[i], p.reflections[i]);
            const size_t w = static_cast<size_t>(p.band[i]) - w0;
            natural(w, p.depth, cls, p.depth == 0 ? 0 : geo.bin_of(p.ray.dir.lane(l)), mean[l]);
        }
    }
    void leaf(const Entry& e, const SurfaceHit&) { tally.absorbed[slot(e)] += fixed(amount(e) * scale); }
    // Every lane of a packet walk sums into the same tallies (fixed point: in any order).
    FarFieldEnds& lane(int) { return *this; }
    bool intercept(RayTreeWalkerT<P>&, const Entry&, const SurfaceHit&, typename RayTreeWalkerT<P>::List&) { return false; }
    double band_ior(const Entry& e, const SurfaceHit& h) const {
        return ctx.index[static_cast<size_t>(e.band)][static_cast<size_t>(h.object->material)];
    }
    double wavelength(const Entry& e) const { return ctx.all_wavelengths[static_cast<size_t>(e.band)]; }
};

bool spectral_scene(const Scene& scene) {
    for (const Material& m : scene.materials)
        if ((m.dielectric() && dispersive(m)) || absorption(m)) return true;  // a crystal: at 550 nm unless asked
    return false;
}

}  // namespace

double FarFieldResult::scattered(int w) const {
    double s = 0;
    for (int c = 0; c < classes; ++c) {
        double v = 0;
        for (int b = 0; b < bins; ++b) v += at(w, c, 0, b);
        s += v;
    }
    return s;
}

double FarFieldResult::absorbed_inside(int w) const {
    const size_t k = static_cast<size_t>(w);
    const double rest = 1.0 - (scattered(w) + unscattered[k] + absorbed[k] + dropped[k]);
    return std::abs(rest) < 1e-9 ? 0.0 : rest;
}

double FarFieldResult::solid_angle(int b) const {
    if (settings.binning == FarFieldSettings::Binning::Sphere) return 4.0 * M_PI / bins;
    const double t0 = M_PI * b / bins, t1 = M_PI * (b + 1) / bins;
    return 2.0 * M_PI * (std::cos(t0) - std::cos(t1));
}

double FarFieldResult::theta_deg(int b) const {
    if (settings.binning == FarFieldSettings::Binning::Axis) return 180.0 * (b + 0.5) / bins;
    const int row = b / settings.azimuth_bins;
    return std::acos(1.0 - 2.0 * (row + 0.5) / settings.polar_bins) * 180.0 / M_PI;
}

double FarFieldResult::phi_deg(int b) const {
    if (settings.binning == FarFieldSettings::Binning::Axis) return 0.0;
    return 360.0 * (b % settings.azimuth_bins + 0.5) / settings.azimuth_bins;
}

Vec3 bin_direction(const FarFieldSettings& s, int b) {
    FarFieldResult r;
    r.settings = s;
    r.bins = Geometry(s).bins();
    const Geometry geo(s);
    const double t = r.theta_deg(b) * M_PI / 180.0, p = r.phi_deg(b) * M_PI / 180.0;
    return std::cos(t) * geo.w + std::sin(t) * (std::cos(p) * geo.u + std::sin(p) * geo.v);
}

int FarFieldResult::bin_of(const Vec3& dir) const { return Geometry(settings).bin_of(dir.normalized()); }
std::vector<int> FarFieldResult::bins_of(const std::vector<Vec3>& dirs) const {
    const Geometry g(settings);
    std::vector<int> out;
    out.reserve(dirs.size());
    for (const Vec3& d : dirs) out.push_back(g.bin_of(d.normalized()));
    return out;
}

std::string FarFieldResult::class_name(int c) const {
    if (c == 0) return "reflected";
    const int k = c - 1;
    const std::string n = std::to_string(k) + (k == 1 ? " internal reflection" : " internal reflections");
    return c == classes - 1 && classes > 2 ? "≥ " + n : n;
}

FarFieldResult far_field(const Scene& scene_in, const FarFieldSettings& settings, int threads) {
    check(settings);
    const auto t0 = std::chrono::steady_clock::now();
    FarFieldResult r;
    r.settings = settings;
    r.settings.axis = *unit_vector(settings.axis);
    // The spectral context of the scene (its limits), with the runs' wavelengths and every
    // material's index at each of them.
    Scene scene = scene_in;
    if (!settings.wavelengths.empty()) {
        r.wavelengths = settings.wavelengths;
    } else if (spectral_scene(scene)) {
        r.wavelengths = spectrum::sample_wavelengths(scene.settings.spectral.sampling, scene.source);
    } else {
        r.wavelengths = {550.0};
    }
    for (size_t k = 1; k < r.wavelengths.size(); ++k)
        if (!(r.wavelengths[k] > r.wavelengths[k - 1]))
            throw InputError("far field: wavelengths must be strictly increasing");
    scene.settings.compat = Compat::Physical;
    scene.settings.spectral.shortcut = false;
    SpectralContext ctx = SpectralContext::build(scene);
    const CompatRules rules(scene.settings);
    ctx.all_wavelengths = r.wavelengths;  // exact values, also for an uneven list
    ctx.index.assign(r.wavelengths.size(), std::vector<double>(scene.materials.size(), 0.0));
    for (size_t mi = 0; mi < scene.materials.size(); ++mi)
        if (dispersive(scene.materials[mi]))
            for (size_t w = 0; w < r.wavelengths.size(); ++w)
                ctx.index[w][mi] = band_index(scene.materials[mi], r.wavelengths[w], rules);

    const Geometry geo(r.settings);
    const bool exact = polarisation_model(scene) == PolarisationModel::Exact;
    r.bins = geo.bins();
    r.classes = settings.classes;
    r.components = exact ? 4 : 1;
    const size_t per_wavelength = static_cast<size_t>(r.classes) * static_cast<size_t>(r.components) * static_cast<size_t>(r.bins);
    if (per_wavelength * r.wavelengths.size() > (size_t{1} << 28))
        throw InputError("far field: " + std::to_string(per_wavelength * r.wavelengths.size()) +
                         " bins × classes × components × wavelengths exceed 2^28 values");
    const int nthreads = worker_threads(threads);
    check_memory(estimate_far_field_memory(per_wavelength, r.wavelengths.size(), nthreads), settings.max_memory,
                 "far field");
    r.power.assign(per_wavelength * r.wavelengths.size(), 0.0);
    r.unscattered.assign(r.wavelengths.size(), 0.0);
    r.absorbed.assign(r.wavelengths.size(), 0.0);
    r.dropped.assign(r.wavelengths.size(), 0.0);

    const std::vector<BoundingSphere> targets = transparent_targets(scene);
    Vec3 centre(0, 0, 0);
    for (const auto& t : targets) centre += t.centre / static_cast<double>(targets.size());
    const std::vector<Emitter> emitters = make_emitters(scene, targets, centre, settings.photons);
    double total = 0;  // emitted per wavelength
    for (const Emitter& em : emitters) total += em.power.mean() * static_cast<double>(em.photons);
    r.emitted_power = total;
    if (emitters.empty() || !(total > 0)) {
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return r;
    }

    SceneTracer tracer(scene, settings.trace);
    const TreeLimits limits = ctx.limits(scene.settings);
    tbb::task_arena arena(nthreads);
    constexpr std::uint64_t kChunk = 4096;
    // Wavelengths in groups whose bins fit a thread's tally (far_field_group); a photon is
    // drawn once for its group and its first segment traced once, then walked at each of
    // the group's wavelengths.
    const size_t group = far_field_group(per_wavelength, r.wavelengths.size());
    std::int64_t work = 0;  // photons × wavelength groups
    for (const Emitter& em : emitters) work += static_cast<std::int64_t>(em.photons);
    Progress progress("far field", "photons", work * static_cast<std::int64_t>((r.wavelengths.size() + group - 1) / group),
                      settings.progress);
    // Powers in units of the emitted power (the lights' spectrum cancels).
    const double scale = kFixedScale / total;
    for (size_t w0 = 0; w0 < r.wavelengths.size(); w0 += group) {
        const size_t gw = std::min(group, r.wavelengths.size() - w0);
        tbb::enumerable_thread_specific<Tally> tallies([&] {
            Tally t;
            t.bins.assign(per_wavelength * gw, 0);
            t.unscattered.assign(gw, 0);
            t.absorbed.assign(gw, 0);
            t.dropped.assign(gw, 0);
            return t;
        });
        for (const Emitter& em : emitters) {
            const PolarisationState& pol = emitter_polarisation(scene, em);
            arena.execute([&] {
                tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, em.photons, kChunk),
                                  [&](const tbb::blocked_range<std::uint64_t>& range) {
                    Tally& tally = tallies.local();
                    RenderStats st;
                    const auto run = [&](auto payload) {
                        using P = decltype(payload);
                        RayTreeWalkerT<P> walker(tracer, limits, st);
                        FarFieldEnds<P> ends{geo, ctx, tally, scale, r.classes, r.components, r.bins, w0, per_wavelength};
                        // The weight the walker dropped for one wavelength of a photon (its power
                        // rides on it), summed per cause from zero.
                        const auto drop = [&](size_t w, double depth, double limits, double threshold) {
                            tally.dropped[w - w0] += fixed((depth + limits + threshold) * scale);
                        };
                        for (std::uint64_t p = range.begin(); p != range.end(); ++p) {
                            const auto [ray, power] = sample_photon(em, settings.seed + w0 * 0x9E3779B9ull, p);
                            TreeEntryT<P> e{ray, Vec3::Constant(power.mean())};
                            if constexpr (std::is_same_v<P, LightStokes>) e.pol = emitted(pol, ray.dir);
                            const auto first = tracer.intersect(ray, st);  // the same at every wavelength
                            if (!first) {
                                for (size_t w = w0; w < w0 + gw; ++w) {
                                    e.band = static_cast<std::int16_t>(w);
                                    ends.background(e);
                                }
                                continue;
                            }
                            // Each wavelength of the group from the first hit on (in packets
                            // where the tracer walks them), its dropped power tallied.
                            walker.walk_bands(
                                static_cast<int>(gw),
                                [&](auto& s, int i) { s.arrive_band(e, *first, static_cast<int>(w0) + i); },
                                ends,
                                [&](int i, const LossesT<double>& lost) {
                                    st.lost_depth += lost.depth;
                                    st.lost_limits += lost.limits;
                                    st.lost_threshold += lost.threshold;
                                    drop(w0 + static_cast<size_t>(i), lost.depth, lost.limits, lost.threshold);
                                });
                        }
                    };
                    if (exact) run(LightStokes{});
                    else run(NaturalLight{});
                    tally.segments += st.segments;
                    progress.add(static_cast<std::int64_t>(range.size()));
                });
            });
        }
        Tally sum;
        sum.bins.assign(per_wavelength * gw, 0);
        sum.unscattered.assign(gw, 0);
        sum.absorbed.assign(gw, 0);
        sum.dropped.assign(gw, 0);
        for (const Tally& t : tallies) {
            for (size_t k = 0; k < sum.bins.size(); ++k) sum.bins[k] += t.bins[k];
            for (size_t k = 0; k < gw; ++k) {
                sum.unscattered[k] += t.unscattered[k];
                sum.absorbed[k] += t.absorbed[k];
                sum.dropped[k] += t.dropped[k];
            }
            sum.segments += t.segments;
        }
        for (size_t k = 0; k < sum.bins.size(); ++k)
            r.power[w0 * per_wavelength + k] = static_cast<double>(sum.bins[k]) / kFixedScale;
        for (size_t k = 0; k < gw; ++k) {
            r.unscattered[w0 + k] = static_cast<double>(sum.unscattered[k]) / kFixedScale;
            r.absorbed[w0 + k] = static_cast<double>(sum.absorbed[k]) / kFixedScale;
            r.dropped[w0 + k] = static_cast<double>(sum.dropped[k]) / kFixedScale;
        }
        r.segments += sum.segments;
    }
    progress.finish();
    for (const Emitter& em : emitters) r.photons += em.photons * r.wavelengths.size();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace refract
