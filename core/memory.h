#pragma once
// The memory a render or a far-field run will hold, estimated before anything large is
// allocated, and refused past a budget (--max-memory; docs/limits.md).
#include <cstdint>
#include <string>
#include <vector>

namespace refract {

struct Scene;
struct RenderOptions;
struct FarFieldSettings;

// One allocation that grows with the input, named by the field or option that sets it.
struct MemoryItem {
    std::string field;  // e.g. "/camera: width × height", "--spectral-channels"
    double bytes = 0;
};

struct MemoryEstimate {
    std::vector<MemoryItem> items;
    double total() const;
    void add(std::string field, double bytes) { items.push_back({std::move(field), bytes}); }
};

// The default budget: three quarters of the machine's physical memory (at least 256 MiB).
std::uint64_t default_memory_budget();

// "4G", "512M", "64k", "1.5G" or a plain byte count (binary units, case-insensitive, an
// optional trailing B); throws InputError naming `what` for anything else, zero or > 2^60.
std::uint64_t parse_memory_size(const std::string& text, const std::string& what);

// "1.5 GiB"-style text.
std::string format_bytes(double bytes);

// Throws InputError (one line: `where`, the total, the budget, the largest item's field)
// when the estimate exceeds `budget` (0: default_memory_budget()).
void check_memory(const MemoryEstimate& e, std::uint64_t budget, const std::string& where);

// A render's images (RGB, and the lost-energy, spectral and Stokes images it was asked
// for), the float copy its writer makes, and the light pass's illumination maps.
MemoryEstimate estimate_render_memory(const Scene& scene, const RenderOptions& opt, int threads);

// The light pass's illumination maps alone (a render of one pixel, `refract trace`).
MemoryEstimate estimate_light_pass_memory(const Scene& scene);

// A far-field run's bins (the result and one tally per thread) and its written map.
MemoryEstimate estimate_far_field_memory(std::size_t values_per_wavelength, std::size_t wavelengths, int threads);
// The far field's wavelengths are traced in groups that share their photons: as many as
// keep a thread's tally of their bins within 2^21 values (at least one).
std::size_t far_field_group(std::size_t values_per_wavelength, std::size_t wavelengths);

}  // namespace refract
