#include <refract/validation/random_geometry.h>

#include <charconv>
#include <map>

#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/geometry/gem/brilliant.h>

namespace refract::validation::random_detail {

double dsin(double x) {
    x -= 2 * kPi * std::floor(x / (2 * kPi) + 0.5);  // to [−π, π]
    const double x2 = x * x;
    double term = x, sum = x;
    for (int k = 1; k < 20; ++k) {
        term *= -x2 / ((2.0 * k) * (2.0 * k + 1));
        sum += term;
    }
    return sum;
}
double dcos(double x) { return dsin(x + kPi / 2); }
double rad(double degrees) { return degrees * (kPi / 180); }

double pow10(int k) {  // exact for 0 <= k <= 22
    double p = 1;
    for (int i = 0; i < k; ++i) p *= 10;
    return p;
}

double sig(double x, int digits) {
    const double a = std::fabs(x);
    if (!(a >= 1e-9)) return 0.0;
    int e = 0;  // 10^e <= a < 10^(e+1)
    if (a >= 1)
        while (e < 21 && a >= pow10(e + 1)) ++e;
    else
        while (a * pow10(-e) < 1) --e;
    const int k = digits - 1 - e;
    const double r = k >= 0 ? std::round(a * pow10(k)) / pow10(k) : std::round(a / pow10(-k)) * pow10(-k);
    return x < 0 ? -r : r;
}
double dec(double x, int places) {
    const double p = pow10(places);
    return std::round(x * p) / p + 0.0;
}
Vec3 sig3(const Vec3& v) { return {sig(v.x()), sig(v.y()), sig(v.z())}; }
Vec3 dec3(const Vec3& v, int places) { return {dec(v.x(), places), dec(v.y(), places), dec(v.z(), places)}; }
json arr(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

std::string num(double v) { return format_shortest(v); }  // shortest round-trip form (geometry/format.h)

Mat3 axis_angle(const Vec3& axis, double angle) {  // Rodrigues
    const Vec3 k = axis.normalized();
    Mat3 K;
    K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
    return Mat3::Identity() + dsin(angle) * K + (1 - dcos(angle)) * K * K;
}

bool apart(const Box& a, const Box& b, double gap) {
    for (int k = 0; k < 3; ++k)
        if (a.hi[k] + gap <= b.lo[k] || b.hi[k] + gap <= a.lo[k]) return true;
    return false;
}

std::optional<std::vector<Vec3>> vertices_within(std::vector<Half> h, const Vec3& c, double half) {
    const size_t n = h.size();
    for (int k = 0; k < 3; ++k) {
        Vec3 e = Vec3::Zero();
        e[k] = 1;
        h.push_back({e, c[k] + half});
        h.push_back({-e, half - c[k]});
    }
    const double tol = 1e-9 * (1 + half + c.norm());
    std::vector<Vec3> v;
    for (size_t i = 0; i < h.size(); ++i)
        for (size_t j = i + 1; j < h.size(); ++j) {
            const Vec3 ij = h[i].n.cross(h[j].n);
            for (size_t k = j + 1; k < h.size(); ++k) {
                const double det = h[k].n.dot(ij);
                if (std::abs(det) < 1e-12) continue;
                const Vec3 x =
                    (h[i].d * h[j].n.cross(h[k].n) + h[j].d * h[k].n.cross(h[i].n) + h[k].d * ij) / det;
                bool inside = true;
                for (const Half& q : h) inside = inside && q.n.dot(x) <= q.d + tol;
                if (!inside) continue;
                if (k >= n) return std::nullopt;  // the solid reaches the cube
                v.push_back(x);
            }
        }
    if (v.empty()) return std::nullopt;
    return v;
}

Box box_of(const std::vector<Vec3>& v) {
    Box b;
    for (const Vec3& p : v) b.add(p);
    return b;
}

bool closed_oriented(const MeshData& m) {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : m.t)
        for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, count] : edges) {
        const auto r = edges.find({e.second, e.first});
        if (count != 1 || r == edges.end() || r->second != 1) return false;
    }
    return true;
}

