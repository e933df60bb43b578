#pragma once
// Gem optics metrics of one round brilliant (issue 15; docs/gem-metrics.md): light
// return (brilliance), dispersed coloured light return (fire), leakage through the
// pavilion, and a scintillation measure, each with its statistical error, from the exact
// cut under the documented observation set-ups. `measure` is single-threaded and
// deterministic for a given gem and options: a sweep runs many cuts at once and its CSV is
// byte-identical for any number of threads or MPI ranks.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <refract/core/fields.h>
#include <refract/geometry/gem/brilliant.h>

namespace refract::gem_metrics {

struct MetricOptions {
    std::string material = "diamond";  // catalogue name (core/spectrum/dispersion.h)
    int rays = 4096;                    // eye rays per metric (the documented count)
    int wavelengths = 31;               // spectral bands, 400..700 nm
    bool exact_polarisation = true;     // Stokes–Mueller along every path
    std::uint64_t seed = 1;             // the cut's own stream: results do not depend on order
    // Added with the implementation (docs/gem-metrics.md, "Ray counts"):
    double threshold = 1e-3;  // ray-tree pruning threshold (Yasuda's cumulative attenuation)
    int max_depth = 32;       // surface interactions along one path
    // Eye rays of each metric: light return and leakage `rays`; fire rays/16 pixels, each
    // traced at every wavelength; scintillation rays/4 pixels, each at three tilts.
    int fire_divisor = 16;
    int scintillation_divisor = 4;
    // The nail-head's central-zone eye rays: rays × centre_share of them (at least 4);
    // the detector maps raise it (experiments/gem_detectors.h).
    double centre_share = 0.25;
    double tilt_deg = 2.0;    // scintillation: the small tilt of the stone
    int spot_rotations = 32;  // fire, scintillation: the spot layout turned about the axis
    // The viewer's eye, drawn per eye ray uniformly over the directions within this angle
    // of the stone's axis (the observer moving the head a little, as a tilted stone would
    // be seen); 0: straight above.
    double viewer_cone_deg = 10.0;
    // The stone's size across the viewer's line, in its own units: 1 for the brilliant
    // (girdle radius 1); any other stone (a design, experiments/design_metrics.h) the largest
    // distance of a vertex from the origin. Eye rays start 4·frame from the stone and are
    // drawn over the disk of radius 1.1·frame; the images span 2.1·frame.
    double frame = 1.0;
    // The observer and lighting model of the light return (experiments/gem_observer.h):
    // "aset" (the default), "sasian", "hemisphere", "tilt".
    std::string observer = "aset";
    // Further face-up observer models (no tilts) whose light return and nail-head are
    // measured on the same eye rays, into GemMetrics::also (a study of the models costs no
    // further tracing; experiments/gem_cuts.h).
    std::vector<std::string> also_observers;
};

// A measured value and its standard error (one sigma, from the ray statistics).
struct Metric {
    double value = 0;
    double error = 0;
};

// Mean and standard error of independent samples.
struct Mean {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double v) {
        sum += v;
        sum2 += v * v;
        ++n;
    }
    double mean() const { return n > 0 ? sum / n : 0.0; }
    // The variance of the mean: the samples' variance over n (0 below two samples).
    double variance_of_mean() const {
        if (n < 2) return 0.0;
        const double m = sum / n;
        return std::max(0.0, (sum2 - n * m * m) / (n - 1)) / n;
    }
    Metric metric() const {
        if (n == 0) return {};
        return {mean(), std::sqrt(variance_of_mean())};
    }
};

