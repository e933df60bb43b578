#include "core/interaction.h"

#include <cmath>

#include "core/tracer.h"

namespace refract {

namespace {

Interaction leaf() {
    Interaction n;
    n.leaf = true;
    return n;
}

Interaction mirror(const Vec3& color, const SurfaceHit& h, const Ray& ray, bool exact) {
    Interaction n;
    n.branch[0] = Branch{Ray{h.hit.point, optics::reflect(ray.dir, h.normal).normalized()}, color, color.maxCoeff()};
    n.branches = 1;
    n.reflectance = color.maxCoeff();
    // A perfect conductor: rs = −1, rp = +1 at every angle (the η → ∞ limit of Hecht's
    // amplitudes), so the Mueller matrix is diag(1, 1, −1, −1) in the s/p frames.
    if (exact) n.mueller[0] = polar::jones_diagonal_to_mueller(-1.0, 1.0);
    return n;
}

// POV-Ray 3.7 with `reflection { MIN, MAX fresnel on } conserve_energy` or
// `reflection { ks } conserve_energy` and `pigment { rgbf <filter, 1> }`
// (trace.cpp ComputeLightedTexture, ComputeReflectivity, ComputeRefraction):
// - reflectivity R: the model's value; on total internal reflection Fresnel gives
//   MAX = 1, a constant ks stays ks (dispersion: Fresnel with the nominal index, the
//   TIR test with the band's);
// - the surface's filter colour is filter·(1 − R), and a refracted ray is spawned only
//   when its greyscale exceeds adc_bailout (a local test, not the cumulative weight);
//   its adc weight is parent × max3(filter·(1 − R));
// - if that refracted ray meets total internal reflection it becomes a mirror ray of
//   colour factor 1 (unfiltered) with the refraction's adc weight, and replaces the
//   reflection term;
// - the reflected ray has colour factor R and adc weight parent × R; none when R = 0.
// Dispersion (ComputeRefraction): an RGB ray splits into bands at its first refraction
// whenever the refracted ray is spawned, even where the nominal index meets total
// internal reflection (a constant ks); a band meeting total internal reflection there
// (`split`) becomes a mirror ray filtered by filter·(1 − R) like the refraction (the
// band loop discards the TIR flag), and the reflection term is kept; that mirror ray
// is made from the incoming ray (TraceRefractionRay → ComputeReflection), so it is
// not one band but a full ray that splits again at its next dispersive hit. A ray that is
// already one band (`band`) follows the rule above with its own index.
//
// Absorption (trace.cpp ComputeLightedTexture): at a hit from inside an interior with
// fading, only the light of the refraction computation is faded, over the last segment:
// the refracted ray, the mirror ray that a refraction meeting TIR turns into, a band's
// TIR mirror at the split; not the reflected branch, and not the adc weight. So a path
// fades over the segments that end in a transmission only.
Interaction dielectric_pov(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray, double cos_i,
                           double eta, const std::optional<Vec3>& refr, bool band, bool split, double adc) {
    const Vec3 fade = !h.entering && m.absorption ? pov_fade(m.absorption->rgb, h.hit.t) : Vec3(1, 1, 1);
    double R = dielectric_reflectance(m.reflectance, m.constant_reflectivity, cos_i, eta);
    // A band ray (dispersion) keeps the nominal index's R even where its own index meets
    // total internal reflection; the refracted ray then turns into the mirror ray below.
    if (!refr && !band && m.reflectance != ReflectanceModel::Constant) R = 1.0;
    const Vec3 filter = (1.0 - R) * m.filter;
    const double f[3] = {filter[0], filter[1], filter[2]};
    const double trans = pov_filter_greyscale(f, SceneTracer::kPovGreyscale);
    const double adc_weight = largest_of(std::abs(f[0]), std::abs(f[1]), std::abs(f[2]));
    const Ray reflected{h.hit.point, optics::reflect(ray.dir, h.normal).normalized()};
    Interaction n;
    n.reflectance = R;
    if (trans > adc && !refr && split) {  // a band's total internal reflection at the split
        n.branch[0] = Branch{reflected, Vec3::Constant(R), R};
        n.branch[1] = Branch{reflected, filter.cwiseProduct(fade), adc_weight};
        n.branches = 2;
        n.split_mirror = true;
        return n;
    }
    if (trans > adc && !refr) {  // the refracted ray turns into total internal reflection
        n.branch[0] = Branch{reflected, fade, adc_weight};
        n.branches = 1;
        n.reflectance = 1.0;
        return n;
    }
    n.branch[0] = Branch{reflected, Vec3::Constant(R), R};
    n.branches = 1;
    if (trans > adc) {
        n.branch[1] = Branch{Ray{h.hit.point, refr->normalized()}, filter.cwiseProduct(fade), adc_weight};
        n.branches = 2;
    }
    return n;
}

}  // namespace

Vec3 pov_fade(const Vec3& alpha, double distance) {
    Vec3 f;
    for (int c = 0; c < 3; ++c) {
        const float colour = static_cast<float>(1.0 - alpha[c]);  // fade_color, stored as float
        const float x = static_cast<float>(static_cast<float>(1.0f - colour) * distance);  // D = 1
        f[c] = static_cast<double>(static_cast<float>(std::exp(-static_cast<double>(x))));
    }
    return f;
}

Interaction interact(const material::Diffuse&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf();
}
// The tree integrators light RTIOW's Lambertian directly, as a diffuse surface.
Interaction interact(const material::Lambertian&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf();
}
Interaction interact(const material::Emissive&, const SurfaceHit&, const Ray&, const InteractionContext&) {
    return leaf();
}
Interaction interact(const material::Mirror& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return mirror(m.color, h, ray, c.exact);
}
// Fuzz needs sampling: the tree takes the mirror direction.
Interaction interact(const material::Metal& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return mirror(m.color, h, ray, c.exact);
}

namespace {

// The physical mode's dielectric node (Yasuda 1984 §3.1.3 ③④), with Mueller matrices on
// the branches for exact polarisation.
Interaction dielectric_physical(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray,
                                const InteractionContext& c, double eta) {
    const DielectricNode<Vec3> d = dielectric_node(ray.dir, h.normal, eta, m.reflectance, m.constant_reflectivity,
                                                   m.filter);
    Interaction n;
    n.reflectance = d.R;
    n.branches = 1;
    if (c.exact) {
        // The threshold keeps natural light's weights, so both models walk the same tree.
        const double cos_i = std::fmin(-ray.dir.dot(h.normal), 1.0);
        n.branch[0] = Branch{Ray{h.hit.point, d.reflected}, Vec3(1, 1, 1), d.R};
        n.mueller[0] = polar::mueller_reflection(cos_i, eta);
        if (d.transmits()) {
            n.branch[1] = Branch{Ray{h.hit.point, *d.refracted}, m.filter, d.transmit_bailout};
            n.mueller[1] = *polar::mueller_transmission(cos_i, eta);
            n.branches = 2;
        }
        return n;
    }
    n.branch[0] = Branch{Ray{h.hit.point, d.reflected}, Vec3::Constant(d.R), d.R};
    if (d.transmits()) {
        n.branch[1] = Branch{Ray{h.hit.point, *d.refracted}, d.transmit_factor, d.transmit_bailout};
        n.branches = 2;
    }
    return n;
}

}  // namespace

Interaction interact(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    // POV-Ray stores an interior's ior in single precision (frame.h, class Interior):
    // n = 1.333 refracts as 1.33299994..., which moves far-away hits by ~0.1 unit.
    const double nominal = c.pov ? static_cast<double>(static_cast<float>(m.ior)) : m.ior;
    const double ior = c.band_ior > 0 ? c.band_ior : nominal;
    const double eta = h.entering ? ior : 1.0 / ior;
    if (!c.pov) return dielectric_physical(m, h, ray, c, eta);
    const double cos_i = std::fmin(-ray.dir.dot(h.normal), 1.0);
    const auto refr = optics::refract(ray.dir, h.normal, eta);
    return dielectric_pov(m, h, ray, cos_i, h.entering ? nominal : 1.0 / nominal, refr, c.band_ior > 0, c.split, c.adc);
}

Interaction interact(const Material& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    return std::visit([&](const auto& kind) { return interact(kind, h, ray, c); }, m.kind);
}

std::optional<Scatter> scatter(const material::Lambertian&, const Vec3& pigment, const SurfaceHit& h, Rng& rng) {
    Vec3 dir = h.normal + rng.unit_vector();  // RTIOW lambertian scatter
    if (dir.squaredNorm() < 1e-16) dir = h.normal;
    return Scatter{dir, pigment};
}

std::optional<Scatter> scatter(const material::Metal& m, const SurfaceHit& h, const Ray& ray, Rng& rng) {
    const Vec3 dir = optics::reflect(ray.dir, h.normal) + m.fuzz * rng.in_unit_sphere();
    if (dir.dot(h.normal) <= 0) return std::nullopt;  // absorbed
    return Scatter{dir, m.color};
}

Scatter scatter(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray, Rng& rng) {
    const double eta = h.entering ? m.ior : 1.0 / m.ior;
    const DielectricTerms<double> t = dielectric_terms(ray.dir, h.normal, eta, m.reflectance, m.constant_reflectivity);
    // A choice only where dielectric_physical spawns two branches (DielectricNode::transmits).
    namespace gen = optics::generic;
    if (t.transmits() && !(rng.uniform() < t.R))
        return Scatter{gen::refracted_direction(ray.dir, h.normal, t.cos_i, *t.cos_t, eta), m.filter};
    return Scatter{gen::reflect(ray.dir, h.normal), Vec3(1, 1, 1)};
}

std::optional<Scatter> sample_branch(const Material& m, const Interaction& in, Rng& rng) {
    if (in.branches == 0) return std::nullopt;
    if (const auto* d = m.dielectric()) {
        const bool refl = in.branches == 1 || rng.uniform() < in.reflectance;
        if (!refl) return Scatter{in.branch[1].ray.dir, d->filter};
        return Scatter{in.branch[0].ray.dir, Vec3(1, 1, 1)};
    }
    return Scatter{in.branch[0].ray.dir, in.branch[0].factor};
}

}  // namespace refract