std::optional<MeshData> convex_hull(const std::vector<Vec3>& p) {
    double scale = 0;
    for (const Vec3& q : p) scale = std::max(scale, q.norm());
    const double eps = 1e-3 * scale;
    const int n = static_cast<int>(p.size());
    MeshData m;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k) {
                const Vec3 nn = (p[j] - p[i]).cross(p[k] - p[i]);
                const double len = nn.norm();
                if (len < 1e-9 * scale * scale) continue;
                int pos = 0, neg = 0, zero = 0;
                for (int l = 0; l < n; ++l) {
                    if (l == i || l == j || l == k) continue;
                    const double s = nn.dot(p[l] - p[i]) / len;
                    (s > eps ? pos : s < -eps ? neg : zero)++;
                }
                if (pos && neg) continue;
                if (zero) return std::nullopt;
                m.t.push_back(neg ? std::array<int, 3>{i, j, k} : std::array<int, 3>{i, k, j});
            }
    std::vector<int> index(p.size(), -1);
    for (auto& t : m.t)
        for (int& i : t) {
            if (index[i] < 0) {
                index[i] = static_cast<int>(m.v.size());
                m.v.push_back(p[i]);
            }
            i = index[i];
        }
    if (m.t.size() < 4 || !closed_oriented(m)) return std::nullopt;
    return m;
}

MeshData box_mesh() {  // vertex index = x + 2y + 4z, coordinates ±1
    MeshData m;
    for (int i = 0; i < 8; ++i) m.v.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.t.push_back({q[0], q[1], q[2]});
        m.t.push_back({q[0], q[2], q[3]});
    }
    return m;
}

