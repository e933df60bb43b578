#include <refract/experiments/experiment.h>

#include <refract/experiments/drivers.h>
#include <refract/geometry/error.h>

namespace refract::experiments {

const std::vector<Experiment>& all() {
    static const std::vector<Experiment> list{
        // name, description, driver (experiments/drivers.h)
        {"yasuda1984",
         "Yasuda et al. 1984: Fig. 4 and 7 (reflectivity, transmissivity), Fig. 8 and 9 (spheres), cost and memory",
         yasuda1984::run},
        {"rtiow-dielectric",
         "Ray Tracing in One Weekend, dielectric chapter: stages, Schlick error, 1/sqrt(spp) convergence",
         rtiow::run},
        {"gem-geometry",
         "Round brilliant: facet drawings, proportions measured back, Fresnel diamond renders, plane-set vs mesh cost",
         gem_geometry::run},
        {"gem-metrics",
         "Round brilliant optics: light return, fire, leakage and scintillation with their errors (exact polarisation "
         "and natural light), ASET / ideal-scope / hearts-and-arrows images, convergence with the ray count",
         gem_metrics_experiment::run},
        {"ohtsuka1998",
         "Ohtsuka & Kawai 1998: dispersion in a diamond, light + eye pass, shortcut speed-up, wavelength/threshold studies, the floor map against photons and element size",
         ohtsuka1998::run},
        {"polarisation",
         "Exact polarisation against natural light: a sphere's DoP per path vs closed forms, the 1998 diamond and a glass sphere in both models, the diamond through an analyser",
         polarisation::run},
        {"optics-bench",
         "Classic optics with the far-field detector against closed forms: a water drop's scattering per path class, "
         "rainbow angles against wavelength, a prism's deviation, a slab's transmittance (s and p)",
         optics_bench::run},
        {"gem-cuts",
         "Round brilliant proportion sweep: light return, fire, leakage and scintillation over crown x pavilion "
         "angle, Tolkowsky 1919 against the optimum, the star and lower-half lengths",
         gem_cuts::run},
        {"birefringence",
         "Double refraction in uniaxial crystals: a calcite plate's double image against walk-off x thickness and through "
         "an analyser; diamond, cubic zirconia and moissanite brilliants through the table (facet doubling, walk-off)",
         birefringence::run},
        {"grin",
         "Gradient-index media by the ray equation: Luneburg and fish-eye lenses, sech and parabolic rods, a rod imaging a "
         "grid, mirages over a hot road and a cold sea, the setting sun's flattening and green limb, astronomical "
         "refraction against Bennett and Saemundsson, the integrator's convergence",
         grin_media::run},
        {"grin-layers",
         "A Luneburg lens as N constant-index shells (compat mode, the validation case grin-stack) converging to the "
         "continuous grin lens (physical mode): image difference against N, its order, the modes' floor",
         grin_layers::run},
    };
    return list;
}

const Experiment& find(const std::string& name) {
    std::string names;
    for (const auto& e : all()) {
        if (e.name == name) return e;
        names += (names.empty() ? "" : ", ") + e.name;
    }
    throw InputError("experiment '" + name + "': unknown (known: " + names + ")");
}

}  // namespace refract::experiments
