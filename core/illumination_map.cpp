#include <refract/core/illumination_map.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <refract/geometry/error.h>

namespace refract {

namespace {
// A plane's map: cells × cells square elements.
double plane_cells(double half, double element_size) { return std::fmax(1.0, std::ceil(2.0 * half / element_size)); }

// Triangle t of a mesh is cut into k² triangles, k = ceil(longest edge / element_size).
double subdivision(const TriangleMesh& mesh, const Eigen::Vector3i& t, double element_size) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double edge = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    return std::max(1.0, std::ceil(edge / element_size));
}
}  // namespace

IlluminationMap IlluminationMap::for_plane(const Plane& p, const Vec3& centre, double half, double element_size) {
    IlluminationMap m;
    m.kind_ = Kind::Plane;
    const Vec3 n = p.normal;
    const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    m.u_ = n.cross(a).normalized();
    m.v_ = n.cross(m.u_);
    const double cells = plane_cells(half, element_size);
    if (!(cells * cells <= static_cast<double>(kMaxCells)))
        throw InputError("/render/light_pass/element_size: a plane's map of " + format_value(cells) + " × " +
                         format_value(cells) + " elements exceeds " + std::to_string(kMaxCells) +
                         " elements (raise element_size)");
    m.cells_ = std::max(1, static_cast<int>(cells));
    m.size_ = element_size;
    const Vec3 c = centre - (n.dot(centre) - p.offset) * n;  // projection onto the plane
    const double h = 0.5 * m.cells_ * element_size;
    m.origin_ = c - h * m.u_ - h * m.v_;
    m.area_.assign(static_cast<size_t>(m.cells_) * m.cells_, element_size * element_size);
    m.irradiance.assign(m.area_.size(), Vec3(0, 0, 0));
    return m;
}

double IlluminationMap::plane_elements(double half, double element_size) {
    const double cells = plane_cells(half, element_size);
    return cells * cells;
}

double IlluminationMap::mesh_elements(const TriangleMesh& mesh, double element_size) {
    double total = 0;
    for (const auto& t : mesh.triangles) {
        const double k = subdivision(mesh, t, element_size);
        total += k * k;
    }
    return total;
}

IlluminationMap IlluminationMap::for_mesh(const TriangleMesh& mesh, double element_size) {
    IlluminationMap m;
    m.kind_ = Kind::Mesh;
    m.mesh_ = &mesh;
    int total = 0;
    for (const auto& t : mesh.triangles) {
        const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        const double kd = subdivision(mesh, t, element_size);
        if (!(total + kd * kd <= static_cast<double>(kMaxCells)))  // before any int arithmetic
            throw InputError("/render/light_pass/element_size: a mesh's map exceeds " + std::to_string(kMaxCells) +
                             " elements (raise element_size)");
        const int k = static_cast<int>(kd);
        const double area = 0.5 * (b - a).cross(c - a).norm() / (static_cast<double>(k) * k);
        m.k_.push_back(k);
        m.first_.push_back(total);
        total += k * k;
        m.area_.insert(m.area_.end(), static_cast<size_t>(k) * k, area);
    }
    m.irradiance.assign(m.area_.size(), Vec3(0, 0, 0));
    return m;
}

bool IlluminationMap::grid(const Hit& hit, double& x, double& y) const {
    const Vec3 d = hit.point - origin_;
    x = d.dot(u_) / size_;
    y = d.dot(v_) / size_;
    return x >= 0 && y >= 0 && x < cells_ && y < cells_;
}

bool IlluminationMap::lattice(const Hit& hit, int& facet, int& k, double& s, double& r) const {
    if (hit.facet < 0 || hit.facet >= static_cast<int>(k_.size())) return false;
    facet = hit.facet;
    const auto& t = mesh_->triangles[static_cast<size_t>(facet)];
    const Vec3 &a = mesh_->vertices[t[0]], &b = mesh_->vertices[t[1]], &c = mesh_->vertices[t[2]];
    // Barycentric (s, t) of the hit: p = a + s(b − a) + t(c − a).
    const Vec3 e1 = b - a, e2 = c - a, w = hit.point - a;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), w1 = w.dot(e1), w2 = w.dot(e2);
    const double den = d11 * d22 - d12 * d12;
    k = k_[static_cast<size_t>(facet)];
    s = std::clamp((d22 * w1 - d12 * w2) / den, 0.0, 1.0) * k;
    r = std::clamp((d11 * w2 - d12 * w1) / den, 0.0, 1.0) * k;
    // A hit on the long edge may lie past it by rounding: back onto it.
    if (s + r > k) {
        const double f = k / (s + r);
        s *= f;
        r *= f;
    }
    return true;
}

void IlluminationMap::cell(int k, double s, double r, int& i, int& j, bool& upper) {
    i = std::min(k - 1, static_cast<int>(s));
    j = std::min(k - 1, static_cast<int>(r));
    // A lattice point of the long edge (s + r = k, both whole) belongs to the lower
    // triangle below it: cell (i, j) with i + j = k does not exist.
    if (i + j > k - 1) --j;
    upper = (s - i) + (r - j) > 1.0 && i + j < k - 1;
}

