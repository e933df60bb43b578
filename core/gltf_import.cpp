// glTF 2.0 → refract scene (core/gltf_scene.h, docs/gltf.md).
#include <refract/core/gltf_scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include <Eigen/Geometry>

#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/input_file.h>

namespace refract {

double gltf_dispersion_of_abbe(double Vd) { return 20.0 / Vd; }
double abbe_of_gltf_dispersion(double dispersion) { return 20.0 / dispersion; }

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

std::uint32_t le32(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// The JSON text of a .glb: its header and first chunk checked against the file's size.
std::string glb_json(const std::string& path) {
    std::error_code ec;
    const auto st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw InputError(path + ": cannot open the glTF file");
    if (!fs::is_regular_file(st)) throw InputError(path + ": is not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (ec || !in) throw InputError(path + ": cannot open the glTF file");
    unsigned char h[20] = {};
    in.read(reinterpret_cast<char*>(h), size < 20 ? static_cast<std::streamsize>(size) : 20);
    const std::string sz = std::to_string(size);
    if (size < 12) throw InputError(path + ": truncated: " + sz + " bytes, shorter than the GLB header (12 bytes)");
    if (std::memcmp(h, "glTF", 4) != 0) throw InputError(path + ": not a binary glTF (no 'glTF' magic at its start)");
    if (le32(h + 4) != 2) throw InputError(path + ": GLB version " + std::to_string(le32(h + 4)) + " (refract reads 2)");
    const std::uint32_t length = le32(h + 8);
    if (length > size)
        throw InputError(path + ": truncated: the GLB header gives " + std::to_string(length) + " bytes, the file has " + sz);
    if (length < size)
        throw InputError(path + ": the GLB header gives " + std::to_string(length) + " bytes, the file has " + sz);
    if (size < 20) throw InputError(path + ": truncated: no JSON chunk after the GLB header");
    const std::uint32_t chunk = le32(h + 12);
    if (std::memcmp(h + 16, "JSON", 4) != 0) throw InputError(path + ": the GLB's first chunk is not its JSON");
    if (std::uint64_t{chunk} + 20 > length)
        throw InputError(path + ": truncated: the JSON chunk of " + std::to_string(chunk) + " bytes runs past the file's end");
    std::string text(chunk, '\0');
    in.read(text.data(), chunk);
    if (!in) throw InputError(path + ": cannot read the glTF file");
    return text;
}

// Reading the glTF JSON: every error names the file and the JSON pointer of the item.
struct Doc {
    std::string file;
    json j;
    std::vector<std::string>* warnings;

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw InputError(file + ": " + where + ": " + what);
    }
    void warn(const std::string& where, const std::string& what) const { warnings->push_back(file + ": " + where + ": " + what); }
    const json& list(const char* key) const {
        static const json empty = json::array();
        if (!j.contains(key)) return empty;
        if (!j[key].is_array()) fail(std::string("/") + key, "must be an array");
        return j[key];
    }
    double number(const json& o, const char* key, double def, const std::string& where) const {
        if (!o.contains(key)) return def;
        const json& v = o[key];
        if (!v.is_number() || !std::isfinite(v.get<double>())) fail(where + "/" + key, "must be a finite number");
        return v.get<double>();
    }
    std::vector<double> numbers(const json& o, const char* key, std::vector<double> def, const std::string& where) const {
        if (!o.contains(key)) return def;
        const json& v = o[key];
        if (!v.is_array() || v.size() != def.size())
            fail(where + "/" + key, "must be an array of " + std::to_string(def.size()) + " finite numbers");
        for (size_t k = 0; k < def.size(); ++k) {
            if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
                fail(where + "/" + key, "must be an array of " + std::to_string(def.size()) + " finite numbers");
            def[k] = v[k].get<double>();
        }
        return def;
    }
    // An index into the top-level array `of`; -1 when absent.
    int index(const json& o, const char* key, const char* of, const std::string& where) const {
        if (!o.contains(key)) return -1;
        const json& v = o[key];
        const size_t n = list(of).size();
        if (!v.is_number_unsigned() || v.get<std::uint64_t>() >= n)
            fail(where + "/" + key, "must be an index into /" + std::string(of) + " (0 to " +
                                        (n ? std::to_string(n - 1) : std::string("none")) + ")");
        return v.get<int>();
    }
    const json& object(const json& o, const char* key, const std::string& where) const {
        static const json empty = json::object();
        if (!o.contains(key)) return empty;
        if (!o[key].is_object()) fail(where + "/" + key, "must be an object");
        return o[key];
    }
    std::string name_of(const json& o) const {
        return o.contains("name") && o["name"].is_string() ? o["name"].get<std::string>() : std::string();
    }
    std::string item(const std::string& where, const json& o) const {
        const std::string n = name_of(o);
        return n.empty() ? where : where + " ('" + clip_echo(n) + "')";
    }
};

using Affine = Eigen::Matrix4d;

Affine node_matrix(const Doc& d, const json& n, const std::string& where) {
    Affine M = Affine::Identity();
    if (n.contains("matrix")) {
        const auto m = d.numbers(n, "matrix", std::vector<double>(16, 0.0), where);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) M(r, c) = m[static_cast<size_t>(4 * c + r)];  // column-major
        return M;
    }
    const auto t = d.numbers(n, "translation", {0, 0, 0}, where);
    const auto q = d.numbers(n, "rotation", {0, 0, 0, 1}, where);
    const auto s = d.numbers(n, "scale", {1, 1, 1}, where);
    Eigen::Quaterniond Q(q[3], q[0], q[1], q[2]);
    if (!(Q.norm() > 0)) d.fail(where + "/rotation", "must be a unit quaternion [x, y, z, w]");
    M.topLeftCorner<3, 3>() = Q.normalized().toRotationMatrix() * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
    M.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
    return M;
}

json json_vec3(const Vec3& v) { return json::array({v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}); }

// Texture references, anywhere in a material or its extensions.
void warn_textures(const Doc& d, const json& o, const std::string& where, const std::string& item) {
    for (const auto& [k, v] : o.items()) {
        if (k.size() > 7 && k.compare(k.size() - 7, 7, "Texture") == 0)
            d.warn(item, where + k + " not honoured (textures are not read)");
        else if (v.is_object() && k != "extras")
            warn_textures(d, v, where + k + "/", item);
    }
}

json material_json(const Doc& d, const json& m, const std::string& where) {
    const std::string item = d.item(where, m);
    const json& pbr = d.object(m, "pbrMetallicRoughness", where);
    const std::string pw = where + "/pbrMetallicRoughness";
    const auto base = d.numbers(pbr, "baseColorFactor", {1, 1, 1, 1}, pw);
    const double metallic = d.number(pbr, "metallicFactor", 1.0, pw);
    const double roughness = d.number(pbr, "roughnessFactor", 1.0, pw);
    const json& ext = d.object(m, "extensions", where);
    const std::string ew = where + "/extensions";
    static const std::set<std::string> known{"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                                             "KHR_materials_dispersion"};
    for (const auto& [k, v] : ext.items()) {
        (void)v;
        if (!known.count(k)) d.warn(item, "extension " + clip_echo(k) + " not honoured");
    }
    warn_textures(d, m, "", item);
    const auto emissive = d.numbers(m, "emissiveFactor", {0, 0, 0}, where);
    if (emissive[0] != 0 || emissive[1] != 0 || emissive[2] != 0)
        d.warn(item, "emissiveFactor not honoured (imported materials do not emit)");
    const Vec3 colour(base[0], base[1], base[2]);
    const json& tr = d.object(ext, "KHR_materials_transmission", ew);
    const double transmission = d.number(tr, "transmissionFactor", 0.0, ew + "/KHR_materials_transmission");
    if (transmission > 0) {
        json out = {{"type", "dielectric"}};
        if (transmission != 1) d.warn(item, "transmissionFactor " + format_value(transmission) + " taken as 1");
        if (roughness != 0) d.warn(item, "roughnessFactor " + format_value(roughness) + " not honoured (a smooth interface)");
        const std::string iw = ew + "/KHR_materials_ior";
        double ior = d.number(d.object(ext, "KHR_materials_ior", ew), "ior", 1.5, iw);
        if (!(ior >= 1)) {
            d.warn(item, "ior " + format_value(ior) + " not honoured (refract's dielectrics need ior >= 1 here): 1.5");
            ior = 1.5;
        }
        const std::string dw = ew + "/KHR_materials_dispersion";
        const double disp = d.number(d.object(ext, "KHR_materials_dispersion", ew), "dispersion", 0.0, dw);
        if (disp < 0) d.fail(dw + "/dispersion", "must be >= 0 (20/V_d)");
        if (disp > 0) out["dispersion"] = {{"model", "abbe"}, {"nd", ior}, {"Vd", abbe_of_gltf_dispersion(disp)}};
        else out["ior"] = ior;
        if (ext.contains("KHR_materials_volume")) {
            const std::string vw = ew + "/KHR_materials_volume";
            const json& vol = d.object(ext, "KHR_materials_volume", ew);
            const auto c = d.numbers(vol, "attenuationColor", {1, 1, 1}, vw);
            if (vol.contains("attenuationDistance")) {
                const double D = d.number(vol, "attenuationDistance", 0.0, vw);
                if (!(D > 0)) d.fail(vw + "/attenuationDistance", "must be > 0");
                for (double t : c)
                    if (!(t > 0 && t <= 1)) d.fail(vw + "/attenuationColor", "each component must be in (0, 1]");
                if (c[0] != 1 || c[1] != 1 || c[2] != 1)
                    out["absorption"] = {{"transmittance", c}, {"thickness", D}};
            }
        } else {
            d.warn(item, "no KHR_materials_volume (thin-walled in glTF): imported as a solid dielectric");
        }
        if (colour != Vec3(1, 1, 1)) out["filter"] = json_vec3(colour);
        if (base[3] != 1) d.warn(item, "baseColorFactor alpha not honoured");
        return out;
    }
    if (base[3] != 1 || (m.contains("alphaMode") && m["alphaMode"] != "OPAQUE"))
        d.warn(item, "alpha (alphaMode, baseColorFactor's alpha) not honoured: opaque");
    if (metallic != 0 && metallic != 1)
        d.warn(item, "metallicFactor " + format_value(metallic) + " taken as " + (metallic >= 0.5 ? "1" : "0"));
    if (metallic >= 0.5) return {{"type", "metal"}, {"color", json_vec3(colour)}, {"fuzz", std::fmin(std::fmax(roughness, 0.0), 1.0)}};
    return {{"type", "diffuse"}, {"color", json_vec3(colour)}};
}

struct Importer {
    Importer(Doc doc, std::string file, int w, int h) : d(std::move(doc)), mesh_file(std::move(file)), width(w), height(h) {}
    Doc d;
    std::string mesh_file;
    int width = 0, height = 0;
    json objects = json::array(), lights = json::array(), materials = json::object();
    std::optional<json> camera;
    std::map<int, std::string> material_names;  // glTF index (−1: none) → refract name
    std::map<std::string, int> node_names;      // name → how many nodes have it

    std::string material(int k) {
        const auto it = material_names.find(k);
        if (it != material_names.end()) return it->second;
        std::string name;
        if (k < 0) {
            name = "gltf-default";
            materials[name] = {{"type", "diffuse"}, {"color", {1, 1, 1}}};
        } else {
            const std::string where = "/materials/" + std::to_string(k);
            const json& m = d.list("materials")[static_cast<size_t>(k)];
            if (!m.is_object()) d.fail(where, "must be an object");
            name = d.name_of(m);
            if (name.empty() || materials.contains(name)) name = "material " + std::to_string(k);
            materials[name] = material_json(d, m, where);
        }
        material_names[k] = name;
        return name;
    }

    // The material of a mesh's primitives (the first one's when they differ).
    int mesh_material(int mesh, const std::string& item) {
        const std::string where = "/meshes/" + std::to_string(mesh);
        const json& m = d.list("meshes")[static_cast<size_t>(mesh)];
        if (!m.is_object() || !m.contains("primitives") || !m["primitives"].is_array() || m["primitives"].empty())
            d.fail(where + "/primitives", "must be a non-empty array");
        int first = -2;
        for (size_t p = 0; p < m["primitives"].size(); ++p) {
            const json& prim = m["primitives"][p];
            const std::string pw = where + "/primitives/" + std::to_string(p);
            if (!prim.is_object()) d.fail(pw, "must be an object");
            const int k = d.index(prim, "material", "materials", pw);
            if (first == -2) first = k;
            else if (k != first) d.warn(item, "primitives of different materials: all in the first's");
            if (prim.contains("targets")) d.warn(item, "morph targets not honoured");
        }
        return first;
    }

    void camera_node(const json& n, int cam, const Affine& G, const std::string& item) {
        if (camera) {
            d.warn(item, "a second camera, left out (a refract scene has one)");
            return;
        }
        const std::string where = "/cameras/" + std::to_string(cam);
        const json& c = d.list("cameras")[static_cast<size_t>(cam)];
        if (!c.is_object()) d.fail(where, "must be an object");
        const Vec3 loc = G.block<3, 1>(0, 3), back = G.block<3, 1>(0, 2), up = G.block<3, 1>(0, 1);
        if (!(back.norm() > 0) || !(up.norm() > 0) || !(back.cross(up).norm() > 0))
            d.fail(d.item("/nodes", n), "the camera's transform is singular");
        json out = {{"location", json_vec3(loc)}, {"look_at", json_vec3(loc - back.normalized())}, {"sky", json_vec3(up.normalized())}};
        const std::string type = c.contains("type") && c["type"].is_string() ? c["type"].get<std::string>() : "";
        double aspect = 0;
        if (type == "perspective") {
            const json& p = d.object(c, "perspective", where);
            const double yfov = d.number(p, "yfov", 0.0, where + "/perspective");
            if (!(yfov > 0 && yfov < M_PI)) d.fail(where + "/perspective/yfov", "must be in (0, π) radians");
            out["vfov"] = yfov * (180.0 / M_PI);
            aspect = d.number(p, "aspectRatio", 0.0, where + "/perspective");
        } else if (type == "orthographic") {
            const json& o = d.object(c, "orthographic", where);
            const double xmag = d.number(o, "xmag", 0.0, where + "/orthographic"),
                         ymag = d.number(o, "ymag", 0.0, where + "/orthographic");
            if (!(xmag > 0) || !(ymag > 0)) d.fail(where + "/orthographic", "xmag and ymag must be > 0");
            out["type"] = "orthographic";
            out["ortho_height"] = 2 * ymag;
            aspect = xmag / ymag;
        } else {
            d.fail(where + "/type", "must be \"perspective\" or \"orthographic\"");
        }
        // The image size: the command's, else the one refract's export wrote, else from the
        // camera's aspect ratio (4:3 without one) at 640 pixels wide.
        const json& extras = c.contains("extras") && c["extras"].is_object() ? c["extras"] : json::object();
        int W = width, H = height;
        if (!W && !H && extras.contains("width") && extras.contains("height") && extras["width"].is_number_integer() &&
            extras["height"].is_number_integer()) {
            W = extras["width"].get<int>();
            H = extras["height"].get<int>();
        }
        if (aspect != 0 && !(aspect >= 1e-4 && aspect <= 1e4))
            d.fail(where, "the aspect ratio " + format_value(aspect) + " is outside [1e-4, 1e4]");
        if (aspect == 0) aspect = W && H ? static_cast<double>(W) / H : 4.0 / 3.0;
        if (!W) W = H ? static_cast<int>(std::lround(H * aspect)) : 640;
        if (!H) H = static_cast<int>(std::lround(W / aspect));
        out["width"] = std::max(W, 1);
        out["height"] = std::max(H, 1);
        camera = out;
    }

    void light_node(int k, const Affine& G, const std::string& item) {
        const std::string where = "/extensions/KHR_lights_punctual/lights/" + std::to_string(k);
        const json& l = d.j["extensions"]["KHR_lights_punctual"]["lights"][static_cast<size_t>(k)];
        if (!l.is_object()) d.fail(where, "must be an object");
        const auto c = d.numbers(l, "color", {1, 1, 1}, where);
        const double intensity = d.number(l, "intensity", 1.0, where);
        if (!(intensity >= 0)) d.fail(where + "/intensity", "must be >= 0");
        const std::string type = l.contains("type") && l["type"].is_string() ? l["type"].get<std::string>() : "";
        const std::string li = d.item(where, l);
        if (l.contains("range")) d.warn(li, "range not honoured (refract's point lights do not fall off)");
        json out = {{"color", json_vec3(Vec3(c[0], c[1], c[2]) * intensity)}};
        if (type == "directional") {
            const Vec3 back = G.block<3, 1>(0, 2);
            if (!(back.norm() > 0)) d.fail(item, "the light's transform is singular");
            out["type"] = "directional";
            out["direction"] = json_vec3(-back.normalized());
        } else if (type == "point" || type == "spot") {
            if (type == "spot") d.warn(li, "spot cone not honoured: a point light");
            out["type"] = "point";
            out["position"] = json_vec3(G.block<3, 1>(0, 3));
        } else {
            d.fail(where + "/type", "must be \"point\", \"spot\" or \"directional\"");
        }
        lights.push_back(out);
    }

    // `covered`: the name of an ancestor whose node reference reads this node's mesh too.
    void node(int k, const Affine& parent, const std::string& covered, int covered_material, int depth,
              std::vector<bool>& seen) {
        const std::string where = "/nodes/" + std::to_string(k);
        const json& n = d.list("nodes")[static_cast<size_t>(k)];
        if (!n.is_object()) d.fail(where, "must be an object");
        if (seen[static_cast<size_t>(k)]) d.fail(where, "is reached twice (a node has one parent, and no cycle)");
        seen[static_cast<size_t>(k)] = true;
        const std::string item = d.item(where, n);
        const Affine G = parent * node_matrix(d, n, where);
        if (!G.allFinite()) d.fail(where, "its transform is not finite");
        if (n.contains("skin")) d.warn(item, "skin not honoured");
        if (n.contains("weights")) d.warn(item, "morph weights not honoured");
        std::string cover = covered;
        int cover_material = covered_material;
        const int mesh = d.index(n, "mesh", "meshes", where);
        if (mesh >= 0) {
            const int mat = mesh_material(mesh, item);
            const std::string name = d.name_of(n);
            if (!covered.empty()) {
                if (mat != covered_material)
                    d.warn(item, "read with its ancestor '" + clip_echo(covered) + "', in that node's material");
            } else if (name.empty() || node_names[name] > 1) {
                d.warn(item, "a mesh node without a unique name, left out (refract reads a mesh by its node's name)");
            } else {
                objects.push_back({{"type", "mesh"}, {"name", name}, {"file", mesh_file}, {"node", name},
                                   {"material", material(mat)}, {"transform", {{"scale", {1, 1, -1}}}}});
                cover = name;
                cover_material = mat;
            }
        }
        const int cam = d.index(n, "camera", "cameras", where);
        if (cam >= 0) camera_node(n, cam, G, item);
        const json& ext = d.object(n, "extensions", where);
        for (const auto& [key, v] : ext.items()) {
            if (key != "KHR_lights_punctual") {
                d.warn(item, "extension " + clip_echo(key) + " not honoured");
                continue;
            }
            const std::string lw = where + "/extensions/KHR_lights_punctual";
            const json& lights_list = d.j.contains("extensions") && d.j["extensions"].is_object()
                                          ? d.object(d.j["extensions"], "KHR_lights_punctual", "/extensions")
                                          : json::object();
            const size_t count = lights_list.contains("lights") && lights_list["lights"].is_array() ? lights_list["lights"].size() : 0;
            if (!v.is_object() || !v.contains("light") || !v["light"].is_number_unsigned() || v["light"].get<std::uint64_t>() >= count)
                d.fail(lw + "/light", "must be an index into /extensions/KHR_lights_punctual/lights");
            light_node(v["light"].get<int>(), G, item);
        }
        if (n.contains("children")) {
            const json& ch = n["children"];
            if (!ch.is_array()) d.fail(where + "/children", "must be an array");
            if (depth > 256) d.fail(where, "nested more than 256 nodes deep");
            for (size_t c = 0; c < ch.size(); ++c) {
                const std::string cw = where + "/children/" + std::to_string(c);
                if (!ch[c].is_number_unsigned() || ch[c].get<std::uint64_t>() >= d.list("nodes").size())
                    d.fail(cw, "must be an index into /nodes");
                node(ch[c].get<int>(), G, cover, cover_material, depth + 1, seen);
            }
        }
    }
};

json parse_text(const std::string& text, const std::string& path) {
    check_json_depth(text, path);
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        std::string what = e.what();
        auto pos = what.find("] ");
        throw InputError(path + ": malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos + 2)));
    }
}

}  // namespace

GltfImport import_gltf(const std::string& path, const std::string& mesh_file, int width, int height) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".gltf" && ext != ".glb")
        throw InputError(path + ": unknown extension '" + clip_echo(ext) + "' (a glTF file: .gltf or .glb)");
    GltfImport out;
    Importer im(Doc{path, parse_text(ext == ".glb" ? glb_json(path) : read_input_file(path, "glTF file"), path),
                    &out.warnings},
                mesh_file, width, height);
    Doc& d = im.d;
    if (!d.j.is_object()) d.fail("/", "a glTF file is a JSON object");
    const json& asset = d.object(d.j, "asset", "");
    if (!asset.contains("version") || !asset["version"].is_string() || asset["version"].get<std::string>().rfind("2.", 0) != 0)
        d.fail("/asset/version", "must be \"2.0\" (refract reads glTF 2.0)");
    for (const char* key : {"extensionsRequired"})
        for (const auto& e : d.list(key))
            if (!e.is_string() || (e != "KHR_lights_punctual" && e != "KHR_materials_transmission" && e != "KHR_materials_ior" &&
                                   e != "KHR_materials_volume" && e != "KHR_materials_dispersion"))
                d.warn("/extensionsRequired", "extension " + clip_echo(e.dump()) + " not honoured");
    for (const char* key : {"animations", "skins"})
        for (size_t k = 0; k < d.list(key).size(); ++k)
            d.warn(d.item(std::string("/") + key + "/" + std::to_string(k), d.list(key)[k]),
                   std::string(key) + " not honoured (a still scene)");
    const json& nodes = d.list("nodes");
    for (const auto& n : nodes) {
        const std::string name = n.is_object() ? d.name_of(n) : std::string();
        if (!name.empty()) ++im.node_names[name];
    }
    // The scene's root nodes: those of `scene` (0 without one), or every node no other
    // node lists as a child when the file has no scenes.
    std::vector<int> roots;
    const json& scenes = d.list("scenes");
    if (!scenes.empty()) {
        int s = d.index(d.j, "scene", "scenes", "");
        if (s < 0) s = 0;
        const std::string sw = "/scenes/" + std::to_string(s);
        const json& sc = scenes[static_cast<size_t>(s)];
        if (!sc.is_object()) d.fail(sw, "must be an object");
        if (sc.contains("nodes")) {
            if (!sc["nodes"].is_array()) d.fail(sw + "/nodes", "must be an array");
            for (size_t k = 0; k < sc["nodes"].size(); ++k) {
                const json& v = sc["nodes"][k];
                if (!v.is_number_unsigned() || v.get<std::uint64_t>() >= nodes.size())
                    d.fail(sw + "/nodes/" + std::to_string(k), "must be an index into /nodes");
                roots.push_back(v.get<int>());
            }
        }
    } else {
        std::vector<bool> child(nodes.size(), false);
        for (const auto& n : nodes)
            if (n.is_object() && n.contains("children") && n["children"].is_array())
                for (const auto& c : n["children"])
                    if (c.is_number_unsigned() && c.get<std::uint64_t>() < nodes.size()) child[c.get<size_t>()] = true;
        for (size_t k = 0; k < nodes.size(); ++k)
            if (!child[k]) roots.push_back(static_cast<int>(k));
    }
    std::vector<bool> seen(nodes.size(), false);
    // glTF is right-handed and refract's camera POV-Ray's left-handed one (image right =
    // sky × direction): the scene is the file mirrored in z, so that refract's image is the
    // glTF viewer's (docs/gltf.md). Cameras and lights are placed by the mirror; each mesh
    // object carries it as its transform (the reader places the triangles in the file's frame).
    for (int r : roots) im.node(r, gltf_mirror(), "", -1, 0, seen);

    if (im.objects.empty())
        d.fail("/nodes", im.node_names.empty() || out.warnings.empty()
                             ? "no mesh node to import"
                             : "no mesh node to import (a mesh node without a unique name is left out)");
    json& s = out.scene;
    s["description"] = "imported from " + fs::path(path).filename().string() + " by refract import";
    if (!im.camera) {
        d.warn("/cameras", "no camera in the scene: refract's default camera");
        im.camera = json{{"width", width ? width : 640}, {"height", height ? height : 480}};
    }
    s["camera"] = *im.camera;
    s["materials"] = im.materials;
    s["objects"] = im.objects;
    if (im.lights.empty()) d.warn("/extensions/KHR_lights_punctual", "no light in the scene");
    s["lights"] = im.lights;
    return out;
}

}  // namespace refract
