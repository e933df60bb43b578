// The exact round-brilliant construction (CGAL; the half-space intersection is exact_hull.cpp).
// Planes go through exactly constructed points (CGAL's Exact_predicates_exact_constructions
// kernel), so the points where four to eight facets meet are single points, not clusters
// joined by 1e-17 edges; CGAL::halfspace_intersection_3 gives the polyhedron, one polygon per
// plane; we drop repeated and collinear vertices, measure the proportions on the exact result,
// and convert to double only at the end. The construction is described in docs/gems.md.
#include <algorithm>

#include <refract/geometry/constants.h>
#include <cmath>
#include <map>
#include <stdexcept>
#include <variant>

#include <refract/geometry/error.h>
#include <refract/geometry/gem/brilliant.h>
#include <refract/geometry/gem/exact_hull.h>

namespace refract {
namespace {

using exact::dbl;
using exact::FT;
using exact::Loop;
using exact::P3;
using exact::Pl;
using exact::V3;


[[noreturn]] void degenerate(const std::string& why) {
    throw InputError("brilliant cut: these parameters give a degenerate brilliant (" + why + ")");
}

using exact::Dir;
using exact::unit;

P3 meet(const Pl& a, const Pl& b, const Pl& c) {
    const auto r = CGAL::intersection(a, b, c);
    if (r)
        if (const P3* p = boost::get<P3>(&*r)) return *p;
    degenerate("three facet planes do not meet in one point");
}

// The plane through a, b, c oriented so that the origin is strictly on its negative side.
Pl outward(const P3& a, const P3& b, const P3& c) {
    if (CGAL::collinear(a, b, c)) degenerate("a facet is defined by three collinear points");
    const Pl p(a, b, c);
    switch (p.oriented_side(P3(CGAL::ORIGIN))) {
        case CGAL::ON_NEGATIVE_SIDE: return p;
        case CGAL::ON_POSITIVE_SIDE: return p.opposite();
        default: degenerate("a facet plane passes through the centre");
    }
}

// Vertical plane {p : (cos ψ, sin ψ, 0)·p = ρ}: cuts a ridge at azimuth ψ at distance ρ.
Pl at_distance(const Dir& d, double rho) { return Pl(P3(rho * d.c, rho * d.s, 0), V3(d.c, d.s, 0)); }

struct Construction {
    std::vector<Pl> planes;
    std::vector<std::string> labels;
    void add(const Pl& p, std::string label) {
        planes.push_back(p);
        labels.push_back(std::move(label));
    }
};

std::string idx(const char* kind, int k, const char* suffix = "") {
    return std::string(kind) + " " + std::to_string(k) + suffix;
}

Construction construct(const BrilliantCut& cut) {
    const double g = cut.girdle / 100;  // half the girdle thickness, in units of R (D = 2)
    const double t = cut.table / 100, s = cut.star / 100, l = cut.lower_half / 100,
                 c = cut.culet / 100;
    const double tb = std::tan(cut.crown_angle * kPi / 180), ta = std::tan(cut.pavilion_angle * kPi / 180);
    const double zT = g + (1 - t) * tb;  // table plane
    const double c225 = std::cos(22.5 * kPi / 180);
    const double rho_e = t * c225, rho_s = rho_e + s * (1 - rho_e), rho_l = 1 - l;

    Dir phi[8], psi[8];
    P3 G[8], M[8], V[8], W[8], T[8], S[8], L[8];
    Pl bezel[8], pmain[8];
    const P3 crown_apex(0, 0, g + tb), culet_apex(0, 0, -g - ta);
    const Pl table(FT(0), FT(0), FT(1), FT(-zT));
    for (int k = 0; k < 8; ++k) {
        phi[k] = unit(45.0 * k);
        psi[k] = unit(45.0 * k + 22.5);
        G[k] = P3(phi[k].c, phi[k].s, g);
        M[k] = P3(phi[k].c, phi[k].s, -g);
        V[k] = P3(psi[k].c, psi[k].s, g);
        W[k] = P3(psi[k].c, psi[k].s, -g);
        const V3 tangent(-phi[k].s, phi[k].c, 0);
        // Bezel k: through G_k, slope β along φk (through the virtual crown apex).
        bezel[k] = outward(G[k], crown_apex, G[k] + tangent);
        // Pavilion main k: through M_k and the pointed culet apex, slope α along φk.
        pmain[k] = outward(M[k], culet_apex, M[k] + tangent);
        T[k] = meet(table, bezel[k], Pl(P3(CGAL::ORIGIN), tangent));
    }
    for (int k = 0; k < 8; ++k) {
        const int n = (k + 1) % 8;
        S[k] = meet(bezel[k], bezel[n], at_distance(psi[k], rho_s));
        L[k] = meet(pmain[k], pmain[n], at_distance(psi[k], rho_l));
    }

    Construction out;
    out.add(table, "table");
    for (int k = 0; k < 8; ++k) out.add(outward(T[k], T[(k + 1) % 8], S[k]), idx("star", k));
    for (int k = 0; k < 8; ++k) out.add(bezel[k], idx("bezel", k));
    // Upper halves flank bezel k: "k-" towards ψ(k−1), "k+" towards ψk.
    for (int k = 0; k < 8; ++k) {
        const int p = (k + 7) % 8;
        out.add(outward(S[p], V[p], G[k]), idx("upper half", k, "-"));
        out.add(outward(S[k], G[k], V[k]), idx("upper half", k, "+"));
    }
    const int n_girdle = girdle_plane_count(cut);
    for (int j = 0; j < n_girdle; ++j) {
        const Dir d = unit(360.0 * j / n_girdle);  // tangent to the unit circle at this azimuth
        out.add(Pl(P3(d.c, d.s, 0), V3(d.c, d.s, 0)), idx("girdle", j));
    }
    for (int k = 0; k < 8; ++k) {
        const int p = (k + 7) % 8;
        out.add(outward(L[p], W[p], M[k]), idx("lower half", k, "-"));
        out.add(outward(L[k], M[k], W[k]), idx("lower half", k, "+"));
    }
    for (int k = 0; k < 8; ++k) out.add(pmain[k], idx("pavilion main", k));
    if (c > 0) out.add(Pl(FT(0), FT(0), FT(-1), FT(-g - (1 - c) * ta)), "culet");
    return out;
}

// Expected polygon sizes; a mismatch means the parameters slipped past validation into a
// different combinatorial cut, which we refuse rather than hand on.
int expected_vertices(const std::string& kind, const std::string& label, const BrilliantCut& cut) {
    const int n = girdle_plane_count(cut);
    const int halves = cut.girdle > 0 ? 3 + n / 16 : 3;
    if (kind == "table" || kind == "culet") return 8;
    if (kind == "star") return 3;
    if (kind == "bezel") return 4;
    if (kind == "upper half" || kind == "lower half") return halves;
    if (kind == "pavilion main") return cut.culet > 0 ? 5 : 4;
    // girdle j: six vertices where it touches a bezel/main or a half junction, else four
    const int j = std::stoi(label.substr(label.find_last_of(' ') + 1));
    return (j % (n / 16) == 0) ? 6 : 4;
}

double rho(const P3& p) { return std::sqrt(dbl(p.x() * p.x() + p.y() * p.y())); }

const P3& lowest(const Loop& l) {
    return *std::min_element(l.begin(), l.end(), [](const P3& a, const P3& b) { return a.z() < b.z(); });
}
const P3& highest(const Loop& l) {
    return *std::max_element(l.begin(), l.end(), [](const P3& a, const P3& b) { return a.z() < b.z(); });
}
Loop common(const Loop& a, const Loop& b) {
    Loop out;
    for (const P3& p : a)
        if (std::find(b.begin(), b.end(), p) != b.end()) out.push_back(p);
    return out;
}
double degrees(double r) { return r * 180 / kPi; }

BrilliantProportions measure(const std::map<std::string, Loop>& faces, const std::map<std::string, Pl>& planes) {
    const auto face = [&](const std::string& l) -> const Loop& { return faces.at(l); };
    BrilliantProportions m;
    const P3 G0 = lowest(face("bezel 0"));           // girdle top at the bezel position
    const P3 M0 = highest(face("pavilion main 0"));  // girdle bottom at the main position
    const double D = 2 * rho(G0);
    const Loop& table = face("table");
    const FT zT = table[0].z();
    FT zmin = zT;
    for (const auto& f : faces)
        for (const P3& p : f.second) zmin = CGAL::min(zmin, p.z());

    FT widest = 0;  // table corner to corner
    for (const P3& a : table)
        for (const P3& b : table) widest = CGAL::max(widest, CGAL::squared_distance(a, b));
    m.table = 100 * std::sqrt(dbl(widest)) / D;
    m.crown_height = 100 * dbl(zT - G0.z()) / D;
    m.girdle = 100 * dbl(G0.z() - M0.z()) / D;
    m.pavilion_depth = 100 * dbl(M0.z() - zmin) / D;
    m.total_depth = 100 * dbl(zT - zmin) / D;

    const Pl& bz = planes.at("bezel 0");
    const Pl& pm = planes.at("pavilion main 0");
    m.crown_angle = degrees(std::atan2(std::sqrt(dbl(bz.a() * bz.a() + bz.b() * bz.b())), dbl(bz.c())));
    m.pavilion_angle = degrees(std::atan2(std::sqrt(dbl(pm.a() * pm.a() + pm.b() * pm.b())), -dbl(pm.c())));

    // Star: tip S0, table-edge midpoint, girdle at the half junction V0 (all along ψ0).
    const Loop& star = face("star 0");
    const P3 S0 = lowest(star);
    Loop edge;
    for (const P3& p : star)
        if (p != S0) edge.push_back(p);
    const double rho_e = rho(CGAL::midpoint(edge[0], edge[1]));
    const P3 V0 = lowest(common(face("upper half 0+"), face("upper half 1-")));
    m.star = 100 * (rho(S0) - rho_e) / (rho(V0) - rho_e);

    // Lower half: point L0 on the main ridge, girdle at the half junction W0.
    const P3 L0 = highest(common(face("pavilion main 0"), face("pavilion main 1")));
    const P3 W0 = highest(common(face("lower half 0+"), face("lower half 1-")));
    m.lower_half = 100 * (rho(W0) - rho(L0)) / rho(W0);

    const auto culet = faces.find("culet");
    if (culet != faces.end()) {  // across the flats: twice the nearest edge midpoint
        const Loop& cl = culet->second;
        double r = rho(CGAL::midpoint(cl.back(), cl.front()));
        for (std::size_t i = 0; i + 1 < cl.size(); ++i) r = std::min(r, rho(CGAL::midpoint(cl[i], cl[i + 1])));
        m.culet = 100 * 2 * r / D;
    }
    return m;
}

}  // namespace

Gem build_brilliant(const BrilliantCut& cut) {
    validate(cut);
    const Construction con = construct(cut);

    const std::vector<Loop> loops = exact::facet_loops(con.planes, P3(CGAL::ORIGIN), degenerate);

    std::map<std::string, Loop> faces;
    std::map<std::string, Pl> planes;
    for (std::size_t i = 0; i < loops.size(); ++i) {
        const std::string& label = con.labels[i];
        const std::string kind = facet_kind(label);
        if (loops[i].empty()) {
            if (kind == "girdle" && cut.girdle == 0) continue;  // knife edge: no girdle facets
            degenerate("facet '" + label + "' vanishes");
        }
        const int want = expected_vertices(kind, label, cut);
        if (static_cast<int>(loops[i].size()) != want)
            degenerate("facet '" + label + "' has " + std::to_string(loops[i].size()) + " vertices, expected " +
                       std::to_string(want));
        faces[label] = loops[i];
        planes.emplace(label, con.planes[i]);
    }

    Gem gem;
    gem.cut = cut;
    gem.measured = measure(faces, planes);

    exact::append_facets(gem, con.planes, con.labels, loops);
    return gem;
}

Shape tracing_shape(const Gem& gem) {
    if (gem.convex) return gem.solid;
    return gem.mesh;
}

namespace {
// The facet of each hit index, by the kind of shape that traces the gem (hit_facets).
std::vector<int> facet_of_hit(const ConvexPolyhedron& c, const Gem&) {
    std::vector<int> f(c.planes.size());
    for (size_t i = 0; i < f.size(); ++i) f[i] = static_cast<int>(i);
    return f;
}
std::vector<int> facet_of_hit(const TriangleMesh&, const Gem& gem) { return gem.triangle_facet; }
std::vector<int> facet_of_hit(const Sphere&, const Gem&) {
    throw std::logic_error("a gem is traced as a plane set or a mesh, not a sphere");
}
std::vector<int> facet_of_hit(const Plane&, const Gem&) {
    throw std::logic_error("a gem is traced as a plane set or a mesh, not a plane");
}
}  // namespace

std::vector<int> hit_facets(const Gem& gem) {
    return std::visit([&](const auto& s) { return facet_of_hit(s, gem); }, tracing_shape(gem));
}

}  // namespace refract
