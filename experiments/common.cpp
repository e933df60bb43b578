#include <refract/experiments/common.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

#include <refract/core/scene_json.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/error.h>

namespace refract::experiments {

Scene scene_from_json(const nlohmann::json& j, const std::string& name) { return parse_scene(j, name); }

namespace {

// Pretty JSON with two-space indentation, but arrays of plain values on one line
// ("center": [0.0, 1.0, 0.0]), as a person would write a scene file.
void dump_json(const nlohmann::json& j, int indent, std::string& out) {
    const std::string pad(static_cast<size_t>(indent) + 2, ' '), close_pad(static_cast<size_t>(indent), ' ');
    if (j.is_object()) {
        if (j.empty()) {
            out += "{}";
            return;
        }
        out += "{\n";
        size_t k = 0;
        for (const auto& [key, value] : j.items()) {
            out += pad + nlohmann::json(key).dump() + ": ";
            dump_json(value, indent + 2, out);
            out += (++k < j.size() ? ",\n" : "\n");
        }
        out += close_pad + "}";
    } else if (j.is_array()) {
        bool flat = true;
        for (const auto& v : j) flat = flat && !v.is_structured();
        if (flat) {
            out += "[";
            for (size_t k = 0; k < j.size(); ++k) out += (k ? ", " : "") + j[k].dump();
            out += "]";
            return;
        }
        out += "[\n";
        for (size_t k = 0; k < j.size(); ++k) {
            out += pad;
            dump_json(j[k], indent + 2, out);
            out += (k + 1 < j.size() ? ",\n" : "\n");
        }
        out += close_pad + "]";
    } else {
        out += j.dump();
    }
}

}  // namespace

std::string json_text(const nlohmann::json& j) {
    std::string out;
    dump_json(j, 0, out);
    return out + "\n";
}

void save_json(const std::string& dir, const std::string& name, const nlohmann::json& j) {
    ensure_dir(dir);
    write_text_atomic((std::filesystem::path(dir) / name).string(), json_text(j));
}

double rmse(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) throw std::logic_error("rmse: images differ in size");
    double sum = 0;
    for (size_t k = 0; k < a.rgb.size(); ++k) {
        const double d = a.rgb[k] - b.rgb[k];
        sum += d * d;
    }
    return std::sqrt(sum / static_cast<double>(a.rgb.size()));
}

LineFit loglog_fit(const std::vector<double>& x, const std::vector<double>& y) {
    if (x.size() != y.size() || x.size() < 2) throw std::logic_error("loglog_fit: need two or more points");
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t k = 0; k < x.size(); ++k) {
        const double lx = std::log(x[k]), ly = std::log(y[k]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    LineFit f;
    f.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    f.intercept = (sy - f.slope * sx) / n;
    return f;
}

bool ensure_dir(const std::string& dir) {
    std::error_code ec;
    const bool existed = std::filesystem::exists(std::filesystem::symlink_status(dir, ec));
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw InputError(dir + ": cannot create the output directory" + (ec ? " (" + ec.message() + ")" : std::string()));
    if (::access(dir.c_str(), W_OK) != 0) throw InputError(dir + ": the output directory is not writable");
    return !existed;
}

nlohmann::json vec(double x, double y, double z) { return nlohmann::json::array({x, y, z}); }

}  // namespace refract::experiments
