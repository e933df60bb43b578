#include <refract/core/json_reader.h>

#include <cmath>

namespace refract {

JsonReader::JsonReader(const nlohmann::json& j, std::string file, std::string path)
    : j_(j), file_(std::move(file)), path_(std::move(path)) {
    if (!j_.is_object() && !j_.is_array()) fail("must be an object");
}

void JsonReader::fail(const std::string& what) const {
    throw InputError(file_ + ": " + (path_.empty() ? "/" : path_) + ": " + what);
}
void JsonReader::fail_at(const std::string& key, const std::string& what) const {
    throw InputError(file_ + ": " + path_of(key) + ": " + what);
}

bool JsonReader::has(const std::string& key) const { return j_.is_object() && j_.contains(key); }

const nlohmann::json& JsonReader::raw(const std::string& key) const {
    if (!has(key)) fail_at(key, "missing required field");
    return j_.at(key);
}

JsonReader JsonReader::child(const std::string& key) const {
    const auto& v = raw(key);
    if (!v.is_object()) fail_at(key, "must be an object");
    return JsonReader(v, file_, path_of(key));
}

JsonReader JsonReader::element(size_t index) const {
    const auto& v = j_.at(index);
    if (!v.is_object()) throw InputError(file_ + ": " + path_ + "/" + std::to_string(index) + ": must be an object");
    return JsonReader(v, file_, path_ + "/" + std::to_string(index));
}

double JsonReader::number(const std::string& key) const {
    const auto& v = raw(key);
    if (!v.is_number()) fail_at(key, "must be a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail_at(key, "must be a finite number");
    return x;
}
double JsonReader::number(const std::string& key, double fallback) const {
    return has(key) ? number(key) : fallback;
}
double JsonReader::positive(const std::string& key, double fallback) const {
    const double x = number(key, fallback);
    if (!(x > 0)) fail_at(key, "must be > 0 (got " + std::to_string(x) + ")");
    return x;
}
int JsonReader::integer(const std::string& key, int fallback, int lo, int hi) const {
    if (!has(key)) return fallback;
    const auto& v = raw(key);
    if (!v.is_number_integer()) fail_at(key, "must be an integer");
    // An unsigned value past 2^63 would read as a negative long long: report it as given.
    const bool huge = v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi);
    const long long x = huge ? static_cast<long long>(hi) + 1 : v.get<long long>();
    if (x < lo || x > hi)
        fail_at(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + v.dump() + ")");
    return static_cast<int>(x);
}
bool JsonReader::boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const auto& v = raw(key);
    if (!v.is_boolean()) fail_at(key, "must be true or false");
    return v.get<bool>();
}
std::string JsonReader::string(const std::string& key) const {
    const auto& v = raw(key);
    if (!v.is_string()) fail_at(key, "must be a string");
    return v.get<std::string>();
}
std::string JsonReader::string(const std::string& key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
}

Vec3 JsonReader::vec3_value(const nlohmann::json& v, const std::string& file, const std::string& path) {
    if (!v.is_array() || v.size() != 3) throw InputError(file + ": " + path + ": must be an array of 3 numbers");
    Vec3 out;
    for (int k = 0; k < 3; ++k) {
        if (!v[k].is_number()) throw InputError(file + ": " + path + "/" + std::to_string(k) + ": must be a number");
        out[k] = v[k].get<double>();
        if (!std::isfinite(out[k]))
            throw InputError(file + ": " + path + "/" + std::to_string(k) + ": must be a finite number");
    }
    return out;
}
Vec3 JsonReader::vec3(const std::string& key) const { return vec3_value(raw(key), file_, path_of(key)); }
Vec3 JsonReader::vec3(const std::string& key, const Vec3& fallback) const {
    return has(key) ? vec3(key) : fallback;
}

Vec3 JsonReader::colour_value(const nlohmann::json& v, const std::string& file, const std::string& path) {
    const Vec3 c = vec3_value(v, file, path);
    for (int k = 0; k < 3; ++k)
        if (!(c[k] >= 0 && c[k] <= kMaxColour))
            throw InputError(file + ": " + path + ": components must be in [0, 1e30] (got " + format_value(c[k]) + ")");
    return c;
}
Vec3 JsonReader::colour(const std::string& key, const Vec3& fallback) const {
    return has(key) ? colour_value(raw(key), file_, path_of(key)) : fallback;
}
double JsonReader::coefficient(const std::string& key, double fallback) const {
    const double x = number(key, fallback);
    if (!(x >= 0 && x <= kMaxColour)) fail_at(key, "must be in [0, 1e30] (got " + format_value(x) + ")");
    return x;
}

void JsonReader::only(const std::set<std::string>& allowed) const {
    if (!j_.is_object()) return;
    for (const auto& [key, value] : j_.items()) {
        (void)value;
        if (!allowed.count(key)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            fail_at(key, "unknown field (expected one of: " + list + ")");
        }
    }
}

}  // namespace refract
