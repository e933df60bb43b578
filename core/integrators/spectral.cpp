#include <refract/core/integrators/spectral.h>

#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <optional>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/compat/refraction_split.h>
#include <refract/core/ray_tree.h>
#include <refract/core/spectrum/cie.h>
#include <refract/geometry/error.h>

namespace refract {

Vec3 SpectralContext::finish(const Vec3& rgb) const { return clip ? Vec3(rgb.cwiseMax(0.0)) : rgb; }

SpectralContext SpectralContext::build(const Scene& scene) {
    const SpectralSettings& s = scene.settings.spectral;
    const size_t materials = scene.materials.size();
    const CompatRules rules(scene.settings);
    SpectralContext c;
    c.shortcut_threshold = s.shortcut_threshold;
    c.max_reflections = s.max_reflections.value_or(SpectralContext::kUnlimited);
    c.max_transmissions = s.max_transmissions.value_or(SpectralContext::kUnlimited);
    rules.spectral_bands(scene, c);
    std::vector<double> all = c.wavelengths;
    all.insert(all.end(), s.shortcut_wavelengths.begin(), s.shortcut_wavelengths.end());
    c.all_wavelengths = all;
    c.index.assign(all.size(), std::vector<double>(materials, 0.0));
    for (size_t mi = 0; mi < materials; ++mi) {
        if (!c.dispersive[mi]) continue;
        for (size_t b = 0; b < all.size(); ++b) c.index[b][mi] = band_index(scene.materials[mi], all[b], rules);
    }
    return c;
}

namespace {

// The spectral eye pass's branch ends; `sum` collects one walk's light.
template <class P>
class SpectralEnds {
public:
    using Walker = RayTreeWalkerT<P>;
    using Entry = TreeEntryT<P>;
    using List = typename Walker::List;
    using Acc = decltype(seen(P{}, Vec3(), Vec3()));

    SpectralEnds(const SceneTracer& t, const SpectralContext& c, RenderStats& s, std::vector<double>* bands = nullptr)
        : tracer_(t), ctx_(c), stats_(s), bands_(bands) {
        sum.setZero();
    }

    Acc sum;

    void background(const Entry& e) { add(e, seen(e.pol, e.weight, tracer_.background(e.ray.dir))); }

    void leaf(const Entry& e, const SurfaceHit& h) {
        Vec3 local = tracer_.local_light(h, stats_);
        const LeafLight l = leaf_light(*h.material);
        if (ctx_.maps && l.kind == LeafLight::Kind::Lit) {
            const int obj = static_cast<int>(h.object - tracer_.scene().objects.data());
            const Vec3 e_map = ctx_.maps->irradiance(obj, h.hit, tracer_.scene().settings.light_pass.filter);
            local += l.diffuse * tracer_.pigment(*l.pigment, h.hit.point).cwiseProduct(e_map);
        }
        add(e, seen(e.pol, e.weight, local));
    }

    double wavelength(const Entry& e) const {
        return e.band < 0 ? 0.0 : ctx_.all_wavelengths[static_cast<size_t>(e.band)];
    }

    double band_ior(const Entry& e, const SurfaceHit& h) const {
        return e.band < 0 ? 0.0 : ctx_.index[static_cast<size_t>(e.band)][static_cast<size_t>(h.object->material)];
    }

    // Packets: each lane's ends are its band's (bands_ends below).
    SpectralEnds& lane(int) { return *this; }

    // An RGB ray at its first dispersive hit splits into bands.
    bool intercept(Walker& w, const Entry& e, const SurfaceHit& h, List& list) {
        if (e.band >= 0 || !ctx_.dispersive[static_cast<size_t>(h.object->material)]) return false;
        ++stats_.spectral_splits;
        switch (ctx_.split) {
            case SpectralContext::Split::Subtree: sum += split_subtree(w, e, h); break;
            case SpectralContext::Split::Refraction: sum += split_at_refraction(w, e, h, list, *this); break;
        }
        return true;
    }

    // Fresh ends of the same walk (a band's, the mirror ray's).
    SpectralEnds fresh() const { return SpectralEnds(tracer_, ctx_, stats_, bands_); }
    const SpectralContext& context() const { return ctx_; }
    RenderStats& stats() const { return stats_; }

