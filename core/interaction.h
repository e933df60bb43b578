#pragma once
// What happens where a ray meets a surface: the interaction returns the branches the ray
// spawns (direction, colour factor, the factor the pruning threshold uses), or says that
// the branch ends there (a leaf: diffuse surfaces and emitters, whose light the
// integrator gathers). Each material kind's interaction is one of its rules
// (core/materials/); this header holds the types they share and the physics of the
// dielectric node, written once over the scalar type: S = double for one ray, S = Lanes
// for a packet (geometry/width.h), and a counting scalar for experiments/yasuda_cost.cpp.
// Total internal reflection is a mask (`tir`), not an empty optional, so that lanes 2 and
// 5 of a packet can reflect totally while the others refract.
#include <array>
#include <cstdint>
#include <type_traits>
#include <utility>

#include <refract/core/birefringence.h>
#include <refract/core/optics.h>
#include <refract/core/polarisation.h>
#include <refract/core/random.h>
#include <refract/geometry/shapes.h>
#include <refract/geometry/width.h>

namespace refract {

struct Object;
struct Material;
class CompatRules;

enum class ReflectanceModel {
    Constant,  // Whitted: ks = constant_reflectivity, kt = 1 − ks
    Fresnel,   // exact, natural light (Yasuda eq. 7)
    FresnelS,  // s-polarised only
    FresnelP,  // p-polarised only
    Schlick,   // RTIOW approximation
};

// Where a ray starts: the object (index in Scene::objects) and facet of the hit it leaves
// (a reflected or refracted branch), or none (-1: a camera ray, a photon from a light).
// `inverted` (compat "povray" only): POV-Ray's interior list holds the opposite of the
// geometry for that object on this ray (SurfaceHit::inverted).
struct RayOrigin {
    std::int32_t object = -1;
    std::int32_t facet = -1;
    bool inverted = false;
};

struct SurfaceHit {
    Hit hit;
    const Object* object = nullptr;
    const Material* material = nullptr;
    Vec3 normal;           // unit normal on the incident side (normal·dir < 0)
    bool entering = true;  // the ray goes from outside to inside the object
    // Compat "povray": `entering` is POV-Ray's interior list's decision, the opposite of the
    // outward normal's (HitSearch, CompatRules::interior_lists); hit.normal stays outward.
    bool inverted = false;
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

// What an interaction depends on besides the hit.
struct InteractionContext {
    const CompatRules* rules = nullptr;  // the render's compatibility policy (core/compat.h)
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

// One sampled continuation of a path (stochastic integrator): the new direction (to be
// normalised by the caller) and the factor the path's throughput is multiplied by.
struct Scatter {
    Vec3 dir;
    Vec3 factor;
};

// ---- The dielectric node, over the scalar type -------------------------------------------

// The mask type of a scalar (bool for doubles and counting scalars, LaneMask for Lanes).
template <class S>
using MaskFor = decltype(std::declval<S>() >= std::declval<S>());
// The mask of the scalar type with every lane set (one ray: true).
template <class S>
MaskFor<S> every_lane() {
    if constexpr (std::is_same_v<MaskFor<S>, bool>) {
        return true;
    } else {
        return MaskFor<S>::Constant(true);
    }
}

// m ? a() : b(): one ray evaluates the branch it takes; a packet evaluates both and blends
// (geometry/width.h select), each lane getting the one-ray answer.
template <class M, class A, class B>
auto choose(const M& m, A&& a, B&& b) {
    if constexpr (std::is_same_v<M, bool>) {
        return m ? a() : b();
    } else {  // only the side the lanes take, when they all take one
        if (!(!m).any()) return decltype(select(m, a(), b()))(a());
        if (!m.any()) return decltype(select(m, a(), b()))(b());
        return select(m, a(), b());
    }
}

// The largest component: Eigen's maxCoeff for vectors that have one (width.h for lanes).
template <class V>
auto max_coeff(const V& v) -> decltype(v.maxCoeff()) {
    return v.maxCoeff();
}

// The largest of three values (Eigen's maxCoeff of a 3-vector: max(max(x, y), z)), over
// the scalar type (doubles, lanes).
template <class S>
S largest_of(const S& x, const S& y, const S& z) {
    using optics::generic::max_of;
    return max_of(max_of(x, y), z);
}

// Reflectance of a dielectric for its model at cos θi, with cos θt from Snell's law valid
// where the ray is not totally reflected (Constant, Fresnel, Fresnel-s, Fresnel-p,
// Schlick). A constant ks is the model's value everywhere.
template <class S>
S model_reflectance(ReflectanceModel model, S constant, S cos_i, S cos_t, S eta) {
    namespace gen = optics::generic;
    switch (model) {
        case ReflectanceModel::Constant: return constant;
        case ReflectanceModel::Fresnel: return gen::fresnel_terms(cos_i, cos_t, eta).R();
        case ReflectanceModel::FresnelS: return gen::fresnel_terms(cos_i, cos_t, eta).Rs;
        case ReflectanceModel::FresnelP: return gen::fresnel_terms(cos_i, cos_t, eta).Rp;
        case ReflectanceModel::Schlick: return gen::schlick(cos_i, eta);
    }
    return S(1.0);
}

// What a dielectric node's branches depend on: cos θi, cos θt by Snell's law (meaningful
// where `tir` is false: total internal reflection) and the reflectance R (1 on total
// internal reflection, whatever the model: a constant ks too, Whitted's Fig. 9).
template <class S>
struct DielectricTerms {
    S cos_i, cos_t, R;
    MaskFor<S> tir;
    // Whether light is transmitted: a refracted branch exists and carries some of it.
    MaskFor<S> transmits() const { return !tir && (R < S(1.0)); }
};
template <class V>
DielectricTerms<typename V::Scalar> dielectric_terms(const V& dir, const V& normal, typename V::Scalar eta,
                                                     ReflectanceModel model, typename V::Scalar constant) {
    using S = typename V::Scalar;
    namespace gen = optics::generic;
    const S cos_i = gen::cos_incident(dir, normal);
    const S sin2_t = gen::sin2_transmitted(cos_i, eta);  // Snell's law, once
    const MaskFor<S> tir = sin2_t >= S(1.0);
    if constexpr (std::is_same_v<MaskFor<S>, bool>) {
        if (tir) return {cos_i, S(0.0), S(1.0), tir};
        const S cos_t = gen::cos_of_sin2(sin2_t);
        return {cos_i, cos_t, model_reflectance(model, constant, cos_i, cos_t, eta), tir};
    } else {
        const S cos_t = gen::cos_of_sin2(sin2_t);  // NaN in the lanes under total internal reflection
        return {cos_i, cos_t, select(tir, S(1.0), model_reflectance(model, constant, cos_i, cos_t, eta)), tir};
    }
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
    return optics::generic::refracted_direction(dir, normal, t.cos_i, t.cos_t, eta).normalized();
}

// A dielectric node in the physical mode (Yasuda 1984 §3.1.3 ③ and ④): reflected and
// refracted directions (unit; `refracted` meaningful where the node transmits), the
// reflectance R, and the refracted branch's colour and threshold factors.
template <class V>
struct DielectricNode {
    using S = typename V::Scalar;
    V reflected, refracted;
    S R;
    V transmit_factor;   // (1 − R) · filter
    S transmit_bailout;  // its largest component
    MaskFor<S> tir;
    // Whether light is transmitted: the refracted branch exists and carries some of it.
    MaskFor<S> transmits() const { return !tir && (R < S(1.0)); }
};

template <class V>
DielectricNode<V> dielectric_node(const V& dir, const V& normal, typename V::Scalar eta, ReflectanceModel model,
                                  typename V::Scalar constant, const V& filter,
                                  const MaskFor<typename V::Scalar>& on = every_lane<typename V::Scalar>()) {
    using S = typename V::Scalar;
    const DielectricTerms<S> t = dielectric_terms(dir, normal, eta, model, constant);
    DielectricNode<V> n;  // `refracted` and `transmit_factor` set only where light refracts
    n.reflected = reflected_unit(dir, normal);
    n.R = t.R;
    n.transmit_bailout = S(0.0);
    n.tir = t.tir;
    if (!any(on && !t.tir)) return n;  // every ray `on` reflected totally: nothing refracts
    n.transmit_factor = (S(1.0) - t.R) * filter;
    n.transmit_bailout = max_coeff(n.transmit_factor);
    n.refracted = refracted_unit(dir, normal, t, eta);
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

// A dielectric node's two branches over the scalar type, in either mode (the physical node
// above, or POV-Ray's, CompatRules::dielectric): branch 0 the reflection (POV-Ray: or the
// refraction turned into a mirror ray), branch 1 the refraction (POV-Ray's split: or a
// band's mirror ray); `exists` where each is spawned, before the walker's threshold and
// limits.
template <class V>
struct NodeBranches {
    using S = typename V::Scalar;
    V dir[2], factor[2];
    S bailout[2];
    MaskFor<S> exists[2];
    S reflectance;              // R of the split (1 where the refraction turned into a mirror ray)
    MaskFor<S> split_mirror{};  // POV-Ray's split: branch 1 is a band's mirror ray
};
// Where a dielectric node is: the ray's direction and the normal on its incident side, the
// segment's length and side (POV-Ray's fading), and the relative indices, the ray's (a
// band's) and the material's nominal one.
template <class V>
struct NodeAt {
    using S = typename V::Scalar;
    V dir, normal;
    S t;
    MaskFor<S> entering;
    S eta, eta_nominal;
    MaskFor<S> on = every_lane<S>();  // the lanes at this node (the others carry anything)
};
// The physical node's branches.
template <class V>
NodeBranches<V> physical_branches(const DielectricNode<V>& d) {
    using S = typename V::Scalar;
    NodeBranches<V> b;
    b.dir[0] = d.reflected;
    b.factor[0] = splat<S>(d.R);
    b.bailout[0] = d.R;
    b.exists[0] = all_lanes<S>(true);
    b.exists[1] = d.transmits();
    b.dir[1] = d.refracted;
    b.factor[1] = d.transmit_factor;
    b.bailout[1] = d.transmit_bailout;
    b.reflectance = d.R;
    b.split_mirror = all_lanes<S>(false);
    return b;
}

// The physical mode's dielectric interaction of one ray (Yasuda 1984 §3.1.3 ③④): the node's
// branches, with Mueller matrices for exact polarisation.
Interaction dielectric_interaction(const DielectricNode<Vec3>& d, const SurfaceHit& h, const Ray& ray,
                                   const Vec3& filter, double eta, bool exact);

// A mirror's single branch (perfect reflection, reflectivity `color`).
Interaction mirror_interaction(const Vec3& color, const SurfaceHit& h, const Ray& ray, bool exact);

// The leaf interaction: the branch ends here.
inline Interaction leaf_interaction() {
    Interaction n;
    n.leaf = true;
    return n;
}

}  // namespace refract
