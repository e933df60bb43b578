#include <refract/core/scene_json.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <refract/core/environment_map.h>
#include <refract/core/area_light.h>
#include <refract/core/compat.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/json_reader.h>
#include <refract/core/mesh_file.h>
#include <refract/core/object_transform.h>
#include <refract/core/scene_gem.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/error.h>
#include <refract/geometry/input_file.h>

namespace refract {
namespace {

constexpr long long kMaxPixels = 1LL << 26;  // width × height (docs/scene-format.md)

using nlohmann::json;

// The thin lens (core/camera.h): `aperture` (diameter) > 0 with `focus_distance` > 0, on
// a perspective camera; focus_distance defaults to |look_at − location|.
void read_thin_lens(const JsonReader& r, Camera& c) {
    if (!r.has("aperture")) {
        if (r.has("focus_distance")) r.fail_at("focus_distance", "applies with an \"aperture\" only (a thin lens)");
        return;
    }
    if (c.type != Camera::Type::Perspective)
        r.fail_at("aperture", "applies to a perspective camera only (this one is orthographic)");
    c.aperture = r.number("aperture");
    if (!(c.aperture >= 0) || !(c.aperture < 1e150)) r.fail_at("aperture", "must be a lens diameter >= 0 (0: a pinhole)");
    c.focus_distance = r.number("focus_distance", (c.look_at - c.location).norm());
    if (!(c.focus_distance > 0) || !(c.focus_distance < 1e150)) r.fail_at("focus_distance", "must be > 0");
    if (c.aperture == 0) c.focus_distance = 0;
}

Camera parse_camera(const JsonReader& r) {
    r.only({"type", "location", "look_at", "sky", "angle", "vfov", "ortho_height", "width", "height", "aperture",
            "focus_distance"});
    Camera c;
    const std::string type = r.string("type", "perspective");
    if (type == "perspective") c.type = Camera::Type::Perspective;
    else if (type == "orthographic") c.type = Camera::Type::Orthographic;
    else r.fail_at("type", "unknown camera type '" + clip_echo(type) + "' (perspective, orthographic)");
    c.location = r.vec3("location", c.location);
    c.look_at = r.vec3("look_at", c.look_at);
    c.sky = r.vec3("sky", c.sky);
    c.width = r.integer("width", c.width, 1, 1 << 15);
    c.height = r.integer("height", c.height, 1, 1 << 15);
    if (static_cast<long long>(c.width) * c.height > kMaxPixels)
        r.fail_at("height", std::to_string(c.width) + " × " + std::to_string(c.height) +
                                " pixels exceed the limit of 2^26 (67 108 864) pixels");
    if ((c.look_at - c.location).norm() == 0) r.fail_at("look_at", "must differ from location");
    if (!std::isfinite((c.look_at - c.location).norm()) || !(c.location.norm() < 1e150) || !(c.look_at.norm() < 1e150))
        r.fail_at("location", "the camera's location and look_at must lie within 1e150 of the origin (rays would overflow)");
    // Rescaled (geometry/ray.h): a sky of 1e200 neither overflows nor turns into zero.
    if (rescaled(c.sky).cross(rescaled(c.look_at - c.location)).norm() == 0)
        r.fail_at("sky", "must not be parallel to the view direction");
    c.sky = rescaled(c.sky);
    // A field that does not apply to the camera's type is refused, not ignored.
    if (c.type == Camera::Type::Perspective && r.has("ortho_height"))
        r.fail_at("ortho_height", "applies to an orthographic camera only (this one is perspective)");
    if (c.type == Camera::Type::Orthographic)
        for (const char* k : {"angle", "vfov"})
            if (r.has(k)) r.fail_at(k, "applies to a perspective camera only (this one is orthographic: use ortho_height)");
    if (r.has("angle") && r.has("vfov")) r.fail_at("vfov", "give either angle (horizontal) or vfov (vertical)");
    if (r.has("vfov")) {
        // RTIOW's vertical field of view, converted to POV-Ray's horizontal angle.
        const double v = r.number("vfov");
        if (!(v > 0 && v < 180)) r.fail_at("vfov", "must be in (0, 180) degrees");
        const double aspect = static_cast<double>(c.width) / c.height;
        c.angle_deg = 2.0 * std::atan(std::tan(v * M_PI / 360.0) * aspect) * 180.0 / M_PI;
    } else {
        c.angle_deg = r.number("angle", c.angle_deg);
        if (!(c.angle_deg > 0 && c.angle_deg < 180)) r.fail_at("angle", "must be in (0, 180) degrees");
    }
    c.ortho_height = r.positive("ortho_height", c.ortho_height);
    read_thin_lens(r, c);
    return c;
}

// The map of an environment light, read once: the path is relative to the scene file's
// directory; any problem with the file names the field.
std::shared_ptr<const EnvironmentMap> read_environment_map(const JsonReader& r, const std::string& file) {
    const std::string name = r.string("map");
    if (name.empty()) r.fail_at("map", "must name an image file");
    const std::filesystem::path path = std::filesystem::path(file).parent_path() / name;
    try {
        return std::make_shared<const EnvironmentMap>(load_environment_map(path.lexically_normal().string()));
    } catch (const InputError& e) {
        r.fail_at("map", e.what());
    }
}

// An environment light: a constant `color` or a `map`, times `scale`, turned by `rotation_deg`.
Background parse_environment(const JsonReader& r, const std::string& file) {
    r.only({"type", "color", "map", "scale", "rotation_deg"});
    Background b;
    b.kind = Background::Kind::Environment;
    if (r.has("color") == r.has("map")) r.fail("an environment needs either \"color\" or \"map\"");
    if (r.has("color")) {
        b.color = r.colour("color", b.color);
    } else {
        b.map = read_environment_map(r, file);
    }
    b.scale = r.positive("scale", b.scale);
    if (!(b.scale <= kMaxColour)) r.fail_at("scale", "must be in (0, 1e30]");
    b.rotation_deg = r.number("rotation_deg", b.rotation_deg);
    return b;
}

Background parse_background(const json& v, const std::string& file) {
    Background b;
    if (v.is_array()) {
        b.color = JsonReader::colour_value(v, file, "/background");
        return b;
    }
    JsonReader r(v, file, "/background");
    const std::string type = r.string("type", "solid");
    if (type == "environment") return parse_environment(r, file);
    r.only({"type", "color", "top", "bottom"});
    if (type == "solid") {
        b.color = r.colour("color", b.color);
    } else if (type == "gradient") {
        b.kind = Background::Kind::Gradient;
        b.top = r.colour("top", b.top);
        b.bottom = r.colour("bottom", b.bottom);
    } else {
        r.fail_at("type", "unknown background type '" + clip_echo(type) + "' (solid, gradient, environment)");
    }
    return b;
}

Material parse_material(const JsonReader& r, const std::string& name, const std::string& file) {
    Material m;
    m.name = name;
    m.kind = read_material_kind(r, r.string("type"), file);
    return m;
}

int material_ref(const JsonReader& o, std::vector<Material>& materials, const std::map<std::string, int>& by_name,
                 const std::string& file) {
    const auto& v = o.raw("material");
    if (v.is_string()) {
        const auto it = by_name.find(v.get<std::string>());
        if (it == by_name.end()) o.fail_at("material", "unknown material '" + clip_echo(v.get<std::string>()) + "'");
        return it->second;
    }
    if (!v.is_object()) o.fail_at("material", "must be a material name or a material object");
    materials.push_back(parse_material(o.child("material"), o.path_of("material"), file));
    return static_cast<int>(materials.size()) - 1;
}

// A round-brilliant gem (geometry/gem/brilliant.h), built exactly, then placed
// (core/scene_gem.h): scaled to `diameter` (girdle diameter).
Shape parse_brilliant(const JsonReader& o) {
    o.only({"type", "name", "material", "preset", "table", "crown_angle", "pavilion_angle", "star", "lower_half",
            "girdle", "culet", "girdle_facets", "bruted_planes", "position", "diameter", "rotation", "transform"});
    BrilliantCut cut = brilliant_preset(o.string("preset", "gia-default"));
    cut.table = o.number("table", cut.table);
    cut.crown_angle = o.number("crown_angle", cut.crown_angle);
    cut.pavilion_angle = o.number("pavilion_angle", cut.pavilion_angle);
    cut.star = o.number("star", cut.star);
    cut.lower_half = o.number("lower_half", cut.lower_half);
    cut.girdle = o.number("girdle", cut.girdle);
    cut.culet = o.number("culet", cut.culet);
    cut.girdle_facets = o.integer("girdle_facets", cut.girdle_facets, 0, 1 << 16);
    cut.bruted_planes = o.integer("bruted_planes", cut.bruted_planes, 0, 1 << 16);
    Gem gem;
    try {
        gem = build_brilliant(cut);
    } catch (const InputError& e) {
        o.fail(e.what());
    }
    return place_gem(gem, o.positive("diameter", 2.0) / 2.0, o);
}

// A mesh file's path, relative to the scene file's directory.
std::string mesh_path(const JsonReader& o, const std::string& file) {
    const std::string name = o.string("file");
    if (name.empty()) o.fail_at("file", "must name a mesh file");
    return (std::filesystem::path(file).parent_path() / name).lexically_normal().string();
}

// The mesh of a mesh file, shared by every object that uses the same file and node.
std::shared_ptr<const Shape> mesh_file(const JsonReader& o, const std::string& file, MeshFileCache& meshes) {
    if (o.has("vertices") || o.has("triangles")) o.fail_at("file", "a mesh takes either a file or vertices and triangles");
    try {
        return meshes.get(mesh_path(o, file), o.string("node", ""));
    } catch (const MeshFileError& e) {
        o.fail_at(e.field, e.what());
    }
}

Shape parse_shape(const JsonReader& o, const std::string& type, const std::string& file, MeshFileCache& meshes) {
    if (type == "sphere") {
        o.only({"type", "name", "material", "center", "radius", "transform"});
        const double radius = o.number("radius");
        if (radius == 0) o.fail_at("radius", "must be non-zero (negative: hollow, normals flipped)");
        return Sphere{o.vec3("center"), radius};
    }
    if (type == "plane") {
        o.only({"type", "name", "material", "normal", "offset", "transform"});
        const auto n = unit_vector(o.vec3("normal"));
        if (!n) o.fail_at("normal", "must be non-zero");
        return Plane{*n, o.number("offset", 0.0)};
    }
    if (type == "mesh") {
        o.only({"type", "name", "material", "vertices", "triangles", "file", "node", "transform"});
        if (o.has("file")) return *mesh_file(o, file, meshes);
        if (o.has("node")) o.fail_at("node", "names a node of a mesh file: give the file too");
        TriangleMesh m;
        const auto& vs = o.raw("vertices");
        const auto& ts = o.raw("triangles");
        if (!vs.is_array() || vs.size() < 3) o.fail_at("vertices", "must be an array of at least 3 points");
        if (!ts.is_array() || ts.empty()) o.fail_at("triangles", "must be a non-empty array of index triples");
        for (size_t k = 0; k < vs.size(); ++k)
            m.vertices.push_back(JsonReader::vec3_value(vs[k], "", o.path_of("vertices") + "/" + std::to_string(k)));
        for (size_t k = 0; k < ts.size(); ++k) {
            const auto& t = ts[k];
            const std::string p = o.path_of("triangles") + "/" + std::to_string(k);
            if (!t.is_array() || t.size() != 3) o.fail("triangle " + p + " must be 3 vertex indices");
            Eigen::Vector3i tri;
            for (int c = 0; c < 3; ++c) {
                if (!t[c].is_number_integer() || t[c].get<long long>() < 0 ||
                    t[c].get<long long>() >= static_cast<long long>(vs.size()))
                    o.fail("triangle " + p + ": indices must be integers in [0, " + std::to_string(vs.size() - 1) + "]");
                tri[c] = t[c].get<int>();
            }
            if ((m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]).norm() == 0)
                o.fail("triangle " + p + " is degenerate (zero area)");
            m.triangles.push_back(tri);
        }
        return m;
    }
    if (type == "polyhedron") {
        o.only({"type", "name", "material", "planes", "labels", "transform"});
        ConvexPolyhedron c;
        const auto& ps = o.raw("planes");
        if (!ps.is_array() || ps.size() < 4) o.fail_at("planes", "must be an array of at least 4 [nx, ny, nz, d]");
        for (size_t k = 0; k < ps.size(); ++k) {
            const auto& p = ps[k];
            const std::string path = o.path_of("planes") + "/" + std::to_string(k);
            bool ok = p.is_array() && p.size() == 4;
            for (size_t q = 0; ok && q < 4; ++q) ok = p[q].is_number() && std::isfinite(p[q].get<double>());
            if (!ok) o.fail("plane " + path + " must be [nx, ny, nz, d] with finite numbers");
            const Vec3 n(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
            const auto unit = unit_vector(n);
            if (!unit) o.fail("plane " + path + " has a zero normal");
            const double offset = over_norm(p[3].get<double>(), n);
            if (!std::isfinite(offset)) o.fail("plane " + path + ": d/|n| overflows (a plane beyond any scene)");
            c.planes.push_back(Plane{*unit, offset});
        }
        if (o.has("labels")) {
            const auto& ls = o.raw("labels");
            if (!ls.is_array() || ls.size() != ps.size()) o.fail_at("labels", "must be an array of one string per plane");
            for (const auto& l : ls) c.labels.push_back(l.is_string() ? l.get<std::string>() : std::string());
        }
        return c;
    }
    if (type == "brilliant") return parse_brilliant(o);
    if (type == "gem") return parse_gem_design(o);
    o.fail_at("type", "unknown object type '" + clip_echo(type) + "' (sphere, plane, mesh, polyhedron, brilliant, gem)");
}

// A transparent mesh from a file must enclose a solid: the tracer decides entering and
// leaving by the triangles' outward normals.
void check_closed(const JsonReader& o, const std::string& file, MeshFileCache& meshes) {
    const std::string path = mesh_path(o, file);
    const std::string node = o.string("node", "");
    const MeshClosure& c = meshes.closure(path, node);
    if (!c.closed_outward())
        o.fail_at("file", path + (node.empty() ? "" : " (node '" + clip_echo(node) + "')") +
                              ": a transparent mesh must be closed and consistently oriented: " + c.describe());
}

// The object's "transform": its shape moved, the shape before it kept for the export.
// A mesh file's mesh is kept once, in the cache's copy, for all its instances.
void place(Object& obj, const JsonReader& o, std::shared_ptr<const Shape> local) {
    const Transform T = parse_transform(o.child("transform"));
    auto moved = transformed(obj.shape, T);
    if (!moved)
        o.fail_at("transform", "a sphere takes only rotation, translation and uniform scale (for a non-uniform scale "
                               "or a shear, use a mesh)");
    obj.placement = Object::Placement{T, local ? std::move(local) : std::make_shared<const Shape>(std::move(obj.shape))};
    obj.shape = std::move(*moved);
}

SpectralSettings parse_spectral(const JsonReader& r, const std::string& file) {
    r.only({"range", "step", "pipeline", "light", "shortcut", "shortcut_wavelengths", "shortcut_threshold",
            "max_reflections", "max_transmissions"});
    SpectralSettings s;
    s.enabled = true;
    if (r.has("range")) {
        const auto& v = r.raw("range");
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
            r.fail_at("range", "must be [min_nm, max_nm]");
        s.sampling.min_nm = v[0].get<double>();
        s.sampling.max_nm = v[1].get<double>();
    }
    s.sampling.step_nm = r.number("step", s.sampling.step_nm);
    spectrum::validate(s.sampling, file + ": " + r.path());
    if (r.has("pipeline")) s.pipeline = spectrum::parse_colour_pipeline(r.string("pipeline"), file + ": " + r.path_of("pipeline"));
    if (r.has("light")) {
        const auto& v = r.raw("light");
        if (v.is_string() && v.get<std::string>() == "equal") s.light = spectrum::LightSpectrum{};
        else if (v.is_string() && v.get<std::string>() == "d65") s.light = spectrum::LightSpectrum{spectrum::Illuminant::D65};
        else s.light = spectrum::parse_light_spectrum(v, file + ": " + r.path_of("light"));
    }
    s.shortcut = r.boolean("shortcut", s.shortcut);
    if (r.has("shortcut_wavelengths")) {
        const auto& v = r.raw("shortcut_wavelengths");
        if (!v.is_array() || v.size() != 3) r.fail_at("shortcut_wavelengths", "must be three wavelengths in nm");
        for (int k = 0; k < 3; ++k) {
            if (!v[k].is_number() || !(v[k].get<double>() >= spectrum::kMinWavelength) ||
                !(v[k].get<double>() <= spectrum::kMaxWavelength))
                r.fail_at("shortcut_wavelengths", "each must be a number in [360, 830] nm");
            s.shortcut_wavelengths[k] = v[k].get<double>();
        }
    }
    s.shortcut_threshold = r.number("shortcut_threshold", s.shortcut_threshold);
    if (s.shortcut_threshold < 0) r.fail_at("shortcut_threshold", "must be >= 0");
    if (r.has("max_reflections")) s.max_reflections = r.integer("max_reflections", 0, 0, 10000);
    if (r.has("max_transmissions")) s.max_transmissions = r.integer("max_transmissions", 0, 0, 10000);
    return s;
}

LightPassSettings parse_light_pass(const JsonReader& r) {
    r.only({"enabled", "photons", "element_size", "region", "seed", "filter"});
    LightPassSettings s;
    s.enabled = r.boolean("enabled", true);
    if (r.has("photons")) {
        const auto& v = r.raw("photons");
        if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > (1ll << 31))
            r.fail_at("photons", "must be an integer in [1, 2^31]");
        s.photons = static_cast<std::uint64_t>(v.get<long long>());
    }
    s.element_size = r.positive("element_size", s.element_size);
    s.region = r.positive("region", s.region);
    if (r.has("seed")) {
        const auto& v = r.raw("seed");
        if (!v.is_number_integer() || (!v.is_number_unsigned() && v.get<long long>() < 0))
            r.fail_at("seed", "must be a non-negative integer");
        s.seed = v.get<std::uint64_t>();
    }
    const std::string filter = r.string("filter", "bilinear");
    if (filter == "box") s.filter = MapFilter::Box;
    else if (filter == "bilinear") s.filter = MapFilter::Bilinear;
    else r.fail_at("filter", "unknown filter '" + clip_echo(filter) + "' (box, bilinear)");
    return s;
}

// {"type": "unpolarised" | "linear" | "circular", "angle": degrees, "reference": [x, y, z],
// "handedness": "left" | "right"} (docs/polarisation.md).
PolarisationState parse_polarisation_state(const JsonReader& r, bool reference) {
    if (reference) r.only({"type", "angle", "reference", "handedness"});
    else r.only({"type", "angle", "handedness"});
    PolarisationState p;
    const std::string type = r.string("type");
    if (type == "unpolarised") p.kind = PolarisationState::Kind::Unpolarised;
    else if (type == "linear") p.kind = PolarisationState::Kind::Linear;
    else if (type == "circular") p.kind = PolarisationState::Kind::Circular;
    else r.fail_at("type", "unknown polarisation '" + clip_echo(type) + "' (unpolarised, linear, circular)");
    if (p.kind != PolarisationState::Kind::Linear && r.has("angle")) r.fail_at("angle", "only for linear polarisation");
    if (p.kind != PolarisationState::Kind::Circular && r.has("handedness"))
        r.fail_at("handedness", "only for circular polarisation");
    p.angle_deg = r.number("angle", 0.0);
    if (!std::isfinite(p.angle_deg)) r.fail_at("angle", "must be a finite number of degrees");
    if (reference) {
        const auto unit = unit_vector(r.vec3("reference", p.reference));
        if (!unit) r.fail_at("reference", "must be a non-zero vector");
        p.reference = *unit;
    }
    const std::string hand = r.string("handedness", "left");
    if (hand == "left") p.handedness = 1;
    else if (hand == "right") p.handedness = -1;
    else r.fail_at("handedness", "must be \"left\" (S3 > 0) or \"right\" (S3 < 0), Born & Wolf's naming");
    return p;
}

void parse_polarisation(const JsonReader& r, RenderSettings& s) {
    std::string model;
    if (r.raw("polarisation").is_string()) {
        model = r.string("polarisation");
    } else {
        const JsonReader p = r.child("polarisation");
        p.only({"model", "analyser"});
        model = p.string("model", "exact");
        if (p.has("analyser")) s.analyser = parse_polarisation_state(p.child("analyser"), false);
    }
    if (model == "natural") s.requested_polarisation = PolarisationModel::Natural;
    else if (model == "exact") s.requested_polarisation = PolarisationModel::Exact;
    else r.fail_at("polarisation", "unknown model '" + clip_echo(model) + "' (natural, exact)");
    if (s.analyser && s.requested_polarisation != PolarisationModel::Exact)
        r.fail_at("polarisation", "an analyser needs the \"exact\" model");
}

RenderSettings parse_settings(const JsonReader& r, const std::string& file) {
    r.only({"integrator", "max_depth", "threshold", "samples", "jitter", "seed", "compat", "spectral", "light_pass",
            "polarisation"});
    RenderSettings s;
    const std::string integ = r.string("integrator", "fresnel-tree");
    if (const auto k = integrator_of(integ)) {
        s.integrator = *k;
    } else {
        std::string names;
        for (const std::string& n : integrator_names()) names += (names.empty() ? "" : ", ") + n;
        r.fail_at("integrator", "unknown integrator '" + clip_echo(integ) + "' (" + names + ")");
    }
    s.max_depth = r.integer("max_depth", s.max_depth, 0, 10000);
    s.threshold = r.number("threshold", s.threshold);
    if (s.threshold < 0 || s.threshold >= 1) r.fail_at("threshold", "must be in [0, 1)");
    s.samples = r.integer("samples", s.samples, 1, 1 << 20);
    s.jitter = r.boolean("jitter", s.jitter);
    if (r.has("seed")) {
        const auto& v = r.raw("seed");
        if (!v.is_number_unsigned()) r.fail_at("seed", "must be a non-negative integer");
        s.seed = v.get<std::uint64_t>();
    }
    const std::string compat = r.string("compat", CompatRules::name(Compat::Physical));
    if (const auto c = CompatRules::from_name(compat)) {
        s.compat = *c;
    } else {
        r.fail_at("compat", "unknown mode '" + clip_echo(compat) + "' (" + CompatRules::name(Compat::Physical) + ", " +
                                CompatRules::name(Compat::PovRay) + ")");
    }
    // `"spectral": false`: RGB rays only, even with dispersive or uniaxial materials (their
    // index at the sodium D line).
    if (r.has("spectral") && !(r.raw("spectral").is_boolean() && !r.raw("spectral").get<bool>()))
        s.spectral = parse_spectral(r.child("spectral"), file);
    if (r.has("light_pass")) s.light_pass = parse_light_pass(r.child("light_pass"));
    if (r.has("polarisation")) parse_polarisation(r, s);
    return s;
}

}  // namespace

