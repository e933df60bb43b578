// A GemCad design built exactly (gemcad.h): every tier's facets become exact planes (their
// double coefficients taken as exact numbers), the stone is their half-space intersection
// (exact_hull.h, the brilliant's machinery), then it is checked closed and convex and measured.
// A design with cleft tiers: that intersection of the other tiers is the preform, the notch
// (the preform's part outside every cleft facet) is removed from it exactly (exact_cleft.h),
// and the stone is checked closed and convex except at its cleft.
#include <CGAL/Convex_hull_3/dual/halfspace_intersection_interior_point_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/gem/exact_cleft.h>
#include <refract/geometry/gem/exact_hull.h>
#include <refract/geometry/gem/gemcad.h>

namespace refract {
namespace {

using namespace exact;

struct Planes {
    std::vector<Pl> planes;
    std::vector<std::string> labels;
    std::vector<int> tier;  // tier number (1-based) of each plane; 0 for the bounding box
};

std::string index_text(double i) { return format_shortest(i); }

// The preform's tiers (every tier but the cleft's), or the cleft's alone.
enum class Which { Preform, Cleft };

// The facets of tiers 1..upto of one kind (Which), the preform's after the six planes of a
// box far outside every facet (so that the intersection is bounded whatever the tiers are;
// a box face left on the stone means the tiers do not close it).
Planes design_planes(const GemcadDesign& d, std::size_t upto, Which which = Which::Preform) {
    Planes p;
    double far = 1;
    for (const GemcadTier& t : d.tiers) far = std::max(far, std::fabs(t.distance));
    far *= 1e3;
    static const char* const kBox[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    for (int k = 0; k < 6 && which == Which::Preform; ++k) {
        const double s = k % 2 ? -1 : 1;
        const int axis = k / 2;
        p.planes.emplace_back(axis == 0 ? s : 0.0, axis == 1 ? s : 0.0, axis == 2 ? s : 0.0, -far);
        p.labels.push_back(kBox[k]);
        p.tier.push_back(0);
    }
    for (std::size_t k = 0; k < upto && k < d.tiers.size(); ++k) {
        const GemcadTier& t = d.tiers[k];
        if (is_cleft_tier(t, static_cast<int>(k) + 1) != (which == Which::Cleft)) continue;
        const Dir a = unit(t.angle);  // (cos, sin) of the angle to the girdle plane
        const double nz = t.pavilion ? -a.c : a.c;
        for (std::size_t j = 0; j < t.indices.size(); ++j) {
            const Dir az = unit(360.0 * (t.indices[j] - d.location) / d.gear - 90.0);
            p.planes.emplace_back(a.s * az.c, a.s * az.s, nz, -t.distance);
            const std::string name = t.names[j].empty() ? t.name(static_cast<int>(k) + 1) : t.names[j];
            p.labels.push_back(name + " " + index_text(t.indices[j]));
            p.tier.push_back(static_cast<int>(k) + 1);
        }
    }
    return p;
}

std::string tier_text(const GemcadDesign& d, int k) {
    const GemcadTier& t = d.tiers[static_cast<std::size_t>(k - 1)];
    return "tier " + std::to_string(k) + " ('" + clip_echo(t.name(k)) + "'" +
           (t.line > 0 ? ", line " + std::to_string(t.line) : std::string()) + ")";
}

// A point strictly inside every plane, if the solid has any volume.
boost::optional<P3> interior_point(const std::vector<Pl>& planes) {
    bool origin = true;
    for (const Pl& p : planes) origin = origin && p.has_on_negative_side(P3(CGAL::ORIGIN));
    if (origin) return P3(CGAL::ORIGIN);
    const auto q = CGAL::halfspace_intersection_interior_point_3(planes.begin(), planes.end());
    if (!q) return boost::none;
    for (const Pl& p : planes)
        if (!p.has_on_negative_side(*q)) return boost::none;  // a flat (zero-volume) remainder
    return q;
}

thread_local std::string t_source;  // the design being built, for refuse()
[[noreturn]] void refuse(const std::string& why) {
    throw InputError(t_source + ": the design's facets give a degenerate stone (" + why + ")");
}

// Merges vertices closer than `tol` (the slivers left where a design's rounded angles and
// distances make several facets meet almost, not exactly, in one point), drops facets that
// shrink below three vertices, and rebuilds the mesh.
void merge_close_vertices(Gem& gem, double tol) {
    const auto& v = gem.mesh.vertices;
    std::vector<int> rep(v.size());
    std::iota(rep.begin(), rep.end(), 0);
    const auto find = [&](int i) {
        while (rep[static_cast<std::size_t>(i)] != i) i = rep[static_cast<std::size_t>(i)];
        return i;
    };
    for (std::size_t i = 0; i < v.size(); ++i)
        for (std::size_t j = i + 1; j < v.size(); ++j)
            if ((v[i] - v[j]).norm() < tol) {
                const int a = find(static_cast<int>(i)), b = find(static_cast<int>(j));
                if (a != b) rep[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
            }
    Gem out;
    out.cut = gem.cut;
    std::map<int, int> ids;
    for (const GemFacet& f : gem.facets) {
        std::vector<int> loop;
        for (int id : f.vertex_ids) {
            const int r = find(id);
            if (loop.empty() || loop.back() != r) loop.push_back(r);
        }
        while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
        if (loop.size() < 3) continue;
        GemFacet g;
        g.label = f.label;
        g.plane = f.plane;
        for (int r : loop) {
            auto it = ids.find(r);
            if (it == ids.end()) {
                it = ids.emplace(r, static_cast<int>(out.mesh.vertices.size())).first;
                out.mesh.vertices.push_back(v[static_cast<std::size_t>(r)]);
            }
            g.vertex_ids.push_back(it->second);
            g.polygon.push_back(v[static_cast<std::size_t>(r)]);
        }
        exact::append_facet(out, std::move(g));
    }
    gem = std::move(out);
}

// Closed (every edge shared by exactly two facets, in opposite directions; Euler
// characteristic 2) and convex (every vertex on or inside every facet plane, within `tol`).
// The facets marked in `exempt` (a cleft's; null: none) are left out of the convexity test.
void check_closed_convex(const Gem& gem, double tol, const std::vector<bool>* exempt = nullptr) {
    std::map<std::pair<int, int>, int> edges;
    for (const GemFacet& f : gem.facets)
        for (std::size_t k = 0; k < f.vertex_ids.size(); ++k)
            ++edges[{f.vertex_ids[k], f.vertex_ids[(k + 1) % f.vertex_ids.size()]}];
    for (const auto& [e, n] : edges) {
        const auto back = edges.find({e.second, e.first});
        if (n != 1 || back == edges.end() || back->second != 1)
            refuse("the facets do not close: an edge is not shared by exactly two facets");
    }
    const long V = static_cast<long>(gem.mesh.vertices.size()), E = static_cast<long>(edges.size() / 2),
               F = static_cast<long>(gem.facets.size());
    if (V - E + F != 2) refuse("Euler characteristic " + std::to_string(V - E + F) + ", not 2");
    for (std::size_t k = 0; k < gem.facets.size(); ++k) {
        if (exempt && (*exempt)[k]) continue;
        const GemFacet& f = gem.facets[k];
        for (const Vec3& p : gem.mesh.vertices)
            if (f.plane.normal.dot(p) - f.plane.offset > tol)
                refuse(std::string(exempt ? "not convex away from the cleft" : "not convex") +
                       ": a vertex lies outside facet '" + f.label + "'");
    }
}

struct Extent {
    double width, length;
};

// The narrowest caliper width of the points seen along z, and the extent across it.
Extent caliper(const std::vector<Vec3>& pts) {
    std::vector<std::array<double, 2>> p;
    for (const Vec3& q : pts) p.push_back({q.x(), q.y()});
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    const auto cross = [](const std::array<double, 2>& o, const std::array<double, 2>& a,
                          const std::array<double, 2>& b) {
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    };
    std::vector<std::array<double, 2>> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {  // Andrew's monotone chain
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k > 0 ? k - 1 : 0);
    Extent best{std::numeric_limits<double>::infinity(), 0};
    for (std::size_t i = 0; i < h.size(); ++i) {
        const auto& a = h[i];
        const auto& b = h[(i + 1) % h.size()];
        const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
        if (len == 0) continue;
        double w = 0, lo = 0, hi = 0;
        for (const auto& q : h) {
            w = std::max(w, std::fabs(ex * (q[1] - a[1]) - ey * (q[0] - a[0])) / len);
            const double along = (ex * (q[0] - a[0]) + ey * (q[1] - a[1])) / len;
            lo = std::min(lo, along);
            hi = std::max(hi, along);
        }
        if (w < best.width) best = {w, hi - lo};
    }
    return best;
}

// The exact volume inside closed, outward loops (or triangles): the divergence theorem.
template <class Faces>
FT volume_of(const Faces& faces) {
    FT v = 0;
    for (const auto& l : faces)
        for (std::size_t k = 1; k + 1 < l.size(); ++k)
            v += CGAL::determinant(l[0] - CGAL::ORIGIN, l[k] - CGAL::ORIGIN, l[k + 1] - CGAL::ORIGIN);
    return v / 6;
}

void measure_extent(DesignGem& out) {
    const Extent e = caliper(out.gem.mesh.vertices);
    out.width = e.width;
    out.length = e.length;
    double zlo = out.gem.mesh.vertices.front().z(), zhi = zlo;
    for (const Vec3& v : out.gem.mesh.vertices) {
        zlo = std::min(zlo, v.z());
        zhi = std::max(zhi, v.z());
    }
    out.height = zhi - zlo;
}

DesignGem build_preform(const GemcadDesign& d);
void grind_cleft(const GemcadDesign& d, DesignGem& out);

}  // namespace

DesignGem build_design(const GemcadDesign& d) {
    t_source = d.source;
    DesignGem out = build_preform(d);
    out.preform_volume = out.volume;
    for (std::size_t k = 0; k < d.tiers.size(); ++k)
        if (is_cleft_tier(d.tiers[k], static_cast<int>(k) + 1)) {
            grind_cleft(d, out);
            break;
        }
    return out;
}

namespace {

DesignGem build_preform(const GemcadDesign& d) {
    const Planes all = design_planes(d, d.tiers.size());
    const auto inside = interior_point(all.planes);
    if (!inside) {
        // Name the first tier after which nothing (of any volume) is left.
        for (std::size_t k = 1; k <= d.tiers.size(); ++k)
            if (!interior_point(design_planes(d, k).planes))
                throw InputError(d.source + ": " + tier_text(d, static_cast<int>(k)) +
                                 " cuts the stone away: nothing of the stone is left");
        throw InputError(d.source + ": the facets cut the stone away: nothing is left");
    }
    const std::vector<Loop> loops = facet_loops(all.planes, *inside, refuse);
    for (int k = 0; k < 6; ++k)
        if (!loops[static_cast<std::size_t>(k)].empty())
            throw InputError(d.source + ": the tiers do not close the stone: it is unbounded towards " + all.labels[k] +
                             " (" + (k == 4 ? "no crown facet or table" : k == 5 ? "no pavilion facet or culet" : "no girdle facet") +
                             " closes that side)");

    DesignGem out;
    out.planes = static_cast<int>(all.planes.size()) - 6;
    out.volume = dbl(volume_of(loops));

    append_facets(out.gem, all.planes, all.labels, loops);
    double size = 0;
    for (const Vec3& v : out.gem.mesh.vertices) size = std::max(size, v.norm());
    merge_close_vertices(out.gem, 1e-7 * size);
    check_closed_convex(out.gem, 1e-9 * size);
    measure_extent(out);
    return out;
}

// The facet loops of one plane's triangles: one loop per edge-connected patch (its boundary,
// counter-clockwise seen from outside); refused when a patch has a hole or pinches.
std::vector<std::vector<int>> patch_loops(const std::vector<std::array<int, 3>>& tris) {
    const std::size_t n = tris.size();
    std::vector<std::size_t> rep(n);
    std::iota(rep.begin(), rep.end(), std::size_t{0});
    const auto find = [&](std::size_t i) {
        while (rep[i] != i) i = rep[i] = rep[rep[i]];
        return i;
    };
    std::map<std::pair<int, int>, std::size_t> edge_tri;
    for (std::size_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) edge_tri[{tris[t][k], tris[t][(k + 1) % 3]}] = t;
    for (const auto& [e, t] : edge_tri) {
        const auto back = edge_tri.find({e.second, e.first});
        if (back != edge_tri.end()) rep[find(t)] = find(back->second);
    }
    std::map<std::size_t, std::map<int, int>> next;  // patch -> boundary edge a -> b
    for (const auto& [e, t] : edge_tri)
        if (!edge_tri.count({e.second, e.first}))
            if (!next[find(t)].emplace(e.first, e.second).second) refuse("a facet of the stone pinches in a vertex");
    std::vector<std::vector<int>> loops;
    for (auto& [patch, nx] : next) {
        std::vector<int> loop{nx.begin()->first};
        for (int v = nx.begin()->second; v != loop.front(); v = nx.at(v)) {
            if (loop.size() > nx.size()) refuse("a facet's boundary does not close");
            loop.push_back(v);
        }
        if (loop.size() != nx.size()) refuse("a facet of the stone has a hole (the cleft lies inside a facet)");
        loops.push_back(std::move(loop));
    }
    return loops;
}

// Removes the notch (the preform's part outside every cleft facet) from the built preform
// `out`, replacing its gem by the stone with a cleft.
void grind_cleft(const GemcadDesign& d, DesignGem& out) {
    const Planes pre = design_planes(d, d.tiers.size(), Which::Preform);
    const Planes cl = design_planes(d, d.tiers.size(), Which::Cleft);
    const std::string cleft = tier_text(d, cl.tier.front());
    const std::vector<Loop> pre_loops = facet_loops(pre.planes, *interior_point(pre.planes), refuse);
    std::vector<Pl> notch = pre.planes;
    for (const Pl& p : cl.planes) notch.push_back(p.opposite());
    const auto in_notch = interior_point(notch);
    if (!in_notch)
        throw InputError(d.source + ": " + cleft +
                         ": the cleft removes nothing (no part of the stone lies outside every cleft facet)");
    const std::vector<Loop> notch_loops = facet_loops(notch, *in_notch, refuse);
    const Difference diff = convex_difference(pre_loops, notch_loops, refuse);
    if (diff.triangles.empty()) throw InputError(d.source + ": " + cleft + ": the cleft removes the whole stone");
    if (diff.pieces != 1)
        throw InputError(d.source + ": " + cleft + ": the cleft cuts the stone in " + std::to_string(diff.pieces) +
                         " pieces");
    const FT v_pre = volume_of(pre_loops), v_notch = volume_of(notch_loops), v = volume_of(diff.triangles);
    if (v != v_pre - v_notch) refuse("the stone's volume is not the preform's less the notch's");

    // Each triangle's plane: the preform's facets, then the cleft's (same orientation).
    std::vector<Pl> planes = pre.planes;
    std::vector<std::string> labels = pre.labels;
    planes.insert(planes.end(), cl.planes.begin(), cl.planes.end());
    labels.insert(labels.end(), cl.labels.begin(), cl.labels.end());
    const std::size_t first_cleft = pre.planes.size();
    std::map<P3, int, LessPoint> ids;
    std::vector<Vec3> vertices;
    std::map<std::size_t, std::vector<std::array<int, 3>>> by_plane;
    for (const auto& t : diff.triangles) {
        std::size_t i = 0;
        const V3 n = CGAL::cross_product(t[1] - t[0], t[2] - t[1]);
        while (i < planes.size() && !(planes[i].has_on(t[0]) && planes[i].has_on(t[1]) && planes[i].has_on(t[2]) &&
                                      n * planes[i].orthogonal_vector() > 0))
            ++i;
        if (i == planes.size()) refuse("a face of the stone lies on no facet plane");
        std::array<int, 3> tri{};
        for (int k = 0; k < 3; ++k) {
            auto it = ids.find(t[static_cast<std::size_t>(k)]);
            if (it == ids.end()) {
                const P3& q = t[static_cast<std::size_t>(k)];
                it = ids.emplace(q, static_cast<int>(vertices.size())).first;
                vertices.emplace_back(dbl(q.x()), dbl(q.y()), dbl(q.z()));
            }
            tri[static_cast<std::size_t>(k)] = it->second;
        }
        by_plane[i].push_back(tri);
    }

    Gem gem;
    gem.convex = false;
    gem.mesh.vertices = vertices;
    int cleft_facets = 0;
    std::vector<bool> on_cleft;  // per facet
    for (const auto& [i, tris] : by_plane) {
        const Pl& p = planes[i];
        const double a = dbl(p.a()), b = dbl(p.b()), c = dbl(p.c()), dd = dbl(p.d());
        const double norm = std::sqrt(a * a + b * b + c * c);
        for (std::vector<int>& loop : patch_loops(tris)) {
            GemFacet f;
            f.label = labels[i];
            f.plane.normal = Vec3(a, b, c) / norm;
            f.plane.offset = -dd / norm;
            for (int id : loop) f.polygon.push_back(vertices[static_cast<std::size_t>(id)]);
            f.vertex_ids = std::move(loop);
            const int facet = static_cast<int>(gem.facets.size());
            // The patch's own triangles (a patch of several facets: the ones of this loop).
            std::set<int> in(f.vertex_ids.begin(), f.vertex_ids.end());
            for (const auto& t : tris)
                if (in.count(t[0]) && in.count(t[1]) && in.count(t[2])) {
                    gem.mesh.triangles.emplace_back(t[0], t[1], t[2]);
                    gem.triangle_facet.push_back(facet);
                }
            on_cleft.push_back(i >= first_cleft);
            if (on_cleft.back()) ++cleft_facets;
            gem.solid.planes.push_back(f.plane);
            gem.solid.labels.push_back(f.label);
            gem.facets.push_back(std::move(f));
        }
    }
    if (gem.mesh.triangles.size() != diff.triangles.size()) refuse("a facet's triangles are not one patch");

    double size = 0;
    for (const Vec3& q : vertices) size = std::max(size, q.norm());
    check_closed_convex(gem, 1e-9 * size, &on_cleft);
    out.gem = std::move(gem);
    out.planes += static_cast<int>(cl.planes.size());
    out.volume = dbl(v);
    out.preform_volume = dbl(v_pre);
    out.notch_volume = dbl(v_notch);
    out.cleft_facets = cleft_facets;
    measure_extent(out);
}

}  // namespace

}  // namespace refract
