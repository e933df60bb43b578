#include <refract/validation/pov_export.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include <Eigen/Dense>

#include <refract/core/environment_map.h>
#include <refract/core/image.h>
#include <refract/geometry/error.h>
#include <refract/validation/files.h>
#include <refract/validation/pov_nesting.h>

namespace refract::validation {

std::string pov_number(double v) {
    if (!std::isfinite(v)) throw InputError("POV-Ray export: non-finite number " + std::to_string(v));
    if (v == 0) return "0";  // also -0
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
    return std::string(buf, r.ptr);
}

namespace {

// ---- formatting -----------------------------------------------------------------

std::string vec(const Vec3& v) {
    return "<" + pov_number(v.x()) + ", " + pov_number(v.y()) + ", " + pov_number(v.z()) + ">";
}

// Object and material names go into comments only; keep them on one printable line.
std::string comment_text(const std::string& s) {
    std::string out;
    for (unsigned char c : s) out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
    return out;
}

// ---- refusals ---------------------------------------------------------------------

class Refuser {
public:
    explicit Refuser(const Scene& s) : file_(s.source.empty() ? std::string("scene") : s.source) {}
    [[noreturn]] void operator()(const std::string& where, const std::string& what) const {
        throw InputError(file_ + ": " + where + ": " + what + "; POV-Ray 3.7 cannot express this exactly, export refused");
    }

private:
    std::string file_;
};

std::string material_where(const Material& m) { return "material '" + comment_text(m.name) + "'"; }
std::string object_where(const Object& o) { return "object '" + comment_text(o.name) + "'"; }

void check_settings(const Scene& s, const Refuser& refuse, bool photons) {
    const RenderSettings& r = s.settings;
    if (r.integrator == IntegratorKind::Stochastic)
        refuse("/render/integrator", "the stochastic integrator (RTIOW path sampling) has no POV-Ray equivalent");
    // A thin lens is POV-Ray's focal blur, which jitters within the pixel too.
    if (r.samples > 1 && r.jitter && !s.camera.thin_lens())
        refuse("/render/jitter", "jittered supersampling (" + std::to_string(r.samples) +
                                     " samples) differs from POV-Ray's antialiasing");
    if (r.light_pass.enabled && !photons)
        refuse("/render/light_pass", "the light pass (illumination maps) has no exact POV-Ray counterpart (photons are statistical)");
    // The paper's separate limits (only when the scene sets them): POV-Ray has
    // max_trace_level alone, so a limit below max_depth cannot be expressed.
    for (const auto& [field, limit] : {std::pair{"max_reflections", r.spectral.max_reflections},
                                       std::pair{"max_transmissions", r.spectral.max_transmissions}})
        if (r.spectral.enabled && limit && *limit < r.max_depth)
            refuse(std::string("/render/spectral/") + field,
                   std::string(field) + " " + std::to_string(*limit) + " below max_depth " + std::to_string(r.max_depth) +
                       " (the 1998 paper's separate limit; POV-Ray has max_trace_level only)");
    for (size_t k = 0; k < s.lights.size(); ++k)
        if (s.lights[k].kind == Light::Kind::Beam)
            refuse("/lights/" + std::to_string(k), "a collimated beam (a parallel light bounded by a cylinder) has no POV-Ray counterpart");
    if (r.max_depth + 1 > 256)
        refuse("/render/max_depth", "max_depth " + std::to_string(r.max_depth) +
                                        " needs max_trace_level " + std::to_string(r.max_depth + 1) + " > 256");
}

// What POV-Ray cannot express, per material kind.
void check(const material::Diffuse&, const Material&, const Refuser&) {}
void check(const material::Mirror&, const Material&, const Refuser&) {}
void check(const material::Emissive&, const Material&, const Refuser&) {}
void check(const material::Lambertian&, const Material& m, const Refuser& refuse) {
    refuse(material_where(m), "a lambertian material scatters randomly (path tracing)");
}
void check(const material::Metal& k, const Material& m, const Refuser& refuse) {
    if (k.fuzz != 0) refuse(material_where(m), "metal with fuzz " + pov_number(k.fuzz) + " scatters randomly (path tracing)");
}
void check(const material::Uniaxial&, const Material& m, const Refuser& refuse) {
    refuse(material_where(m), "a uniaxial crystal (POV-Ray has no double refraction)");
}
void check(const material::Grin&, const Material& m, const Refuser& refuse) {
    refuse(material_where(m), "a gradient-index medium (POV-Ray has no curved rays; a stack of constant-index layers "
                              "stands in for one)");
}
void check(const material::Dielectric& k, const Material& m, const Refuser& refuse) {
    if (k.dispersion && k.dispersion->dispersive() && !k.dispersion->is_povray())
        refuse(material_where(m), "dispersion '" + comment_text(k.dispersion->label) +
                                      "' (POV-Ray's law is n·D^((555 − λ)/350): only the \"povray\" model exports)");
    if (k.reflectance == ReflectanceModel::Schlick)
        refuse(material_where(m), "reflectance 'schlick' (POV-Ray has exact unpolarised Fresnel only)");
    if (k.reflectance == ReflectanceModel::FresnelS || k.reflectance == ReflectanceModel::FresnelP)
        refuse(material_where(m), "a polarised reflectance (POV-Ray has unpolarised Fresnel only)");
    // POV-Ray stores the index in single precision and passes an interface of
    // index 1.0f straight on without counting a trace level (trace.cpp, continuedRay).
    if (static_cast<float>(k.ior) == 1.0f)
        refuse(material_where(m), "ior 1 in single precision (POV-Ray passes such an interface without counting a trace level)");
    for (int c = 0; c < 3; ++c)
        if (k.filter[c] < 0) refuse(material_where(m), "a negative filter component");
}
void check_material(const Material& m, const Refuser& refuse) {
    std::visit([&](const auto& kind) { check(kind, m, refuse); }, m.kind);
}

// ---- geometry checks for transparent objects -----------------------------------------

// POV-Ray decides whether a refracted ray enters or leaves by the list of objects the ray
// is inside; refract by the side of the surface normal it hits. They agree when the
// transparent solids are disjoint (the camera may be inside one), and the only
// nesting is RTIOW's hollow sphere (a negative-radius sphere inside a sphere of the same
// material), which is exported as one intersection sharing one interior, and spheres
// strictly nested with a constant reflectivity (validation/pov_nesting.h).

struct Box {
    Vec3 lo, hi;
};

bool overlap(const Box& a, const Box& b) {
    for (int k = 0; k < 3; ++k)
        if (a.hi[k] <= b.lo[k] || b.hi[k] <= a.lo[k]) return false;
    return true;
}

std::optional<Box> object_box(const Shape& shape) {
    const auto b = bounds(shape);  // geometry/shapes.h: none for planes and unbounded polyhedra
    if (!b) return std::nullopt;
    return Box{b->lo, b->hi};
}

// Closed and consistently wound counter-clockwise seen from outside: every directed edge
// once, its reverse once, and a positive volume. refract decides entering by the
// triangle's normal, POV-Ray by the ray's list of interiors; they agree only then.
bool mesh_is_closed_outward(const TriangleMesh& m) {
    std::map<std::pair<int, int>, int> edges;
    double volume6 = 0;
    for (const auto& t : m.triangles) {
        for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
        volume6 += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
    }
    for (const auto& [edge, count] : edges) {
        const auto rev = edges.find({edge.second, edge.first});
        if (count != 1 || rev == edges.end() || rev->second != 1) return false;
    }
    return volume6 > 0;
}

// POV-Ray 3.7's inside test of an exported opaque object (Inside_BBox and Object::Inside):
// strictly inside a sphere, on the negative side of a plane, inside every plane of an
// intersection; never inside a mesh2 without inside_vector (opaque meshes have none).
bool pov_inside(const Sphere& s, const Vec3& p) { return (p - s.center).squaredNorm() < s.radius * s.radius; }
bool pov_inside(const Plane& pl, const Vec3& p) { return pl.normal.dot(p) - pl.offset < 0; }
bool pov_inside(const TriangleMesh&, const Vec3&) { return false; }
bool pov_inside(const ConvexPolyhedron& c, const Vec3& p) {
    for (const Plane& q : c.planes)
        if (!(q.normal.dot(p) - q.offset < 0)) return false;
    return true;
}
bool pov_inside(const Shape& shape, const Vec3& p) {
    return std::visit([&](const auto& s) { return pov_inside(s, p); }, shape);
}

// Where the camera's rays start relative to an opaque object, by POV-Ray's inside test:
// perspective rays start at the location; orthographic ones on the image rectangle, which
// may lie wholly inside, wholly outside or across the surface (spheres exactly, planes by
// the corners, polyhedra by boxes: "across" when unsure).
enum class Containment { Outside, Inside, Across };

Containment camera_containment(const Shape& shape, const Camera& cam) {
    if (cam.type == Camera::Type::Perspective)
        return pov_inside(shape, cam.location) ? Containment::Inside : Containment::Outside;
    if (std::holds_alternative<TriangleMesh>(shape)) return Containment::Outside;
    const Camera::Basis b = cam.basis();
    const Vec3 corner = cam.location - 0.5 * b.R - 0.5 * b.U;
    const Vec3 corners[4] = {corner, corner + b.R, corner + b.U, corner + b.R + b.U};
    int inside = 0;
    for (const Vec3& c : corners) inside += pov_inside(shape, c);
    if (inside == 4) return Containment::Inside;  // convex solids: the rectangle too
    if (inside > 0) return Containment::Across;
    if (std::holds_alternative<Plane>(shape)) return Containment::Outside;
    if (const auto* s = std::get_if<Sphere>(&shape)) {
        const Vec3 q = s->center - corner;
        const double u = std::clamp(q.dot(b.R) / b.R.squaredNorm(), 0.0, 1.0);
        const double v = std::clamp(q.dot(b.U) / b.U.squaredNorm(), 0.0, 1.0);
        return (corner + u * b.R + v * b.U - s->center).norm() < std::abs(s->radius) ? Containment::Across
                                                                                      : Containment::Outside;
    }
    const auto box = object_box(shape);
    if (!box) return Containment::Across;
    Box rect{corner, corner};
    for (const Vec3& p : corners) {
        rect.lo = rect.lo.cwiseMin(p);
        rect.hi = rect.hi.cwiseMax(p);
    }
    for (int k = 0; k < 3; ++k) {  // a flat rectangle has zero thickness along one axis
        rect.lo[k] -= 1e-9;
        rect.hi[k] += 1e-9;
    }
    return overlap(rect, *box) ? Containment::Across : Containment::Outside;
}

bool same_dispersion(const material::Dielectric& a, const material::Dielectric& b) {
    if (a.dispersion.has_value() != b.dispersion.has_value()) return false;
    if (!a.dispersion) return true;
    for (double l : {400.0, 550.0, 700.0})
        if (a.dispersion->n(l) != b.dispersion->n(l)) return false;
    return a.dispersion->label == b.dispersion->label;
}

bool same_optics(const material::Dielectric& a, const material::Dielectric& b) {
    return a.ior == b.ior && a.filter == b.filter && a.reflectance == b.reflectance &&
           a.constant_reflectivity == b.constant_reflectivity && same_dispersion(a, b) &&
           a.absorption.has_value() == b.absorption.has_value() && (!a.absorption || a.absorption->rgb == b.absorption->rgb);
}

// Groups of transparent objects exported as one POV-Ray object each (one interior):
// a solid alone, or a sphere with the negative-radius spheres hollowing it.
// A transparent sphere strictly inside another is a nest (validation/pov_nesting.h):
// `nest` gets POV-Ray's absolute indices.
std::vector<std::vector<size_t>> dielectric_groups(const Scene& s, const Refuser& refuse, SphereNesting& nest) {
    std::vector<size_t> solids, holes;
    for (size_t k = 0; k < s.objects.size(); ++k) {
        const Object& o = s.objects[k];
        if (!s.materials[o.material].is<material::Dielectric>()) continue;
        const auto* sp = std::get_if<Sphere>(&o.shape);
        (sp && sp->radius < 0 ? holes : solids).push_back(k);
        if (const auto* m = std::get_if<TriangleMesh>(&o.shape))
            if (!mesh_is_closed_outward(*m))
                refuse(object_where(o), "a transparent mesh must be closed and wound counter-clockwise seen from "
                                        "outside (every edge in two triangles, in opposite directions)");
    }
    // Solids pairwise disjoint.
    for (size_t a = 0; a < solids.size(); ++a)
        for (size_t b = a + 1; b < solids.size(); ++b) {
            const Object& A = s.objects[solids[a]];
            const Object& B = s.objects[solids[b]];
            const auto* sa = std::get_if<Sphere>(&A.shape);
            const auto* sb = std::get_if<Sphere>(&B.shape);
            bool hit;
            if (sa && sb && (sphere_strictly_inside(*sa, *sb) || sphere_strictly_inside(*sb, *sa))) {
                for (const Object* o : {&A, &B})
                    if (const std::string why = nesting_refusal(s.materials[o->material]); !why.empty())
                        refuse(object_where(A) + " and " + object_where(B), why);
                continue;
            } else if (sa && sb) {
                hit = (sa->center - sb->center).norm() < sa->radius + sb->radius;
            } else {
                const auto ba = object_box(A.shape), bb = object_box(B.shape);
                hit = !ba || !bb || overlap(*ba, *bb);
            }
            if (hit)
                refuse(object_where(A) + " and " + object_where(B),
                       "transparent objects that overlap (or unbounded ones together)");
        }
    nest = sphere_nesting(s, solids);
    if (nest.any && !holes.empty())
        refuse(object_where(s.objects[holes[0]]), "a hollow sphere in a scene with nested transparent spheres");
    if (nest.any)
        for (size_t k : solids)
            if (nest.container[k] >= 0 && camera_containment(s.objects[nest.container[k]].shape, s.camera) != Containment::Outside)
                refuse(object_where(s.objects[nest.container[k]]), "the camera inside a sphere with transparent spheres nested in it");
    std::vector<std::vector<size_t>> groups;
    for (size_t k : solids) groups.push_back({k});
    // Each hole strictly inside one sphere of the same material, holes disjoint.
    for (size_t h : holes) {
        const Object& H = s.objects[h];
        const Sphere& hs = std::get<Sphere>(H.shape);
        bool placed = false;
        for (auto& g : groups) {
            const Object& O = s.objects[g[0]];
            const auto* os = std::get_if<Sphere>(&O.shape);
            if (!os || !same_optics(*s.materials[O.material].dielectric(), *s.materials[H.material].dielectric())) continue;
            if ((hs.center - os->center).norm() - hs.radius >= os->radius) continue;  // hs.radius < 0
            for (size_t other = 1; other < g.size(); ++other) {
                const Sphere& q = std::get<Sphere>(s.objects[g[other]].shape);
                if ((q.center - hs.center).norm() < -q.radius - hs.radius)
                    refuse(object_where(H), "hollow spheres inside one sphere must not overlap");
            }
            g.push_back(h);
            placed = true;
            break;
        }
        if (!placed)
            refuse(object_where(H), "a transparent negative-radius sphere must lie inside a sphere of the same material "
                                    "(RTIOW's hollow sphere)");
    }
    return groups;
}

// ---- statements -------------------------------------------------------------------

// The texture of each material kind (the Lambertian is refused earlier).
std::string texture_of(const material::Diffuse& m) {
    std::ostringstream t;
    if (m.pigment.checker)
        t << "pigment { checker rgb " << vec(m.pigment.color) << " rgb " << vec(m.pigment.checker->color2) << " scale "
          << pov_number(m.pigment.checker->size) << " } ";
    else
        t << "pigment { rgb " << vec(m.pigment.color) << " } ";
    t << "finish { ambient " << pov_number(m.ambient) << " emission 0 diffuse " << pov_number(m.diffuse) << " }";
    return t.str();
}
std::string texture_of(const material::Lambertian&) { return ""; }
std::string mirror_texture(const Vec3& color) {
    return "pigment { rgb 0 } finish { ambient 0 emission 0 diffuse 0 reflection { rgb " + vec(color) + " } }";
}
std::string texture_of(const material::Mirror& m) { return mirror_texture(m.color); }
std::string texture_of(const material::Metal& m) { return mirror_texture(m.color); }  // fuzz 0: a tinted mirror
std::string texture_of(const material::Emissive& m) {
    return "pigment { rgb " + vec(m.color) + " } finish { ambient 0 emission 1 diffuse 0 }";
}
std::string texture_of(const material::Uniaxial&) { return ""; }  // refused by check()
std::string texture_of(const material::Grin&) { return ""; }      // refused by check()
std::string texture_of(const material::Dielectric& m) {
    // rgbf <filter, 1>: transmitted light × filter, no surface colour of its own.
    // conserve_energy: the transmitted part is also × (1 − reflectivity).
    std::ostringstream t;
    t << "pigment { rgbf <" << pov_number(m.filter.x()) << ", " << pov_number(m.filter.y()) << ", "
      << pov_number(m.filter.z()) << ", 1> } finish { ambient 0 emission 0 diffuse 0 reflection { ";
    if (m.reflectance == ReflectanceModel::Constant)
        t << pov_number(m.constant_reflectivity);  // Whitted: ks constant, kt = 1 − ks
    else
        t << "0, 1 fresnel on";  // exact unpolarised Fresnel
    t << " } conserve_energy }";
    return t.str();
}

std::string texture(const Material& m) {
    return "texture { " + std::visit([](const auto& kind) { return texture_of(kind); }, m.kind) + " }";
}

// `ior`: the material's, or POV-Ray's absolute index of a nested sphere.
std::string interior(const material::Dielectric& m, double ior) {
    std::string s = "interior { ior " + pov_number(ior);
    if (m.dispersion && m.dispersion->is_povray() && m.dispersion->dispersive()) {
        const auto& p = std::get<spectrum::PovRayModel>(m.dispersion->model);
        s += " dispersion " + pov_number(p.dispersion) + " dispersion_samples " + std::to_string(p.samples);
    }
    // Absorption: the exponential fade (fade_power >= 1000), exp(−(1 − C)·d/D) per
    // channel, with D = 1 and C = 1 − α (core/interaction.h pov_fade). POV-Ray fades only
    // the segments that end in a transmission, which compat mode reproduces.
    if (m.absorption) {
        const Vec3& a = m.absorption->rgb;
        s += " fade_distance 1 fade_power 1001 fade_color rgb <" + pov_number(1.0 - a.x()) + ", " +
             pov_number(1.0 - a.y()) + ", " + pov_number(1.0 - a.z()) + ">";
    }
    return s + " }";
}

// `solid`: a transparent object, whose mesh gets an inside_vector so that POV-Ray's
// inside test (a camera inside it) sees the solid (mesh.cpp: no vector, never inside).
std::string pov_shape(const Sphere& s, bool) {
    return "sphere { " + vec(s.center) + ", " + pov_number(std::abs(s.radius)) + (s.radius < 0 ? " inverse" : "");
}
std::string pov_shape(const Plane& p, bool) { return "plane { " + vec(p.normal) + ", " + pov_number(p.offset); }
std::string pov_shape(const TriangleMesh& m, bool solid) {
    std::ostringstream o;
    o << "mesh2 {\n    vertex_vectors { " << m.vertices.size();
    for (const Vec3& v : m.vertices) o << ",\n      " << vec(v);
    o << " }\n    face_indices { " << m.triangles.size();
    for (const auto& t : m.triangles) o << ",\n      <" << t[0] << ", " << t[1] << ", " << t[2] << ">";
    o << " }\n   ";
    if (solid) o << " inside_vector <0.5773, 0.5774, 0.5775>\n   ";
    return o.str();
}
std::string pov_shape(const ConvexPolyhedron& c, bool) {
    std::ostringstream o;
    o << "intersection {";
    for (size_t k = 0; k < c.planes.size(); ++k) {
        o << "\n    plane { " << vec(c.planes[k].normal) << ", " << pov_number(c.planes[k].offset) << " }";
        if (k < c.labels.size() && !c.labels[k].empty()) o << "  // " << comment_text(c.labels[k]);
    }
    o << "\n   ";
    return o.str();
}
// Open: the caller appends texture, interior and the closing brace.
std::string shape(const Shape& sh, bool solid = false) {
    return std::visit([&](const auto& s) { return pov_shape(s, solid); }, sh);
}

// POV-Ray's `matrix <…>` of x ↦ A x + t: POV-Ray multiplies row vectors, so its rows are
// A's columns, then t.
std::string pov_matrix(const Transform& T) {
    std::string s = "matrix <";
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j)
            s += (i || j ? ", " : "") + pov_number(i < 3 ? T.linear(j, i) : T.translation[j]);
    return s + ">";
}

// An object as POV-Ray takes it: the shape in the scene's coordinates, or, when the object
// has a transform, its shape before it and POV-Ray's matrix (POV-Ray applies the transform).
// `opaque`: a hollow sphere's inverse dropped (the normal side is moot).
std::string object_shape(const Object& obj, bool solid, bool opaque = false) {
    Shape sh = obj.placement ? *obj.placement->local : obj.shape;
    if (auto* sp = std::get_if<Sphere>(&sh); sp && opaque) sp->radius = std::abs(sp->radius);
    if (!obj.placement) return shape(sh, solid);
    return shape(sh, solid) + " " + pov_matrix(obj.placement->transform) + "\n   ";
}

std::string camera(const Camera& c, int samples) {
    std::ostringstream o;
    if (c.type == Camera::Type::Perspective) {
        o << "camera {\n  perspective\n  location " << vec(c.location) << "\n  sky " << vec(c.sky)
          << "\n  up y\n  right x*" << c.width << "/" << c.height << "\n  angle " << pov_number(c.angle_deg);
        if (c.thin_lens()) {
            // The thin lens as POV-Ray's focal blur (tracepixel.cpp, JitterCameraRay): it
            // moves the eye by aperture/2 times a point of a disk of radius 1/2, so its
            // aperture is twice the lens diameter; the plane in focus is the one normal to
            // the view through focal_point (placed on the view axis); every pixel takes
            // `samples` lens samples (blur_samples min = max: no early stop).
            const Vec3 focus = c.location + (c.look_at - c.location).normalized() * c.focus_distance;
            o << "\n  aperture " << pov_number(2.0 * c.aperture) << "\n  focal_point " << vec(focus)
              << "\n  blur_samples " << samples << ", " << samples;
        }
    } else {
        const double aspect = static_cast<double>(c.width) / c.height;
        o << "camera {\n  orthographic\n  location " << vec(c.location) << "\n  sky " << vec(c.sky) << "\n  up y*"
          << pov_number(c.ortho_height) << "\n  right x*" << pov_number(c.ortho_height * aspect);
    }
    o << "\n  look_at " << vec(c.look_at) << "\n}\n";
    return o.str();
}

// Whether v is a half-precision float exactly (POV-Ray reads OpenEXR files through
// OpenEXR's RgbaInputFile, in half precision: base/image/openexr.cpp).
bool exact_in_half(double v) {
    if (v == 0) return true;
    if (!(std::abs(v) <= 65504.0)) return false;  // the largest half
    int e = 0;
    std::frexp(v, &e);  // |v| = m·2^e, m ∈ [0.5, 1)
    const int step = std::max(e - 1, -14) - 10;  // log2 of the spacing of halves at v (subnormals below 2^−14)
    const double k = std::ldexp(v, -step);
    return k == std::floor(k);
}

void check_environment_map(const EnvironmentMap& m, const Refuser& refuse) {
    for (int j = 0; j < m.height; ++j)
        for (int i = 0; i < m.width; ++i)
            for (int c = 0; c < 3; ++c)
                if (!exact_in_half(m.pixel(i, j)[c]))
                    refuse("/background/map", "pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") of '" +
                                                  comment_text(m.path) + "' holds " + pov_number(m.pixel(i, j)[c]) +
                                                  ", not a half-precision value (POV-Ray reads OpenEXR maps in half precision)");
}