// A light's own spectrum becomes the scene's (refract has one light spectrum per scene):
// lights giving different spectra, or one differing from render.spectral.light, are refused.
void apply_light_spectra(Scene& s, const JsonReader& root) {
    const std::string file = s.source;
    std::optional<size_t> first;
    for (size_t k = 0; k < s.lights.size(); ++k) {
        if (!s.lights[k].spectrum) continue;
        if (!first) {
            first = k;
            continue;
        }
        if (s.lights[k].spectrum->name() != s.lights[*first].spectrum->name())
            throw InputError(file + ": /lights/" + std::to_string(k) + "/spectrum: " + s.lights[k].spectrum->name() +
                             " differs from /lights/" + std::to_string(*first) + "/spectrum (" +
                             s.lights[*first].spectrum->name() + "): a scene has one light spectrum");
    }
    if (!first) return;
    const spectrum::LightSpectrum& L = *s.lights[*first].spectrum;
    const auto& j = root.json();
    if (j.contains("render") && j["render"].contains("spectral") && j["render"]["spectral"].is_object() &&
        j["render"]["spectral"].contains("light") && s.settings.spectral.light.name() != L.name())
        throw InputError(file + ": /render/spectral/light: " + s.settings.spectral.light.name() + " differs from /lights/" +
                         std::to_string(*first) + "/spectrum (" + L.name() + "): a scene has one light spectrum");
    s.settings.spectral.light = L;
}

