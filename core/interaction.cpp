#include <refract/core/interaction.h>

#include <refract/core/material.h>

namespace refract {

Interaction mirror_interaction(const Vec3& color, const SurfaceHit& h, const Ray& ray, bool exact) {
    Interaction n;
    n.branch[0] = Branch{Ray{h.hit.point, optics::reflect(ray.dir, h.normal).normalized()}, color, color.maxCoeff()};
    n.branches = 1;
    n.reflectance = color.maxCoeff();
    // A perfect conductor: rs = −1, rp = +1 at every angle (the η → ∞ limit of Hecht's
    // amplitudes), so the Mueller matrix is diag(1, 1, −1, −1) in the s/p frames.
    if (exact) n.mueller[0] = polar::jones_diagonal_to_mueller(-1.0, 1.0);
    return n;
}

Interaction material::uniaxial_interaction(const Uniaxial& m, const SurfaceHit& h, const Ray& ray,
                                           const InteractionContext& c) {
    const biref::Medium air{1.0, 1.0, Vec3::Zero()};
    const biref::Medium crystal = m.medium(c.wavelength_nm);
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

namespace {

template <class... K>
Material::Kind read_kind(const std::variant<K...>*, const JsonReader& r, const std::string& type,
                         const std::string& file) {
    std::optional<Material::Kind> kind;
    (void)((type == K::kType && (kind = K::read(r, file), true)) || ...);
    if (!kind) {
        std::string names;
        ((names += (names.empty() ? "" : ", ") + std::string(K::kType)), ...);
        r.fail_at("type", "unknown material type '" + clip_echo(type) + "' (" + names + ")");
    }
    return *kind;
}

}  // namespace

Material::Kind read_material_kind(const JsonReader& r, const std::string& type, const std::string& file) {
    return read_kind(static_cast<const Material::Kind*>(nullptr), r, type, file);
}

}  // namespace refract
