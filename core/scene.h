#pragma once
// The in-memory scene: what a scene file (docs/scene-format.md) describes.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/camera.h"
#include "core/material.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/dispersion.h"
#include "core/spectrum/wavelengths.h"
#include "geometry/shapes.h"

namespace refract {

struct Object {
    std::string name;
    Shape shape;
    int material = 0;  // index into Scene::materials
};

// A polarisation state (docs/polarisation.md): of a light's emission, or the state an
// analyser in front of the camera passes.
struct PolarisationState {
    enum class Kind { Unpolarised, Linear, Circular };
    Kind kind = Kind::Unpolarised;
    // Linear: the angle of the electric field. A light's is measured about its beam from
    // `reference` projected across the beam (default the world's y axis; x when the beam
    // runs along y), towards ŷ = k̂ × x̂; an analyser's on the image, from its right
    // towards its top.
    double angle_deg = 0;
    Vec3 reference{0, 1, 0};
    int handedness = 1;  // Circular: sign of S3 (+1: left-circular in Born & Wolf's naming)
};

// A point light, or a directional one (a sun of no angular size): parallel light
// travelling along `direction`, of irradiance `color` on a surface facing it. Shadow rays
// of a directional light run to the plane across it at kDirectionalDistance from the
// origin (where the POV-Ray export puts its `parallel` light).
struct Light {
    enum class Kind { Point, Directional };
    Vec3 position{0, 10, 0};  // point light
    Vec3 color{1, 1, 1};      // no distance falloff (POV-Ray default)
    PolarisationState polarisation;  // what the light pass's photons start with
    Kind kind = Kind::Point;
    Vec3 direction{0, -1, 0};  // directional: unit, the way the light travels

    static constexpr double kDirectionalDistance = 1e5;
    // Directional: the point standing for the light (the export's light_source location).
    Vec3 directional_position() const { return -kDirectionalDistance * direction; }

    // Seen from point p: the unit direction towards the light and where a shadow ray from
    // p ends (a point light's position; for a directional light the plane across it
    // through directional_position(), as POV-Ray's `parallel`: trace.cpp
    // ComputeOneWhiteLightRay).
    struct Toward {
        Vec3 dir, end;
    };
    Toward toward(const Vec3& p) const {
        if (kind == Kind::Directional)
            return {-direction, p - (directional_position() - p).dot(-direction) * direction};
        return {(position - p).normalized(), position};
    }
};

struct Background {
    enum class Kind { Solid, Gradient };  // Gradient: RTIOW sky, lerp on 0.5(dir.y + 1)
    Kind kind = Kind::Solid;
    Vec3 color{0, 0, 0};     // Solid
    Vec3 bottom{1, 1, 1};    // Gradient at dir.y = −1
    Vec3 top{0.5, 0.7, 1.0}; // Gradient at dir.y = +1
};

// Spectral eye pass (Ohtsuka & Kawai 1998): render.spectral in the scene file.
struct SpectralSettings {
    bool enabled = false;  // on when the block is given or a material has a dispersion
    spectrum::WavelengthSampling sampling;  // 400–700 nm every 10 nm
    spectrum::ColourPipeline pipeline = spectrum::ColourPipeline::CieRgb;
    spectrum::LightSpectrum light;          // the lights' spectrum (equal energy)
    bool shortcut = false;                  // three-wavelength test before the full split
    std::array<double, 3> shortcut_wavelengths{610.0, 545.0, 445.0};
    double shortcut_threshold = 0.01;       // RGB distance of the three contributions
    // Separate limits per path (the paper used 8 and 8): none unless the scene sets them.
    // POV-Ray has max_trace_level only, so the compat mode has none by default either.
    std::optional<int> max_reflections;
    std::optional<int> max_transmissions;
};

// Light pass (bidirectional ray tracing): photons from each point light at the transparent
// objects, deposited in illumination maps of the diffuse surfaces (render.light_pass).
struct LightPassSettings {
    bool enabled = false;
    std::uint64_t photons = 200000;  // per light
    double element_size = 0.02;      // edge of an illumination-map element (scene units)
    double region = 3.0;             // plane maps: half-size of the square under the gems,
                                     // in units of the gems' bounding radius
    std::uint64_t seed = 7;
};

enum class IntegratorKind { Whitted, FresnelTree, Stochastic };
// Natural: Yasuda's eq. 7 at every node, as if light were natural again after each
// interface (and POV-Ray's model). Exact: Stokes vectors carried through Mueller matrices.
enum class PolarisationModel { Natural, Exact };
enum class Compat { Physical, PovRay };

struct RenderSettings {
    IntegratorKind integrator = IntegratorKind::FresnelTree;
    // Longest path: a ray spawned after `max_depth` surface interactions is not traced
    // (returns black). POV-Ray's max_trace_level = max_depth + 1.
    int max_depth = 16;
    // Yasuda's cumulative-attenuation threshold (POV-Ray adc_bailout): a branch whose
    // weight falls below it is dropped. 0 keeps every branch.
    double threshold = 1.0 / 255.0;
    // The threshold in force: Whitted's stored tree never prunes, whichever pass walks it
    // (the spectral eye pass included).
    double pruning_threshold() const { return integrator == IntegratorKind::Whitted ? 0.0 : threshold; }
    int samples = 1;          // samples per pixel
    bool jitter = false;      // jittered supersampling inside the pixel
    std::uint64_t seed = 1;   // stochastic integrator and jitter
    Compat compat = Compat::Physical;
    SpectralSettings spectral;
    LightPassSettings light_pass;
    PolarisationModel polarisation = PolarisationModel::Natural;
    std::optional<PolarisationState> analyser;  // exact only: an ideal polariser before the camera
};

struct Scene {
    std::string source;  // file the scene came from (for messages)
    Camera camera;
    std::vector<Material> materials;
    std::vector<Object> objects;
    std::vector<Light> lights;
    Background background;
    RenderSettings settings;
};

}  // namespace refract
