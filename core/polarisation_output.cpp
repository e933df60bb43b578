#include <refract/core/polarisation_output.h>

#include <cmath>
#include <filesystem>

#include <refract/core/image.h>

namespace refract {

std::vector<std::string> polarisation_paths(const std::string& image_path) {
    const std::filesystem::path p(image_path);
    const std::filesystem::path stem = p.parent_path() / p.stem();
    return {stem.string() + ".stokes.exr", stem.string() + ".dolp.exr", stem.string() + ".aolp.exr"};
}

std::vector<std::string> write_polarisation(const std::string& image_path, int width, int height,
                                            const PolarisationImages& p, bool signed_colours) {
    const auto paths = polarisation_paths(image_path);
    std::vector<std::string> names, signed_names;
    for (const char* s : {"S0", "S1", "S2", "S3"})
        for (const char* c : {"R", "G", "B"}) {
            names.push_back(std::string(s) + "." + c);
            if (names.back()[1] != '0' || signed_colours) signed_names.push_back(names.back());
        }
    write_channels(paths[0], width, height, names, p.stokes, {}, signed_names);
    write_channels(paths[1], width, height, {"Y"}, p.dolp);
    std::vector<double> deg(p.aolp.size());
    for (size_t k = 0; k < deg.size(); ++k) deg[k] = p.aolp[k] * 180.0 / M_PI;
    write_channels(paths[2], width, height, {"Y"}, deg, {}, {"Y"});
    return paths;
}

}  // namespace refract
