// Gem export: OBJ, OFF, PLY (ASCII) and POV-Ray, written atomically.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <unistd.h>

#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/gem/gem_io.h>
#include <refract/geometry/gem/gemcad.h>

namespace refract {
namespace {

std::string g17(double v) { return format_significant(v == 0 ? 0.0 : v, 17); }  // no "-0"
// The gem's frame (z up) to the scene's (y up): a quarter turn about x, exact.
Vec3 y_up(const Vec3& p) { return Vec3(p.x(), p.z(), -p.y()); }
std::string xyz(const Vec3& q, const char* sep = " ") {
    const Vec3 p = y_up(q);
    return g17(p.x()) + sep + g17(p.y()) + sep + g17(p.z());
}

std::string header_comment(const Gem& gem) {
    if (!gem.description.empty()) return gem.description + "; y up; " + std::to_string(gem.facets.size()) + " facets";
    const BrilliantCut& c = gem.cut;
    std::ostringstream s;
    s << "round brilliant by refract: table " << c.table << " %, crown " << c.crown_angle << " deg, pavilion "
      << c.pavilion_angle << " deg, star " << c.star << " %, lower half " << c.lower_half << " %, girdle "
      << c.girdle << " % (" << girdle_description(c) << "), culet " << c.culet << " %; girdle radius 1, y up; "
      << gem.facets.size() << " facets";
    return s.str();
}

std::string obj(const Gem& gem) {
    std::ostringstream s;
    s << "# " << header_comment(gem) << "\n";
    for (const Vec3& v : gem.mesh.vertices) s << "v " << xyz(v) << "\n";
    for (const GemFacet& f : gem.facets) {
        std::string name = f.label;
        std::replace(name.begin(), name.end(), ' ', '_');
        s << "g " << name << "\nf";
        for (int i : f.vertex_ids) s << " " << i + 1;
        s << "\n";
    }
    return s.str();
}

// OFF and PLY share their body: one "x y z" line per vertex, then "count i j k ..." per facet.
void write_vertices_and_faces(std::ostringstream& s, const Gem& gem) {
    for (const Vec3& v : gem.mesh.vertices) s << xyz(v) << "\n";
    for (const GemFacet& f : gem.facets) {
        s << f.vertex_ids.size();
        for (int i : f.vertex_ids) s << " " << i;
        s << "\n";
    }
}

std::string off(const Gem& gem) {
    std::ostringstream s;
    s << "OFF\n# " << header_comment(gem) << "\n";
    std::size_t edges = 0;
    for (const GemFacet& f : gem.facets) edges += f.vertex_ids.size();
    s << gem.mesh.vertices.size() << " " << gem.facets.size() << " " << edges / 2 << "\n";
    write_vertices_and_faces(s, gem);
    return s.str();
}

std::string ply(const Gem& gem) {
    std::ostringstream s;
    s << "ply\nformat ascii 1.0\ncomment " << header_comment(gem) << "\nelement vertex " << gem.mesh.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << gem.facets.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
    write_vertices_and_faces(s, gem);
    return s.str();
}

std::string lower(std::string s) {
    for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return s;
}

}  // namespace

namespace {

// The #declare's body by the kind of shape that traces the gem (tracing_shape): an
// intersection of its facets' planes, or the closed mesh of a stone with a cleft.
std::string pov_body(const ConvexPolyhedron&, const Gem& gem, const std::string& name) {
    std::ostringstream s;
    s << "#declare " << name << " = intersection {\n";
    for (const GemFacet& f : gem.facets)
        s << "  plane { <" << xyz(f.plane.normal, ", ") << ">, " << g17(f.plane.offset) << " }  // " << f.label
          << "\n";
    s << "}\n";
    return s.str();
}
std::string pov_body(const TriangleMesh& m, const Gem&, const std::string& name) {
    std::ostringstream s;
    s << "#declare " << name << " = mesh {\n";
    for (const auto& t : m.triangles)
        s << "  triangle { <" << xyz(m.vertices[static_cast<size_t>(t[0])], ", ") << ">, <"
          << xyz(m.vertices[static_cast<size_t>(t[1])], ", ") << ">, <" << xyz(m.vertices[static_cast<size_t>(t[2])], ", ")
          << "> }\n";
    s << "  inside_vector <0, 0, 1>\n}\n";
    return s.str();
}
std::string pov_body(const Sphere&, const Gem&, const std::string&) {
    throw std::logic_error("a gem is traced as a plane set or a mesh, not a sphere");
}
std::string pov_body(const Plane&, const Gem&, const std::string&) {
    throw std::logic_error("a gem is traced as a plane set or a mesh, not a plane");
}

}  // namespace

std::string pov_gem_declaration(const Gem& gem, const std::string& name) {
    return "// " + header_comment(gem) + "\n" +
           std::visit([&](const auto& shape) { return pov_body(shape, gem, name); }, tracing_shape(gem));
}

void write_gem(const Gem& gem, const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    std::string text;
    if (ext == ".obj") text = obj(gem);
    else if (ext == ".off") text = off(gem);
    else if (ext == ".ply") text = ply(gem);
    else if (ext == ".pov") text = pov_gem_declaration(gem);
    else if (ext == ".asc" && gem.description.empty()) text = gemcad_text(brilliant_design(gem));
    else
        throw InputError("output file '" + path + "': unknown extension '" + ext +
                         "' (allowed: .obj, .off, .ply, .pov" + (gem.description.empty() ? ", .asc" : "") + ")");
    write_file_atomic(path, text);  // geometry/atomic_file.h: the one atomic writer
}

}  // namespace refract
