// A convex preform minus a convex notch (exact_cleft.h): both become Nef polyhedra, their
// regularised difference is converted back to a triangulated surface. The one translation
// unit that instantiates CGAL::Nef_polyhedron_3.
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <map>

#include <refract/geometry/gem/exact_cleft.h>

namespace refract::exact {
namespace {

using Nef = CGAL::Nef_polyhedron_3<K>;
using Mesh = CGAL::Surface_mesh<P3>;

// The loops as a closed polygon mesh (exactly equal points one vertex).
Mesh mesh_of_loops(const std::vector<Loop>& loops, Fail fail) {
    Mesh m;
    std::map<P3, Mesh::Vertex_index, LessPoint> ids;
    for (const Loop& l : loops) {
        if (l.empty()) continue;
        std::vector<Mesh::Vertex_index> f;
        for (const P3& p : l) {
            auto it = ids.find(p);
            if (it == ids.end()) it = ids.emplace(p, m.add_vertex(p)).first;
            f.push_back(it->second);
        }
        if (m.add_face(f) == Mesh::null_face()) fail("a convex solid's faces do not form a closed surface");
    }
    if (!CGAL::is_closed(m)) fail("a convex solid's faces leave it open");
    return m;
}

}  // namespace

Difference convex_difference(const std::vector<Loop>& solid, const std::vector<Loop>& notch, Fail fail) {
    Difference out;
    try {
        const Nef a(mesh_of_loops(solid, fail)), b(mesh_of_loops(notch, fail));
        const Nef r = (a - b).regularization();
        out.pieces = static_cast<int>(r.number_of_volumes()) - 1;  // less the unbounded outside
        if (r.is_empty()) return out;
        if (!r.is_simple()) fail("the stone is not a simple closed surface (pieces touch along an edge or in a point)");
        std::vector<P3> points;
        std::vector<std::vector<std::size_t>> polygons;
        CGAL::convert_nef_polyhedron_to_polygon_soup(r, points, polygons, true);
        for (const auto& p : polygons) {
            if (p.size() != 3) fail("a face of the stone was not triangulated");
            out.triangles.push_back({points[p[0]], points[p[1]], points[p[2]]});
        }
    } catch (const CGAL::Failure_exception& e) {
        fail(std::string("CGAL: ") + e.what());
    }
    return out;
}

}  // namespace refract::exact