// An environment light: a constant one is POV-Ray's background colour; a map a
// sky_sphere with the map as a spherical image map (imageutil.cpp spherical_image_map,
// bilinear `interpolate 2`), the scale as its emission, the rotation as `rotate y*deg`
// (POV-Ray looks the sky up at the inverse transform of the ray direction, as
// Background::radiance does).
std::string environment(const Background& b, const std::string& map_file) {
    if (!b.map) return "background { rgb " + vec(b.scale * b.color) + " }\n";
    std::string o = "sky_sphere {\n  pigment { image_map { exr \"" + map_file + "\" map_type 1 interpolate 2 } }\n";
    if (b.scale != 1) o += "  emission rgb " + vec(Vec3::Constant(b.scale)) + "\n";
    if (b.rotation_deg != 0) o += "  rotate y*" + pov_number(b.rotation_deg) + "\n";
    return o + "}\n";
}

std::string background(const Background& b, const std::string& map_file) {
    if (b.kind == Background::Kind::Solid) return "background { rgb " + vec(b.color) + " }\n";
    if (b.kind == Background::Kind::Environment) return environment(b, map_file);
    // RTIOW sky: lerp(bottom, top, (dir.y + 1)/2). The gradient is evaluated on the unit
    // ray direction; scale 2 and translate −y map dir.y ∈ [−1, 1] onto [0, 1].
    return "sky_sphere {\n  pigment { gradient y color_map { [0 rgb " + vec(b.bottom) + "] [1 rgb " + vec(b.top) +
           "] } scale 2 translate -y }\n}\n";
}

}  // namespace

