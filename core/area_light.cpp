#include <refract/core/area_light.h>

#include <cmath>
#include <string>

#include <refract/core/emitters.h>

namespace refract {

namespace {

// Grid coordinate k of n in [0, 1]: k / (n − 1); the middle for a grid of one.
double grid_coordinate(int k, int n) { return n > 1 ? static_cast<double>(k) / static_cast<double>(n - 1) : 0.5; }

int grid_size(const JsonReader& r, int index, int lo) {
    const nlohmann::json& v = r.raw("size")[static_cast<size_t>(index)];
    const std::string key = "size/" + std::to_string(index);
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(kMaxAreaLightGrid) + "]";
    if (!v.is_number_integer()) r.fail_at(key, "must be an integer in " + range);
    const bool huge = v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(kMaxAreaLightGrid);
    const long long n = huge ? kMaxAreaLightGrid + 1 : v.get<long long>();
    if (n < lo || n > kMaxAreaLightGrid) r.fail_at(key, "must be in " + range + " (got " + v.dump() + ")");
    return static_cast<int>(n);
}

Vec3 edge(const JsonReader& r, const std::string& key) {
    const Vec3 a = r.vec3(key);
    if (!(a.norm() > 0 && a.norm() <= 1e15)) r.fail_at(key, "must be a non-zero vector of length at most 1e15");
    return a;
}

}  // namespace

Vec3 area_light_point(const Light& l, double a, double b) {
    double s = a - 0.5, t = b - 0.5;
    switch (l.kind) {
        case Light::Kind::Disk: {
            // POV-Ray's circular area light (trace.cpp, the [ENB 9/97] mapping).
            s += 0.001;
            t += 0.001;
            const double scale = std::fmax(std::abs(s), std::abs(t)) / std::sqrt(s * s + t * t);
            s *= scale;
            t *= scale;
            break;
        }
        case Light::Kind::Rectangle:
        case Light::Kind::Point:
        case Light::Kind::Directional:
        case Light::Kind::Beam: break;
    }
    return l.position + s * l.axis1 + t * l.axis2;
}

Vec3 Light::grid_point(int k) const {
    switch (kind) {
        case Kind::Rectangle:
        case Kind::Disk:
            return area_light_point(*this, grid_coordinate(k % size[0], size[0]), grid_coordinate(k / size[0], size[1]));
        case Kind::Point:
        case Kind::Directional:
        case Kind::Beam: break;
    }
    return position;
}

void parse_area_light(const JsonReader& r, Light& light) {
    light.position = r.vec3("position");
    if (!(light.position.norm() < 1e150)) r.fail_at("position", "must lie within 1e150 of the origin");
    int lo = 1;
    switch (light.kind) {
        case Light::Kind::Rectangle:
            r.only({"type", "position", "axis1", "axis2", "size", "color", "polarisation", "spectrum"});
            light.axis1 = edge(r, "axis1");
            light.axis2 = edge(r, "axis2");
            if (!(light.axis1.cross(light.axis2).norm() > 1e-9 * light.axis1.norm() * light.axis2.norm()))
                r.fail_at("axis2", "must not be parallel to axis1");
            break;
        case Light::Kind::Disk: {
            r.only({"type", "position", "normal", "radius", "size", "color", "polarisation", "spectrum"});
            const auto n = unit_vector(r.vec3("normal"));
            if (!n) r.fail_at("normal", "must be a finite, non-zero vector");
            light.normal = *n;
            light.radius = r.number("radius");
            if (!(light.radius > 0 && light.radius <= 1e15)) r.fail_at("radius", "must be in (0, 1e15]");
            const Frame f = frame_across(light.normal);
            light.axis1 = 2.0 * light.radius * f.u;
            light.axis2 = 2.0 * light.radius * f.v;
            lo = 2;  // POV-Ray's circular grid divides by size − 1
            break;
        }
        case Light::Kind::Point:
        case Light::Kind::Directional:
        case Light::Kind::Beam: break;
    }
    const auto& sz = r.raw("size");
    if (!sz.is_array() || sz.size() != 2)
        r.fail_at("size", "must be [n1, n2], two integers in [" + std::to_string(lo) + ", " + std::to_string(kMaxAreaLightGrid) + "]");
    light.size = {grid_size(r, 0, lo), grid_size(r, 1, lo)};
}

}  // namespace refract