std::vector<Vec3> platonic_points(int which) {  // 0 tetrahedron, 1 octahedron, 2 icosahedron
    if (which == 0) return {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    if (which == 1) return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const double f = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> v;
    for (double a : {-1.0, 1.0})
        for (double b : {-f, f}) {
            v.emplace_back(0, a, b);
            v.emplace_back(a, b, 0);
            v.emplace_back(b, 0, a);
        }
    return v;
}

bool reaches(const Solid& s, const Vec3& p, double margin) {
    if (s.sphere) return (p - s.centre).norm() < s.radius + margin;
    if (!s.planes.empty()) {
        for (const Half& q : s.planes)
            if (q.n.dot(p) > q.d + margin) return false;
        return true;
    }
    return s.box.contains(p, margin);
}

bool rectangle_cuts(const Solid& s, const Camera& cam, double margin) {
    const Camera::Basis b = cam.basis();
    const Vec3 corner = cam.location - 0.5 * b.R - 0.5 * b.U;
    if (s.sphere) {
        const Vec3 q = s.centre - corner;
        const double u = std::clamp(q.dot(b.R) / b.R.squaredNorm(), 0.0, 1.0);
        const double v = std::clamp(q.dot(b.U) / b.U.squaredNorm(), 0.0, 1.0);
        return (corner + u * b.R + v * b.U - s.centre).norm() <= s.radius + margin;
    }
    Box rect;
    for (const Vec3& p : {corner, Vec3(corner + b.R), Vec3(corner + b.U), Vec3(corner + b.R + b.U)}) rect.add(p);
    return !apart(rect, s.box, margin);
}

bool above(const std::vector<Half>& planes, const Vec3& p) {
    for (const Half& h : planes)
        if (h.n.dot(p) <= h.d + 0.05) return false;
    return true;
}

Mat3 orientation(Rand& rng) {
    switch (rng.pick({40, 30, 30})) {
        case 0: return axis_angle(Vec3::UnitY(), rng.uniform(0, 2 * kPi));
        case 1: {
            const Vec3 axis = rng.unit();
            return axis_angle(axis, rad(rng.uniform(5, 30)));
        }
        default: return rng.rotation();
    }
}

Template sphere_template(double size) {
    Template t;
    t.kind = Template::Sphere;
    t.radius = size;
    t.box = {Vec3::Constant(-size), Vec3::Constant(size)};
    t.desc = "sphere";
    return t;
}

Template hollow_template(Rand& rng, double size) {
    Template t = sphere_template(size);
    t.kind = Template::Hollow;
    if (rng.chance(0.15)) {  // two holes side by side
        const Vec3 axis = rng.unit();
        const double r1 = size * rng.uniform(0.25, 0.42);
        const double r2 = size * rng.uniform(0.25, 0.42);
        t.holes = {{0.5 * size * axis, r1}, {-0.5 * size * axis, r2}};
        t.desc = "hollow sphere (2 holes)";
    } else {
        const double r = size * rng.uniform(0.5, 0.95);
        Vec3 off = Vec3::Zero();
        if (rng.chance(0.5)) {
            const Vec3 dir = rng.unit();
            off = dir * (rng.uniform(0, 0.9) * (size - r));
        }
        t.holes = {{off, r}};
        t.desc = "hollow sphere";
    }
    return t;
}

Template mesh_template(Rand& rng, double size) {
    Template t;
    t.kind = Template::Mesh;
    const int kind = rng.pick({12, 12, 16, 12, 28, 20});
    std::optional<MeshData> m;
    if (kind <= 2) {
        m = convex_hull(platonic_points(kind));
        t.desc = kind == 0 ? "tetrahedron mesh" : kind == 1 ? "octahedron mesh" : "icosahedron mesh";
    } else if (kind == 3) {
        m = box_mesh();
        t.desc = "box mesh";
    } else {
        // Convex hull of random points (in a ball or on a sphere); star-shaped: the hull's
        // vertices moved along their rays from the centre (same cones, so still closed,
        // oriented and without self-intersection).
        const bool star = kind == 5;
        while (!m) {
            const bool on_sphere = star || rng.chance(0.5);
            const int n = on_sphere ? rng.integer(6, 40) : rng.integer(5, 14);
            std::vector<Vec3> p;
            for (int i = 0; i < n; ++i) {
                const Vec3 d = rng.unit();
                p.push_back(on_sphere ? d : Vec3(d * std::sqrt(rng.uniform(0.3, 1))));
            }
            m = convex_hull(p);
            if (m && star)
                for (Vec3& v : m->v) v *= rng.uniform(0.55, 1.15);
        }
        t.desc = star ? "star-shaped mesh" : "convex hull mesh";
    }
    // Random proportions, orientation and size (circumradius `size`).
    Vec3 stretch(1, 1, 1);
    if (rng.chance(0.5)) stretch = rng.box(0.6, 1.4);
    const Mat3 R = rng.rotation();
    double rmax = 0;
    for (Vec3& v : m->v) {
        v = R * stretch.cwiseProduct(v);
        rmax = std::max(rmax, v.norm());
    }
    for (Vec3& v : m->v) v *= size / rmax;
    t.mesh = *m;
    t.box = box_of(t.mesh.v);
    t.desc += " (" + std::to_string(t.mesh.t.size()) + " triangles)";
    return t;
}

Template polyhedron_template(Rand& rng, double size) {
    // k planes tangent to the unit sphere with random normals, bounded with every vertex
    // within 4 of the centre; after 20 tries the first four start from a tetrahedron.
    Template t;
    t.kind = Template::Poly;
    const int k = rng.integer(4, 30);
    std::optional<std::vector<Vec3>> v;
    for (int attempt = 0; !v; ++attempt) {
        t.planes.clear();
        const Mat3 R = rng.rotation();
        const std::vector<Vec3> tet = platonic_points(0);
        for (int i = 0; i < k; ++i) {
            Vec3 n = rng.unit();
            if (attempt >= 20 && i < 4) n = (R * tet[i].normalized() + 0.3 * n).normalized();
            t.planes.push_back({n, 1.0});
        }
        v = vertices_within(t.planes, Vec3::Zero(), 4.0);
    }
    double rmax = 0;
    for (const Vec3& p : *v) rmax = std::max(rmax, p.norm());
    for (Half& h : t.planes) h.d = size / rmax;
    for (Vec3& p : *v) p *= size / rmax;
    t.box = box_of(*v);
    t.desc = "random polyhedron (" + std::to_string(k) + " planes)";
    return t;
}

Template brilliant_like_template(Rand& rng, double size) {
    // Girdle radius 1, y up: a table, n crown planes through the girdle top at angle β,
    // g vertical girdle planes tangent to the unit circle, m pavilion planes through the
    // girdle bottom at angle α, an optional culet.
    Template t;
    t.kind = Template::Poly;
    const int n = rng.chance(0.4) ? 8 : rng.integer(3, 10);
    const int m = (2 * n <= 16 && rng.chance(0.5)) ? 2 * n : n;
    const bool culet = rng.chance(0.3);
    const int g = std::min(rng.integer(8, 32), 46 - 1 - n - m - (culet ? 1 : 0));
    const double beta = rad(rng.uniform(20, 45)), alpha = rad(rng.uniform(35, 50));
    const double table = rng.uniform(0.4, 0.75), h = rng.uniform(0.01, 0.08);
    const double phi0 = rng.uniform(0, 2 * kPi / n);
    const double psi0 = rng.chance(0.5) ? phi0 : rng.uniform(0, 2 * kPi / m);
    const double theta0 = rng.chance(0.5) ? phi0 : rng.uniform(0, 2 * kPi / g);
    const double c = culet ? rng.uniform(0.02, 0.15) : 0.0;
    const double sb = dsin(beta), cb = dcos(beta), sa = dsin(alpha), ca = dcos(alpha);
    auto add = [&](const Vec3& normal, double d, const std::string& label) {
        t.planes.push_back({normal, d});
        t.labels.push_back(label);
    };
    add(Vec3::UnitY(), h + (1 - table) * sb / cb, "table");
    for (int k = 0; k < n; ++k) {
        const double phi = phi0 + 2 * kPi * k / n;
        add(Vec3(sb * dcos(phi), cb, sb * dsin(phi)), sb + h * cb, "crown " + std::to_string(k));
    }
    for (int k = 0; k < g; ++k) {
        const double theta = theta0 + 2 * kPi * k / g;
        add(Vec3(dcos(theta), 0, dsin(theta)), 1.0, "girdle " + std::to_string(k));
    }
    for (int k = 0; k < m; ++k) {
        const double psi = psi0 + 2 * kPi * k / m;
        add(Vec3(sa * dcos(psi), -ca, sa * dsin(psi)), sa + h * ca, "pavilion " + std::to_string(k));
    }
    if (culet) add(-Vec3::UnitY(), h + (1 - c) * sa / ca, "culet");
    const Mat3 R = orientation(rng);
    for (Half& p : t.planes) {
        p.n = R * p.n;
        p.d *= size;
    }
    t.box = box_of(*vertices_within(t.planes, Vec3::Zero(), 4.0 * size));
    t.desc = "brilliant-like polyhedron (" + std::to_string(n) + "-fold crown, " + std::to_string(g) +
             " girdle planes, " + std::to_string(m) + "-fold pavilion" + (culet ? ", culet" : "") + ")";
    return t;
}

Template brilliant_template(Rand& rng, double size) {
    // The exact round brilliant with random parameters inside GIA's domain, checked by
    // validate(); girdles of 16 or 32 planes keep it cheap.
    Template t;
    t.kind = Template::Brilliant;
    BrilliantCut cut;
    cut.table = dec(rng.uniform(50, 66), 1);
    cut.crown_angle = dec(rng.uniform(28, 38), 1);
    cut.pavilion_angle = dec(rng.uniform(39, 42.5), 1);
    cut.star = dec(rng.uniform(45, 65), 1);
    cut.lower_half = dec(rng.uniform(70, 85), 1);
    const bool faceted = rng.chance(0.5);
    const int planes = rng.chance(0.5) ? 16 : 32;
    cut.girdle_facets = faceted ? planes : 0;
    cut.bruted_planes = planes;
    cut.culet = rng.chance(0.3) ? dec(rng.uniform(1, 5), 1) : 0.0;
    const bool knife = rng.chance(0.25);
    const double extra = rng.uniform(0.5, 3);
    cut.girdle = knife ? 0.0 : std::min(11.0, std::ceil((min_girdle_percent(cut) + extra) * 100) / 100);
    try {
        validate(cut);
    } catch (const InputError&) {
        cut = brilliant_preset("gia-default");  // its 3 % girdle keeps 32 bruted planes
        cut.bruted_planes = 32;
    }
    const int rot = rng.pick({40, 30, 30});
    const double rx = rng.uniform(-30, 30), ry = rng.uniform(0, 360), rz = rng.uniform(-30, 30);
    const double fx = rng.uniform(-180, 180), fz = rng.uniform(-180, 180);
    const Vec3 rotation = rot == 0 ? Vec3(0, dec(ry, 1), 0)
                          : rot == 1 ? Vec3(dec(rx, 1), dec(ry, 1), dec(rz, 1))
                                     : Vec3(dec(fx, 1), dec(ry, 1), dec(fz, 1));
    t.brilliant = {{"type", "brilliant"}, {"table", cut.table}, {"crown_angle", cut.crown_angle},
                   {"pavilion_angle", cut.pavilion_angle}, {"star", cut.star}, {"lower_half", cut.lower_half},
                   {"girdle", cut.girdle}, {"culet", cut.culet}, {"girdle_facets", cut.girdle_facets},
                   {"bruted_planes", cut.bruted_planes}, {"diameter", dec(2 * size, 4)}, {"rotation", arr(rotation)}};
    // Every vertex lies within the girdle polygon's corner radius (<= 1/cos(π/16) < 1.03)
    // horizontally and within the total depth of the girdle plane: a bounding sphere.
    const double depth = closed_form_proportions(cut).total_depth * 2 / 100;
    t.radius = dec(2 * size, 4) / 2 * std::sqrt(1.03 * 1.03 + depth * depth) * 1.001;
    t.box = {Vec3::Constant(-t.radius), Vec3::Constant(t.radius)};
    t.desc = "brilliant (" +
             (cut.girdle_facets ? std::to_string(cut.girdle_facets) + " girdle facets"
                                : "bruted " + std::to_string(cut.bruted_planes)) +
             (cut.girdle == 0 ? ", knife edge" : "") + ")";
    return t;
}

std::optional<Solid> place(const Template& t, const Vec3& p, const std::string& name, bool transparent) {
    Solid s;
    s.desc = t.desc;
    s.transparent = transparent;
    json o = {{"name", name}};
    switch (t.kind) {
        case Template::Sphere:
        case Template::Hollow: {
            s.sphere = true;
            s.centre = sig3(p);
            s.radius = sig(t.radius);
            s.box = {s.centre - Vec3::Constant(s.radius), s.centre + Vec3::Constant(s.radius)};
            o["type"] = "sphere";
            o["center"] = arr(s.centre);
            o["radius"] = s.radius;
            s.objects.push_back(o);
            for (size_t k = 0; k < t.holes.size(); ++k) {
                json hole = {{"type", "sphere"}, {"name", name + " hole " + std::to_string(k)},
                             {"center", arr(sig3(p + t.holes[k].first))}, {"radius", -sig(t.holes[k].second)}};
                s.objects.push_back(hole);
            }
            break;
        }
        case Template::Mesh: {
            o["type"] = "mesh";
            o["vertices"] = json::array();
            for (const Vec3& v : t.mesh.v) {
                const Vec3 q = sig3(v + p);
                s.box.add(q);
                o["vertices"].push_back(arr(q));
            }
            o["triangles"] = json::array();
            for (const auto& tri : t.mesh.t) o["triangles"].push_back(json::array({tri[0], tri[1], tri[2]}));
            s.objects.push_back(o);
            break;
        }
        case Template::Poly: {
            o["type"] = "polyhedron";
            o["planes"] = json::array();
            for (const Half& h : t.planes) {
                const Vec3 n = sig3(h.n);
                const double d = sig(h.d + h.n.dot(p));
                o["planes"].push_back(json::array({n.x(), n.y(), n.z(), d}));
                s.planes.push_back({n / n.norm(), d / n.norm()});  // as the scene reader normalises
            }
            if (!t.labels.empty()) o["labels"] = t.labels;
            const double reach = 2 * (t.box.hi - t.box.lo).cwiseAbs().maxCoeff() + 1;
            const auto v = vertices_within(s.planes, p, reach);
            if (!v) return std::nullopt;
            s.box = box_of(*v);
            s.box.lo -= Vec3::Constant(1e-6 * reach);
            s.box.hi += Vec3::Constant(1e-6 * reach);
            s.objects.push_back(o);
            break;
        }
        case Template::Brilliant: {
            o.update(t.brilliant);
            o["position"] = arr(sig3(p));
            s.centre = sig3(p);
            s.radius = t.radius;
            s.box = {s.centre - Vec3::Constant(t.radius), s.centre + Vec3::Constant(t.radius)};
            s.objects.push_back(o);
            break;
        }
    }
    return s;
}

}  // namespace refract::validation::random_detail
