// The experiments (experiments/): the list, a run into files, and the drivers whose
// compute() returns a Result, converted through the Result's field list (to_python,
// python/src/bindings.h): dicts, lists and NumPy arrays with the names the CSV files use.
#include <pybind11/stl.h>

#include <refract/experiments/drivers.h>
#include <refract/geometry/error.h>
#include "python/src/bindings.h"

namespace refract::python {

namespace {

namespace ex = refract::experiments;

// `name(quick=True, threads=0)`: the driver's compute() without the GIL, its Result as a dict.
template <class Result>
void bind_compute(py::module_& m, const char* name, Result (*compute)(const ex::ExperimentOptions&), const char* doc) {
    m.def(name, [compute](bool quick, int threads) {
        return to_python(without_gil([&] { return compute(ex::ExperimentOptions{"", threads, quick}); }));
    }, py::arg("quick") = true, py::arg("threads") = 0, doc);
}

}  // namespace

void bind_experiments(py::module_& m) {
    m.def("experiments", [] {
        py::list l;
        for (const auto& e : ex::all()) l.append(py::dict(py::arg("name") = e.name, py::arg("description") = e.description));
        return l;
    }, "The experiment drivers, in the order `refract reproduce` runs them.");
    m.def("run_experiment", [](const std::string& name, const std::string& out_dir, int threads, bool quick) {
        const ex::Experiment& e = ex::find(name);
        without_gil([&] { e.run(ex::ExperimentOptions{out_dir, threads, quick}); });
    }, py::arg("name"), py::arg("out_dir"), py::arg("threads") = 0, py::arg("quick") = false,
       "Runs one experiment driver, writing its CSV, figures and summary.md into out_dir.");
    bind_compute(m, "optics_bench", &ex::optics_bench::compute,
                 "optics-bench measured into a dict: drop classes and bins, rainbow, prism and slab rows with closed forms.");
    bind_compute(m, "polarisation", &ex::polarisation::compute,
                 "polarisation measured into a dict: the sphere's degree of polarisation per path class against the "
                 "closed forms, the 1998 diamond and a glass sphere in natural and exact polarisation (images, DoLP, ΔE, "
                 "light per depth), the diamond through an analyser at 0/45/90/135°.");
    m.def("polarisation_sphere", [](double n, const std::vector<double>& angles_deg) {
        return to_python(without_gil([&] { return ex::polarisation::sphere_points(n, angles_deg); }));
    }, py::arg("n"), py::arg("angles_deg"),
       "polarisation, part 1: per incidence angle and path class the Stokes vector of natural light through a "
       "sphere of index n, its degree of polarisation and the closed form.");
    bind_compute(m, "gem_geometry", &ex::gem_geometry::compute,
                 "gem-geometry measured into a dict: per preset the proportions, facet counts, plane-set vs mesh timing, "
                 "the rendered diamond (rgb) and its scene.");
    bind_compute(m, "rtiow_dielectric", &ex::rtiow::compute,
                 "rtiow-dielectric measured into a dict: the stages (images, TIR node counts), Schlick against Fresnel "
                 "per case (rows: angle, fresnel, schlick), and the stochastic integrator's RMSE per spp with the log-log "
                 "slope.");
    bind_compute(m, "yasuda1984", &ex::yasuda1984::compute,
                 "yasuda1984 measured into a dict: Fig. 4 (angle, Rs, Rp, R) and Fig. 7 (n, angle, T) as arrays, the "
                 "transmissivity peaks, the Fig. 8 and 9 panels (images, counters), the §5 cost and memory measurements.");
    bind_compute(m, "ohtsuka1998", &ex::ohtsuka1998::compute,
                 "ohtsuka1998 measured into a dict: the diamond with the full split and the shortcut (images, times, "
                 "difference), the wavelength-step, floor-map, shortcut-threshold and dropped-light studies.");
    m.def("gem_proportions", [](const std::string& preset) {
        return to_python(ex::gem_geometry::proportion_rows(preset, build_brilliant(brilliant_preset(preset))));
    }, py::arg("preset"), "gem-geometry: the preset's proportions, expected against measured on the exact polyhedron.");
}

}  // namespace refract::python
