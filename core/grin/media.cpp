// The gradient-index media of a scene (core/grin/media.h).
#include <refract/core/grin/media.h>

#include <algorithm>
#include <cmath>

#include <refract/core/scene.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>

namespace refract::grin {

namespace {

// The region inside each shape, or an InputError naming `where` (exhaustive over the shapes).
Region region_of(const refract::Sphere& s, const std::string& where) {
    if (!(s.radius > 0))
        throw InputError(where + ": a hollow sphere (radius " + format_value(s.radius) +
                         ") has no inside for a gradient-index medium");
    return Sphere{s.center, s.radius};
}
Region region_of(const refract::Plane&, const std::string& where) {
    throw InputError(where + ": a plane has no inside for a gradient-index medium (use a sphere or a polyhedron)");
}
Region region_of(const refract::TriangleMesh&, const std::string& where) {
    throw InputError(where + ": a gradient-index medium fills a sphere or a convex polyhedron (a mesh is not supported)");
}
Region region_of(const refract::ConvexPolyhedron& c, const std::string& where) {
    Polyhedron q;
    for (const refract::Plane& p : c.planes) q.faces.push_back(HalfSpace{p.normal, p.offset});
    q.vertices = refract::vertices(c);
    if (q.vertices.size() < 4) throw InputError(where + ": an unbounded polyhedron has no inside for a gradient-index medium");
    return q;
}

std::string object_where(const Scene& scene, size_t k) {
    const std::string f = scene.source.empty() ? std::string("scene") : scene.source;
    return f + ": /objects/" + std::to_string(k);
}

// Whether a shape reaches into `r` beyond a margin (exhaustive over the shapes): a plane
// against the region's extent across it, the others by their bounds.
bool box_overlaps(const std::optional<Bounds>& b, const Region& r, double margin) {
    if (!b) return true;
    for (int i = 0; i < 3; ++i) {
        const auto [lo, hi] = extent(r, Vec3::Unit(i));
        if (b->hi[i] <= lo + margin || b->lo[i] >= hi - margin) return false;
    }
    return true;
}
bool overlaps(const refract::Plane& p, const Region& r, double margin) {
    const auto [lo, hi] = extent(r, p.normal);
    return p.offset > lo + margin && p.offset < hi - margin;
}
bool overlaps(const refract::Sphere& s, const Region& r, double margin) { return box_overlaps(bounds(s), r, margin); }
bool overlaps(const refract::TriangleMesh& m, const Region& r, double margin) {
    return box_overlaps(bounds(m), r, margin);
}
bool overlaps(const refract::ConvexPolyhedron& c, const Region& r, double margin) {
    return box_overlaps(bounds(c), r, margin);
}

}  // namespace

std::vector<Medium> media(const Scene& scene) {
    std::vector<Medium> out;
    const std::string f = scene.source.empty() ? std::string("scene") : scene.source;
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        const Object& o = scene.objects[k];
        const Material& m = scene.materials[static_cast<size_t>(o.material)];
        const auto* g = m.as<material::Grin>();
        if (!g) continue;
        const std::string where = object_where(scene, k);
        Medium md{static_cast<int>(k), std::visit([&](const auto& s) { return region_of(s, where); }, o.shape), g->profile,
                  g->settings, {}};
        validate(md.region, where);
        validate(md.profile, md.region, 0.36, 0.83, f + ": /materials/" + clip_echo(m.name) + "/profile");
        out.push_back(std::move(md));
    }
    for (Medium& md : out) {
        const double margin = 1e-9 * length_scale(md.region);
        for (size_t k = 0; k < scene.objects.size(); ++k) {
            if (static_cast<int>(k) == md.object ||
                !std::visit([&](const auto& sh) { return overlaps(sh, md.region, margin); }, scene.objects[k].shape))
                continue;
            const Material& m = scene.materials[static_cast<size_t>(scene.objects[k].material)];
            if (leaf_light(m).kind == LeafLight::Kind::None)
                throw InputError(object_where(scene, k) + ": reaches into the gradient-index medium of " +
                                 object_where(scene, static_cast<size_t>(md.object)).substr(f.size() + 2) +
                                 " (only lit or emitting surfaces, such as \"diffuse\" or \"emissive\", can be "
                                 "inside a medium; material '" + clip_echo(m.name) + "' is not one)");
            md.inside.push_back(static_cast<int>(k));
        }
    }
    return out;
}

const Medium* medium_of(const std::vector<Medium>& media, const Vec3& origin, const Vec3& dir, int from) {
    for (const Medium& m : media) {
        if (from >= 0) {
            if (m.object == from) return outward_normal(m.region, origin).dot(dir) < 0 ? &m : nullptr;
        } else if (signed_distance(m.region, origin) < 0) {
            return &m;
        }
    }
    return nullptr;
}

}  // namespace refract::grin
