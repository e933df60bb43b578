#pragma once
// The observation set-ups of the gem metrics (docs/gem-metrics.md), in the gem's own frame
// (girdle radius 1, z up, table on top): what a ray leaving the stone sees, as a function
// of its direction (the illuminations), and the tracer that follows an eye ray through the
// exact cut with the one ray-tree walker (core/ray_tree.h), reporting where its light
// leaves the stone.
//
// Eye rays run backwards from the viewer (reciprocity): the light a viewer receives along
// an eye ray is the sum over the tree's exits of the exit's weight times the radiance the
// set-up sends along the reversed exit direction.
#include <memory>
#include <string>
#include <vector>

#include <refract/core/image.h>
#include <refract/experiments/gem_metrics.h>
#include <refract/geometry/ray.h>

namespace refract {
struct Scene;
class SceneTracer;
}  // namespace refract

namespace refract::gem_metrics {

// Elevation (degrees) of direction d (unit) above the viewer's horizon, `up` pointing from
// the stone to the viewer.
double elevation_deg(const Vec3& d, const Vec3& up);

// The observer's head: directions within kHeadDeg of `up` (elevation above 75°) are
// blocked by the viewer (ASET's blue zone, AGS; used for the brilliance set-up too).
constexpr double kHeadDeg = 15.0;

// Brilliance set-up (Hemphill et al. 1998: diffuse hemispherical illumination, the
// observer's head an obstruction): radiance 1 from every direction above the horizon
// (`up` the stone's axis) outside the head cone, within kHeadDeg of `viewer` (the unit
// direction from the stone to the viewer's eye, by default on the axis), 0 from the
// head and from below.
double diffuse_with_head(const Vec3& d, const Vec3& up);
double diffuse_with_head(const Vec3& d, const Vec3& up, const Vec3& viewer);

// Fire and scintillation set-up (spot lighting after Reinitz et al. 2001; the layout is
// refract's own): round spots of kSpotRadiusDeg on rings at elevations 10°, 20°, ... 70°,
// spaced about 10° apart along each ring (ring k rotated by 5°·k in azimuth), radiance 1
// inside a spot and 0 elsewhere.
constexpr double kSpotRadiusDeg = 3.0;
// The layout turned by `rotation_deg` about `up` (the stone turned under the lights).
double spot_lighting(const Vec3& d, const Vec3& up, double rotation_deg = 0);

// One direction tested against the spot layout at many rotations: its ring and azimuth
// found once, then one cosine per rotation (spot_lighting is this).
class SpotProbe {
public:
    SpotProbe(const Vec3& d, const Vec3& up);
    bool near_ring() const { return ring_ >= 0; }  // false: dark at every rotation
    double lit(double rotation_deg) const;

private:
    int ring_ = -1;
    double az_ = 0, spacing_ = 0;
    double a_ = 0, b_ = 0;  // cos(angle to a spot's centre) = a + b·cos(Δazimuth)
};

// The images' colour coding of an exit direction (refract's renderings of the viewers):
// ASET (AGS): red 45–75°, green 0–45°, blue 75–90° (the viewer); leakage (below the
// horizon) white. Ideal-scope: the red reflector up to 80°, the viewing hole above 80°
// black, leakage white. Hearts-and-arrows viewer: the reflector tube 20–70° white, the
// viewing tube above 70° and the dark base below 20° black.
enum class AsetZone { Green, Red, Blue, Leak };  // 0–45°, 45–75°, 75–90°, below the horizon
AsetZone aset_zone(const Vec3& d, const Vec3& up);
Vec3 aset_colour(const Vec3& d, const Vec3& up);
Vec3 ideal_scope_colour(const Vec3& d, const Vec3& up);
Vec3 hearts_arrows_colour(const Vec3& d, const Vec3& up);

// Where light leaves the stone: facet kinds grouped.
enum class Region { Crown, Girdle, Pavilion };
Region region_of_kind(const std::string& kind);
// A facet's region: the brilliant's kinds by name (region_of_kind); any other (a design's
// tier names) by the side its outward normal faces: up the crown, down the pavilion,
// level (|n_z| <= 1e-9) the girdle.
Region region_of_facet(const std::string& kind, const Vec3& normal);
// The kinds light leaks through, in GemMetrics::leakage_by_kind's order (each listed,
// 0 when the cut has none): girdle, lower half, pavilion main, culet.
std::vector<std::string> leakage_kinds();

// The gem as a one-object scene and its ray tracer at the options' wavelengths.
class GemTracer {
public:
    GemTracer(const Gem& gem, const MetricOptions& options);
    ~GemTracer();
    GemTracer(const GemTracer&) = delete;
    GemTracer& operator=(const GemTracer&) = delete;