struct GemMetrics {
    Metric light_return;   // brilliance
    Metric fire;           // dispersed coloured light return
    Metric leakage;        // light lost through the pavilion
    Metric scintillation;  // pattern change under small tilts
    // The face-up detectors (experiments/gem_detectors.h), from the light-return eye rays:
    // nail-head (the table's centre dark under the observer's head) and fish-eye (the
    // share of the table's light leaving through the girdle), and obstruction (the share of
    // the whole face's light that comes from the observer's head).
    Metric nail_head;
    Metric fish_eye;
    Metric obstruction;
    // Leakage per facet kind, facet_kind() names: always "girdle", "lower half",
    // "pavilion main", "culet" in this order (0 where the cut has none); `leakage` sums the
    // last three (the pavilion), the girdle is listed apart.
    std::vector<std::pair<std::string, double>> leakage_by_kind;
    // Energy bookkeeping of the light-return eye rays (means over the rays, whose bands are
    // drawn by luminance): light leaving through the crown (any direction), through the girdle, through
    // the pavilion, dropped by the threshold or depth limit, and eye rays that missed the
    // stone; they sum to 1 up to rounding for a clear stone.
    struct Balance {
        double crown = 0, girdle = 0, pavilion = 0, lost = 0, missed = 0;
    };
    Balance balance;
    // The same rays' light by the ASET zone it comes from (AGS ASET; the zones about the
    // direction to the eye): red 45–75°, green 0–45°, blue 75–90° (the viewer), white
    // below the horizon; with balance.lost they sum to 1.
    struct Aset {
        double red = 0, green = 0, blue = 0, white = 0;
    };
    Aset aset;
    // Fire resolved by wavelength: per band (nm), the mean over pixels and layout turns of
    // the coloured part r_b − min r of the returned spectrum (no luminance weight).
    std::vector<std::pair<double, double>> fire_spectrum;
    int light_return_rays = 0, fire_pixels = 0, scintillation_pixels = 0;  // as traced
    std::string observer;  // MetricOptions::observer the light return was measured under
    // MetricOptions::also_observers in order: the light return, nail-head and obstruction
    // under each.
    struct UnderObserver {
        std::string observer;
        Metric light_return, nail_head, obstruction;
    };
    std::vector<UnderObserver> also;
};

// Throws InputError (one line naming the option, its value and the allowed range) for
// options `measure` cannot use; `measure` calls it first.
void validate(const MetricOptions& options);

GemMetrics measure(const Gem& gem, const MetricOptions& options);

}  // namespace refract::gem_metrics

namespace refract {

template <>
struct Fields<gem_metrics::Metric> {
    static auto list() {
        using M = gem_metrics::Metric;
        return std::make_tuple(field("value", &M::value), field("error", &M::error));
    }
};
template <>
struct Fields<gem_metrics::GemMetrics::Balance> {
    static auto list() {
        using B = gem_metrics::GemMetrics::Balance;
        return std::make_tuple(field("crown", &B::crown), field("girdle", &B::girdle), field("pavilion", &B::pavilion),
                               field("lost", &B::lost), field("missed", &B::missed));
    }
};
template <>
struct Fields<gem_metrics::GemMetrics::Aset> {
    static auto list() {
        using A = gem_metrics::GemMetrics::Aset;
        return std::make_tuple(field("red", &A::red), field("green", &A::green), field("blue", &A::blue),
                               field("white", &A::white));
    }
};
// The Python module's metrics dict (python/src/gem.cpp).
template <>
struct Fields<gem_metrics::GemMetrics> {
    static auto list() {
        using G = gem_metrics::GemMetrics;
        return std::make_tuple(field("light_return", &G::light_return), field("fire", &G::fire),
                               field("leakage", &G::leakage), field("scintillation", &G::scintillation),
                               field("nail_head", &G::nail_head), field("fish_eye", &G::fish_eye),
                               field("obstruction", &G::obstruction),
                               field("leakage_by_kind", &G::leakage_by_kind), field("balance", &G::balance),
                               field("aset", &G::aset), field("rays", &G::light_return_rays),
                               field("fire_pixels", &G::fire_pixels), field("scintillation_pixels", &G::scintillation_pixels),
                               field("observer", &G::observer));
    }
};

}  // namespace refract
