#include <refract/core/render_metadata.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <refract/core/integrators/integrator.h>
#include <refract/core/provenance.h>
#include <refract/core/scene.h>
#include <refract/core/spectrum/chromaticities.h>

namespace refract {

std::vector<std::pair<std::string, std::string>> render_attributes(const Scene& scene, const std::string& scene_path) {
    const RenderSettings& s = scene.settings;
    const auto c = spectrum::chromaticities(s.spectral.pipeline, spectrum::sample_wavelengths(s.spectral.sampling),
                                            s.spectral.light);
    std::string chroma;
    for (const double v : c) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.9g", v);
        chroma += (chroma.empty() ? "" : " ") + std::string(buf);
    }
    std::vector<std::pair<std::string, std::string>> a{
        {"chromaticities", chroma},
        {"Software", std::string("refract ") + version()},
        {"refract:version", version()},
        {"refract:scene", scene_path},
    };
    std::ifstream in(scene_path, std::ios::binary);
    if (in) {
        std::ostringstream bytes;
        bytes << in.rdbuf();
        a.emplace_back("refract:scene_fnv1a64", fnv1a64_hex(bytes.str()));
    }
    a.emplace_back("refract:integrator", integrator_name(s.integrator));
    a.emplace_back("refract:samples", std::to_string(s.samples));
    a.emplace_back("refract:seed", std::to_string(s.seed));
    a.emplace_back("refract:colour_pipeline", spectrum::to_string(s.spectral.pipeline));
    if (!command_line().empty()) a.emplace_back("refract:command_line", command_line());
    return a;
}

}  // namespace refract
