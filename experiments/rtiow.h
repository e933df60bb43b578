#pragma once
// "Ray Tracing in One Weekend", dielectric chapter (Japanese edition, listings 1.50-1.58,
// figures 1.27-1.29): the chapter's scene in its stages, Schlick against exact Fresnel,
// and the 1/√spp convergence of the stochastic integrator to the Fresnel tree.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "experiments/experiment.h"

namespace refract::experiments::rtiow {

void run(const ExperimentOptions& opt);

// The stages in the chapter's order.
struct Stage {
    std::string id;       // file stem: "fig1_27_always_refract", ...
    std::string caption;  // figure caption
};
const std::vector<Stage>& stages();

// The chapter's scene (listing 1.55 / 1.58) for a stage, mirrored in z so that refract's
// POV-Ray camera (right = sky × direction) sees it as the book's right-handed camera does.
nlohmann::json stage_scene(const std::string& id, bool quick);

// The convergence scene: the "+ Schlick" stage with the Lambertian surfaces replaced by
// directly lit diffuse ones and no fuzz, so that `stochastic` and `fresnel-tree`
// estimate the same pixel values. spp = 0 gives the fresnel-tree reference.
nlohmann::json convergence_scene(int spp, bool quick);
std::vector<int> convergence_spp(bool quick);  // 1, 4, 16, ...

// Dielectric nodes with total internal reflection met by the ray trees of the pixel
// centres (branches of weight >= 1e-4, up to the scene's depth; Lambertian surfaces end
// a branch).
std::uint64_t count_tir_nodes(const Scene& scene);

}  // namespace refract::experiments::rtiow