    // One exit of an eye ray's tree: the direction the ray leaves in, its weight (the
    // share of unpolarised light arriving along it that reaches the eye) and the facet
    // kind it leaves through (index into kinds(); −1: the eye ray missed the stone).
    struct Exit {
        Vec3 dir;
        double weight;
        int kind;
    };
    struct Trace {
        double lost = 0;  // weight of the branches dropped by the threshold or depth limit
    };
    // Traces the eye ray at band b; `exits` is cleared and filled.
    Trace trace(const Ray& ray, int band, std::vector<Exit>& exits);

    int bands() const { return static_cast<int>(wavelengths_.size()); }
    double wavelength(int b) const { return wavelengths_[static_cast<size_t>(b)]; }
    double index(int b) const { return index_[static_cast<size_t>(b)]; }
    // CIE 1931 ȳ(λ_b) over its mean over the bands: a band's luminance weight.
    double luminance_weight(int b) const { return luminance_[static_cast<size_t>(b)]; }
    // The band nearest 560 nm (the images).
    int middle_band() const;
    // The band whose share of the cumulative luminance holds u in [0, 1): bands drawn with
    // probability ∝ ȳ(λ), so that a ray's light needs no luminance weight.
    int band_by_luminance(double u) const;
    const std::vector<std::string>& kinds() const { return kinds_; }
    const std::vector<Region>& kind_regions() const { return regions_; }

private:
    template <class P>
    Trace trace_with(const Ray& ray, int band, std::vector<Exit>& exits);

    struct Lists;  // the walker's FIFO lists, reused from trace to trace
    std::unique_ptr<Scene> scene_;
    std::unique_ptr<SceneTracer> tracer_;
    std::unique_ptr<Lists> lists_;
    std::vector<double> wavelengths_, index_, luminance_;
    std::vector<std::string> kinds_;   // distinct facet kinds in plane order of first use
    std::vector<Region> regions_;      // per kind
    std::vector<int> hit_kind_;        // per facet index a hit reports (hit_facets: a plane of
                                       // the solid, or a triangle of a stone with a cleft)
    bool exact_ = true;
    double threshold_ = 0;
    int max_depth_ = 0;
};

// The wavelengths the options ask for: `wavelengths` evenly from 400 to 700 nm (one: 550).
std::vector<double> metric_wavelengths(const MetricOptions& options);

// Images of the viewers (docs/gem-metrics.md), `size` pixels square over the girdle
// (2.1·options.frame units across), one eye ray per pixel at `samples`² fixed sub-pixel positions, at
// the band nearest 560 nm. Face-up views look down the z axis (table up): "aset",
// "ideal-scope", "arrows"; "hearts" looks at the pavilion from below (table down),
// mirrored as seen from below; "brilliance" shows the brilliance set-up's radiance.
std::vector<std::string> view_names();
// The colour a view's viewer sends along direction d (unit, leaving the stone), `up`
// pointing from the stone to the viewer: the functions above by name.
Vec3 view_colour(const std::string& view, const Vec3& d, const Vec3& up);
// tilt_deg: the stone tilted by that angle about the image's horizontal axis, the viewer
// and its colours fixed (a tilt series; 0: face-up, as always).
Image render_view(const Gem& gem, const std::string& view, int size, int samples, const MetricOptions& options,
                  double tilt_deg = 0.0);

// A view's viewer as an equirectangular environment map (docs/scene-format.md, width ×
// width/2, row 0 at +y) for scene files with the scene's +y as the stone's axis: the
// colour of each row's elevation; "hearts" has the viewer below (−y).
Image viewer_environment(const std::string& view, int width);

}  // namespace refract::gem_metrics