    // The subtrees of `n` bands (band(i) the band of the i-th), `seed(s, i)` starting the
    // i-th through the walker's BandSeed; each band's light, tinted by its weight, added to
    // `sum` in band order, its losses to the stats. `one_by_one`: never in packets.
    template <class Seed>
    void walk_bands(Walker& w, int n, const std::function<int(int)>& band, Seed&& seed, Acc& sum, bool one_by_one = false) {
        std::vector<SpectralEnds> subs(static_cast<size_t>(std::min(n, kLanes)), fresh());
        const auto ends_of = [&](int i) -> SpectralEnds& { return subs[static_cast<size_t>(i % kLanes)]; };
        const std::uint64_t before = stats_.segments;
        w.walk_bands(
            n,
            [&](auto& s, int i) {
                ends_of(i).sum.setZero();
                seed(s, i);
            },
            ends_of,
            [&](int i, const LossesT<double>& lost) {
                stats_.lost_depth += lost.depth;
                stats_.lost_limits += lost.limits;
                stats_.lost_threshold += lost.threshold;
                sum += tinted(ctx_.weights[static_cast<size_t>(band(i))], ends_of(i).sum);
            },
            one_by_one);
        stats_.wavelength_segments += stats_.segments - before;
    }

private:
    // A branch's light: to the sum, and to the per-wavelength light when it is asked for.
    void add(const Entry& e, const Acc& c) {
        sum += c;
        if (!bands_) return;
        const double v = rgb_of(c).mean();
        if (e.band < 0) {
            for (double& b : *bands_) b += v;
        } else if (static_cast<size_t>(e.band) < bands_->size()) {
            (*bands_)[static_cast<size_t>(e.band)] += v;
        }
    }

    // The physical split: the whole subtree below hit h walked at every band (each band's
    // node with its own index), after the shortcut's three-wavelength test.
    Acc split_subtree(Walker& w, const Entry& e, const SurfaceHit& h) {
        const size_t mi = static_cast<size_t>(h.object->material);
        Acc sum;
        sum.setZero();
        // Band k's subtree: entry e at band k, at hit h, with the band's index.
        const auto at_band = [&](const std::vector<int>& bands) {
            return [&, bands](auto& s, int i) {
                const int band = bands[static_cast<size_t>(i)];
                s.expand_band(e, h, band, ctx_.index[static_cast<size_t>(band)][mi]);
            };
        };
        if (ctx_.shortcut) {
            ++stats_.shortcut_tests;
            const int first = static_cast<int>(ctx_.bands());
            const std::vector<int> test{first, first + 1, first + 2};
            Acc c[3];
            for (int k = 0; k < 3; ++k) {
                Acc one;
                one.setZero();
                SpectralEnds sub = fresh();
                const std::uint64_t before = stats_.segments;
                w.walk_bands(
                    1, [&](auto& s, int) { at_band(std::vector<int>{test[static_cast<size_t>(k)]})(s, 0); }, sub,
                    [&](int, const LossesT<double>& lost) {
                        stats_.lost_depth += lost.depth;
                        stats_.lost_limits += lost.limits;
                        stats_.lost_threshold += lost.threshold;
                    },
                    true);
                stats_.wavelength_segments += stats_.segments - before;
                c[k] = sub.sum;
            }
            const Vec3 r0 = rgb_of(c[0]), r1 = rgb_of(c[1]), r2 = rgb_of(c[2]);
            const double d = std::fmax((r0 - r1).norm(), std::fmax((r1 - r2).norm(), (r0 - r2).norm()));
            if (d < ctx_.shortcut_threshold) {
                ++stats_.shortcut_taken;
                const Acc mean = (c[0] + c[1] + c[2]) / 3.0;
                if (bands_)
                    for (double& b : *bands_) b += rgb_of(mean).mean();
                return mean;
            }
        }
        const std::vector<int>& bands = ctx_.split_bands[mi];
        walk_bands(w, static_cast<int>(bands.size()), [&](int i) { return bands[static_cast<size_t>(i)]; }, at_band(bands),
                   sum);
        return sum;
    }

