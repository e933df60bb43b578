#include "validation/random_scene.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "geometry/error.h"
#include "geometry/gem/brilliant.h"
#include "geometry/ray.h"

namespace refract::validation {
namespace {

using nlohmann::json;
using Mat3 = Eigen::Matrix3d;

constexpr double kPi = 3.14159265358979323846;

// ---- numbers that are the same on every platform --------------------------------------
// Only + − × ÷, sqrt, floor and round (exact or correctly rounded in IEEE 754) reach the
// output: libm's sin/cos/tan may differ in the last bit between platforms. Every random
// draw is its own statement (the order of evaluation of function arguments is unspecified).

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

// x to `digits` significant digits (|x| < 1e-9 to 0): readable scene files.
double sig(double x, int digits = 6) {
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
// x to `places` decimals (never −0).
double dec(double x, int places) {
    const double p = pow10(places);
    return std::round(x * p) / p + 0.0;
}
Vec3 sig3(const Vec3& v) { return {sig(v.x()), sig(v.y()), sig(v.z())}; }
Vec3 dec3(const Vec3& v, int places) { return {dec(v.x(), places), dec(v.y(), places), dec(v.z(), places)}; }
json arr(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

std::string num(double v) {  // shortest round-trip form
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

class Rand {
public:
    explicit Rand(std::uint64_t seed) : engine_(seed) {}
    double u() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double a, double b) { return a + (b - a) * u(); }
    int integer(int a, int b) { return std::min(b, a + static_cast<int>(u() * (b - a + 1))); }
    bool chance(double p) { return u() < p; }
    int pick(std::initializer_list<double> weights) {
        double total = 0;
        for (double w : weights) total += w;
        double x = u() * total;
        int i = 0;
        for (double w : weights) {
            if (x < w) return i;
            x -= w;
            ++i;
        }
        return i - 1;
    }
    Vec3 box(double lo, double hi) {
        const double x = uniform(lo, hi);
        const double y = uniform(lo, hi);
        const double z = uniform(lo, hi);
        return {x, y, z};
    }
    Vec3 unit() {  // uniform on the sphere, by rejection
        for (;;) {
            const Vec3 v = box(-1, 1);
            const double n2 = v.squaredNorm();
            if (n2 > 1e-4 && n2 <= 1) return v / std::sqrt(n2);
        }
    }
    Mat3 rotation() {  // uniform, from a unit quaternion
        for (;;) {
            const double w = uniform(-1, 1);
            const Vec3 v = box(-1, 1);
            const double n2 = w * w + v.squaredNorm();
            if (n2 < 1e-4 || n2 > 1) continue;
            const double s = 1 / std::sqrt(n2);
            const double a = w * s, x = v.x() * s, y = v.y() * s, z = v.z() * s;
            Mat3 m;
            m << 1 - 2 * (y * y + z * z), 2 * (x * y - a * z), 2 * (x * z + a * y),  //
                2 * (x * y + a * z), 1 - 2 * (x * x + z * z), 2 * (y * z - a * x),   //
                2 * (x * z - a * y), 2 * (y * z + a * x), 1 - 2 * (x * x + y * y);
            return m;
        }
    }

private:
    std::mt19937_64 engine_;
};

Mat3 axis_angle(const Vec3& axis, double angle) {  // Rodrigues
    const Vec3 k = axis.normalized();
    Mat3 K;
    K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
    return Mat3::Identity() + dsin(angle) * K + (1 - dcos(angle)) * K * K;
}

// ---- geometry -----------------------------------------------------------------------

struct Box {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    void add(const Vec3& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    void add(const Box& b) {
        add(b.lo);
        add(b.hi);
    }
    Vec3 centre() const { return 0.5 * (lo + hi); }
    bool contains(const Vec3& p, double margin) const {
        for (int k = 0; k < 3; ++k)
            if (p[k] <= lo[k] - margin || p[k] >= hi[k] + margin) return false;
        return true;
    }
    std::array<Vec3, 8> corners() const {
        std::array<Vec3, 8> c;
        for (int i = 0; i < 8; ++i) c[i] = Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
        return c;
    }
};

// The exporter's rule for boxes, with a gap: apart along some axis.
bool apart(const Box& a, const Box& b, double gap) {
    for (int k = 0; k < 3; ++k)
        if (a.hi[k] + gap <= b.lo[k] || b.hi[k] + gap <= a.lo[k]) return true;
    return false;
}

struct Half {  // n·x <= d, n unit
    Vec3 n;
    double d;
};

// Vertices of the polyhedron of `h`, or nothing when it reaches the cube |x − c|∞ <= half
// (unbounded, or larger than the cube): the cube's planes are added and must stay unused.
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

struct MeshData {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> t;
};

// Every directed edge once and its reverse once: closed, consistently oriented.
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

// Convex hull of points in general position (triangles counter-clockwise seen from
// outside, unused points dropped), or nothing when four points are nearly coplanar on a face.
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

// ---- the scene's pieces ----------------------------------------------------------------

struct Mat {
    std::string name, desc;
    json j;
    bool transparent = false, dispersive = false;
};

// A shape before placement: final orientation and size, centred near the origin.
struct Template {
    enum Kind { Sphere, Hollow, Mesh, Poly, Brilliant } kind = Sphere;
    std::string desc;
    double radius = 0;                   // sphere, hollow (outer); brilliant: bounding radius
    std::vector<std::pair<Vec3, double>> holes;  // hollow: centre offset, radius
    MeshData mesh;
    std::vector<Half> planes;
    std::vector<std::string> labels;
    json brilliant;  // the cut's fields
    Box box;         // local bounds
};

// A placed object as the exporter will read it (rounded values).
struct Solid {
    std::string desc;
    json objects = json::array();
    bool sphere = false;
    Vec3 centre{0, 0, 0};
    double radius = 0;
    std::vector<Half> planes;  // polyhedron: exact inside test
    Box box;
    bool transparent = false;
};

// Does the solid reach point p (within margin)? Spheres and polyhedra exactly, others by box.
bool reaches(const Solid& s, const Vec3& p, double margin) {
    if (s.sphere) return (p - s.centre).norm() < s.radius + margin;
    if (!s.planes.empty()) {
        for (const Half& q : s.planes)
            if (q.n.dot(p) > q.d + margin) return false;
        return true;
    }
    return s.box.contains(p, margin);
}

// The exporter's camera_inside for an orthographic camera: does the image rectangle the
// rays start from cut the solid? Spheres exactly, others by boxes; with a margin.
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

// ---- the generator ----------------------------------------------------------------------

class Generator {
public:
    Generator(std::uint64_t seed, const RandomSceneOptions& opt) : rng_(seed), opt_(opt), seed_(seed) {}
    json run();

private:
    // materials
    std::string add_material(Mat m);
    std::string dielectric();
    std::string diffuse(bool checker_likely);
    std::string mirror();
    std::string emissive();
    // shapes
    Template sphere_template(double size);
    Template hollow_template(double size);
    Template mesh_template(double size);
    Template polyhedron_template(double size);
    Template brilliant_like_template(double size);
    Template brilliant_template(double size);
    Mat3 orientation();
    std::optional<Solid> place(const Template& t, const Vec3& p, const std::string& name, bool transparent);
    void add_solid(int index);
    // the rest of the scene
    void camera();
    bool clear_of_camera(const Solid& s) const;
    bool outside_plane(const Vec3& n, double d) const;
    void planes();
    void lights();
    void highlights(int count);
    void enclosure();
    void render();
    Box solids_box() const;

    Rand rng_;
    RandomSceneOptions opt_;
    std::uint64_t seed_;
    json scene_ = json::object();
    json objects_ = json::array();
    std::map<std::string, Mat> materials_;
    std::vector<std::string> dielectrics_;
    std::vector<Solid> solids_;
    std::vector<std::string> parts_;  // description of each object
    std::vector<Vec3> light_positions_;
    int dispersive_ = 0, max_dispersive_ = 2;
    bool floor_ = false, room_ = false, cocoon_ = false;
    double region_ = 2;
    Camera cam_;
    std::string camera_desc_, render_desc_;
    Vec3 view_dir_{0, 0, 1};
    std::vector<std::pair<Vec3, double>> highlights_;
    std::vector<Half> planes_;  // the opaque planes, as the scene reader sees them
};

// Is p on the outer side of every plane (lights behind a wall or under the floor are wasted)?
bool above(const std::vector<Half>& planes, const Vec3& p) {
    for (const Half& h : planes)
        if (h.n.dot(p) <= h.d + 0.05) return false;
    return true;
}

std::string Generator::add_material(Mat m) {
    m.name = m.name + " " + std::to_string(materials_.size());
    const std::string name = m.name;
    materials_[name] = std::move(m);
    return name;
}

std::string Generator::dielectric() {
    if (!dielectrics_.empty() && rng_.chance(0.15))
        return dielectrics_[static_cast<size_t>(rng_.integer(0, static_cast<int>(dielectrics_.size()) - 1))];
    Mat m;
    m.name = "glass";
    m.transparent = true;
    // n uniform on [0.3, 0.98] ∪ [1.02, 4]: never within 0.02 of 1.
    const double x = rng_.uniform(0, 3.66);
    const double n = sig(x < 0.68 ? 0.3 + x : 1.02 + (x - 0.68), 4);
    m.j = {{"type", "dielectric"}, {"ior", n}};
    std::string filter;
    switch (rng_.pick({35, 35, 10, 20})) {
        case 0: break;  // clear: the default [1, 1, 1]
        case 1:
            m.j["filter"] = arr(dec3(rng_.box(0.4, 1), 3));
            filter = " tinted";
            break;
        case 2:
            m.j["filter"] = arr(Vec3(0, 0, 0));
            filter = " filter 0";
            break;
        default:
            m.j["filter"] = arr(dec3(rng_.box(0, 1), 3));
            filter = " filtered";
    }
    std::string refl = "fresnel";
    if (rng_.chance(0.3)) {
        const int k = rng_.pick({10, 10, 80});
        const double u = rng_.uniform(0, 1);
        const double ks = k == 0 ? 0.0 : k == 1 ? 1.0 : dec(u, 3);
        m.j["reflectance"] = "constant";
        m.j["reflectivity"] = ks;
        refl = "constant ks=" + num(ks);
    }
    std::string kind = "dielectric n=" + num(n);
    if (opt_.dispersion && dispersive_ < max_dispersive_ && rng_.chance(0.35)) {
        const int k = rng_.pick({5, 20, 75});
        const double u = rng_.u();
        const double D = k == 0 ? 1.0 : k == 1 ? sig(0.75 + 0.25 * u, 4) : sig(1.0 + 0.3 * u, 4);
        const bool big = rng_.chance(0.4);
        const int S = big ? rng_.integer(13, 31) : rng_.integer(2, 12);
        m.j["dispersion"] = {{"model", "povray"}, {"ior", n}, {"dispersion", D}, {"samples", S}};
        m.dispersive = true;
        ++dispersive_;
        kind = "dispersive n=" + num(n) + " D=" + num(D) + " x" + std::to_string(S);
    }
    m.desc = kind + " " + refl + filter;
    const std::string name = add_material(std::move(m));
    dielectrics_.push_back(name);
    return name;
}

std::string Generator::diffuse(bool checker_likely) {
    Mat m;
    m.name = "diffuse";
    const Vec3 c = dec3(rng_.box(0.05, 0.95), 3);
    const double d = dec(rng_.uniform(0.3, 1), 3);
    const bool ambient = rng_.chance(0.7);
    const double a = ambient ? dec(rng_.uniform(0, 0.3), 3) : 0.0;
    m.j = {{"type", "diffuse"}, {"color", arr(c)}, {"diffuse", d}, {"ambient", a}};
    m.desc = "diffuse";
    if (rng_.chance(checker_likely ? 0.85 : 0.4)) {
        const Vec3 c2 = dec3(rng_.box(0, 0.95), 3);
        const double s = dec(rng_.uniform(0.2, 1.5), 3);
        m.j["checker"] = {{"color2", arr(c2)}, {"size", s}};
        m.desc = "checker";
    }
    return add_material(std::move(m));
}

std::string Generator::mirror() {
    Mat m;
    m.name = "mirror";
    Vec3 c;
    if (rng_.chance(0.3)) c = Vec3::Constant(dec(rng_.uniform(0.5, 1), 3));
    else c = dec3(rng_.box(0.2, 1), 3);
    m.j = {{"type", "mirror"}, {"color", arr(c)}};
    m.desc = "mirror";
    return add_material(std::move(m));
}

std::string Generator::emissive() {
    Mat m;
    m.name = "lamp";
    const double k = rng_.uniform(2, 20);
    m.j = {{"type", "emissive"}, {"color", arr(dec3(k * rng_.box(0.5, 1), 3))}};
    m.desc = "emissive";
    return add_material(std::move(m));
}

Mat3 Generator::orientation() {
    switch (rng_.pick({40, 30, 30})) {
        case 0: return axis_angle(Vec3::UnitY(), rng_.uniform(0, 2 * kPi));
        case 1: {
            const Vec3 axis = rng_.unit();
            return axis_angle(axis, rad(rng_.uniform(5, 30)));
        }
        default: return rng_.rotation();
    }
}

Template Generator::sphere_template(double size) {
    Template t;
    t.kind = Template::Sphere;
    t.radius = size;
    t.box = {Vec3::Constant(-size), Vec3::Constant(size)};
    t.desc = "sphere";
    return t;
}

Template Generator::hollow_template(double size) {
    Template t = sphere_template(size);
    t.kind = Template::Hollow;
    if (rng_.chance(0.15)) {  // two holes side by side
        const Vec3 axis = rng_.unit();
        const double r1 = size * rng_.uniform(0.25, 0.42);
        const double r2 = size * rng_.uniform(0.25, 0.42);
        t.holes = {{0.5 * size * axis, r1}, {-0.5 * size * axis, r2}};
        t.desc = "hollow sphere (2 holes)";
    } else {
        const double r = size * rng_.uniform(0.5, 0.95);
        Vec3 off = Vec3::Zero();
        if (rng_.chance(0.5)) {
            const Vec3 dir = rng_.unit();
            off = dir * (rng_.uniform(0, 0.9) * (size - r));
        }
        t.holes = {{off, r}};
        t.desc = "hollow sphere";
    }
    return t;
}

Template Generator::mesh_template(double size) {
    Template t;
    t.kind = Template::Mesh;
    const int kind = rng_.pick({12, 12, 16, 12, 28, 20});
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
            const bool on_sphere = star || rng_.chance(0.5);
            const int n = on_sphere ? rng_.integer(6, 40) : rng_.integer(5, 14);
            std::vector<Vec3> p;
            for (int i = 0; i < n; ++i) {
                const Vec3 d = rng_.unit();
                p.push_back(on_sphere ? d : Vec3(d * std::sqrt(rng_.uniform(0.3, 1))));
            }
            m = convex_hull(p);
            if (m && star)
                for (Vec3& v : m->v) v *= rng_.uniform(0.55, 1.15);
        }
        t.desc = star ? "star-shaped mesh" : "convex hull mesh";
    }
    // Random proportions, orientation and size (circumradius `size`).
    Vec3 stretch(1, 1, 1);
    if (rng_.chance(0.5)) stretch = rng_.box(0.6, 1.4);
    const Mat3 R = rng_.rotation();
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

Template Generator::polyhedron_template(double size) {
    // k planes tangent to the unit sphere with random normals, bounded with every vertex
    // within 4 of the centre; after 20 tries the first four start from a tetrahedron.
    Template t;
    t.kind = Template::Poly;
    const int k = rng_.integer(4, 30);
    std::optional<std::vector<Vec3>> v;
    for (int attempt = 0; !v; ++attempt) {
        t.planes.clear();
        const Mat3 R = rng_.rotation();
        const std::vector<Vec3> tet = platonic_points(0);
        for (int i = 0; i < k; ++i) {
            Vec3 n = rng_.unit();
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

Template Generator::brilliant_like_template(double size) {
    // Girdle radius 1, y up: a table, n crown planes through the girdle top at angle β,
    // g vertical girdle planes tangent to the unit circle, m pavilion planes through the
    // girdle bottom at angle α, an optional culet.
    Template t;
    t.kind = Template::Poly;
    const int n = rng_.chance(0.4) ? 8 : rng_.integer(3, 10);
    const int m = (2 * n <= 16 && rng_.chance(0.5)) ? 2 * n : n;
    const bool culet = rng_.chance(0.3);
    const int g = std::min(rng_.integer(8, 32), 46 - 1 - n - m - (culet ? 1 : 0));
    const double beta = rad(rng_.uniform(20, 45)), alpha = rad(rng_.uniform(35, 50));
    const double table = rng_.uniform(0.4, 0.75), h = rng_.uniform(0.01, 0.08);
    const double phi0 = rng_.uniform(0, 2 * kPi / n);
    const double psi0 = rng_.chance(0.5) ? phi0 : rng_.uniform(0, 2 * kPi / m);
    const double theta0 = rng_.chance(0.5) ? phi0 : rng_.uniform(0, 2 * kPi / g);
    const double c = culet ? rng_.uniform(0.02, 0.15) : 0.0;
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
    const Mat3 R = orientation();
    for (Half& p : t.planes) {
        p.n = R * p.n;
        p.d *= size;
    }
    t.box = box_of(*vertices_within(t.planes, Vec3::Zero(), 4.0 * size));
    t.desc = "brilliant-like polyhedron (" + std::to_string(n) + "-fold crown, " + std::to_string(g) +
             " girdle planes, " + std::to_string(m) + "-fold pavilion" + (culet ? ", culet" : "") + ")";
    return t;
}

Template Generator::brilliant_template(double size) {
    // The exact round brilliant with random parameters inside GIA's domain, checked by
    // validate(); girdles of 16 or 32 planes keep it cheap.
    Template t;
    t.kind = Template::Brilliant;
    BrilliantCut cut;
    cut.table = dec(rng_.uniform(50, 66), 1);
    cut.crown_angle = dec(rng_.uniform(28, 38), 1);
    cut.pavilion_angle = dec(rng_.uniform(39, 42.5), 1);
    cut.star = dec(rng_.uniform(45, 65), 1);
    cut.lower_half = dec(rng_.uniform(70, 85), 1);
    const bool faceted = rng_.chance(0.5);
    const int planes = rng_.chance(0.5) ? 16 : 32;
    cut.girdle_facets = faceted ? planes : 0;
    cut.bruted_planes = planes;
    cut.culet = rng_.chance(0.3) ? dec(rng_.uniform(1, 5), 1) : 0.0;
    const bool knife = rng_.chance(0.25);
    const double extra = rng_.uniform(0.5, 3);
    cut.girdle = knife ? 0.0 : std::min(11.0, std::ceil((min_girdle_percent(cut) + extra) * 100) / 100);
    try {
        validate(cut);
    } catch (const InputError&) {
        cut = brilliant_preset("gia-default");  // its 3 % girdle keeps 32 bruted planes
        cut.bruted_planes = 32;
    }
    const int rot = rng_.pick({40, 30, 30});
    const double rx = rng_.uniform(-30, 30), ry = rng_.uniform(0, 360), rz = rng_.uniform(-30, 30);
    const double fx = rng_.uniform(-180, 180), fz = rng_.uniform(-180, 180);
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

// The template at p, rounded; its scene-file objects get their material later.
std::optional<Solid> Generator::place(const Template& t, const Vec3& p, const std::string& name, bool transparent) {
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

void Generator::add_solid(int index) {
    const int kind = rng_.pick({22, 12, 20, 19, 23, 4});
    const int m = kind == 1 ? 0 : rng_.pick({60, 22, 18});  // hollow spheres are glass
    const bool transparent = m == 0;
    for (int attempt = 0; attempt < 40; ++attempt) {
        const double size = rng_.uniform(0.3, 1.2) * (attempt >= 20 ? 0.5 : 1.0);
        Template t;
        switch (kind) {
            case 0: t = sphere_template(size); break;
            case 1: t = hollow_template(size); break;
            case 2: t = mesh_template(size); break;
            case 3: t = polyhedron_template(size); break;
            case 4: t = brilliant_like_template(size); break;
            default: t = brilliant_template(size); break;
        }
        const double x = rng_.uniform(-region_, region_), z = rng_.uniform(-region_, region_);
        const int rest = rng_.pick({10, 45, 45});  // touching, slightly sunk, lifted
        const double sunk = rng_.uniform(0, 0.05) * size, lift = rng_.uniform(0.02, 1.5);
        const double free_y = rng_.uniform(-1.5, 1.5);
        const double y = !floor_ ? free_y : -t.box.lo.y() + (rest == 0 ? 0.0 : rest == 1 ? -sunk : lift);
        const std::string name = "object " + std::to_string(index);
        auto s = place(t, Vec3(x, y, z), name, transparent);
        if (!s) continue;
        bool ok = true;
        for (const Solid& other : solids_) {
            if (!transparent || !other.transparent) continue;
            ok = ok && (s->sphere && other.sphere
                            ? (s->centre - other.centre).norm() >= s->radius + other.radius + 0.02
                            : apart(s->box, other.box, 0.02));
        }
        if (!ok) continue;
        const std::string material = m == 0 ? dielectric() : m == 1 ? diffuse(false) : mirror();
        for (json& o : s->objects) {
            o["material"] = material;
            objects_.push_back(o);
        }
        solids_.push_back(*s);
        parts_.push_back(s->desc + " (" + materials_.at(material).desc + ")");
        return;
    }
}

Box Generator::solids_box() const {
    Box b;
    for (const Solid& s : solids_) b.add(s.box);
    if (solids_.empty()) b = {Vec3::Constant(-1), Vec3::Constant(1)};
    return b;
}

void Generator::camera() {
    const Box all = solids_box();
    const Vec3 c = all.centre();
    const double rs = std::max(0.5, 0.5 * (all.hi - all.lo).norm());
    const Vec3 jitter = rng_.box(-0.15, 0.15) * rs;
    cam_.look_at = sig3(c + jitter);
    cam_.width = opt_.width;
    cam_.height = opt_.height;
    const bool ortho = rng_.chance(0.2);
    cam_.type = ortho ? Camera::Type::Orthographic : Camera::Type::Perspective;
    if (rng_.chance(0.15)) {
        const double sx = rng_.uniform(-0.3, 0.3), sz = rng_.uniform(-0.3, 0.3);
        cam_.sky = Vec3(dec(sx, 3), 1, dec(sz, 3));
    }
    const bool far = !ortho && rng_.chance(0.12);
    for (int attempt = 0;; ++attempt) {
        const double az = rng_.uniform(0, 2 * kPi);
        const double el = rad(floor_ ? rng_.uniform(5, 65) : rng_.uniform(-50, 70));
        const Vec3 dir(dcos(el) * dsin(az), -dsin(el), dcos(el) * dcos(az));  // towards look_at
        const double grow = 1 + 0.05 * attempt;
        double dist;
        if (ortho) {
            const double h = rng_.uniform(0.8, 1.5);
            cam_.ortho_height = sig(2 * rs * h, 4);
            dist = (rs + rng_.uniform(0.5, 4)) * grow;
        } else {
            cam_.angle_deg = dec(far ? rng_.uniform(20, 32) : rng_.uniform(20, 90), 1);
            const double half = rad(cam_.angle_deg / 2);
            dist = rs * rng_.uniform(0.9, 1.6) * dcos(half) / dsin(half) * grow;
            if (far) dist *= rng_.uniform(2, 4);
        }
        cam_.location = sig3(cam_.look_at - dist * dir);
        const Vec3 d = (cam_.look_at - cam_.location).normalized();
        bool ok = std::abs(d.dot(cam_.sky.normalized())) < 0.98;
        // Perspective: outside every solid (after 40 tries, outside the transparent ones);
        // orthographic: the image rectangle clear of every solid (the exporter refuses one
        // crossing a surface) and above the floor.
        const bool strict = attempt < 40;
        if (floor_ && (strict || ortho)) ok = ok && outside_plane(Vec3::UnitY(), 0.0);
        for (const Solid& s : solids_) ok = ok && ((!s.transparent && !strict && !ortho) || clear_of_camera(s));
        if (!ok) continue;
        view_dir_ = d;
        break;
    }
    json j = {{"type", ortho ? "orthographic" : "perspective"}, {"location", arr(cam_.location)},
              {"look_at", arr(cam_.look_at)}, {"sky", arr(cam_.sky)}, {"width", opt_.width}, {"height", opt_.height}};
    if (ortho) j["ortho_height"] = cam_.ortho_height;
    else j["angle"] = cam_.angle_deg;
    scene_["camera"] = j;
    camera_desc_ = ortho ? "orthographic (height " + num(cam_.ortho_height) + ")"
                         : std::string(far ? "far " : "") + "perspective (angle " + num(cam_.angle_deg) + ")";
}

// The camera's rays start outside the solid: the location, or the orthographic image
// rectangle (spheres exactly, other solids by their boxes), with a margin.
bool Generator::clear_of_camera(const Solid& s) const {
    if (cam_.type == Camera::Type::Orthographic) return !rectangle_cuts(s, cam_, 0.02);
    return !reaches(s, cam_.location, 0.02);
}

// The camera's rays start on the outer side of the plane n·x = d (n unit).
bool Generator::outside_plane(const Vec3& n, double d) const {
    if (cam_.type == Camera::Type::Perspective) return n.dot(cam_.location) > d + 0.05;
    const Camera::Basis b = cam_.basis();
    for (double sy : {-0.5, 0.5})
        for (double sx : {-0.5, 0.5})
            if (n.dot(cam_.location + sx * b.R + sy * b.U) <= d + 0.05) return false;
    return true;
}

void Generator::planes() {
    // 0–2 opaque planes: a checker floor at y = 0, a back wall or a tilted plane behind or
    // below every object; the camera always on their outer side.
    std::vector<int> kinds;
    if (floor_) kinds.push_back(0);
    const int extra = rng_.pick({floor_ ? 65.0 : 40.0, 35, floor_ ? 0.0 : 25.0});
    const int first = rng_.chance(0.6) ? 1 : 2;
    if (extra >= 1) kinds.push_back(first);
    if (extra >= 2) kinds.push_back(3 - first);
    const Box all = solids_box();
    int index = 0;
    for (int kind : kinds) {
        Vec3 n = Vec3::UnitY();
        double gap = 0;
        if (kind == 1) {
            n = -Vec3(view_dir_.x(), 0, view_dir_.z());
            if (n.norm() < 0.2) continue;  // looking straight down: no wall
            n.normalize();
            gap = rng_.uniform(0.5, 3);
        } else if (kind == 2) {
            const double tilt = rad(rng_.uniform(15, 60)), az = rng_.uniform(0, 2 * kPi);
            n = Vec3(dsin(tilt) * dcos(az), dcos(tilt), dsin(tilt) * dsin(az));
            gap = rng_.uniform(0.2, 2);
        }
        n = sig3(n);
        double d = 0;
        if (kind != 0) {
            d = INFINITY;
            for (const Vec3& p : all.corners()) d = std::min(d, n.normalized().dot(p));
            d = sig(d - gap);
        }
        if (!outside_plane(n / n.norm(), d)) continue;  // the reader normalises the normal only
        const int m = rng_.pick({85, 5, 10});
        const std::string material = m == 0 ? diffuse(true) : m == 1 ? diffuse(false) : mirror();
        planes_.push_back({n / n.norm(), d});
        objects_.push_back({{"type", "plane"}, {"name", "plane " + std::to_string(index++)}, {"normal", arr(n)},
                            {"offset", d}, {"material", material}});
        const std::string what = kind == 0 ? "floor" : kind == 1 ? "back wall" : "tilted plane";
        parts_.push_back(materials_.at(material).desc + " " + what);
    }
}

void Generator::lights() {
    const int count = rng_.pick({10, 40, 30, 20});
    const Box all = solids_box();
    const Vec3 c = all.centre();
    const double rs = std::max(0.5, 0.5 * (all.hi - all.lo).norm());
    json ls = json::array();
    for (int i = 0; i < count; ++i) {
        Vec3 p;
        for (int attempt = 0;; ++attempt) {
            Vec3 d = rng_.unit();
            if (floor_ || rng_.chance(0.7)) d.y() = std::abs(d.y()) + 0.3;
            const double dist = rng_.uniform(3, 12) * std::max(1.0, rs / 2);
            p = sig3(c + dist * d.normalized());
            bool ok = above(planes_, p);
            for (const Solid& s : solids_) ok = ok && !reaches(s, p, 0.05);
            if (ok || attempt > 50) break;
        }
        const bool dim = rng_.chance(0.2);
        const double k = dim ? rng_.uniform(0.05, 0.3) : rng_.uniform(0.4, 1);
        const Vec3 tint = rng_.chance(0.6) ? Vec3(1, 1, 1) : rng_.box(0.4, 1);
        const Vec3 colour = dec3(k * tint, 3).cwiseMax(0.001);
        ls.push_back({{"type", "point"}, {"position", arr(p)}, {"color", arr(colour)}});
        light_positions_.push_back(p);
    }
    scene_["lights"] = ls;
}

void Generator::highlights(int count) {
    // Small emissive spheres: at a light (the 1984 paper's highlight) or beside the objects.
    const Box all = solids_box();
    const double rs = std::max(0.5, 0.5 * (all.hi - all.lo).norm());
    for (int i = 0; i < count; ++i) {
        const double r = sig(rng_.uniform(0.08, 0.35));
        Vec3 p;
        for (int attempt = 0;; ++attempt) {
            if (!light_positions_.empty() && rng_.chance(0.5)) {
                p = light_positions_[static_cast<size_t>(rng_.integer(0, static_cast<int>(light_positions_.size()) - 1))];
            } else {
                Vec3 d = rng_.unit();
                if (floor_) d.y() = std::abs(d.y()) + 0.2;
                const double dist = rs + rng_.uniform(0.5, 4);
                p = sig3(all.centre() + dist * d.normalized());
            }
            Solid lamp;
            lamp.sphere = true;
            lamp.centre = p;
            lamp.radius = r;
            if ((clear_of_camera(lamp) && above(planes_, p)) || attempt > 50) break;
        }
        const std::string material = emissive();
        objects_.push_back({{"type", "sphere"}, {"name", "highlight " + std::to_string(i)}, {"center", arr(p)},
                            {"radius", r}, {"material", material}});
        highlights_.push_back({p, r});
        parts_.push_back("highlight sphere (emissive)");
    }
}

void Generator::enclosure() {
    // The camera inside an opaque sphere: a room holding the whole scene, or a small
    // sphere around the camera alone.
    if (!room_ && !cocoon_) return;
    Vec3 c;
    double r;
    std::string what;
    if (cocoon_) {
        c = sig3(cam_.location + rng_.box(-0.05, 0.05));
        r = sig(rng_.uniform(0.2, 0.6));
        what = "sphere around the camera";
    } else {
        const Box all = solids_box();
        c = sig3(all.centre());
        r = 0;
        std::vector<Vec3> pts = light_positions_;
        for (const Solid& s : solids_)
            for (const Vec3& p : s.box.corners()) pts.push_back(p);
        const Camera::Basis b = cam_.basis();
        for (double sy : {-0.5, 0.5})
            for (double sx : {-0.5, 0.5})
                pts.push_back(cam_.location + (cam_.type == Camera::Type::Orthographic ? sx * b.R + sy * b.U : Vec3(0, 0, 0)));
        for (const Vec3& p : pts) r = std::max(r, (p - c).norm());
        for (const auto& [p, hr] : highlights_) r = std::max(r, (p - c).norm() + hr);
        r = sig(r + rng_.uniform(1, 3));
        what = "room sphere";
    }
    // A mirror cocoon with no light inside would render black: the cocoon is a checker
    // seen by its ambient light.
    const int m = cocoon_ ? 0 : rng_.pick({60, 15, 25});
    const std::string material = m == 2 ? mirror() : diffuse(m == 0);
    if (cocoon_) materials_.at(material).j["ambient"] = dec(rng_.uniform(0.1, 0.3), 3);
    objects_.push_back({{"type", "sphere"}, {"name", what}, {"center", arr(c)}, {"radius", r}, {"material", material}});
    parts_.push_back(materials_.at(material).desc + " " + what + " (camera inside)");
}

void Generator::render() {
    const bool whitted = rng_.chance(0.2);
    const int t = rng_.integer(0, 5);
    const double random_threshold = dec(rng_.uniform(0.0005, 0.1), 4);
    const double threshold = std::array<double, 6>{0.0, sig(1.0 / 255), 1e-3, 0.01, 0.05, random_threshold}[t];
    const bool deep = rng_.chance(0.55);
    const int deep_depth = rng_.integer(11, 24), shallow_depth = rng_.integer(1, 10);
    int depth = deep ? deep_depth : shallow_depth;
    // POV-Ray's cost: without pruning a tree can double at every level, and dispersion
    // multiplies the refracted subtree by the number of bands. With these limits the
    // costliest of 1700 seeds took POV-Ray 3.4 s at 80×60; one dispersive scene at depth
    // 16 instead of 10 took 41 s.
    const double pruning = whitted ? 0.0 : threshold;
    int specular = 0, max_samples = 0;
    for (const json& o : objects_) {
        const Mat& m = materials_.at(o["material"].get<std::string>());
        if (m.transparent || m.j["type"] == "mirror") ++specular;
        if (m.dispersive) max_samples = std::max(max_samples, m.j["dispersion"]["samples"].get<int>());
    }
    if (pruning < 1e-3 && specular >= 2) depth = std::min(depth, 12);
    if (max_samples > 0 && pruning < 1e-3) depth = std::min(depth, 10);
    scene_["render"] = {{"integrator", whitted ? "whitted" : "fresnel-tree"},
                        {"max_depth", depth},
                        {"threshold", threshold},
                        {"compat", "povray"}};
    render_desc_ = std::string(whitted ? "whitted" : "fresnel-tree") + ", max_depth " + std::to_string(depth) +
                   ", threshold " + num(threshold) + (whitted ? " (ignored)" : "");
}

json Generator::run() {
    floor_ = rng_.chance(0.7);
    const double enclosed = rng_.u();
    room_ = enclosed < 0.08;
    cocoon_ = !room_ && enclosed < 0.11;
    max_dispersive_ = rng_.chance(0.2) ? 3 : 2;
    region_ = rng_.uniform(1.5, 3.5);
    const int count = rng_.integer(1, room_ || cocoon_ ? 5 : 6);  // the enclosing sphere is the sixth
    int lamps = 0;
    for (int i = 0; i < count; ++i) {
        if (i > 0 && rng_.chance(0.12)) ++lamps;
        else add_solid(i);
    }
    if (solids_.empty()) add_solid(count);
    camera();
    if (cocoon_ && cam_.type == Camera::Type::Orthographic) {
        cocoon_ = false;
        room_ = true;
    }
    planes();
    lights();
    highlights(lamps);
    enclosure();

    // Background: a random colour, or the RTIOW gradient sky (its colours or random ones).
    std::string background;
    if (rng_.chance(0.35)) {
        const bool rtiow = rng_.chance(0.5);
        const Vec3 bottom = dec3(rng_.box(0, 1), 3), top = dec3(rng_.box(0, 1), 3);
        scene_["background"] = {{"type", "gradient"},
                                {"bottom", arr(rtiow ? Vec3(1, 1, 1) : bottom)},
                                {"top", arr(rtiow ? Vec3(0.5, 0.7, 1) : top)}};
        background = rtiow ? "RTIOW sky" : "gradient sky";
    } else {
        const Vec3 colour = dec3(rng_.box(0, 1), 3);
        const bool black = floor_ && rng_.chance(0.1);  // else glass and mirrors alone would be black
        scene_["background"] = arr(black ? Vec3(0, 0, 0) : colour);
        background = black ? "black background" : "solid background";
    }
    render();

    json mats = json::object();
    for (const auto& [name, m] : materials_) mats[name] = m.j;
    scene_["materials"] = mats;
    scene_["objects"] = objects_;
    std::string desc = "random seed " + std::to_string(seed_) + ": ";
    for (size_t i = 0; i < parts_.size(); ++i) desc += (i ? ", " : "") + parts_[i];
    const size_t nl = light_positions_.size();
    desc += "; " + std::to_string(nl) + (nl == 1 ? " light; " : " lights; ") + camera_desc_ + "; " + background + "; " +
            render_desc_;
    scene_["description"] = desc;
    return scene_;
}

}  // namespace

nlohmann::json random_scene(std::uint64_t seed, const RandomSceneOptions& opt) {
    if (opt.width < 1 || opt.height < 1) throw InputError("random_scene: the image size must be positive");
    return Generator(seed, opt).run();
}

}  // namespace refract::validation
