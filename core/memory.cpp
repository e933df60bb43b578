#include <refract/core/memory.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include <unistd.h>

#include <refract/core/integrators/integrator.h>
#include <refract/core/light_pass.h>
#include <refract/core/render.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/error.h>

namespace refract {

double MemoryEstimate::total() const {
    double t = 0;
    for (const MemoryItem& i : items) t += i.bytes;
    return t;
}

std::uint64_t default_memory_budget() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const double physical = pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
    return static_cast<std::uint64_t>(std::fmax(0.75 * physical, 256.0 * 1024 * 1024));
}

std::uint64_t parse_memory_size(const std::string& text, const std::string& what) {
    const auto bad = [&] {
        return InputError(what + ": '" + text + "' is not a memory size (e.g. 512M, 4G, 1.5G or a byte count)");
    };
    std::string t = text;
    if (!t.empty() && (t.back() == 'b' || t.back() == 'B')) t.pop_back();
    double unit = 1;
    if (!t.empty()) {
        switch (std::tolower(static_cast<unsigned char>(t.back()))) {
            case 'k': unit = 1024.0; break;
            case 'm': unit = 1024.0 * 1024; break;
            case 'g': unit = 1024.0 * 1024 * 1024; break;
            case 't': unit = 1024.0 * 1024 * 1024 * 1024; break;
            default: break;
        }
        if (unit > 1) t.pop_back();
    }
    if (t.empty() || !std::all_of(t.begin(), t.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '.'; }))
        throw bad();
    double v = 0;
    try {
        size_t used = 0;
        v = std::stod(t, &used);
        if (used != t.size()) throw bad();
    } catch (const std::logic_error&) {
        throw bad();
    }
    const double bytes = std::floor(v * unit);
    if (!(bytes >= 1 && bytes <= std::ldexp(1.0, 60)))
        throw InputError(what + ": '" + text + "' must be between 1 byte and 2^60 bytes");
    return static_cast<std::uint64_t>(bytes);
}

std::string format_bytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024 && u < 6) {
        bytes /= 1024;
        ++u;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
    return buf;
}

void check_memory(const MemoryEstimate& e, std::uint64_t budget, const std::string& where) {
    if (budget == 0) budget = default_memory_budget();
    const double total = e.total();
    if (total <= static_cast<double>(budget)) return;
    const MemoryItem* largest = &e.items.front();
    for (const MemoryItem& i : e.items)
        if (i.bytes > largest->bytes) largest = &i;
    throw InputError(where + ": would need about " + format_bytes(total) + " of memory, over the budget of " +
                     format_bytes(static_cast<double>(budget)) + " (--max-memory); most of it (" +
                     format_bytes(largest->bytes) + ") for " + largest->field);
}

MemoryEstimate estimate_light_pass_memory(const Scene& scene) {
    MemoryEstimate e;
    if (scene.settings.spectral.enabled && scene.settings.light_pass.enabled)
        e.add("/render/light_pass/element_size", illumination_elements(scene) * IlluminationMap::kBytesPerElement);
    return e;
}

MemoryEstimate estimate_render_memory(const Scene& scene, const RenderOptions& opt, int threads) {
    MemoryEstimate e;
    const RenderSettings& s = scene.settings;
    const double pixels = static_cast<double>(scene.camera.width) * scene.camera.height;
    const std::string image = "/camera: width × height";
    e.add(image, pixels * (3 * 8 + 4 * 4));  // the RGB image, and the writer's float RGBA copy
    if (opt.lost_energy) e.add("--lost-energy", pixels * 3 * (8 + 4));
    if (polarisation_model(scene) == PolarisationModel::Exact) e.add("/render/polarisation", pixels * 14 * (8 + 4));
    if (opt.spectral_channels && s.spectral.enabled)
        e.add("--spectral-channels",
              pixels * (8 + 4) * static_cast<double>(spectrum::sample_wavelengths(s.spectral.sampling, "/render/spectral").size()));
    if (!opt.maps)
        for (const MemoryItem& i : estimate_light_pass_memory(scene).items) e.items.push_back(i);
    // Per thread: the tiles' statistics and a walker's list, small next to the images.
    e.add("--threads", static_cast<double>(std::max(1, threads)) * 64 * 1024);
    return e;
}

MemoryEstimate estimate_far_field_memory(std::size_t values_per_wavelength, std::size_t wavelengths, int threads) {
    MemoryEstimate e;
    const double v = static_cast<double>(values_per_wavelength);
    e.add("the far-field bins (bins × classes × components × wavelengths)", v * static_cast<double>(wavelengths) * (8 + 4));
    const double group = static_cast<double>(far_field_group(values_per_wavelength, wavelengths));
    e.add("--threads (a tally of the bins per thread)", v * group * 8 * static_cast<double>(std::max(1, threads)));
    return e;
}

std::size_t far_field_group(std::size_t values_per_wavelength, std::size_t wavelengths) {
    const std::size_t fit = (std::size_t{1} << 21) / std::max<std::size_t>(1, values_per_wavelength);
    return std::max<std::size_t>(1, std::min(wavelengths, fit));
}

}  // namespace refract