// Cell (i, j) of the k×k grid in (s, t) holds a lower and an upper triangle; cells with
// i + j = k − 1 have only the lower one. Row j has 2(k − j) − 1 triangles. Lower (i, j)
// has the lattice corners (i, j), (i + 1, j), (i, j + 1); upper (i, j) has (i + 1, j),
// (i, j + 1), (i + 1, j + 1).
int IlluminationMap::mesh_element(int facet, int k, int i, int j, bool upper) const {
    const int row_start = j * (2 * k - j);  // Σ_{q<j} (2(k − q) − 1)
    return first_[static_cast<size_t>(facet)] + row_start + 2 * i + (upper ? 1 : 0);
}

int IlluminationMap::element(const Hit& hit) const {
    if (kind_ == Kind::Plane) {
        double x, y;
        if (!grid(hit, x, y)) return -1;
        return static_cast<int>(y) * cells_ + static_cast<int>(x);
    }
    int facet, k, i, j;
    double s, r;
    bool upper;
    if (!lattice(hit, facet, k, s, r)) return -1;
    cell(k, s, r, i, j, upper);
    return mesh_element(facet, k, i, j, upper);
}

Vec3 IlluminationMap::centre(int e) const {
    return grid_point(e % cells_ + 0.5, e / cells_ + 0.5);
}

// Bilinear between the centres (i + ½, j + ½) around grid point (x, y); indices clamped to
// the map, so the half element along its edge holds the edge values.
Vec3 IlluminationMap::bilinear(double x, double y) const {
    const double fx = x - 0.5, fy = y - 0.5;
    const double i0 = std::floor(fx), j0 = std::floor(fy);
    const double tx = fx - i0, ty = fy - j0;
    auto at = [&](double i, double j) {
        const int ic = std::clamp(static_cast<int>(i), 0, cells_ - 1), jc = std::clamp(static_cast<int>(j), 0, cells_ - 1);
        return irradiance[static_cast<size_t>(jc) * static_cast<size_t>(cells_) + static_cast<size_t>(ic)];
    };
    return (1 - ty) * ((1 - tx) * at(i0, j0) + tx * at(i0 + 1, j0)) + ty * ((1 - tx) * at(i0, j0 + 1) + tx * at(i0 + 1, j0 + 1));
}

// Mean of the elements of triangle `facet` that have lattice vertex (a, b) as a corner.
Vec3 IlluminationMap::corner_mean(int facet, int k, int a, int b) const {
    Vec3 sum(0, 0, 0);
    int n = 0;
    auto add = [&](int i, int j, bool upper) {
        sum += irradiance[static_cast<size_t>(mesh_element(facet, k, i, j, upper))];
        ++n;
    };
    if (a + b <= k - 1) add(a, b, false);                  // lower (a, b), corner (i, j)
    if (a >= 1) add(a - 1, b, false);                      // lower (a − 1, b), corner (i + 1, j)
    if (b >= 1) add(a, b - 1, false);                      // lower (a, b − 1), corner (i, j + 1)
    if (a >= 1 && a + b < k) add(a - 1, b, true);          // upper (a − 1, b), corner (i + 1, j)
    if (b >= 1 && a + b < k) add(a, b - 1, true);          // upper (a, b − 1), corner (i, j + 1)
    if (a >= 1 && b >= 1) add(a - 1, b - 1, true);         // upper (a − 1, b − 1), corner (i + 1, j + 1)
    return sum / static_cast<double>(n);
}

Vec3 IlluminationMap::barycentric(int facet, int k, double s, double r) const {
    int i, j;
    bool upper;
    cell(k, s, r, i, j, upper);
    const double fs = s - i, fr = r - j;
    if (upper)
        return (1 - fr) * corner_mean(facet, k, i + 1, j) + (1 - fs) * corner_mean(facet, k, i, j + 1) +
               (fs + fr - 1) * corner_mean(facet, k, i + 1, j + 1);
    // Lower triangle (fs + fr ≤ 1 but for rounding on the long edge: clamped).
    const double gs = std::fmin(fs, 1.0 - fr);
    return (1 - gs - fr) * corner_mean(facet, k, i, j) + gs * corner_mean(facet, k, i + 1, j) +
           fr * corner_mean(facet, k, i, j + 1);
}

Vec3 IlluminationMap::value(const Hit& hit, MapFilter filter) const {
    if (kind_ == Kind::Plane) {
        double x, y;
        if (!grid(hit, x, y)) return Vec3(0, 0, 0);
        if (filter == MapFilter::Box)
            return irradiance[static_cast<size_t>(static_cast<int>(y) * cells_ + static_cast<int>(x))];
        return bilinear(x, y);
    }
    int facet, k;
    double s, r;
    if (!lattice(hit, facet, k, s, r)) return Vec3(0, 0, 0);
    if (filter == MapFilter::Box) return irradiance[static_cast<size_t>(element(hit))];
    return barycentric(facet, k, s, r);
}

Vec3 IlluminationMaps::irradiance(int object, const Hit& hit, MapFilter filter) const {
    if (object < 0 || object >= static_cast<int>(by_object.size()) || !by_object[static_cast<size_t>(object)])
        return Vec3(0, 0, 0);
    return by_object[static_cast<size_t>(object)]->value(hit, filter);
}

size_t IlluminationMaps::elements() const {
    size_t n = 0;
    for (const auto& m : by_object)
        if (m) n += static_cast<size_t>(m->elements());
    return n;
}

}  // namespace refract
