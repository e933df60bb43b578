#include "core/integrators/spectral.h"

#include <cmath>
#include <deque>
#include <map>
#include <numeric>
#include <optional>

#include "core/illumination_map.h"
#include "core/spectrum/cie.h"
#include "geometry/error.h"

namespace refract {

Vec3 SpectralContext::finish(const Vec3& rgb) const { return clip ? Vec3(rgb.cwiseMax(0.0)) : rgb; }

namespace {

// POV-Ray splits a ray at an interior only when its dispersion, stored in single
// precision, differs from 1 (trace.cpp: haveDispersion = fabs(dispersion - 1.0) >= EPSILON).
const spectrum::PovRayModel* pov_splitting_model(const Material& m) {
    constexpr double kPovEpsilon = 1e-10;
    if (m.kind != MaterialKind::Dielectric || !m.dispersion || !m.dispersion->is_povray()) return nullptr;
    const auto& p = std::get<spectrum::PovRayModel>(m.dispersion->model);
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
            c.dispersive[mi] = m.kind == MaterialKind::Dielectric && m.dispersion.has_value();
        }
    }
    std::vector<double> all = c.wavelengths;
    all.insert(all.end(), s.shortcut_wavelengths.begin(), s.shortcut_wavelengths.end());
    c.index.assign(all.size(), std::vector<double>(materials, 0.0));
    for (size_t mi = 0; mi < materials; ++mi) {
        if (!c.dispersive[mi]) continue;
        const Material& m = scene.materials[mi];
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

struct Entry {
    Ray ray;
    Vec3 weight;
    double bailout;
    int depth, refl, trans;
};

class Walker {
public:
    Walker(const SceneTracer& t, const SpectralContext& c, RenderStats& s) : tracer_(t), ctx_(c), stats_(s) {}

    // Walks the FIFO list to the end. band < 0: RGB rays that split at their first
    // dispersive hit; else every dispersive dielectric has its index at band `band`.
    Vec3 walk(std::deque<Entry>& list, int band) {
        Vec3 sum(0, 0, 0);
        while (!list.empty()) {
            const Entry e = list.front();
            list.pop_front();
            const auto hit = tracer_.intersect(e.ray, stats_);
            if (!hit) {
                sum += e.weight.cwiseProduct(tracer_.background(e.ray.dir));
                continue;
            }
            const int mi = hit->object->material;
            if (band < 0 && ctx_.dispersive[mi]) {
                sum += split(e, *hit, list);
                continue;
            }
            sum += expand(e, *hit, band < 0 ? 0.0 : ctx_.index[band][mi], list);
        }
        return sum;
    }

private:
    // The node at a hit: adds its children to `list`, returns the local light.
    Vec3 expand(const Entry& e, const SurfaceHit& h, double band_ior, std::deque<Entry>& list) {
        const Node n = tracer_.node(h, e.ray, stats_, band_ior);
        Vec3 local = n.local;
        const Material& m = *h.material;
        if (ctx_.maps && (m.kind == MaterialKind::Diffuse || m.kind == MaterialKind::Lambertian)) {
            const int obj = static_cast<int>(h.object - tracer_.scene().objects.data());
            local += m.diffuse * tracer_.pigment(m, h.hit.point).cwiseProduct(ctx_.maps->irradiance(obj, h.hit));
        }
        for (int b = 0; b < n.branches; ++b) push(e, n.branch[b], b == 1, list);
        return e.weight.cwiseProduct(local);
    }

    void push(const Entry& e, const Branch& br, bool transmitted, std::deque<Entry>& list) {
        const double bail = e.bailout * br.bailout_factor;
        if (bail <= 0 || bail < tracer_.settings().pruning_threshold()) {
            ++stats_.pruned;
            return;
        }
        const int refl = e.refl + (transmitted ? 0 : 1), trans = e.trans + (transmitted ? 1 : 0);
        if (e.depth + 1 > tracer_.settings().max_depth || refl > ctx_.max_reflections ||
            trans > ctx_.max_transmissions) {
            ++stats_.depth_limited;
            return;
        }
        list.push_back({br.ray, e.weight.cwiseProduct(br.factor), bail, e.depth + 1, refl, trans});
    }

    // The subtree below hit h traced at one band.
    Vec3 band_tree(const Entry& e, const SurfaceHit& h, int band) {
        const std::uint64_t before = stats_.segments;
        std::deque<Entry> list;
        Vec3 v = expand(e, h, ctx_.index[band][h.object->material], list);
        v += walk(list, band);
        stats_.wavelength_segments += stats_.segments - before;
        return v;
    }

    Vec3 split(const Entry& e, const SurfaceHit& h, std::deque<Entry>& rgb_list) {
        ++stats_.spectral_splits;
        const int mi = h.object->material;
        if (ctx_.pov) {
            // POV-Ray: Fresnel and the reflected ray with the nominal index (stays RGB);
            // the refracted ray, when spawned, splits into bands, each with its own
            // direction and TIR test (SceneTracer::dielectric_node_pov, `split`).
            const std::vector<int>& bands = ctx_.split_bands[mi];
            const Node first = tracer_.node(h, e.ray, stats_, ctx_.index[bands[0]][mi], true);
            if (first.branches > 0) push(e, first.branch[0], false, rgb_list);
            if (first.branches < 2) return e.weight.cwiseProduct(first.local);  // nothing refracts
            Vec3 sum(0, 0, 0);
            // A band's TIR mirror ray is a full ray (it splits again), the same for every
            // band that meets TIR: traced once with the sum of their weights.
            Vec3 mirror_weight(0, 0, 0);
            std::optional<Branch> mirror;
            for (const int k : bands) {
                const Node bn = k == bands[0] ? first : tracer_.node(h, e.ray, stats_, ctx_.index[k][mi], true);
                if (bn.split_mirror) {
                    mirror = bn.branch[1];
                    mirror_weight += ctx_.weights[k];
                    continue;
                }
                const std::uint64_t before = stats_.segments;
                std::deque<Entry> list;
                push(e, bn.branch[1], true, list);
                sum += ctx_.weights[k].cwiseProduct(walk(list, k));
                stats_.wavelength_segments += stats_.segments - before;
            }
            if (mirror) {
                std::deque<Entry> list;
                push(e, *mirror, false, list);
                sum += mirror_weight.cwiseProduct(walk(list, -1));
            }
            return sum;
        }
        if (ctx_.shortcut) {
            ++stats_.shortcut_tests;
            const int first = static_cast<int>(ctx_.bands());
            const Vec3 c0 = band_tree(e, h, first), c1 = band_tree(e, h, first + 1), c2 = band_tree(e, h, first + 2);
            const double d = std::fmax((c0 - c1).norm(), std::fmax((c1 - c2).norm(), (c0 - c2).norm()));
            if (d < ctx_.shortcut_threshold) {
                ++stats_.shortcut_taken;
                return (c0 + c1 + c2) / 3.0;
            }
        }
        Vec3 sum(0, 0, 0);
        for (const int k : ctx_.split_bands[mi]) sum += ctx_.weights[k].cwiseProduct(band_tree(e, h, k));
        return sum;
    }

    const SceneTracer& tracer_;
    const SpectralContext& ctx_;
    RenderStats& stats_;
};

}  // namespace

Vec3 spectral_radiance(const SceneTracer& tracer, const SpectralContext& ctx, const Ray& primary,
                       RenderStats& stats) {
    Walker w(tracer, ctx, stats);
    std::deque<Entry> list;
    list.push_back({primary, Vec3(1, 1, 1), 1.0, 0, 0, 0});
    return w.walk(list, -1);
}

}  // namespace refract