namespace {

bool has_area_light(const Scene& s) {
    for (const Light& l : s.lights)
        if (l.kind == Light::Kind::Rectangle || l.kind == Light::Kind::Disk) return true;
    return false;
}

}  // namespace

std::string export_pov(const Scene& s) { return export_pov(s, ExportOptions{}); }

std::string export_pov(const Scene& s, const ExportOptions& opt) {
    const Refuser refuse(s);
    check_settings(s, refuse, opt.photons);
    for (const Material& m : s.materials) check_material(m, refuse);
    if (has_environment_map(s)) check_environment_map(*s.background.map, refuse);
    SphereNesting nest;
    const auto groups = dielectric_groups(s, refuse, nest);

    std::ostringstream o;
    o << "#version 3.7;\n"
      << "// Exported by refract from " << comment_text(s.source.empty() ? "a scene" : s.source)
      << "; renders what refract renders with \"compat\": \"povray\".\n";
    o << "global_settings {\n  assumed_gamma 1.0\n  max_trace_level " << s.settings.max_depth + 1
      << "\n  adc_bailout " << pov_number(s.settings.pruning_threshold());
    if (opt.photons) {
        const std::uint64_t n = opt.photon_count ? opt.photon_count : s.settings.light_pass.photons;
        o << "\n  photons { count " << n << " }";
    }
    o << "\n}\n";
    o << camera(s.camera, s.settings.samples);
    o << background(s.background, opt.environment_map);
    // POV-Ray's shadow cache (the last opaque object that blocked a light is tested first,
    // without the shadow ray's 1e-3 tolerances; docs/validation.md D7) acts between the
    // grid points of an area light at one surface point: a grazing ray to one point is then
    // shadowed by the object that blocked the point before, in the order POV-Ray tests them.
    // Lights in a light_group use no cache, so with an area light the lights and the objects
    // are written as one light_group.
    const bool light_group = has_area_light(s) && !opt.photons;
    if (light_group) o << "light_group {\n";
    for (const Light& l : s.lights) {
        switch (l.kind) {
            case Light::Kind::Directional: {
                // POV-Ray's parallel light: shadow rays along −direction to the plane through
                // the location (trace.cpp ComputeOneWhiteLightRay), as refract's directional light
                // (whose eye passes see a sun of any angular size as its centre direction).
                const Vec3 at = l.directional_position();
                o << "light_source { " << vec(at) << " color rgb " << vec(l.color) << " parallel point_at "
                  << vec(at + l.direction) << " }\n";
                break;
            }
            case Light::Kind::Rectangle:
            case Light::Kind::Disk:
                // The grid without jitter; area_illumination lights from each grid point (not
                // the centre). POV-Ray's shadow is still its adaptive corner average
                // (docs/validation.md): the two agree exactly for a 2 × 2 grid.
                o << "light_source { " << vec(l.position) << " color rgb " << vec(l.color) << " area_light "
                  << vec(l.axis1) << ", " << vec(l.axis2) << ", " << l.size[0] << ", " << l.size[1]
                  << (l.kind == Light::Kind::Disk ? " circular" : "") << " area_illumination on }\n";
                break;
            case Light::Kind::Point:
            case Light::Kind::Beam:  // refused above
                o << "light_source { " << vec(l.position) << " color rgb " << vec(l.color) << " }\n";
                break;
        }
    }

    bool fresnel_glass = false;  // the only rule a container changes is Fresnel at exits
    for (const Object& obj : s.objects) {
        const Material& m = s.materials[obj.material];
        fresnel_glass = fresnel_glass || (m.dielectric() && m.dielectric()->reflectance == ReflectanceModel::Fresnel);
    }
    std::set<size_t> grouped;
    for (const auto& g : groups) grouped.insert(g.begin(), g.end());
    for (size_t k = 0; k < s.objects.size(); ++k) {
        if (grouped.count(k)) continue;
        const Object& obj = s.objects[k];
        const Material& m = s.materials[obj.material];
        Shape sh = obj.shape;
        if (auto* sp = std::get_if<Sphere>(&sh)) sp->radius = std::abs(sp->radius);  // opaque: the normal side is moot
        // POV-Ray starts every camera ray inside the objects that contain the camera, and
        // then computes the Fresnel reflectance at every exit from glass with the relative
        // index 1 (trace.cpp ComputeRelativeIOR uses the index of the object being left).
        // An opaque object looks the same turned inside out, so the export inverts one that
        // contains the camera and POV-Ray's lists stay those of refract.
        const Containment c = camera_containment(sh, s.camera);
        if (c == Containment::Across && fresnel_glass)
            refuse(object_where(obj), "the orthographic image plane crosses the surface of an object (POV-Ray "
                                      "starts such rays inside it and drops Fresnel reflection at glass exits)");
        o << "// " << comment_text(obj.name) << " (" << comment_text(m.name) << ")\n";
        o << object_shape(obj, false, true) << (c == Containment::Inside ? " inverse" : "") << " " << texture(m);
        if (!casts_shadow(m)) o << " no_shadow";  // a highlight sphere, not an occluder
        o << " }\n";
    }
    const std::string target = opt.photons ? " photons { target refraction on reflection on }" : "";
    for (const auto& g : groups) {
        const Material& m = s.materials[s.objects[g[0]].material];
        o << "// " << comment_text(s.objects[g[0]].name) << " (" << comment_text(m.name) << ")";
        if (g.size() == 1) {
            o << "\n" << object_shape(s.objects[g[0]], true) << " " << texture(m) << " " << interior(*m.dielectric(), nest.absolute_ior[g[0]]) << target << " }\n";
            continue;
        }
        o << " hollowed by";
        for (size_t i = 1; i < g.size(); ++i) o << " " << comment_text(s.objects[g[i]].name);
        // One interior for all the surfaces of the hollow solid; an intersection, so that
        // POV-Ray's inside test (a camera in the shell or in a cavity) is the solid's.
        o << "\nintersection {\n";
        for (size_t i : g) o << "  " << object_shape(s.objects[i], false) << " }\n";
        o << "  " << texture(m) << "\n  " << interior(*m.dielectric(), m.dielectric()->ior) << target << "\n}\n";
    }
    if (light_group) o << "}\n";
    return o.str();
}

bool has_environment_map(const Scene& s) {
    return s.background.kind == Background::Kind::Environment && s.background.map != nullptr;
}

void write_environment_map(const Scene& s, const std::string& path) {
    if (!has_environment_map(s)) return;
    const EnvironmentMap& m = *s.background.map;
    std::error_code ec;
    if (std::filesystem::equivalent(path, m.path, ec))
        throw InputError(path + ": the exported map would overwrite the scene's own map; export elsewhere");
    Image img(m.width, m.height);
    img.rgb = m.rgb;
    write_image(path, img);  // float OpenEXR: POV-Ray reads back the same halves
}

void write_pov(const Scene& scene, const std::string& path) {
    // The map beside the .pov, named after it; only file-name-safe characters, so the
    // name needs no escaping in the SDL string.
    ExportOptions opt;
    opt.environment_map = std::filesystem::path(path).stem().string() + "-environment.exr";
    for (char& c : opt.environment_map)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
    const std::string sdl = export_pov(scene, opt);  // refuses before anything is written
    write_environment_map(scene, (std::filesystem::path(path).parent_path() / opt.environment_map).string());
    write_text_file(path, sdl);
}

}  // namespace refract::validation