    const SceneTracer& tracer_;
    const SpectralContext& ctx_;
    RenderStats& stats_;
    std::vector<double>* bands_;
};

template <class P>
auto walk_spectral(const SceneTracer& tracer, const SpectralContext& ctx, const Ray& primary, const P& start,
                   RenderStats& stats, std::vector<double>* bands = nullptr) {
    TreeLimits limits = ctx.limits(tracer.settings());
    limits.band_weights = &ctx.weights;
    RayTreeWalkerT<P> walker(tracer, limits, stats);
    SpectralEnds<P> ends(tracer, ctx, stats, bands);
    typename RayTreeWalkerT<P>::List list{TreeEntryT<P>{primary, Vec3(1, 1, 1)}};
    list.front().pol = start;
    // A camera inside a dispersive gradient-index medium (an observer in the air): the
    // curved root ray already depends on the wavelength, so it splits at once, each band
    // walked from the camera with its own index (as the split at a first dispersive hit).
    if (const grin::Medium* m = tracer.medium_of(primary, RayOrigin{})) {
        const size_t mi = static_cast<size_t>(tracer.scene().objects[static_cast<size_t>(m->object)].material);
        if (ctx.dispersive[mi]) {
            ++stats.spectral_splits;
            const std::uint64_t before = stats.segments;
            for (const int band : ctx.split_bands[mi]) {
                SpectralEnds<P> sub(tracer, ctx, stats, bands);
                typename RayTreeWalkerT<P>::List one{list.front()};
                one.front().band = static_cast<std::int16_t>(band);
                walker.walk(one, sub);
                ends.sum += tinted(ctx.weights[static_cast<size_t>(band)], sub.sum);
            }
            stats.wavelength_segments += stats.segments - before;
            return ends.sum;
        }
    }
    walker.walk(list, ends);
    return ends.sum;
}

}  // namespace

TreeLimits SpectralContext::limits(const RenderSettings& s) const {
    TreeLimits l = tree_limits(s);
    l.max_reflections = max_reflections;
    l.max_transmissions = max_transmissions;
    return l;
}

Vec3 spectral_radiance(const SceneTracer& tracer, const SpectralContext& ctx, const Ray& primary,
                       RenderStats& stats, std::vector<double>* band_light) {
    return walk_spectral(tracer, ctx, primary, NaturalLight{}, stats, band_light);
}

StokesRGB spectral_stokes(const SceneTracer& tracer, const SpectralContext& ctx, const Ray& primary,
                          const EyeStokes& start, RenderStats& stats) {
    return walk_spectral(tracer, ctx, primary, start, stats);
}

namespace {

// The spectral eye pass per sample (the tree's rule: Yasuda's threshold, or Whitted's
// none), the samples averaged and the pixel finished; per-wavelength light; exact
// polarisation: Stokes vectors.
// Its sample loops are written out rather than through Integrator::sample_mean: with the
// template, GCC 12 inlined this file's packet walk differently and the 1998 diamond rendered
// 10 % slower (paired whole-process runs, same images).
class Spectral : public Integrator {
public:
    Spectral(const SceneTracer& tracer, const SpectralContext& ctx) : Integrator(tracer), ctx_(ctx) {}
    Vec3 pixel(int i, int j, RenderStats& stats, std::vector<double>* bands) const override {
        const int n = tracer_.settings().samples;
        Vec3 sum(0, 0, 0);
        for (int k = 0; k < n; ++k) {
            Rng rng;
            const Ray ray = sample_ray(i, j, k, rng);
            ++stats.primary_rays;
            sum += spectral_radiance(tracer_, ctx_, ray, stats, bands);
        }
        if (bands)
            for (double& b : *bands) b /= n;
        return ctx_.finish(sum / n);
    }
    StokesRGB pixel_stokes(int i, int j, RenderStats& stats, LinearPolarisation& lp) const override {
        const int n = tracer_.settings().samples;
        StokesRGB sum = StokesRGB::Zero();
        for (int k = 0; k < n; ++k) {
            Rng rng;
            const Ray ray = sample_ray(i, j, k, rng);
            ++stats.primary_rays;
            sum += spectral_stokes(tracer_, ctx_, ray, camera_stokes(tracer_.scene(), ray), stats);
        }
        sum /= n;
        lp = linear_polarisation(sum, tracer_.scene(), tracer_.camera_ray(i + 0.5, j + 0.5));
        sum.row(0) = ctx_.finish(sum.row(0).transpose()).transpose();
        return sum;
    }

private:
    const SpectralContext& ctx_;
};

}  // namespace

std::unique_ptr<Integrator> spectral_integrator(const SceneTracer& tracer, const SpectralContext& ctx) {
    return std::make_unique<Spectral>(tracer, ctx);
}

}  // namespace refract
