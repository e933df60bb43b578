#pragma once
// Strict reading of JSON objects with the JSON path in every error message:
// "FILE: /objects/2/radius: must be a finite number". Unknown fields are errors.
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/geometry/error.h>
#include <refract/geometry/ray.h>

namespace refract {

// Every colour, radiance and coefficient of a scene (light and material colours, filters,
// background, ambient, diffuse): in [0, 1e30], so that none is negative and each stays far
// inside a float's range (docs/limits.md).
constexpr double kMaxColour = 1e30;

class JsonReader {
public:
    JsonReader(const nlohmann::json& j, std::string file, std::string path);

    [[noreturn]] void fail(const std::string& what) const;
    [[noreturn]] void fail_at(const std::string& key, const std::string& what) const;
    const std::string& path() const { return path_; }
    const std::string& file() const { return file_; }
    // A key's path; a key longer than 64 bytes is clipped there (geometry/format.h).
    std::string path_of(const std::string& key) const { return path_ + "/" + clip_echo(key); }
    const nlohmann::json& json() const { return j_; }

    bool has(const std::string& key) const;
    JsonReader child(const std::string& key) const;    // required object field
    JsonReader element(size_t index) const;            // for arrays
    const nlohmann::json& raw(const std::string& key) const;  // required field, any type

    double number(const std::string& key) const;  // required finite number
    double number(const std::string& key, double fallback) const;
    double positive(const std::string& key, double fallback) const;  // > 0
    int integer(const std::string& key, int fallback, int lo, int hi) const;
    bool boolean(const std::string& key, bool fallback) const;
    std::string string(const std::string& key) const;
    std::string string(const std::string& key, const std::string& fallback) const;
    Vec3 vec3(const std::string& key) const;
    Vec3 vec3(const std::string& key, const Vec3& fallback) const;
    static Vec3 vec3_value(const nlohmann::json& v, const std::string& file, const std::string& path);
    // A colour: components in [0, kMaxColour]; a coefficient: a number in [0, kMaxColour].
    Vec3 colour(const std::string& key, const Vec3& fallback) const;
    double coefficient(const std::string& key, double fallback) const;
    static Vec3 colour_value(const nlohmann::json& v, const std::string& file, const std::string& path);

    // Throws on any field not in `allowed` (checks typos such as "raduis").
    void only(const std::set<std::string>& allowed) const;

private:
    const nlohmann::json& j_;
    std::string file_;
    std::string path_;
};

}  // namespace refract
