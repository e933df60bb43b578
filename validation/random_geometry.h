#pragma once
// Internal to random_scene.cpp: numbers that are the same on every platform, the seeded
// random source, and the geometry of the random solids (shapes, placement, overlap checks).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/geometry/constants.h>
#include <refract/core/camera.h>
#include <refract/geometry/ray.h>

namespace refract::validation::random_detail {

using nlohmann::json;
using Mat3 = Eigen::Matrix3d;


// ---- numbers that are the same on every platform --------------------------------------
// Only + − × ÷, sqrt, floor and round (exact or correctly rounded in IEEE 754) reach the
// output: libm's sin/cos/tan may differ in the last bit between platforms. Every random
// draw is its own statement (the order of evaluation of function arguments is unspecified).

double dsin(double x);
double dcos(double x);
double rad(double degrees);
double pow10(int k);  // exact for 0 <= k <= 22
// x to `digits` significant digits (|x| < 1e-9 to 0): readable scene files.
double sig(double x, int digits = 6);
// x to `places` decimals (never −0).
double dec(double x, int places);
Vec3 sig3(const Vec3& v);
Vec3 dec3(const Vec3& v, int places);
json arr(const Vec3& v);
std::string num(double v);  // shortest round-trip form

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

Mat3 axis_angle(const Vec3& axis, double angle);  // Rodrigues

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
bool apart(const Box& a, const Box& b, double gap);

struct Half {  // n·x <= d, n unit
    Vec3 n;
    double d;
};

// Vertices of the polyhedron of `h`, or nothing when it reaches the cube |x − c|∞ <= half
// (unbounded, or larger than the cube): the cube's planes are added and must stay unused.
std::optional<std::vector<Vec3>> vertices_within(std::vector<Half> h, const Vec3& c, double half);
Box box_of(const std::vector<Vec3>& v);

struct MeshData {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> t;
};

// Every directed edge once and its reverse once: closed, consistently oriented.
bool closed_oriented(const MeshData& m);

// Convex hull of points in general position (triangles counter-clockwise seen from
// outside, unused points dropped), or nothing when four points are nearly coplanar on a face.
std::optional<MeshData> convex_hull(const std::vector<Vec3>& p);
MeshData box_mesh();  // vertex index = x + 2y + 4z, coordinates ±1
std::vector<Vec3> platonic_points(int which);  // 0 tetrahedron, 1 octahedron, 2 icosahedron

// ---- solids ---------------------------------------------------------------------------

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
bool reaches(const Solid& s, const Vec3& p, double margin);

// The exporter's camera_inside for an orthographic camera: does the image rectangle the
// rays start from cut the solid? Spheres exactly, others by boxes; with a margin.
bool rectangle_cuts(const Solid& s, const Camera& cam, double margin);

// Is p on the outer side of every plane (lights behind a wall or under the floor are wasted)?
bool above(const std::vector<Half>& planes, const Vec3& p);

// ---- random shapes and their placement ---------------------------------------------

Mat3 orientation(Rand& rng);
Template sphere_template(double size);
Template hollow_template(Rand& rng, double size);
Template mesh_template(Rand& rng, double size);
Template polyhedron_template(Rand& rng, double size);
Template brilliant_like_template(Rand& rng, double size);
Template brilliant_template(Rand& rng, double size);
// The template at p, rounded; its scene-file objects get their material later.
std::optional<Solid> place(const Template& t, const Vec3& p, const std::string& name, bool transparent);

// Transforms drawn onto a generated scene (validation/random_transforms.cpp), from a stream
// of their own: the objects stay where they were, each written untransformed plus its
// "transform".
void draw_transforms(json& scene, std::uint64_t seed);
// RandomSceneOptions::mesh_files (random_mesh_files.cpp): meshes moved into OBJ files.
std::vector<std::pair<std::string, std::string>> draw_mesh_files(json& scene, std::uint64_t seed);

}  // namespace refract::validation::random_detail
