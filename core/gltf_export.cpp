// refract scene → glTF 2.0 (core/gltf_scene.h, docs/gltf.md).
#include <refract/core/gltf_scene.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>

#include <refract/core/material.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/icosphere.h>

namespace refract {

namespace {

using nlohmann::json;

constexpr int kSphereSubdivisions = 3;  // 1280 triangles

json vec(const Vec3& v) { return json::array({v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}); }

// A 4×4 column-major matrix of [A | t].
json matrix(const Eigen::Matrix3d& A, const Vec3& t) {
    json m = json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m.push_back(c < 3 ? (r < 3 ? A(r, c) + 0.0 : 0.0) : (r < 3 ? t[r] + 0.0 : 1.0));
    return m;
}


void put32(std::string& s, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) s += static_cast<char>(v >> (8 * k) & 0xff);
}

struct Writer {
    Writer(const Scene& s, std::vector<std::string>& w) : scene(s), warnings(w) {}
    const Scene& scene;
    std::vector<std::string>& warnings;
    std::string bin;
    json nodes = json::array(), meshes = json::array(), accessors = json::array(), views = json::array(),
         materials = json::array(), lights = json::array();
    std::set<std::string> used;                         // extensions
    std::map<int, int> material_index;                  // refract → glTF
    std::map<std::pair<const Shape*, int>, int> shared;  // (local shape, material) → glTF mesh

    void warn(const std::string& item, const std::string& what) { warnings.push_back(item + ": " + what); }