namespace refract {

Interaction interact(const material::Uniaxial& m, const SurfaceHit& h, const Ray& ray, const InteractionContext& c) {
    const biref::Medium air{1.0, 1.0, Vec3::Zero()};
    const biref::Medium crystal{m.n_o(c.wavelength_nm), m.n_e(c.wavelength_nm), m.optic_axis};
    const biref::Medium& from = h.entering ? air : crystal;
    const biref::Medium& to = h.entering ? crystal : air;
    // A ray inside the crystal travels as o or e (a ray not known as either, as o).
    const biref::Wave w_in = h.entering ? biref::Wave::Isotropic
                                        : (c.wave == biref::Wave::Isotropic ? biref::Wave::Ordinary : c.wave);
    const biref::InterfaceSplit split = biref::split_at_interface(from, w_in, to, ray.dir, h.normal);
    Interaction n;
    for (int i = 0; i < split.count; ++i) {
        const biref::Beam& b = split.beam[static_cast<size_t>(i)];
        if (b.power <= 0) continue;
        const Vec3 colour = b.transmitted ? m.filter : Vec3(1, 1, 1);
        const size_t k = static_cast<size_t>(n.branches++);
        Branch& br = n.branch[k];
        br.ray = Ray{h.hit.point, b.dir};
        br.wave = b.wave;
        // The threshold keeps natural light's weights in both models (as the dielectric).
        br.bailout_factor = b.power * colour.maxCoeff();
        br.factor = c.exact ? colour : Vec3(b.power * colour);
        n.transmitted[k] = b.transmitted;
        if (!b.transmitted) n.reflectance += b.power;
        if (!c.exact) continue;
        // An eye pass needs light arriving along the child's ray (reversed) and leaving along
        // the parent's: by reciprocity the Jones matrix biref::reversed(J), same frames.
        n.mueller[k] = polar::jones_to_mueller(c.adjoint ? biref::reversed(b.J) : b.J);
        br.frame_parent = split.x_in;
        br.frame_child = b.x;
    }
    return n;
}

}  // namespace refract
