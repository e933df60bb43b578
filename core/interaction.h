#pragma once
// What each material kind does where a ray meets it: the interaction returns the
// branches the ray spawns (direction, colour factor, the factor the pruning threshold
// uses), or says that the branch ends there (a leaf: diffuse surfaces and emitters, whose
// light the integrator gathers). One function per kind, dispatched over the Material
// variant, so a kind without one fails to compile. The stochastic integrator samples
// these same branches (core/integrators/stochastic.cpp); only Lambertian and fuzzy metal
// scatter randomly, and own that sampling here too.
#include <array>
#include <cstdint>
#include <optional>

#include "core/birefringence.h"
#include "core/material.h"
#include "core/optics.h"
#include "core/polarisation.h"
#include "core/random.h"
#include "geometry/shapes.h"

namespace refract {

struct Object;

// Where a ray starts: the object (index in Scene::objects) and facet of the hit it leaves
// (a reflected or refracted branch), or none (-1: a camera ray, a photon from a light).
struct RayOrigin {
    std::int32_t object = -1;
    std::int32_t facet = -1;
};

struct SurfaceHit {
    Hit hit;
    const Object* object = nullptr;
    const Material* material = nullptr;
    Vec3 normal;           // unit normal on the incident side (normal·dir < 0)
    bool entering = true;  // the ray goes from outside to inside the object
};

// One branch: the new ray, its colour factor (reflectance, transmittance × filter) and
// the factor the pruning threshold uses (Yasuda's cumulative attenuation; POV-Ray's adc
// weight in compat mode).
struct Branch {
    Ray ray;
    Vec3 factor;
    double bailout_factor;
    // Uniaxial crystals: the wave the new ray travels as (o or e inside the crystal), and,
    // with exact polarisation, the Stokes frames of the branch's Mueller matrix: x̂ on the
    // parent's side and on the new ray's (zero: ŝ of the interface, as for isotropic media).
    biref::Wave wave = biref::Wave::Isotropic;
    Vec3 frame_parent = Vec3::Zero(), frame_child = Vec3::Zero();
};

struct Interaction {
    bool leaf = false;          // the branch ends here (diffuse, Lambertian, emissive)
    std::array<Branch, 3> branch;
    int branches = 0;           // branch[0]: reflection; branch[1]: refraction
    // Which branches are transmitted (crossing the surface): a uniaxial crystal spawns up to
    // three (one beam and two waves of the crystal).
    std::array<bool, 3> transmitted{false, true, true};
    double reflectance = 0;     // dielectric: R used for the split (1 on TIR)
    bool split_mirror = false;  // POV-Ray dispersion split: branch[1] is a band's TIR mirror ray
    // Exact polarisation (InteractionContext::exact): each branch's Mueller matrix in the
    // interface's s/p frames (core/polarisation.h); `factor` then holds only the colour
    // (filter, mirror tint), the Fresnel part being in the matrix.
    std::array<polar::Mueller, 3> mueller;
};

// What a dielectric interaction depends on besides the hit.
struct InteractionContext {
    bool pov = false;     // POV-Ray 3.7 compat semantics
    double adc = 0;       // POV-Ray: adc_bailout (local test of the refracted ray)
    double band_ior = 0;  // > 0: the index at one wavelength instead of `ior`
    bool split = false;   // POV-Ray: the band's share of an RGB ray splitting here
    bool exact = false;   // exact polarisation: Mueller matrices on the branches
    // Uniaxial crystals: the wave the incoming ray travels as, its wavelength (nm; 0: an RGB
    // ray, taken at the D line), and whether light runs against the rays (an eye pass, whose
    // Mueller matrices map light from the child's ray into the parent's).
    biref::Wave wave = biref::Wave::Isotropic;
    double wavelength_nm = 0;
    bool adjoint = false;
};

// Reflectance of a dielectric for its model at cos θi, with cos θt from Snell's law (empty:
// total internal reflection), and relative index eta (Constant, Fresnel, Fresnel-s,
// Fresnel-p, Schlick); 1 on total internal reflection for the physical models. Written
// over the scalar type (experiments count its arithmetic).
template <class S>
S dielectric_reflectance(ReflectanceModel model, S constant, S cos_i, const std::optional<S>& cos_t, S eta) {
    namespace gen = optics::generic;
    switch (model) {
        case ReflectanceModel::Constant: return constant;
        case ReflectanceModel::Fresnel: return cos_t ? gen::fresnel_terms(cos_i, *cos_t, eta).R() : S(1.0);
        case ReflectanceModel::FresnelS: return cos_t ? gen::fresnel_terms(cos_i, *cos_t, eta).Rs : S(1.0);
        case ReflectanceModel::FresnelP: return cos_t ? gen::fresnel_terms(cos_i, *cos_t, eta).Rp : S(1.0);
        case ReflectanceModel::Schlick: return cos_t ? gen::schlick(cos_i, eta) : S(1.0);
    }
    return S(1.0);
}
template <class S>
S dielectric_reflectance(ReflectanceModel model, S constant, S cos_i, S eta) {
    return dielectric_reflectance(model, constant, cos_i, optics::generic::cos_transmitted(cos_i, eta), eta);
}

// The largest of three values (Eigen's maxCoeff of a 3-vector: max(max(x, y), z)), over
// the scalar type (doubles, lanes).
template <class S>
S largest_of(const S& x, const S& y, const S& z) {
    using optics::generic::max_of;
    return max_of(max_of(x, y), z);
}

// POV-Ray 3.7's refraction test (trace.cpp ComputeRefraction): the greyscale of the
// surface's filter colour f = (1 − R)·filter under the weights `grey` (RED, GREEN and
// BLUE_INTENSITY), |f·grey| at most 1 (fmin(1, ·): a NaN gives 1). A refracted ray is spawned
// only where it exceeds adc_bailout; its adc weight is largest_of(|f|). Over the scalar type.
template <class S>
S pov_filter_greyscale(const S (&f)[3], const Vec3& grey) {
    using std::abs;
    using optics::generic::min_of;
    return min_of(S(abs(f[0] * S(grey[0]) + f[1] * S(grey[1]) + f[2] * S(grey[2]))), S(1.0));
}

// A dielectric node in the physical mode (Yasuda 1984 §3.1.3 ③ and ④): reflected and
// refracted directions (unit), the reflectance R, and the refracted branch's colour and
// threshold factors. Written over the vector type V (Scalar, dot, normalized, maxCoeff,
// cwiseProduct); refract renders with V = Vec3 and experiments/yasuda_cost.cpp counts
// the arithmetic of this same function.
template <class V>
struct DielectricNode {
    using S = typename V::Scalar;
    V reflected;
    std::optional<V> refracted;  // empty on total internal reflection
    S R;
    V transmit_factor;           // (1 − R) · filter
    S transmit_bailout;          // its largest component
    // Whether light is transmitted: the refracted branch exists and carries some of it.
    bool transmits() const { return refracted && R < S(1.0); }
};

// What a dielectric node's branches depend on: cos θi, cos θt by Snell's law (empty: total
// internal reflection) and the reflectance R (1 on total internal reflection, whatever the
// model: a constant ks too, Whitted's Fig. 9).
template <class S>
struct DielectricTerms {
    S cos_i;
    std::optional<S> cos_t;
    S R;
    // Whether light is transmitted: a refracted branch exists and carries some of it.
    bool transmits() const { return cos_t && R < S(1.0); }
};
template <class V>
DielectricTerms<typename V::Scalar> dielectric_terms(const V& dir, const V& normal, typename V::Scalar eta,
                                                     ReflectanceModel model, typename V::Scalar constant) {
    using S = typename V::Scalar;
    namespace gen = optics::generic;
    const S cos_i = gen::cos_incident(dir, normal);
    const std::optional<S> cos_t = gen::cos_transmitted(cos_i, eta);  // Snell's law, once
    return {cos_i, cos_t, cos_t ? dielectric_reflectance(model, constant, cos_i, cos_t, eta) : S(1.0)};
}
// The node's two directions, unit length. Rays are unit length by convention: renormalise,
// or the rounding error of |dir| grows about tenfold per bounce in a chain of internal
// reflections (the sphere intersection assumes |dir| = 1, so the hit leaves the surface and
// the next normal is off), and after ~10 bounces the path is wrong.
template <class V>
V reflected_unit(const V& dir, const V& normal) {
    return optics::generic::reflect(dir, normal).normalized();
}
template <class V>
V refracted_unit(const V& dir, const V& normal, const DielectricTerms<typename V::Scalar>& t, typename V::Scalar eta) {
    return optics::generic::refracted_direction(dir, normal, t.cos_i, *t.cos_t, eta).normalized();
}

template <class V>
DielectricNode<V> dielectric_node(const V& dir, const V& normal, typename V::Scalar eta, ReflectanceModel model,
                                  typename V::Scalar constant, const V& filter) {
    using S = typename V::Scalar;
    const DielectricTerms<S> t = dielectric_terms(dir, normal, eta, model, constant);
    DielectricNode<V> n{reflected_unit(dir, normal), std::nullopt, t.R, V(), S(0.0)};
    if (t.cos_t) {
        n.transmit_factor = (S(1.0) - t.R) * filter;
        n.transmit_bailout = n.transmit_factor.maxCoeff();
        n.refracted = refracted_unit(dir, normal, t, eta);
    }
    return n;
}

// The child's cumulative attenuation (Yasuda eq. 12): the parent's weight times the
// branch's factor, and the scalar the threshold is compared with.
template <class V>
struct Attenuation {
    V weight;
    typename V::Scalar bailout;
};
template <class V>
Attenuation<V> attenuate(const V& weight, typename V::Scalar bailout, const V& factor,
                         typename V::Scalar bailout_factor) {
    return {weight.cwiseProduct(factor), bailout * bailout_factor};
}

// POV-Ray 3.7's interior fading as the exporter writes absorption (fade_distance 1,
// fade_power 1001: the exponential form, fade_color 1 − α per channel; trace.cpp
// ComputeLightedTexture): f = exp(−(1 − C)·d/D) with C and D stored in single precision
// and the product and exp rounded to single precision, over a segment of length d.
Vec3 pov_fade(const Vec3& alpha, double distance);

// The interaction of each kind at hit h of `ray`.
Interaction interact(const material::Diffuse& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
Interaction interact(const material::Lambertian& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
Interaction interact(const material::Mirror& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
Interaction interact(const material::Metal& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
Interaction interact(const material::Emissive& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
Interaction interact(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
// A uniaxial crystal: biref::split_at_interface's beams (core/birefringence.h). Natural
// light: each branch's factor is its power for unpolarised incidence (a crystal wave: the
// power of that wave) times the filter on transmission; exact polarisation: its Mueller
// matrix, for an eye pass (c.adjoint) the one of the reversed path, light arriving along
// the child's ray and leaving along the parent's (biref::reversed, reciprocity).
Interaction interact(const material::Uniaxial& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);
Interaction interact(const Material& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c);

// One sampled continuation of a path (stochastic integrator): the new direction and the
// factor the path's throughput is multiplied by; empty when the path is absorbed.
struct Scatter {
    Vec3 dir;
    Vec3 factor;
};
// Random scattering of the kinds that scatter randomly (RTIOW: Lambertian, fuzzy metal);
// `pigment` is the Lambertian's albedo at the hit. Empty optional: absorbed.
std::optional<Scatter> scatter(const material::Lambertian& m, const Vec3& pigment, const SurfaceHit& h, Rng& rng);
std::optional<Scatter> scatter(const material::Metal& m, const SurfaceHit& h, const Ray& ray, Rng& rng);
// RTIOW's dielectric in the physical mode: reflection with probability R, else refraction
// (the filter colour), the throughput unweighted by R; the node's R (dielectric_node), the
// chosen direction alone computed. Like the other kinds' scatters, the direction is left
// for the caller to normalise (normalised, it is dielectric_node's).
Scatter scatter(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray, Rng& rng);
// One branch of an interaction chosen at random (RTIOW's dielectric: reflection with
// probability R, else refraction, the throughput unweighted by R; a mirror's single
// branch with its colour factor).
std::optional<Scatter> sample_branch(const Material& m, const Interaction& in, Rng& rng);

}  // namespace refract
