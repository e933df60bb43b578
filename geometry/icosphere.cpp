#include <refract/geometry/icosphere.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace refract {

TriangleMesh icosphere(int subdivisions, const Vec3& centre, double radius) {
    if (subdivisions < 0 || subdivisions > 9) throw std::invalid_argument("icosphere: subdivisions must be in [0, 9]");
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> v = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& p : v) p.normalize();
    std::vector<Eigen::Vector3i> t = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> mid;
        const auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back((v[static_cast<size_t>(a)] + v[static_cast<size_t>(b)]).normalized());
            return mid[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<Eigen::Vector3i> next;
        next.reserve(t.size() * 4);
        for (const auto& f : t) {
            const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
            next.push_back({f[0], a, c});
            next.push_back({f[1], b, a});
            next.push_back({f[2], c, b});
            next.push_back({a, b, c});
        }
        t = std::move(next);
    }
    TriangleMesh m;
    m.vertices.reserve(v.size());
    for (const Vec3& p : v) m.vertices.push_back(centre + radius * p);
    m.triangles = std::move(t);
    return m;
}

}  // namespace refract
