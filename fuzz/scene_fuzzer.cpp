// libFuzzer target: the scene reader, a tiny render and the files it writes (docs/limits.md,
// "Fuzzing"). Any input must end in a scene or one InputError; a scene that loads is
// rendered small (at most 8×6 pixels, depth 6, a few photons, one thread) with its
// lost-energy image, its spectral channels when it has them, and its Stokes images with
// exact polarisation, and every file `refract render` would write is written to a private
// temporary directory and read back: every value must be finite and >= 0 but in the
// channels that may be negative (Stokes S1–S3, the angle, the colours of the xyz-srgb
// pipeline). Anything else (a crash, a sanitizer report, another exception, such as the
// writer's own internal error, or a bad value in a file) is a finding. Build and run:
// `bash run.sh fuzz [SECONDS]`.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/core/polarisation_output.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/geometry/error.h>

namespace {

// The process's own directory for the files, removed when it exits (never destroyed
// itself: the exit handler that removes it runs after the static destructors).
const std::string& scratch_dir() {
    static const std::string* dir = [] {
        auto* d = new std::string((std::filesystem::temp_directory_path() / "refract-fuzz-XXXXXX").string());
        if (!mkdtemp(d->data())) std::abort();
        return d;
    }();
    static const bool cleanup = std::atexit([] { std::filesystem::remove_all(*dir); }) == 0;
    (void)cleanup;
    return *dir;
}

// The file read back: a value that is not finite, or negative in a channel that may not
// be, is a finding.
void check_file(const std::string& path, bool (*may_be_negative)(const std::string& channel, bool), bool signed_colours) {
    const refract::Channels c = refract::read_channels(path);
    const size_t nc = c.names.size();
    for (size_t k = 0; k < c.data.size(); ++k) {
        const double v = c.data[k];
        if (std::isfinite(v) && (v >= 0 || may_be_negative(c.names[k % nc], signed_colours))) continue;
        std::fprintf(stderr, "scene_fuzzer: %s: value %zu (channel %s) is %g\n", path.c_str(), k / nc,
                     c.names[k % nc].c_str(), v);
        std::abort();
    }
}

bool colour_signed(const std::string& channel, bool signed_colours) {
    return signed_colours && (channel == "R" || channel == "G" || channel == "B");
}
bool stokes_signed(const std::string& channel, bool signed_colours) {
    return channel.rfind("S0", 0) == 0 ? signed_colours : true;
}
bool never_signed(const std::string&, bool) { return false; }
bool always_signed(const std::string&, bool) { return true; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    using namespace refract;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(data, data + size);
    } catch (const nlohmann::json::exception&) {
        return 0;  // not JSON: the reader's syntax errors are nlohmann's
    }
    Scene scene;
    try {
        scene = parse_scene(j, "fuzz.json");
    } catch (const InputError&) {
        return 0;
    }
    // Keep the render tiny: the limits themselves are tested elsewhere.
    scene.camera.width = std::min(scene.camera.width, 8);
    scene.camera.height = std::min(scene.camera.height, 6);
    RenderSettings& s = scene.settings;
    s.max_depth = std::min(s.max_depth, 6);
    s.samples = std::min(s.samples, 2);
    s.light_pass.photons = std::min<std::uint64_t>(s.light_pass.photons, 200);
    s.light_pass.element_size = std::max(s.light_pass.element_size, 0.05);
    for (Material& m : scene.materials)  // a curved ray's work: a few thousand steps
        if (auto* g = m.as<material::Grin>()) {
            g->settings.max_steps = std::min(g->settings.max_steps, 2000);
            g->settings.abs_tol = std::max(g->settings.abs_tol, 1e-10);
            g->settings.rel_tol = std::max(g->settings.rel_tol, 1e-10);
        }
    RenderOptions o;
    o.threads = 1;
    o.lost_energy = true;
    // Spectral channels are natural light's: asked for unless the scene asks for exact light.
    o.spectral_channels = s.spectral.enabled && s.compat == Compat::Physical &&
                          s.requested_polarisation.value_or(PolarisationModel::Natural) == PolarisationModel::Natural;
    RenderResult r;
    try {
        r = render(scene, o);
    } catch (const InputError&) {
        return 0;
    }
    for (double v : r.image.rgb)
        if (!std::isfinite(v)) std::abort();  // render() reports these itself; belt and braces
    // The files, as `refract render IMAGE.exr --lost [--spectral]` writes them (its
    // checks throw std::runtime_error, uncaught here: a finding).
    const int w = r.image.width, h = r.image.height;
    const std::string image = scratch_dir() + "/image.exr";
    write_image(image, r.image, {false, r.signed_colours});
    check_file(image, colour_signed, r.signed_colours);
    write_channels(scratch_dir() + "/image.lost.exr", w, h, {"depth", "limits", "threshold"}, r.lost);
    check_file(scratch_dir() + "/image.lost.exr", never_signed, false);
    if (o.spectral_channels) {
        std::vector<std::string> names;
        for (double nm : r.wavelengths) names.push_back(std::to_string(nm) + "nm");
        write_channels(scratch_dir() + "/image.spectral.exr", w, h, names, r.spectral);
        check_file(scratch_dir() + "/image.spectral.exr", never_signed, false);
    }
    if (r.polarisation) {
        const auto paths = write_polarisation(image, w, h, *r.polarisation, r.signed_colours);
        check_file(paths[0], stokes_signed, r.signed_colours);
        check_file(paths[1], never_signed, false);
        check_file(paths[2], always_signed, false);
    }
    return 0;
}
