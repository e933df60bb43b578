#pragma once
// The gem metrics' options shared by `refract metrics` and `refract sweep design`.
#include <string>

#include "cli/commands.h"
#include <refract/core/spectrum/dispersion.h>
#include <refract/experiments/gem_metrics.h>
#include <refract/experiments/gem_observer.h>
#include <refract/geometry/error.h>

namespace refract::cli {

// --observer NAME: the light return's observer model (experiments/gem_observer.h).
inline void add_observer_option(CLI::App* sub, std::string& observer) {
    sub->add_option("--observer", observer,
                    "Observer model of the light return: " + gem_metrics::observer_names_text() +
                        " (aset; docs/gem-metrics.md)");
}

// The observer name checked: InputError "--observer 'NAME': expected aset, ..." else.
inline void check_observer(const std::string& observer) {
    try {
        gem_metrics::find_observer(observer);
    } catch (const InputError& e) {
        throw InputError("--" + std::string(e.what()));
    }
}

struct GemOptionArgs {
    std::string material = "diamond", polarisation = "exact", observer = "aset";
    int rays = 4096, wavelengths = 31;
    std::uint64_t seed = 1;
};

inline void add_gem_options(CLI::App* sub, GemOptionArgs& a, const std::string& seed_help) {
    sub->add_option("--material", a.material, "Material (catalogue name, core/spectrum/dispersion.h)");
    sub->add_option("--rays", a.rays, "Eye rays per metric")->check(CLI::Range(16, 1 << 26));
    sub->add_option("--wavelengths", a.wavelengths, "Spectral bands, 400..700 nm")->check(CLI::Range(1, 301));
    sub->add_option("--polarisation", a.polarisation, "exact (Stokes-Mueller) or natural");
    sub->add_option("--seed", a.seed, seed_help)->check(CLI::NonNegativeNumber);
    add_observer_option(sub, a.observer);
}

// The options checked (InputError naming the option) before any work.
inline gem_metrics::MetricOptions metric_options(const GemOptionArgs& a) {
    if (a.polarisation != "exact" && a.polarisation != "natural")
        throw InputError("--polarisation '" + a.polarisation + "': expected exact or natural");
    try {
        spectrum::catalogue(a.material);
    } catch (const InputError& e) {
        throw InputError("--material: " + std::string(e.what()));
    }
    check_observer(a.observer);
    gem_metrics::MetricOptions m;
    m.observer = a.observer;
    m.material = a.material;
    m.rays = a.rays;
    m.wavelengths = a.wavelengths;
    m.exact_polarisation = a.polarisation == "exact";
    m.seed = a.seed;
    gem_metrics::validate(m);
    return m;
}

}  // namespace refract::cli
