// Profiles read from scene files (core/grin/profile_json.h).
#include <refract/core/grin/profile_json.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <vector>

namespace refract::grin {

namespace {

CauchyIndex base(const JsonReader& r, double fallback) {
    return CauchyIndex{r.number("n0", fallback), r.number("cauchy_b", 0.0)};
}

// A grid's samples from inline "values" (nested lists, values[i][j][k] at origin +
// (i, j, k)·spacing; what a NumPy array of shape (n_x, n_y, n_z) becomes in Python) or
// from an OpenVDB "file" (relative to the scene file's directory).
GridSamples grid_samples(const JsonReader& r) {
    const bool inline_values = r.has("values"), file = r.has("file");
    if (inline_values == file) r.fail_at(file ? "file" : "values", "give either \"values\" or \"file\" (one of them)");
    if (file) {
        if (r.has("origin") || r.has("spacing"))
            r.fail_at(r.has("origin") ? "origin" : "spacing", "comes from the OpenVDB file's voxel transform");
        const std::string name = r.string("file");
        if (name.empty()) r.fail_at("file", "must name an OpenVDB file");
        const std::string path = (std::filesystem::path(r.file()).parent_path() / name).lexically_normal().string();
        return read_vdb_grid(path, r.string("grid", ""), r.file() + ": " + r.path());
    }
    GridSamples s;
    s.origin = r.vec3("origin");
    const nlohmann::json& sp = r.raw("spacing");
    s.spacing = sp.is_number() ? Vec3::Constant(r.number("spacing")) : r.vec3("spacing");
    const nlohmann::json& v = r.raw("values");
    auto list = [&](const nlohmann::json& a, const std::string& at) -> size_t {
        if (!a.is_array() || a.empty()) r.fail_at(at, "must be a non-empty array (values[i][j][k])");
        return a.size();
    };
    const size_t nx = list(v, "values"), ny = list(v[0], "values/0"), nz = list(v[0][0], "values/0/0");
    s.dims = {static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz)};
    s.values.assign(nx * ny * nz, 0.0);
    for (size_t i = 0; i < nx; ++i) {
        const std::string pi = "values/" + std::to_string(i);
        if (list(v[i], pi) != ny) r.fail_at(pi, std::to_string(v[i].size()) + " rows, the first has " + std::to_string(ny));
        for (size_t j = 0; j < ny; ++j) {
            const std::string pj = pi + "/" + std::to_string(j);
            if (list(v[i][j], pj) != nz)
                r.fail_at(pj, std::to_string(v[i][j].size()) + " values, the first row has " + std::to_string(nz));
            for (size_t k = 0; k < nz; ++k) {
                const nlohmann::json& x = v[i][j][k];
                if (!x.is_number()) r.fail_at(pj + "/" + std::to_string(k), "must be a number");
                s.values[i + nx * (j + ny * k)] = x.get<double>();
            }
        }
    }
    return s;
}

Profile read_grid(const JsonReader& r) {
    r.only({"kind", "quantity", "values", "origin", "spacing", "file", "grid", "reference_temperature", "pressure",
            "relative"});
    const std::string q = r.string("quantity", "index");
    if (q != "index" && q != "temperature") r.fail_at("quantity", "'" + clip_echo(q) + "' must be index or temperature");
    const GridQuantity quantity = q == "index" ? GridQuantity::index : GridQuantity::temperature;
    for (const char* k : {"reference_temperature", "pressure", "relative"})
        if (quantity == GridQuantity::index && r.has(k)) r.fail_at(k, "applies to a temperature grid only");
    const double T_ref = r.number("reference_temperature", 288.15), p = r.number("pressure", 101325.0);
    SampledGrid g = sampled_grid(grid_samples(r), quantity, T_ref, p, r.has("file") ? "file" : "values",
                                 r.file() + ": " + r.path());
    g.relative = r.boolean("relative", false);
    return g;
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
        {"earth-atmosphere",
         [](const JsonReader& r) -> Profile {
             // The air over a spherical Earth of radius kEarthRadius_m centred at `centre`
             // (default: the ground under the origin, y up), scene units metres.
             r.only({"kind", "centre", "sea_level_temperature", "sea_level_pressure", "relative_humidity",
                     "humidity_scale_height", "co2", "surface_delta_T", "surface_height"});
             AtmosphereSpec spec;
             spec.sea_level_temperature_K = r.number("sea_level_temperature", spec.sea_level_temperature_K);
             spec.sea_level_pressure_Pa = r.number("sea_level_pressure", spec.sea_level_pressure_Pa);
             spec.relative_humidity = r.number("relative_humidity", spec.relative_humidity);
             spec.humidity_scale_height_m = r.number("humidity_scale_height", spec.humidity_scale_height_m);
             spec.co2_ppm = r.number("co2", spec.co2_ppm);
             spec.surface_delta_T_K = r.number("surface_delta_T", spec.surface_delta_T_K);
             spec.surface_height_m = r.number("surface_height", spec.surface_height_m);
             return EarthAtmosphere{r.vec3("centre", Vec3(0, -kEarthRadius_m, 0)), Atmosphere(spec, r.file() + ": " + r.path())};
         }},
        {"grid", read_grid},
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
    const char* operator()(const SampledGrid&) const { return "grid"; }
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