Scene parse_scene(const json& j, const std::string& file) {
    JsonReader root(j, file, "");
    if (!j.is_object()) root.fail("a scene must be a JSON object");
    root.only({"camera", "background", "materials", "objects", "lights", "render", "description"});
    if (root.has("description")) (void)root.string("description");  // free text, but text
    Scene s;
    s.source = file;
    s.camera = parse_camera(root.child("camera"));
    if (root.has("background")) s.background = parse_background(j.at("background"), file);
    std::map<std::string, int> by_name;
    if (root.has("materials")) {
        const JsonReader ms = root.child("materials");
        for (const auto& [name, value] : j.at("materials").items()) {
            (void)value;
            s.materials.push_back(parse_material(ms.child(name), name, file));
            by_name[name] = static_cast<int>(s.materials.size()) - 1;
        }
    }
    const auto& objs = root.raw("objects");
    if (!objs.is_array()) root.fail_at("objects", "must be an array");
    MeshFileCache meshes;  // each mesh file read once (instancing)
    for (size_t k = 0; k < objs.size(); ++k) {
        const JsonReader o(objs[k], file, "/objects/" + std::to_string(k));
        if (!objs[k].is_object()) o.fail("must be an object");
        Object obj;
        obj.name = o.string("name", "object " + std::to_string(k));
        obj.shape = parse_shape(o, o.string("type"), file, meshes);
        obj.material = material_ref(o, s.materials, by_name, file);
        if (o.has("file") && transparent(s.materials[static_cast<size_t>(obj.material)])) check_closed(o, file, meshes);
        if (o.has("transform")) place(obj, o, o.has("file") ? mesh_file(o, file, meshes) : nullptr);
        s.objects.push_back(std::move(obj));
    }
    if (root.has("lights")) {
        const auto& ls = root.raw("lights");
        if (!ls.is_array()) root.fail_at("lights", "must be an array");
        for (size_t k = 0; k < ls.size(); ++k) {
            const JsonReader l(ls[k], file, "/lights/" + std::to_string(k));
            if (!ls[k].is_object()) l.fail("must be an object");
            const std::string type = l.string("type", "point");
            Light light;
            const auto direction = [&] {
                const auto d = unit_vector(l.vec3("direction"));
                if (!d) l.fail_at("direction", "must be a finite, non-zero vector");
                return *d;
            };
            if (type == "point") {
                l.only({"type", "position", "color", "polarisation", "spectrum"});
                light.position = l.vec3("position");
            } else if (type == "directional") {
                l.only({"type", "direction", "color", "polarisation", "spectrum", "angular_diameter_deg"});
                light.kind = Light::Kind::Directional;
                light.direction = direction();
                light.angular_diameter_deg = l.number("angular_diameter_deg", 0.0);
                if (!(light.angular_diameter_deg >= 0 && light.angular_diameter_deg < 90))
                    l.fail_at("angular_diameter_deg", "must be in [0, 90) degrees");
            } else if (type == "beam") {
                l.only({"type", "position", "direction", "radius", "color", "polarisation", "spectrum"});
                light.kind = Light::Kind::Beam;
                light.position = l.vec3("position");
                light.direction = direction();
                light.radius = l.number("radius");
                if (!(light.radius > 0 && light.radius <= 1e15)) l.fail_at("radius", "must be in (0, 1e15]");
                if (!(light.position.norm() < 1e150)) l.fail_at("position", "must lie within 1e150 of the origin");
            } else if (type == "rectangle" || type == "disk") {
                light.kind = type == "disk" ? Light::Kind::Disk : Light::Kind::Rectangle;
                parse_area_light(l, light);
            } else {
                l.fail_at("type", "unknown light type '" + clip_echo(type) + "' (point, directional, beam, rectangle, disk)");
            }
            // Colours scale every sum of the render: negative or astronomically large ones
            // would give negative or infinite pixels.
            light.color = l.colour("color", Vec3(1, 1, 1));
            if (l.has("polarisation")) light.polarisation = parse_polarisation_state(l.child("polarisation"), true);
            if (l.has("spectrum")) light.spectrum = spectrum::parse_light_spectrum(l.raw("spectrum"), file + ": " + l.path_of("spectrum"));
            s.lights.push_back(light);
        }
    }
    if (root.has("render")) s.settings = parse_settings(root.child("render"), file);
    apply_light_spectra(s, root);
    const bool rgb_only = root.has("render") && root.child("render").has("spectral") &&
                          root.child("render").raw("spectral").is_boolean() &&
                          !root.child("render").raw("spectral").get<bool>();
    for (const Material& m : s.materials)
        if (!rgb_only && dispersive(m))
            s.settings.spectral.enabled = true;
    if (s.settings.light_pass.enabled) s.settings.spectral.enabled = true;  // the maps are read by the spectral pass
    return s;
}

Scene load_scene(const std::string& path) {
    // At most 64 MiB, from a regular file, a pipe or a device alike (geometry/input_file.h).
    const std::string text = read_input_file(path, "scene file");
    check_json_depth(text, path);
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {  // syntax errors, and numbers too large for a double
        // e.byte locates the error; the message says what was expected.
        std::string what = e.what();
        auto pos = what.find("] ");
        if (pos != std::string::npos) pos += 2;
        throw InputError(path + ": malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos)));
    }
    return parse_scene(j, path);
}

PolarisationState parse_polarisation_state(const nlohmann::json& j, const std::string& source) {
    return parse_polarisation_state(JsonReader(j, source, "/polarisation"), true);
}

}  // namespace refract
