// Profiles read from scene files (core/grin/profile_json.h).
#include <refract/core/grin/profile_json.h>

#include <cmath>
#include <iterator>
#include <vector>

namespace refract::grin {

namespace {

CauchyIndex base(const JsonReader& r, double fallback) {
    return CauchyIndex{r.number("n0", fallback), r.number("cauchy_b", 0.0)};
}

// Each kind's name, reader and fields: a constant table (nothing allocated on first use).
struct KindEntry {
    const char* name;
    Profile (*read)(const JsonReader&);
};

constexpr KindEntry kKinds[] = {
        {"linear-height",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "n0", "cauchy_b", "slope", "h0", "up"});
             return LinearHeight{base(r, 1.0), r.number("slope"), r.number("h0", 0.0), r.vec3("up", Vec3::UnitY())};
         }},
        {"exponential-height",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "n0", "cauchy_b", "scale_height", "h0", "up"});
             return ExponentialHeight{base(r, 1.000293), r.number("scale_height"), r.number("h0", 0.0),
                                      r.vec3("up", Vec3::UnitY())};
         }},
        {"luneburg",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "centre", "radius"});
             return Luneburg{r.vec3("centre", Vec3::Zero()), r.number("radius")};
         }},
        {"maxwell-fish-eye",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "centre", "n0", "cauchy_b", "a"});
             return MaxwellFishEye{r.vec3("centre", Vec3::Zero()), base(r, 2.0), r.number("a")};
         }},
        {"sech-rod",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "point", "axis", "n0", "cauchy_b", "alpha"});
             return SechRod{r.vec3("point", Vec3::Zero()), r.vec3("axis", Vec3::UnitZ()), base(r, 1.5), r.number("alpha")};
         }},
        {"parabolic-rod",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "point", "axis", "n0", "cauchy_b", "A"});
             return ParabolicRod{r.vec3("point", Vec3::Zero()), r.vec3("axis", Vec3::UnitZ()), base(r, 1.5), r.number("A")};
         }},
        {"tabulated-radial",
         [](const JsonReader& r) -> Profile {
             r.only({"kind", "centre", "r", "n"});
             auto numbers = [&](const std::string& key) {
                 const nlohmann::json& a = r.raw(key);
                 if (!a.is_array()) r.fail_at(key, "must be an array of numbers");
                 std::vector<double> v;
                 for (size_t i = 0; i < a.size(); ++i) {
                     if (!a[i].is_number() || !std::isfinite(a[i].get<double>()))
                         r.fail_at(key + "/" + std::to_string(i), "must be a finite number");
                     v.push_back(a[i].get<double>());
                 }
                 return v;
             };
             return tabulated_radial(r.vec3("centre", Vec3::Zero()), numbers("r"), numbers("n"),
                                     r.file() + ": " + r.path());
         }},
};
const KindEntry* kinds_begin() { return std::begin(kKinds); }
const KindEntry* kinds_end() { return std::end(kKinds); }

struct Namer {
    const char* operator()(const LinearHeight&) const { return "linear-height"; }
    const char* operator()(const ExponentialHeight&) const { return "exponential-height"; }
    const char* operator()(const Luneburg&) const { return "luneburg"; }
    const char* operator()(const MaxwellFishEye&) const { return "maxwell-fish-eye"; }
    const char* operator()(const SechRod&) const { return "sech-rod"; }
    const char* operator()(const ParabolicRod&) const { return "parabolic-rod"; }
    const char* operator()(const TabulatedRadial&) const { return "tabulated-radial"; }
    const char* operator()(const EarthAtmosphere&) const { return "earth-atmosphere"; }
};

}  // namespace

Profile read_profile(const JsonReader& r) {
    const std::string kind = r.string("kind");
    std::string known;
    for (const KindEntry* k = kinds_begin(); k != kinds_end(); ++k) {
        if (kind == k->name) return k->read(r);
        known += (known.empty() ? "" : ", ") + std::string(k->name);
    }
    r.fail_at("kind", "unknown profile '" + clip_echo(kind) + "' (" + known + ")");
}

std::string kind_name(const Profile& p) { return std::visit(Namer{}, p); }

}  // namespace refract::grin
