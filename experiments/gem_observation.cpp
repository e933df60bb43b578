// The observation set-ups of the gem metrics and the eye-ray tracer through the exact cut.
#include <refract/experiments/gem_observation.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include <refract/core/ray_tree.h>
#include <refract/core/scene.h>
#include <refract/core/spectrum/cie.h>
#include <refract/core/tracer.h>
#include <refract/experiments/gem_observer.h>
#include <refract/geometry/error.h>

namespace refract::gem_metrics {

namespace {
constexpr double kDeg = M_PI / 180.0;
}

double elevation_deg(const Vec3& d, const Vec3& up) { return std::asin(std::clamp(d.dot(up), -1.0, 1.0)) / kDeg; }

double diffuse_with_head(const Vec3& d, const Vec3& up, const Vec3& viewer) {
    static const double cos_head = std::cos(kHeadDeg * kDeg);
    return observer_radiance(d, up, viewer, cos_head);
}

double diffuse_with_head(const Vec3& d, const Vec3& up) { return diffuse_with_head(d, up, up); }

namespace {
constexpr int kRings = 7;  // at 10°, 20°, ... 70°
double ring_elevation(int k) { return 10.0 + 10.0 * k; }
// Spots about 10° apart along ring k (its circumference 360°·cos e), the first at 5°·k.
int ring_count(int k) { return std::max(1, static_cast<int>(std::lround(36.0 * std::cos(ring_elevation(k) * kDeg)))); }
}  // namespace

SpotProbe::SpotProbe(const Vec3& d, const Vec3& up) {
    const Vec3 u = (std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(up).normalized();
    const Vec3 v = up.cross(u);
    const double e = elevation_deg(d, up);
    const int ring = std::clamp(static_cast<int>(std::lround((e - 10.0) / 10.0)), 0, kRings - 1);
    // Rings are 10° apart and spots 3° across: only the nearest ring can hold d.
    if (std::abs(e - ring_elevation(ring)) > kSpotRadiusDeg) return;
    ring_ = ring;
    az_ = std::atan2(d.dot(v), d.dot(u)) / kDeg;
    spacing_ = 360.0 / ring_count(ring);
    // Spherical law of cosines: the angle between d and a spot's centre on the ring.
    const double re = ring_elevation(ring) * kDeg;
    a_ = std::sin(e * kDeg) * std::sin(re);
    b_ = std::cos(e * kDeg) * std::cos(re);
}

double SpotProbe::lit(double rotation_deg) const {
    static const double cos_radius = std::cos(kSpotRadiusDeg * kDeg);
    if (ring_ < 0) return 0.0;
    const double rel = az_ - rotation_deg - 5.0 * ring_;  // azimuth in the turned layout
    const double daz = (rel - spacing_ * std::nearbyint(rel / spacing_)) * kDeg;  // to the nearest spot
    return a_ + b_ * std::cos(daz) >= cos_radius ? 1.0 : 0.0;
}

double spot_lighting(const Vec3& d, const Vec3& up, double rotation_deg) { return SpotProbe(d, up).lit(rotation_deg); }

AsetZone aset_zone(const Vec3& d, const Vec3& up) {
    const double e = elevation_deg(d, up);
    if (e < 0) return AsetZone::Leak;
    if (e < 45) return AsetZone::Green;
    if (e < 90 - kHeadDeg) return AsetZone::Red;
    return AsetZone::Blue;
}

Vec3 aset_colour(const Vec3& d, const Vec3& up) {
    switch (aset_zone(d, up)) {
        case AsetZone::Leak: return {1, 1, 1};
        case AsetZone::Green: return {0, 1, 0};
        case AsetZone::Red: return {1, 0, 0};
        case AsetZone::Blue: return {0, 0, 1};
    }
    return {0, 0, 0};
}

Vec3 ideal_scope_colour(const Vec3& d, const Vec3& up) {
    const double e = elevation_deg(d, up);
    if (e < 0) return {1, 1, 1};
    if (e < 80) return {0.85, 0.05, 0.05};
    return {0, 0, 0};
}

Vec3 hearts_arrows_colour(const Vec3& d, const Vec3& up) {
    const double e = elevation_deg(d, up);
    return e >= 20 && e < 70 ? Vec3(1, 1, 1) : Vec3(0, 0, 0);
}

Region region_of_kind(const std::string& kind) {
    if (kind == "girdle") return Region::Girdle;
    if (kind == "lower half" || kind == "pavilion main" || kind == "culet") return Region::Pavilion;
    return Region::Crown;
}

Region region_of_facet(const std::string& kind, const Vec3& normal) {
    static const std::vector<std::string> brilliant{"table", "star", "bezel", "upper half",
                                                    "girdle", "lower half", "pavilion main", "culet"};
    if (std::find(brilliant.begin(), brilliant.end(), kind) != brilliant.end()) return region_of_kind(kind);
    if (normal.z() > 1e-9) return Region::Crown;
    return normal.z() < -1e-9 ? Region::Pavilion : Region::Girdle;
}

std::vector<std::string> leakage_kinds() { return {"girdle", "lower half", "pavilion main", "culet"}; }

void validate(const MetricOptions& o) {
    auto bad = [](const std::string& name, double v, const std::string& allowed) {
        std::ostringstream m;
        m << "gem metrics: " << name << " = " << v << " (allowed " << allowed << ")";
        throw InputError(m.str());
    };
    if (o.rays < 16 || o.rays > (1 << 28)) bad("rays", o.rays, "16..2^28");
    if (o.wavelengths < 1 || o.wavelengths > 301) bad("wavelengths", o.wavelengths, "1..301");
    if (!(o.threshold >= 0 && o.threshold < 1)) bad("threshold", o.threshold, "[0, 1)");
    if (o.max_depth < 1 || o.max_depth > 1000) bad("max_depth", o.max_depth, "1..1000");
    if (o.fire_divisor < 1 || o.fire_divisor > o.rays) bad("fire_divisor", o.fire_divisor, "1..rays");
    if (o.scintillation_divisor < 1 || o.scintillation_divisor > o.rays)
        bad("scintillation_divisor", o.scintillation_divisor, "1..rays");
    if (!(o.centre_share > 0 && o.centre_share <= 64)) bad("centre_share", o.centre_share, "(0, 64]");
    if (!(o.tilt_deg > 0 && o.tilt_deg <= 45)) bad("tilt_deg", o.tilt_deg, "(0, 45]");
    if (!(o.viewer_cone_deg >= 0 && o.viewer_cone_deg <= 45)) bad("viewer_cone_deg", o.viewer_cone_deg, "[0, 45]");
    if (o.spot_rotations < 1 || o.spot_rotations > 4096) bad("spot_rotations", o.spot_rotations, "1..4096");
    if (!(o.frame > 0 && o.frame <= 1e6)) bad("frame", o.frame, "(0, 1e6]");
    try {
        find_observer(o.observer);
    } catch (const InputError& e) {
        throw InputError(std::string("gem metrics: ") + e.what());
    }
}

std::vector<double> metric_wavelengths(const MetricOptions& o) {
    validate(o);
    if (o.wavelengths == 1) return {550.0};
    std::vector<double> w;
    for (int b = 0; b < o.wavelengths; ++b) w.push_back(400.0 + 300.0 * b / (o.wavelengths - 1));
    return w;
}

struct GemTracer::Lists {
    RayTreeWalkerT<EyeStokes>::List exact;
    RayTreeWalkerT<NaturalLight>::List natural;
    auto& of(EyeStokes) { return exact; }
    auto& of(NaturalLight) { return natural; }
};

GemTracer::GemTracer(const Gem& gem, const MetricOptions& o)
    : scene_(std::make_unique<Scene>()), lists_(std::make_unique<Lists>()) {
    validate(o);
    const spectrum::Dispersion disp = spectrum::parse_dispersion_text(o.material, "gem metrics: material");
    wavelengths_ = metric_wavelengths(o);
    double ysum = 0;
    for (const double l : wavelengths_) {
        index_.push_back(disp.n(l));
        luminance_.push_back(spectrum::cie_xyz_cmf(l).y());
        ysum += luminance_.back();
    }
    for (double& y : luminance_) y *= static_cast<double>(luminance_.size()) / ysum;

    material::Dielectric d;
    d.ior = disp.nominal();
    d.dispersion = disp;
    scene_->source = "gem metrics";
    scene_->materials.push_back({"gem", d});
    scene_->objects.push_back({"gem", tracing_shape(gem), 0});
    exact_ = o.exact_polarisation;
    scene_->settings.requested_polarisation = exact_ ? PolarisationModel::Exact : PolarisationModel::Natural;
    scene_->settings.threshold = threshold_ = o.threshold;
    scene_->settings.max_depth = max_depth_ = o.max_depth;
    tracer_ = std::make_unique<SceneTracer>(*scene_);

    // A kind is a facet kind in one region (a design may give a crown and a pavilion tier
    // the same name).
    std::vector<int> kind_of_facet;
    for (size_t i = 0; i < gem.solid.labels.size(); ++i) {
        const std::string k = facet_kind(gem.solid.labels[i]);
        const Region r = region_of_facet(k, gem.solid.planes[i].normal);
        size_t j = 0;
        while (j < kinds_.size() && !(kinds_[j] == k && regions_[j] == r)) ++j;
        if (j == kinds_.size()) {
            kinds_.push_back(k);
            regions_.push_back(r);
        }
        kind_of_facet.push_back(static_cast<int>(j));
    }
    for (const int f : hit_facets(gem)) hit_kind_.push_back(kind_of_facet[static_cast<size_t>(f)]);
}

GemTracer::~GemTracer() = default;

int GemTracer::band_by_luminance(double u) const {
    double c = 0;
    const double total = static_cast<double>(bands());  // the weights average to 1
    for (int b = 0; b < bands(); ++b) {
        c += luminance_weight(b);
        if (u * total < c) return b;
    }
    return bands() - 1;
}

int GemTracer::middle_band() const {
    int best = 0;
    for (int b = 1; b < bands(); ++b)
        if (std::abs(wavelength(b) - 560.0) < std::abs(wavelength(best) - 560.0)) best = b;
    return best;
}

namespace {

// The walker's branch ends for an eye ray in the one-object gem scene: a branch leaving
// the scene is an exit; there are no leaves; every band's index is given.
template <class P>
struct ExitEnds {
    using Entry = TreeEntryT<P>;
    using Walker = RayTreeWalkerT<P>;
    const std::vector<int>& hit_kind;
    double n, lambda;
    std::vector<GemTracer::Exit>& exits;

    void background(const Entry& e) {
        const int kind = e.from.facet < 0 ? -1 : hit_kind[static_cast<size_t>(e.from.facet)];
        exits.push_back({e.ray.dir, e.weight.mean() * throughput(e.pol), kind});
    }
    void leaf(const Entry&, const SurfaceHit&) {}
    bool intercept(Walker&, const Entry&, const SurfaceHit&, typename Walker::List&) { return false; }
    double band_ior(const Entry&, const SurfaceHit&) const { return n; }
    double wavelength(const Entry&) const { return lambda; }
};

template <class P>
P root_payload(const Ray&) {
    return P{};
}
template <>
EyeStokes root_payload<EyeStokes>(const Ray& r) {
    // The eye records intensity only: any frame across the ray, no analyser.
    EyeStokes s;
    s.x = (std::abs(r.dir.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(r.dir).normalized();
    return s;
}

}  // namespace

template <class P>
GemTracer::Trace GemTracer::trace_with(const Ray& ray, int band, std::vector<Exit>& exits) {
    RenderStats stats;
    TreeLimits limits;
    limits.threshold = threshold_;
    limits.max_depth = max_depth_;
    RayTreeWalkerT<P> walker(*tracer_, limits, stats);
    auto& list = lists_->of(P{});  // empty: every walk runs to the end
    TreeEntryT<P> root;
    root.ray = ray;
    root.weight = Vec3(1, 1, 1);
    root.band = static_cast<std::int16_t>(band);
    root.pol = root_payload<P>(ray);
    list.push_back(root);
    ExitEnds<P> ends{hit_kind_, index(band), wavelength(band), exits};
    walker.walk(list, ends);
    return {stats.lost_threshold + stats.lost_depth + stats.lost_limits};
}

GemTracer::Trace GemTracer::trace(const Ray& ray, int band, std::vector<Exit>& exits) {
    exits.clear();
    return exact_ ? trace_with<EyeStokes>(ray, band, exits) : trace_with<NaturalLight>(ray, band, exits);
}

std::vector<std::string> view_names() { return {"aset", "ideal-scope", "arrows", "hearts", "brilliance"}; }

namespace {
void check_view(const std::string& view) {
    const auto names = view_names();
    if (std::find(names.begin(), names.end(), view) == names.end())
        throw InputError("gem metrics: unknown view '" + view + "' (aset, ideal-scope, arrows, hearts, brilliance)");
}
}  // namespace

Vec3 view_colour(const std::string& view, const Vec3& d, const Vec3& up) {
    if (view == "aset") return aset_colour(d, up);
    if (view == "ideal-scope") return ideal_scope_colour(d, up);
    if (view == "brilliance") return Vec3::Constant(diffuse_with_head(d, up));
    if (view == "arrows" || view == "hearts") return hearts_arrows_colour(d, up);
    check_view(view);
    return {0, 0, 0};
}

Image viewer_environment(const std::string& view, int width) {
    check_view(view);
    if (width < 2 || width % 2) throw InputError("gem metrics: environment map width must be even and at least 2");
    const int height = width / 2;
    const Vec3 up = view == "hearts" ? Vec3(0, -1, 0) : Vec3(0, 1, 0);
    Image img(width, height);
    for (int j = 0; j < height; ++j) {
        const double e = (90.0 - 180.0 * (j + 0.5) / height) * kDeg;  // the row's elevation above +y's horizon
        const Vec3 c = view_colour(view, Vec3(std::cos(e), std::sin(e), 0), up);
        for (int i = 0; i < width; ++i) img.set(i, j, c);
    }
    return img;
}

Image render_view(const Gem& gem, const std::string& view, int size, int samples, const MetricOptions& options,
                  double tilt_deg) {
    check_view(view);
    if (size < 1 || samples < 1) throw InputError("gem metrics: image size and samples must be positive");
    MetricOptions o = options;
    o.rays = std::max(o.rays, 16);
    GemTracer t(gem, o);
    const bool below = view == "hearts";
    const Vec3 up = below ? Vec3(0, 0, -1) : Vec3(0, 0, 1);
    const int band = t.middle_band();
    const double half = 1.05 * o.frame, far = 4.0 * o.frame;
    const bool tilted = tilt_deg != 0.0;
    const Eigen::Matrix3d back = Eigen::AngleAxisd(-tilt_deg * kDeg, Vec3::UnitX()).toRotationMatrix();
    const Vec3 viewer = back * up;
    Image img(size, size);
    std::vector<GemTracer::Exit> exits;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            Vec3 c(0, 0, 0);
            for (int sy = 0; sy < samples; ++sy)
                for (int sx = 0; sx < samples; ++sx) {
                    const double x = -half + 2 * half * (i + (sx + 0.5) / samples) / size;
                    const double y = half - 2 * half * (j + (sy + 0.5) / samples) / size;
                    // From below, the image's right is the stone's −x (mirrored, as drawn).
                    const Ray r{below ? Vec3(-x, y, -far) : Vec3(x, y, far), -up};
                    // The stone tilted about the image's horizontal axis, the viewer fixed: the
                    // ray and the viewer's direction turned back into the stone's frame.
                    t.trace(tilted ? Ray{back * r.origin, back * r.dir} : r, band, exits);
                    for (const auto& e : exits) {
                        if (e.kind < 0) {  // missed the stone: the viewer's dark background
                            c += e.weight * Vec3(0.08, 0.08, 0.1);
                            continue;
                        }
                        c += e.weight * view_colour(view, e.dir, tilted ? viewer : up);
                    }
                }
            img.set(i, j, c / (samples * samples));
        }
    return img;
}

}  // namespace refract::gem_metrics
