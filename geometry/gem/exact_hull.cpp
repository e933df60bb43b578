// The exact half-space intersection shared by the gem builders (exact_hull.h): the one
// translation unit that instantiates CGAL::halfspace_intersection_3.
#include <CGAL/Convex_hull_3/dual/halfspace_intersection_3.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <refract/geometry/gem/exact_hull.h>

namespace refract::exact {
namespace {

// Removes repeated vertices (where four or more planes meet, the dual hull is triangulated
// and the primal face repeats the vertex) and vertices in the middle of a straight edge.
void clean(Loop& loop) {
    Loop out;
    for (const P3& p : loop)
        if (out.empty() || out.back() != p) out.push_back(p);
    while (out.size() > 1 && out.front() == out.back()) out.pop_back();
    bool changed = true;
    while (changed && out.size() >= 3) {
        changed = false;
        for (std::size_t i = 0; i < out.size(); ++i) {
            const std::size_t n = out.size();
            if (CGAL::collinear(out[(i + n - 1) % n], out[i], out[(i + 1) % n])) {
                out.erase(out.begin() + static_cast<long>(i));
                changed = true;
                break;
            }
        }
    }
    loop.swap(out);
}

struct LessXYZ {
    bool operator()(const P3& a, const P3& b) const { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; }
};

}  // namespace

Dir unit(double deg) {
    constexpr double kPi = 3.14159265358979323846;
    deg = std::fmod(deg, 360.0);
    if (deg < 0) deg += 360.0;
    const int q = static_cast<int>(deg / 90.0);
    const double r = (deg - 90.0 * q) * kPi / 180.0;
    const double c = std::cos(r), s = std::sin(r);
    switch (q & 3) {
        case 0: return {c, s};
        case 1: return {-s, c};
        case 2: return {-c, -s};
        default: return {s, -c};
    }
}

double dbl(const FT& x) { return CGAL::to_double(CGAL::exact(x)); }

std::vector<Loop> facet_loops(const std::vector<Pl>& planes, const P3& inside, Fail fail) {
    CGAL::Surface_mesh<P3> hull;
    try {
        CGAL::halfspace_intersection_3(planes.begin(), planes.end(), hull, boost::optional<P3>(inside));
    } catch (const CGAL::Failure_exception& e) {
        fail(std::string("CGAL: ") + e.what());
    }

    // One polygon per plane: identify each face's plane by exact incidence.
    std::vector<Loop> loops(planes.size());
    for (auto f : hull.faces()) {
        Loop loop;
        for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) loop.push_back(hull.point(v));
        clean(loop);
        if (loop.size() < 3) continue;  // a plane touching the gem in a point or an edge
        std::size_t i = 0;
        while (i < planes.size() &&
               !(planes[i].has_on(loop[0]) && planes[i].has_on(loop[1]) && planes[i].has_on(loop[2])))
            ++i;
        if (i == planes.size() || !loops[i].empty()) fail("a face matches no single facet plane");
        const V3 n = CGAL::cross_product(loop[1] - loop[0], loop[2] - loop[1]);
        if (n * planes[i].orthogonal_vector() < 0) std::reverse(loop.begin(), loop.end());
        loops[i] = std::move(loop);
    }
    return loops;
}

void append_facets(Gem& gem, const std::vector<Pl>& planes, const std::vector<std::string>& labels,
                   const std::vector<Loop>& loops) {
    // To doubles: shared vertices (exactly equal points become one vertex), unit planes.
    std::map<P3, int, LessXYZ> ids;
    for (std::size_t i = 0; i < loops.size(); ++i) {
        if (loops[i].empty()) continue;
        GemFacet f;
        f.label = labels[i];
        const Pl& p = planes[i];
        const double a = dbl(p.a()), b = dbl(p.b()), c = dbl(p.c()), d = dbl(p.d());
        const double norm = std::sqrt(a * a + b * b + c * c);
        f.plane.normal = Vec3(a, b, c) / norm;
        f.plane.offset = -d / norm;
        for (const P3& q : loops[i]) {
            auto it = ids.find(q);
            if (it == ids.end()) {
                it = ids.emplace(q, static_cast<int>(gem.mesh.vertices.size())).first;
                gem.mesh.vertices.emplace_back(dbl(q.x()), dbl(q.y()), dbl(q.z()));
            }
            f.vertex_ids.push_back(it->second);
            f.polygon.push_back(gem.mesh.vertices[static_cast<std::size_t>(it->second)]);
        }
        append_facet(gem, std::move(f));
    }
}

void append_facet(Gem& gem, GemFacet f) {
    const int facet = static_cast<int>(gem.facets.size());
    for (std::size_t v = 1; v + 1 < f.vertex_ids.size(); ++v) {
        gem.mesh.triangles.emplace_back(f.vertex_ids[0], f.vertex_ids[v], f.vertex_ids[v + 1]);
        gem.triangle_facet.push_back(facet);
    }
    gem.solid.planes.push_back(f.plane);
    gem.solid.labels.push_back(f.label);
    gem.facets.push_back(std::move(f));
}

}  // namespace refract::exact
