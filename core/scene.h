#pragma once
// The in-memory scene: what a scene file (docs/scene-format.md) describes.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <refract/core/camera.h>
#include <refract/core/material.h>
#include <refract/core/spectrum/cie.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/shapes.h>
#include <refract/geometry/transform.h>

namespace refract {

struct Object {
    std::string name;
    Shape shape;       // in the scene's coordinates (any transform applied)
    int material = 0;  // index into Scene::materials
    // The object's "transform" and its shape before it (the POV-Ray export writes that
    // shape with POV-Ray's `matrix`); empty when the object has none.
    struct Placement {
        Transform transform;
        std::shared_ptr<const Shape> local;
    };
    std::optional<Placement> placement;
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

// A point light; a directional one (a sun: parallel light travelling along `direction`,
// of irradiance `color` on a surface facing it, seen as a disk of `angular_diameter_deg`);
// or a collimated beam (parallel light along `direction` inside the cylinder of `radius`
// about the axis through `position`, starting on the disk across it there; `color` its
// irradiance). Shadow rays of a directional light run to the plane across it at
// kDirectionalDistance from the origin (where the POV-Ray export puts its `parallel`
// light); a beam's to its starting disk. The eye passes see a sun as its centre
// direction; its angular size spreads the light pass's photons (docs/scene-format.md).
// An area light (a rectangle, or a disk as POV-Ray's `circular` grid) is the grid of
// size[0] × size[1] point lights of colour color / (size[0]·size[1]) that
// grid_point() places (POV-Ray's area_light without jitter; core/area_light.h).
struct Light {
    enum class Kind { Point, Directional, Beam, Rectangle, Disk };
    Vec3 position{0, 10, 0};  // point light; a beam's starting centre
    Vec3 color{1, 1, 1};      // no distance falloff (POV-Ray default)
    PolarisationState polarisation;  // what the light pass's photons start with
    Kind kind = Kind::Point;
    Vec3 direction{0, -1, 0};  // directional and beam: unit, the way the light travels
    double angular_diameter_deg = 0;  // directional: the sun's disk (0: a point at infinity)
    double radius = 0;                // beam: the cylinder's radius; disk: its radius
    // Rectangle: centred on `position`, edges axis1 and axis2; disk: axis1 = 2·radius·u,
    // axis2 = 2·radius·v across `normal` (the export's area_light axes).
    Vec3 axis1{0, 0, 0}, axis2{0, 0, 0};
    Vec3 normal{0, 1, 0};             // disk: unit, the side it faces (either side lights)
    std::array<int, 2> size{1, 1};    // area lights: the grid of point lights
    // The light's relative spectral power (spectral passes); when a light gives one, the
    // scene's render.spectral.light is that spectrum (docs/scene-format.md).
    std::optional<spectrum::LightSpectrum> spectrum;

    static constexpr double kDirectionalDistance = 1e5;
    // Directional: the point standing for the light (the export's light_source location).
    Vec3 directional_position() const { return -kDirectionalDistance * direction; }
    bool parallel() const {
        switch (kind) {
            case Kind::Directional:
            case Kind::Beam: return true;
            case Kind::Point:
            case Kind::Rectangle:
            case Kind::Disk: break;
        }
        return false;
    }
    // The point lights the light is made of: 1, or an area light's grid.
    int samples() const {
        switch (kind) {
            case Kind::Rectangle:
            case Kind::Disk: return size[0] * size[1];
            case Kind::Point:
            case Kind::Directional:
            case Kind::Beam: break;
        }
        return 1;
    }
    // Point light k (0 ≤ k < samples()) of an area light's grid, row-major in size[0]
    // (core/area_light.cpp); a point light's position.
    Vec3 grid_point(int k) const;
    // Each point light's colour.
    Vec3 sample_color() const { return samples() == 1 ? color : color / static_cast<double>(samples()); }

    // Seen from point p: the unit direction towards the light and where a shadow ray from
    // p ends (a point light's position; for a directional light the plane across it
    // through directional_position(), as POV-Ray's `parallel`: trace.cpp
    // ComputeOneWhiteLightRay; for a beam its starting disk). None when p lies outside a
    // beam.
    struct Toward {
        Vec3 dir, end;
    };
    // Of point light k of an area light's grid (k is 0 for the other kinds).
    std::optional<Toward> toward(const Vec3& p, int k = 0) const {
        switch (kind) {
            case Kind::Rectangle:
            case Kind::Disk: {
                const Vec3 q = grid_point(k);
                return Toward{(q - p).normalized(), q};
            }
            case Kind::Directional:
                return Toward{-direction, p - (directional_position() - p).dot(-direction) * direction};
            case Kind::Beam: {
                const double along = (p - position).dot(direction);
                const Vec3 foot = position + along * direction;
                if (along <= 0 || (p - foot).norm() > radius) return std::nullopt;
                return Toward{-direction, p - along * direction};
            }
            case Kind::Point: break;
        }
        return Toward{(position - p).normalized(), position};
    }
};

struct EnvironmentMap;  // core/environment_map.h

// What a ray that leaves the scene sees. Environment: an environment light, of constant
// radiance `color` (no map) or an equirectangular map (POV-Ray's spherical image map,
// core/environment_map.h), times `scale`, the map turned by `rotation_deg` about +y.
struct Background {
    enum class Kind { Solid, Gradient, Environment };  // Gradient: RTIOW sky, lerp on 0.5(dir.y + 1)
    Kind kind = Kind::Solid;
    Vec3 color{0, 0, 0};     // Solid; Environment without a map
    Vec3 bottom{1, 1, 1};    // Gradient at dir.y = −1
    Vec3 top{0.5, 0.7, 1.0}; // Gradient at dir.y = +1
    std::shared_ptr<const EnvironmentMap> map;  // Environment: read once, at scene load
    double scale = 1.0;         // Environment: multiplies the colour or the map
    double rotation_deg = 0.0;  // Environment: the map turned about +y, +z towards +x

    // The radiance arriving from direction `dir` (any length but zero): the one lookup of
    // every ray that leaves the scene (SceneTracer::background), usable on its own.
    Vec3 radiance(const Vec3& dir) const;
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
// How the eye pass reads an illumination map between element centres
// (core/illumination_map.h): Box, the element's constant value; Bilinear (the default),
// plane maps interpolate bilinearly between the four nearest element centres, mesh maps
// barycentrically between the averages at the corners of each triangle's elements.
enum class MapFilter { Box, Bilinear };
inline const char* filter_name(MapFilter f) { return f == MapFilter::Box ? "box" : "bilinear"; }

struct LightPassSettings {
    bool enabled = false;
    std::uint64_t photons = 200000;  // per light
    double element_size = 0.02;      // edge of an illumination-map element (scene units)
    double region = 3.0;             // plane maps: half-size of the square under the gems,
                                     // in units of the gems' bounding radius
    std::uint64_t seed = 7;
    MapFilter filter = MapFilter::Bilinear;  // reconstruction between elements
};

enum class IntegratorKind { Whitted, FresnelTree, Stochastic };
// Natural: Yasuda's eq. 7 at every node, as if light were natural again after each
// interface (and POV-Ray's model). Exact: Stokes vectors carried through Mueller matrices.
// The model in force is polarisation_model(scene) (core/integrators/integrator.h).
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
    // render.polarisation as given; empty: the mode's default (polarisation_model(): exact in
    // the physical mode wherever it is supported, else natural light).
    std::optional<PolarisationModel> requested_polarisation;
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
