#pragma once
// Ohtsuka & Kawai 1998, "A rendering method for transparent objects with bidirectional ray
// tracing": a round-brilliant diamond (Sellmeier diamond) on a diffuse floor, one light,
// 640×480, 400–700 nm every 10 nm, at most 8 reflections / 8 transmissions; the image with
// and without the three-wavelength shortcut, their difference, the paper's conditions and
// time tables, and the studies the paper leaves open (wavelength step, element size,
// shortcut threshold, 610 nm against the measured peak of r̄).
#include <cstdint>

#include <nlohmann/json.hpp>

#include <refract/core/scene.h>
#include <refract/experiments/experiment.h>

namespace refract::experiments::ohtsuka1998 {

struct SceneParams {
    int width = 640, height = 480;
    double step_nm = 10;
    std::uint64_t photons = 30000;  // the experiment's main image uses more (ohtsuka1998.cpp)
    double element_size = 0.025;
    std::uint64_t seed = 7;  // the light pass's
    MapFilter filter = MapFilter::Bilinear;
    bool shortcut = false;
    double shortcut_threshold = 0.01;
    double shortcut_wavelengths[3] = {610, 545, 445};
    bool light_pass = true;
};

// The experiment's scene as a scene file.
nlohmann::json scene_json(const SceneParams& p);

// The same set-up for POV-Ray: the diamond's Sellmeier index replaced by POV-Ray's law
// through n(555 nm) with D = n(380)/n(730) and `samples` bands, POV-Ray compat mode, no
// light pass and no separate reflection/transmission limits (POV-Ray has none).
nlohmann::json povray_scene_json(const SceneParams& p, int samples);

void run(const ExperimentOptions& opt);

}  // namespace refract::experiments::ohtsuka1998
