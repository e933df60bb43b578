#include <refract/validation/pov_nesting.h>

#include <variant>

namespace refract::validation {

bool sphere_strictly_inside(const Sphere& inner, const Sphere& outer) {
    return inner.radius > 0 && outer.radius > 0 && (inner.center - outer.center).norm() + inner.radius < outer.radius;
}

std::string nesting_refusal(const Material& m) {
    const auto* d = m.dielectric();
    if (!d) return "only transparent spheres nest";
    if (d->reflectance != ReflectanceModel::Constant)
        return "nested transparent spheres need a constant reflectivity (POV-Ray 3.7 computes no Fresnel "
               "reflection where a ray leaves a sphere into the one around it)";
    if (d->dispersion) return "nested transparent spheres cannot disperse";
    if (d->absorption) return "nested transparent spheres cannot absorb";
    return "";
}

SphereNesting sphere_nesting(const Scene& s, const std::vector<size_t>& solids) {
    SphereNesting n;
    n.container.assign(s.objects.size(), -1);
    n.absolute_ior.assign(s.objects.size(), 0.0);
    for (size_t k : solids) {
        const auto* in = std::get_if<Sphere>(&s.objects[k].shape);
        if (!in) continue;
        double best = 0;
        for (size_t c : solids) {
            const auto* out = std::get_if<Sphere>(&s.objects[c].shape);
            if (c == k || !out || !sphere_strictly_inside(*in, *out)) continue;
            if (n.container[k] < 0 || out->radius < best) {
                n.container[k] = static_cast<int>(c);
                best = out->radius;
            }
        }
        n.any = n.any || n.container[k] >= 0;
    }
    for (size_t k : solids) {
        double ior = 1;
        for (int c = static_cast<int>(k); c >= 0; c = n.container[c])
            ior *= s.materials[s.objects[c].material].dielectric()->ior;
        n.absolute_ior[k] = ior;
    }
    return n;
}

}  // namespace refract::validation
