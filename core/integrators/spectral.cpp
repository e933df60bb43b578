#include "core/integrators/spectral.h"

#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include "core/illumination_map.h"
#include "core/ray_tree.h"
#include "core/spectrum/cie.h"
#include "geometry/error.h"

namespace refract {

Vec3 SpectralContext::finish(const Vec3& rgb) const { return clip ? Vec3(rgb.cwiseMax(0.0)) : rgb; }

namespace {

// POV-Ray splits a ray at an interior only when its dispersion, stored in single
// precision, differs from 1 (trace.cpp: haveDispersion = fabs(dispersion - 1.0) >= EPSILON).
const spectrum::PovRayModel* pov_splitting_model(const Material& m) {
    constexpr double kPovEpsilon = 1e-10;
    const auto* d = m.dielectric();
    if (!d || !d->dispersion || !d->dispersion->is_povray()) return nullptr;
    const auto& p = std::get<spectrum::PovRayModel>(d->dispersion->model);
    return std::fabs(static_cast<double>(static_cast<float>(p.dispersion)) - 1.0) >= kPovEpsilon ? &p : nullptr;
}

}  // namespace

SpectralContext SpectralContext::build(const Scene& scene) {
    const SpectralSettings& s = scene.settings.spectral;
    const size_t materials = scene.materials.size();
    SpectralContext c;
    c.pov = scene.settings.compat == Compat::PovRay;
    c.shortcut = s.shortcut && !c.pov;
    c.shortcut_threshold = s.shortcut_threshold;
    c.max_reflections = s.max_reflections.value_or(SpectralContext::kUnlimited);
    c.max_transmissions = s.max_transmissions.value_or(SpectralContext::kUnlimited);
    c.dispersive.assign(materials, 0);
    c.split_bands.assign(materials, {});
    if (c.pov) {
        // POV-Ray's bands and hue colours: one band set per distinct dispersion_samples.
        std::map<int, std::vector<int>> sets;  // samples → its bands
        for (size_t mi = 0; mi < materials; ++mi) {
            const spectrum::PovRayModel* p = pov_splitting_model(scene.materials[mi]);
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
    } else {
        const std::string where = scene.source.empty() ? "scene" : scene.source;
        const spectrum::SpectrumToRGB conv(spectrum::sample_wavelengths(s.sampling, where + ": /render/spectral"),
                                           s.pipeline, spectrum::WhiteBalance::PerChannel, s.light);
        c.wavelengths = conv.wavelengths();
        c.weights = conv.weights();
        c.clip = s.pipeline == spectrum::ColourPipeline::CieRgb;
        std::vector<int> all_bands(c.bands());
        std::iota(all_bands.begin(), all_bands.end(), 0);
        c.split_bands.assign(materials, all_bands);
        for (size_t mi = 0; mi < materials; ++mi) {
            const Material& m = scene.materials[mi];
            // A uniaxial crystal's two indices depend on the wavelength: it always splits.
            c.dispersive[mi] = (m.dielectric() && m.dielectric()->dispersion.has_value()) || m.is<material::Uniaxial>();
        }
    }
    std::vector<double> all = c.wavelengths;
    all.insert(all.end(), s.shortcut_wavelengths.begin(), s.shortcut_wavelengths.end());
    c.all_wavelengths = all;
    c.index.assign(all.size(), std::vector<double>(materials, 0.0));
    for (size_t mi = 0; mi < materials; ++mi) {
        if (!c.dispersive[mi]) continue;
        if (const auto* u = scene.materials[mi].as<material::Uniaxial>()) {  // its interaction takes λ
            for (size_t b = 0; b < all.size(); ++b) c.index[b][mi] = u->n_o(all[b]);
            continue;
        }
        const material::Dielectric& m = *scene.materials[mi].dielectric();
        for (size_t b = 0; b < all.size(); ++b) {
            double n = m.dispersion->n(all[b]);
            // POV-Ray's law is relative to the interior's ior (single precision there).
            if (m.dispersion->is_povray()) {
                const auto& p = std::get<spectrum::PovRayModel>(m.dispersion->model);
                const double ior = c.pov ? static_cast<double>(static_cast<float>(m.ior)) : m.ior;
                const double D = c.pov ? static_cast<double>(static_cast<float>(p.dispersion)) : p.dispersion;
                n = spectrum::povray_index(ior, D, all[b]);
            }
            c.index[b][mi] = n;
        }
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
        const Material& m = *h.material;
        if (ctx_.maps && m.diffuse_surface()) {
            const auto* d = m.as<material::Diffuse>();
            const Pigment& pig = d ? d->pigment : m.as<material::Lambertian>()->pigment;
            const int obj = static_cast<int>(h.object - tracer_.scene().objects.data());
            const Vec3 e_map = ctx_.maps->irradiance(obj, h.hit, tracer_.scene().settings.light_pass.filter);
            local += (d ? d->diffuse : 1.0) * tracer_.pigment(pig, h.hit.point).cwiseProduct(e_map);
        }
        add(e, seen(e.pol, e.weight, local));
    }

    double wavelength(const Entry& e) const {
        return e.band < 0 ? 0.0 : ctx_.all_wavelengths[static_cast<size_t>(e.band)];
    }

    double band_ior(const Entry& e, const SurfaceHit& h) const {
        return e.band < 0 ? 0.0 : ctx_.index[static_cast<size_t>(e.band)][static_cast<size_t>(h.object->material)];
    }

    // An RGB ray at its first dispersive hit splits into bands.
    bool intercept(Walker& w, const Entry& e, const SurfaceHit& h, List& list) {
        if (e.band >= 0 || !ctx_.dispersive[static_cast<size_t>(h.object->material)]) return false;
        sum += split(w, e, h, list);
        return true;
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

    // Walks `list` with fresh ends and returns its light.
    Acc subwalk(Walker& w, List& list) {
        SpectralEnds sub(tracer_, ctx_, stats_, bands_);
        w.walk(list, sub);
        return sub.sum;
    }

    // The subtree below hit h traced at one band (its losses summed on their own, as a
    // packet sums each lane's).
    Acc band_tree(Walker& w, const Entry& e, const SurfaceHit& h, int band) {
        const std::uint64_t before = stats_.segments;
        Entry eb = e;
        eb.band = static_cast<std::int16_t>(band);
        List list;
        SpectralEnds sub(tracer_, ctx_, stats_, bands_);
        w.own_losses([&] {
            w.expand(eb, h, ctx_.index[static_cast<size_t>(band)][static_cast<size_t>(h.object->material)], list, sub);
            w.walk(list, sub);
        });
        stats_.wavelength_segments += stats_.segments - before;
        return sub.sum;
    }

    // Each lane of a packet walk with its own ends (its own sum).
    struct LaneEnds {
        std::array<SpectralEnds*, kLanes> ends{};
        SpectralEnds& lane(int l) { return *ends[static_cast<size_t>(l)]; }
    };

    // Whether the bands of a split are walked in packets (RayTreeWalkerT::walk_lanes).
    bool packets() const {
        return std::is_same_v<P, NaturalLight> && SceneTracer::lanes() && tracer_.lanes_apply();
    }

    // The subtrees below hit h at `bands`, walked kLanes bands at a time: band_tree() of each,
    // to the last bit, added to the sum (tinted by the band's weight) in band order.
    void band_trees(Walker& w, const Entry& e, const SurfaceHit& h, const std::vector<int>& bands, Acc& sum) {
        if constexpr (std::is_same_v<P, NaturalLight>) {
            const SceneTracer::LaneHits hl = SceneTracer::lanes_of(h);
            FifoList<LaneEntry> packets;  // reused: it allocates only while it grows
            std::vector<SpectralEnds> subs(static_cast<size_t>(kLanes), SpectralEnds(tracer_, ctx_, stats_, bands_));
            LaneEnds ends;
            for (size_t l = 0; l < subs.size(); ++l) ends.ends[l] = &subs[l];
            for (size_t i0 = 0; i0 < bands.size(); i0 += kLanes) {
                LaneEntry pk;
                for (int l = 0; l < kLanes; ++l) {
                    const size_t i = i0 + static_cast<size_t>(l);
                    Entry eb = e;
                    eb.band = static_cast<std::int16_t>(bands[i < bands.size() ? i : i0]);
                    pk.set(l, eb);
                    pk.active[l] = i < bands.size();
                    subs[static_cast<size_t>(l)].sum.setZero();
                }
                const std::uint64_t before = stats_.segments;
                LaneLosses lost;
                w.expand_lanes(pk, pk.active, hl, packets, ends, lost);
                w.walk_lanes(packets, ends, lost);
                stats_.wavelength_segments += stats_.segments - before;
                for (int l = 0; l < kLanes; ++l) {
                    if (!pk.active[l]) continue;
                    w.add_losses(lost, l);
                    sum += tinted(ctx_.weights[static_cast<size_t>(pk.band[static_cast<size_t>(l)])],
                                  subs[static_cast<size_t>(l)].sum);
                }
            }
        }
    }

    // A band's refracted ray at a POV-Ray split.
    struct BandRay {
        int band;
        Branch branch;
    };

    // POV-Ray mode: the bands' refracted rays walked kLanes at a time, each band's light
    // added to the sum (tinted by its weight) in band order, as one by one.
    void pov_bands_in_packets(Walker& w, const Entry& e, const SurfaceHit& h, const std::vector<BandRay>& rays,
                              Acc& sum) {
        if constexpr (std::is_same_v<P, NaturalLight>) {
            FifoList<LaneEntry> packets;
            std::vector<SpectralEnds> subs(static_cast<size_t>(kLanes), SpectralEnds(tracer_, ctx_, stats_, bands_));
            LaneEnds ends;
            for (size_t l = 0; l < subs.size(); ++l) ends.ends[l] = &subs[l];
            for (size_t i0 = 0; i0 < rays.size(); i0 += kLanes) {
                const std::uint64_t before = stats_.segments;
                LaneEntry child[2];
                LaneLosses lost;
                const int n = static_cast<int>(std::min<size_t>(kLanes, rays.size() - i0));
                for (int l = 0; l < n; ++l) {
                    const BandRay& r = rays[i0 + static_cast<size_t>(l)];
                    subs[static_cast<size_t>(l)].sum.setZero();
                    w.push_lane(child[0], l, e, h, r.branch, true, lost, Vec3(1, 1, 1), r.band);
                }
                w.queue(child, packets, ends);
                w.walk_lanes(packets, ends, lost);
                for (int l = 0; l < n; ++l) {
                    w.add_losses(lost, l);
                    sum += tinted(ctx_.weights[static_cast<size_t>(rays[i0 + static_cast<size_t>(l)].band)],
                                  subs[static_cast<size_t>(l)].sum);
                }
                stats_.wavelength_segments += stats_.segments - before;
            }
        }
    }

    Acc split(Walker& w, const Entry& e, const SurfaceHit& h, List& rgb_list) {
        ++stats_.spectral_splits;
        const size_t mi = static_cast<size_t>(h.object->material);
        Acc sum;
        sum.setZero();
        if (ctx_.pov) {
            // POV-Ray: Fresnel and the reflected ray with the nominal index (stays RGB);
            // the refracted ray, when spawned, splits into bands, each with its own
            // direction and TIR test (core/interaction.cpp, `split`).
            const std::vector<int>& bands = ctx_.split_bands[mi];
            const Interaction first = tracer_.interact(h, e.ray, stats_, ctx_.index[static_cast<size_t>(bands[0])][mi], true);
            if (first.branches > 0) w.push(e, h, first, 0, false, rgb_list);
            if (first.branches < 2) return sum;  // nothing refracts
            // A band's TIR mirror ray is a full ray (it splits again), the same for every
            // band that meets TIR: traced once with the sum of their weights.
            Vec3 mirror_weight(0, 0, 0);
            std::optional<Branch> mirror;  // POV-Ray mode: natural light, no Mueller matrix
            // Each band's interaction, in band order: the mirror bands' weights summed, the
            // others' refracted rays walked (in packets, or one by one).
            std::vector<BandRay> refracted;
            for (const int k : bands) {
                const size_t kb = static_cast<size_t>(k);
                const Interaction bn = k == bands[0] ? first : tracer_.interact(h, e.ray, stats_, ctx_.index[kb][mi], true);
                if (bn.split_mirror) {
                    mirror = bn.branch[1];
                    mirror_weight += ctx_.weights[kb];
                    continue;
                }
                refracted.push_back(BandRay{k, bn.branch[1]});
            }
            if (packets()) {
                pov_bands_in_packets(w, e, h, refracted, sum);
            } else {
                for (const BandRay& r : refracted) {
                    const std::uint64_t before = stats_.segments;
                    Acc band;
                    w.own_losses([&] {
                        List list;
                        w.push(e, h, r.branch, polar::Mueller::Identity(), true, list, Vec3(1, 1, 1), r.band);
                        band = subwalk(w, list);
                    });
                    sum += tinted(ctx_.weights[static_cast<size_t>(r.band)], band);
                    stats_.wavelength_segments += stats_.segments - before;
                }
            }
            if (mirror) {
                List list;
                w.push(e, h, *mirror, polar::Mueller::Identity(), false, list);
                sum += tinted(mirror_weight, subwalk(w, list));
            }
            return sum;
        }
        if (ctx_.shortcut) {
            ++stats_.shortcut_tests;
            const int first = static_cast<int>(ctx_.bands());
            const Acc c0 = band_tree(w, e, h, first), c1 = band_tree(w, e, h, first + 1),
                      c2 = band_tree(w, e, h, first + 2);
            const Vec3 r0 = rgb_of(c0), r1 = rgb_of(c1), r2 = rgb_of(c2);
            const double d = std::fmax((r0 - r1).norm(), std::fmax((r1 - r2).norm(), (r0 - r2).norm()));
            if (d < ctx_.shortcut_threshold) {
                ++stats_.shortcut_taken;
                const Acc mean = (c0 + c1 + c2) / 3.0;
                if (bands_)
                    for (double& b : *bands_) b += rgb_of(mean).mean();
                return mean;
            }
        }
        if (packets()) {
            band_trees(w, e, h, ctx_.split_bands[mi], sum);
            return sum;
        }
        for (const int k : ctx_.split_bands[mi]) sum += tinted(ctx_.weights[static_cast<size_t>(k)], band_tree(w, e, h, k));
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

}  // namespace refract