    int view(const std::string& bytes, int target) {
        views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}, {"target", target}});
        bin += bytes;
        while (bin.size() % 4) bin += '\0';
        return static_cast<int>(views.size()) - 1;
    }

    int mesh(const TriangleMesh& m, int material, const std::string& name) {
        std::string pos, idx;
        std::array<float, 3> lo{}, hi{};
        for (size_t k = 0; k < m.vertices.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                const float f = static_cast<float>(m.vertices[k][c]) + 0.0f;
                lo[c] = k ? std::min(lo[c], f) : f;
                hi[c] = k ? std::max(hi[c], f) : f;
                char b[4];
                std::memcpy(b, &f, 4);
                pos.append(b, 4);
            }
        for (const auto& t : m.triangles)
            for (int c = 0; c < 3; ++c) put32(idx, static_cast<std::uint32_t>(t[c]));
        accessors.push_back({{"bufferView", view(pos, 34962)}, {"componentType", 5126}, {"count", m.vertices.size()},
                             {"type", "VEC3"}, {"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}});
        accessors.push_back({{"bufferView", view(idx, 34963)}, {"componentType", 5125}, {"count", 3 * m.triangles.size()},
                             {"type", "SCALAR"}});
        const int n = static_cast<int>(accessors.size());
        meshes.push_back({{"name", name},
                          {"primitives", {{{"attributes", {{"POSITION", n - 2}}}, {"indices", n - 1}, {"mode", 4},
                                           {"material", material}}}}});
        return static_cast<int>(meshes.size()) - 1;
    }

    json base_colour(const Vec3& c, const std::string& item) {
        if (c.maxCoeff() > 1) warn(item, "colour components above 1 clipped to 1 (glTF's range)");
        const Vec3 k = c.cwiseMin(1.0);
        return {k.x() + 0.0, k.y() + 0.0, k.z() + 0.0, 1.0};
    }

    json dielectric(const Material& m, double ior, const std::optional<spectrum::Dispersion>& disp, const Vec3& filter,
                    const spectrum::Absorption* absorption, const std::string& item) {
        json ext = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", ior}}}};
        json volume = {{"thicknessFactor", 1.0}};
        if (disp && disp->dispersive())
            ext["KHR_materials_dispersion"] = {{"dispersion", gltf_dispersion_of_abbe(disp->abbe_number())}};
        if (disp && disp->dispersive() && !std::holds_alternative<spectrum::AbbeModel>(disp->model))
            warn(item, "dispersion " + disp->label + " exported as its n_d and Abbe number V_d");
        if (absorption) {
            const auto rgb = spectrum::Absorption::from_rgb(absorption->rgb, "");
            if (absorption->nm != rgb.nm || absorption->alpha != rgb.alpha)
                warn(item, "absorption spectrum exported as its R, G, B coefficients");
            // Beer–Lambert as glTF writes it: colour c after distance D, α = −ln(c)/D; D = 1/max α
            // keeps c away from underflow.
            const double amax = absorption->rgb.maxCoeff();
            if (amax > 0) {
                const double D = 1.0 / amax;
                volume["attenuationDistance"] = D;
                volume["attenuationColor"] = vec((-absorption->rgb * D).array().exp().matrix());
            }
        }
        ext["KHR_materials_volume"] = volume;
        for (const auto& [k, v] : ext.items()) {
            (void)v;
            used.insert(k);
        }
        (void)m;
        return {{"pbrMetallicRoughness", {{"baseColorFactor", base_colour(filter, item)}, {"metallicFactor", 0.0},
                                          {"roughnessFactor", 0.0}}},
                {"extensions", ext}};
    }

    int material(int k) {
        const auto it = material_index.find(k);
        if (it != material_index.end()) return it->second;
        const Material& m = scene.materials[static_cast<size_t>(k)];
        const std::string item = "material '" + clip_echo(m.name) + "'";
        json g;
        const auto pbr = [&](const Vec3& c, double metallic, double roughness) {
            return json{{"pbrMetallicRoughness",
                         {{"baseColorFactor", base_colour(c, item)}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}};
        };
        if (const auto* d = m.as<material::Dielectric>()) {
            if (d->reflectance != ReflectanceModel::Fresnel) warn(item, "reflectance model exported as Fresnel's");
            g = dielectric(m, d->ior, d->dispersion, d->filter, d->absorption ? &*d->absorption : nullptr, item);
        } else if (const auto* gr = m.as<material::Grin>()) {
            warn(item, "gradient-index medium exported as a dielectric of its index at the scene's origin (glTF has no gradient index)");
            g = dielectric(m, gr->index_at(Vec3::Zero(), 0.0), std::nullopt, gr->filter, nullptr, item);
        } else if (const auto* u = m.as<material::Uniaxial>()) {
            warn(item, "uniaxial crystal exported as an isotropic dielectric of its ordinary index");
            g = dielectric(m, u->ordinary.nominal(), u->ordinary, u->filter, nullptr, item);
        } else if (const auto* mt = m.as<material::Metal>()) {
            g = pbr(mt->color, 1.0, mt->fuzz);
        } else if (const auto* mi = m.as<material::Mirror>()) {
            warn(item, "mirror exported as a smooth metal");
            g = pbr(mi->color, 1.0, 0.0);
        } else if (const auto* df = m.as<material::Diffuse>()) {
            if (df->pigment.checker) warn(item, "checker not exported (its first colour)");
            if (df->diffuse != 1 || df->ambient != 0) warn(item, "diffuse and ambient coefficients not exported");
            g = pbr(df->pigment.color, 0.0, 1.0);
        } else if (const auto* l = m.as<material::Lambertian>()) {
            if (l->pigment.checker) warn(item, "checker not exported (its first colour)");
            g = pbr(l->pigment.color, 0.0, 1.0);
        } else if (const auto* e = m.as<material::Emissive>()) {
            warn(item, "emissive material exported as emissiveFactor (imported back as a black diffuse)");
            g = pbr(Vec3::Zero(), 0.0, 1.0);
            g["emissiveFactor"] = vec(e->color.cwiseMin(1.0));
        }
        g["name"] = m.name;
        materials.push_back(g);
        return material_index[k] = static_cast<int>(materials.size()) - 1;
    }

    void object(const Object& o, std::set<std::string>& names) {
        const std::string item = "object '" + clip_echo(o.name) + "'";
        const Shape& local = o.placement ? *o.placement->local : o.shape;
        // The triangles of each shape kind (one overload per kind, visited exhaustively: a new
        // kind without one does not compile); null: not exported, with its warning.
        TriangleMesh made;
        struct Triangles {
            Writer& ex;
            const std::string& item;
            TriangleMesh& made;
            const TriangleMesh* operator()(const Sphere& s) const {
                ex.warn(item, "sphere tessellated (" + std::to_string(20 << (2 * kSphereSubdivisions)) + " triangles)" +
                                  (s.radius < 0 ? ", hollow sphere exported as solid" : ""));
                made = icosphere(kSphereSubdivisions, s.center, std::fabs(s.radius));
                return &made;
            }
            const TriangleMesh* operator()(const Plane&) const {
                ex.warn(item, "infinite plane not exported (glTF holds bounded meshes)");
                return nullptr;
            }
            const TriangleMesh* operator()(const ConvexPolyhedron& c) const {
                made = mesh_of(c);
                if (!made.triangles.empty()) return &made;
                ex.warn(item, "unbounded polyhedron not exported");
                return nullptr;
            }
            const TriangleMesh* operator()(const TriangleMesh& m) const { return &m; }
        };
        const TriangleMesh* tris = std::visit(Triangles{*this, item, made}, local);
        if (!tris) return;
        const std::string name = unique(names, o.name);
        const int mat = material(o.material);
        const std::pair<const Shape*, int> key{o.placement ? o.placement->local.get() : &o.shape, mat};
        auto it = shared.find(key);
        if (it == shared.end())
            it = shared.emplace(key, mesh(*tris, mat, name)).first;
        json n = {{"name", name}, {"mesh", it->second}};
        // The object's transform after the mirror into glTF's right-handed frame (gltf_mirror):
        // a node of negative determinant, whose triangles a glTF viewer (and the mesh reader)
        // turns the other way round, so they stay counter-clockwise seen from outside.
        const Eigen::Matrix3d S = gltf_mirror().topLeftCorner<3, 3>();
        n["matrix"] = o.placement ? matrix(S * o.placement->transform.linear, S * o.placement->transform.translation)
                                  : matrix(S, Vec3::Zero());
        nodes.push_back(n);
    }

    std::string unique(std::set<std::string>& names, const std::string& base) {
        std::string name = base;
        for (int k = 2; names.count(name); ++k) name = base + " (" + std::to_string(k) + ")";
        names.insert(name);
        return name;
    }

    void camera(json& doc, std::set<std::string>& names) {
        const Camera& c = scene.camera;
        const Camera::Basis b = c.basis();
        const Eigen::Matrix3d S = gltf_mirror().topLeftCorner<3, 3>();
        const Vec3 d = S * b.D.normalized(), r = S * b.R.normalized(), u = S * b.U.normalized();
        // In the mirrored frame refract's image right (POV-Ray's, sky × D) is d × u, glTF's
        // camera +x: the camera looks along −z with +y up and the glTF viewer sees refract's image.
        Eigen::Matrix3d A;
        A.col(0) = r;
        A.col(1) = u;
        A.col(2) = -d;
        const double aspect = static_cast<double>(c.width) / c.height;
        json cam;
        if (c.type == Camera::Type::Perspective) {
            const double yfov = 2.0 * std::atan(std::tan(c.angle_deg * M_PI / 360.0) / aspect);
            cam = {{"type", "perspective"}, {"perspective", {{"yfov", yfov}, {"aspectRatio", aspect}, {"znear", 1e-3}}}};
        } else {
            cam = {{"type", "orthographic"},
                   {"orthographic", {{"ymag", c.ortho_height / 2}, {"xmag", c.ortho_height / 2 * aspect}, {"znear", 0.0},
                                     {"zfar", 1e30}}}};
        }
        if (c.thin_lens()) warn("camera", "thin lens (aperture, focus_distance) not exported: a pinhole");
        cam["extras"] = {{"width", c.width}, {"height", c.height}};
        doc["cameras"] = json::array({cam});
        nodes.push_back({{"name", unique(names, "camera")}, {"camera", 0}, {"matrix", matrix(A, S * c.location)}});
    }

    void light(const Light& l, size_t k, std::set<std::string>& names) {
        const std::string item = "light " + std::to_string(k);
        if (l.kind != Light::Kind::Point && l.kind != Light::Kind::Directional) {
            warn(item, "beam and area lights not exported (KHR_lights_punctual has point, spot and directional)");
            return;
        }
        if (l.spectrum) warn(item, "spectrum not exported");
        if (l.polarisation.kind != PolarisationState::Kind::Unpolarised) warn(item, "polarisation not exported");
        const double intensity = std::max(1.0, l.color.maxCoeff());
        json g = {{"color", vec(l.color / intensity)}, {"intensity", intensity}};
        json n = {{"name", unique(names, item)}, {"extensions", {{"KHR_lights_punctual", {{"light", lights.size()}}}}}};
        const Eigen::Matrix3d S = gltf_mirror().topLeftCorner<3, 3>();
        if (l.kind == Light::Kind::Point) {
            g["type"] = "point";
            n["translation"] = vec(S * l.position);
        } else {
            if (l.angular_diameter_deg != 0) warn(item, "angular_diameter_deg not exported (a point at infinity)");
            g["type"] = "directional";
            // The light shines along the node's −z.
            const Vec3 z = -(S * l.direction).normalized();
            const Vec3 x = (std::fabs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(z).normalized();
            Eigen::Matrix3d A;
            A.col(0) = x;
            A.col(1) = z.cross(x);
            A.col(2) = z;
            n["matrix"] = matrix(A, Vec3::Zero());
        }
        lights.push_back(g);
        nodes.push_back(n);
        used.insert("KHR_lights_punctual");
    }
};

}  // namespace

// Base64 (RFC 4648 §4, with padding): a glTF buffer as a data URI.
std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((in.size() + 2) / 3 * 4);
    for (size_t i = 0; i < in.size(); i += 3) {
        const auto b = [&](size_t j) { return j < in.size() ? static_cast<unsigned char>(in[j]) : 0u; };
        const unsigned v = b(i) << 16 | b(i + 1) << 8 | b(i + 2);
        out += k[v >> 18 & 63];
        out += k[v >> 12 & 63];
        out += i + 1 < in.size() ? k[v >> 6 & 63] : '=';
        out += i + 2 < in.size() ? k[v & 63] : '=';
    }
    return out;
}

GltfExport export_gltf(const Scene& s, bool binary) {
    GltfExport out;
    Writer w{s, out.warnings};
    json doc = {{"asset", {{"version", "2.0"}, {"generator", "refract export-gltf"}}}, {"scene", 0}};
    std::set<std::string> names;
    for (const Object& o : s.objects) w.object(o, names);
    w.camera(doc, names);
    for (size_t k = 0; k < s.lights.size(); ++k) w.light(s.lights[k], k, names);
    if (s.background.kind != Background::Kind::Solid || s.background.color != Vec3::Zero())
        w.warn("background", "not exported (glTF has none)");
    json roots = json::array();
    for (size_t k = 0; k < w.nodes.size(); ++k) roots.push_back(k);
    doc["scenes"] = json::array({{{"nodes", roots}}});
    doc["nodes"] = w.nodes;
    if (!w.meshes.empty()) {
        doc["meshes"] = w.meshes;
        doc["accessors"] = w.accessors;
        doc["bufferViews"] = w.views;
        json buffer = {{"byteLength", w.bin.size()}};
        if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(w.bin);
        doc["buffers"] = json::array({buffer});
    }
    if (!w.materials.empty()) doc["materials"] = w.materials;
    if (!w.lights.empty()) doc["extensions"] = {{"KHR_lights_punctual", {{"lights", w.lights}}}};
    if (!w.used.empty()) doc["extensionsUsed"] = json(std::vector<std::string>(w.used.begin(), w.used.end()));
    if (!binary) {
        out.bytes = doc.dump(1) + "\n";
        return out;
    }
    std::string js = doc.dump();
    while (js.size() % 4) js += ' ';
    const bool has_bin = !w.meshes.empty();
    const std::size_t total = 12 + 8 + js.size() + (has_bin ? 8 + w.bin.size() : 0);
    if (total > 0xffffffffu) throw InputError("the scene's glTF would exceed the GLB's 4 GiB");
    out.bytes = "glTF";
    put32(out.bytes, 2);
    put32(out.bytes, static_cast<std::uint32_t>(total));
    put32(out.bytes, static_cast<std::uint32_t>(js.size()));
    out.bytes += "JSON";
    out.bytes += js;
    if (has_bin) {
        put32(out.bytes, static_cast<std::uint32_t>(w.bin.size()));
        out.bytes.append("BIN\0", 4);
        out.bytes += w.bin;
    }
    return out;
}

}  // namespace refract
