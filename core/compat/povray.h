#pragma once
// POV-Ray 3.7's rules, the compatibility mode's half of the policy (core/compat.h): its
// constants, its dielectric node, its interior fading, its shadow rays through glass, its
// dispersion bands and its single-precision indices. Sources: POV-Ray 3.7
// source/backend/render/trace.cpp (ComputeLightedTexture, ComputeReflectivity,
// ComputeRefraction, TracePointLightShadowRay), configbackend.h, frame.h; the formulas
// are collected in docs/validation.md. Nothing else in core/ knows them.
#include <cmath>
#include <optional>
#include <vector>

#include <refract/core/interaction.h>
#include <refract/core/material.h>

namespace refract {

struct Scene;
struct RenderStats;

namespace povray {

// Hits are kept for kMinDepth <= t < kMaxDistance (MIN_ISECT_DEPTH, MAX_DISTANCE); shadow
// rays ignore hits within kShadowTolerance of either end (SMALL_TOLERANCE / SHADOW_TOLERANCE);
// the greyscale of a colour weighs r, g, b by RED/GREEN/BLUE_INTENSITY.
constexpr double kMinDepth = 1e-4;
constexpr double kMaxDistance = 1e7;
constexpr double kShadowTolerance = 1e-3;
inline const Vec3 kGreyscale{0.297, 0.589, 0.114};

// An interior's ior as POV-Ray stores it, in single precision (frame.h, class Interior):
// n = 1.333 refracts as 1.33299994..., which moves far-away hits by ~0.1 unit.
inline double stored_index(double ior) { return static_cast<double>(static_cast<float>(ior)); }

// The interior fading as the exporter writes absorption (fade_distance 1, fade_power 1001:
// the exponential form, fade_color 1 − α per channel; trace.cpp ComputeLightedTexture):
// f = exp(−(1 − C)·d/D) with C and D stored in single precision and the product and exp
// rounded to single precision, over a segment of length d.
Vec3 fade(const Vec3& alpha, double distance);

// POV-Ray's refraction test (trace.cpp ComputeRefraction): the greyscale of the surface's
// filter colour f = (1 − R)·filter under kGreyscale, |f·grey| at most 1 (fmin(1, ·): a NaN
// gives 1). A refracted ray is spawned only where it exceeds adc_bailout; its adc weight
// is largest_of(|f|). Over the scalar type.
template <class S>
S filter_greyscale(const S (&f)[3]) {
    using optics::generic::min_of;
    using std::abs;
    return min_of(S(abs(f[0] * S(kGreyscale[0]) + f[1] * S(kGreyscale[1]) + f[2] * S(kGreyscale[2]))), S(1.0));
}

// POV-Ray 3.7 with `reflection { MIN, MAX fresnel on } conserve_energy` or
// `reflection { ks } conserve_energy` and `pigment { rgbf <filter, 1> }`
// (trace.cpp ComputeLightedTexture, ComputeReflectivity, ComputeRefraction), over the
// scalar type (one ray, or the lanes of a packet):
// - reflectivity R: the model's value at the nominal index; on total internal reflection
//   Fresnel gives MAX = 1, a constant ks stays ks (dispersion: Fresnel with the nominal
//   index, the TIR test with the band's);
// - the surface's filter colour is filter·(1 − R), and a refracted ray is spawned only
//   when its greyscale exceeds adc_bailout (a local test, not the cumulative weight);
//   its adc weight is parent × max3(filter·(1 − R));
// - if that refracted ray meets total internal reflection it becomes a mirror ray of
//   colour factor 1 (unfiltered) with the refraction's adc weight, and replaces the
//   reflection term;
// - the reflected ray has colour factor R and adc weight parent × R; none when R = 0.
// Dispersion: an RGB ray splits into bands at its first refraction whenever the refracted
// ray is spawned, even where the nominal index meets total internal reflection (a constant
// ks); a band meeting total internal reflection there (`split`) becomes a mirror ray
// filtered by filter·(1 − R) like the refraction (the band loop discards the TIR flag), and
// the reflection term is kept; that mirror ray is made from the incoming ray
// (TraceRefractionRay → ComputeReflection), so it is not one band but a full ray that
// splits again at its next dispersive hit. A ray that is already one band follows the rule
// above with its own index.
// Absorption: at a hit from inside an interior with fading, only the light of the
// refraction computation is faded, over the last segment: the refracted ray, the mirror
// ray that a refraction meeting TIR turns into, a band's TIR mirror at the split; not the
// reflected branch, and not the adc weight.
template <class V>
NodeBranches<V> dielectric_branches(const material::Dielectric& m, const NodeAt<V>& at, double adc, bool split) {
    using S = typename V::Scalar;
    using M = MaskFor<S>;
    namespace gen = optics::generic;
    V fade_factor = broadcast<S>(Vec3(1, 1, 1));
    if (m.absorption) {
        const M leaving = !at.entering;
        for_each_lane(leaving, [&](int l) { set_lane(fade_factor, l, fade(m.absorption->rgb, lane_of(at.t, l))); });
    }
    const S cos_i = gen::cos_incident(at.dir, at.normal);
    const S sin2_n = gen::sin2_transmitted(cos_i, at.eta_nominal);
    const S constant(m.constant_reflectivity);
    const S R = m.reflectance == ReflectanceModel::Constant
                    ? constant
                    : choose(M(sin2_n >= S(1.0)), [] { return S(1.0); }, [&] {
                          return model_reflectance(m.reflectance, constant, cos_i, gen::cos_of_sin2(sin2_n), at.eta_nominal);
                      });
    const S sin2_t = gen::sin2_transmitted(cos_i, at.eta);
    const M tir = sin2_t >= S(1.0);
    S filter[3];
    for (int c = 0; c < 3; ++c) filter[c] = (S(1.0) - R) * S(m.filter[c]);
    const S grey = filter_greyscale(filter);
    using std::abs;
    const S adc_weight = largest_of(S(abs(filter[0])), S(abs(filter[1])), S(abs(filter[2])));
    const M spawn = grey > S(adc);
    const M mirror = spawn && tir && all_lanes<S>(!split);  // the refracted ray turned into a mirror ray
    NodeBranches<V> b;
    b.dir[0] = reflected_unit(at.dir, at.normal);
    b.factor[0] = select(mirror, fade_factor, splat<S>(R));
    b.bailout[0] = select(mirror, adc_weight, R);
    b.exists[0] = all_lanes<S>(true);
    b.exists[1] = spawn && (!tir || all_lanes<S>(split));
    b.split_mirror = spawn && tir && all_lanes<S>(split);
    b.reflectance = select(mirror, S(1.0), R);
    b.factor[1] = cwise(V{filter[0], filter[1], filter[2]}, fade_factor);
    b.bailout[1] = adc_weight;
    b.dir[1] = choose(M(tir || !at.on), [&] { return b.dir[0]; }, [&] {
        return V(gen::refracted_direction(at.dir, at.normal, cos_i, gen::cos_of_sin2(sin2_t), at.eta).normalized());
    });
    return b;
}

}  // namespace povray
}  // namespace refract

namespace refract {

class HitSearch;
struct SpectralContext;

namespace povray {

// POV-Ray 3.7's point-light shadow ray (trace.cpp TracePointLightShadowRay): a straight
// ray; the nearest hit farther than kShadowTolerance from the current origin and nearer
// than kShadowTolerance to the light is taken; an opaque object blocks, a transparent one
// multiplies by its filter colour (and, leaving a fading interior, its fade over the chord:
// ComputeShadowTexture) and the search goes on from that hit. no_shadow objects (the
// emissive highlights) are not seen.
Vec3 light_transmittance(const HitSearch& search, const Vec3& from, const Vec3& to, RenderStats& stats);

// POV-Ray's dispersion bands (trace.cpp ComputeRefraction): an interior splits an RGB ray
// only when its dispersion, stored in single precision, differs from 1 (|D − 1| >= 1e-10);
// one band set, with its hue weights, per distinct dispersion_samples; the band sums kept
// as they are (no clip).
void spectral_bands(const Scene& scene, SpectralContext& c);

}  // namespace povray
}  // namespace refract
