// The experiments (experiments/): the list, a run into files, and the drivers whose
// compute() returns a Result, as dicts, lists and NumPy arrays.
#include <pybind11/stl.h>

#include <algorithm>

#include "experiments/drivers.h"
#include "geometry/error.h"
#include "python/src/bindings.h"

namespace refract::python {

namespace {

// ---- Experiments: results as dicts ------------------------------------------------------

py::dict optics_bench_dict(const experiments::optics_bench::Result& r) {
    py::dict d;
    d["quick"] = r.quick;
    d["seconds"] = r.seconds;
    py::list bins, classes, rainbow, prism, slab;
    for (const auto& b : r.drop.bins)
        bins.append(py::dict(py::arg("cls") = b.cls, py::arg("theta0_deg") = b.theta0_deg, py::arg("theta1_deg") = b.theta1_deg,
                             py::arg("measured") = b.measured, py::arg("measured_s") = b.measured_s,
                             py::arg("measured_p") = b.measured_p, py::arg("closed") = b.closed,
                             py::arg("closed_s") = b.closed_s, py::arg("closed_p") = b.closed_p));
    for (const auto& c : r.drop.classes)
        classes.append(py::dict(py::arg("cls") = c.cls, py::arg("total") = c.total, py::arg("total_closed") = c.total_closed,
                                py::arg("max_bin_error") = c.max_bin_error, py::arg("max_z") = c.max_z));
    d["drop"] = py::dict(py::arg("n") = r.drop.n, py::arg("photons") = r.drop.photons, py::arg("bins") = bins,
                         py::arg("classes") = classes, py::arg("dropped") = r.drop.dropped,
                         py::arg("seconds") = r.drop.seconds);
    for (const auto& w : r.rainbow.rows)
        rainbow.append(py::dict(py::arg("wavelength_nm") = w.wavelength_nm, py::arg("n") = w.n,
                                py::arg("primary") = w.primary, py::arg("primary_closed") = w.primary_closed,
                                py::arg("secondary") = w.secondary, py::arg("secondary_closed") = w.secondary_closed));
    d["rainbow"] = py::dict(py::arg("bin_deg") = r.rainbow.bin_deg, py::arg("photons") = r.rainbow.photons,
                            py::arg("rows") = rainbow, py::arg("max_error") = r.rainbow.max_error,
                            py::arg("seconds") = r.rainbow.seconds);
    for (const auto& p : r.prism.rows)
        prism.append(py::dict(py::arg("wavelength_nm") = p.wavelength_nm, py::arg("n") = p.n,
                              py::arg("deviation") = p.deviation, py::arg("deviation_closed") = p.deviation_closed));
    d["prism"] = py::dict(py::arg("apex_deg") = r.prism.apex_deg, py::arg("incidence_deg") = r.prism.incidence_deg,
                          py::arg("bin_deg") = r.prism.bin_deg, py::arg("rows") = prism,
                          py::arg("max_error") = r.prism.max_error, py::arg("seconds") = r.prism.seconds);
    for (const auto& s : r.slab.rows)
        slab.append(py::dict(py::arg("incidence_deg") = s.incidence_deg, py::arg("T_s") = s.T_s, py::arg("T_p") = s.T_p,
                             py::arg("T") = s.T, py::arg("T_s_closed") = s.T_s_closed, py::arg("T_p_closed") = s.T_p_closed,
                             py::arg("T_closed") = s.T_closed));
    d["slab"] = py::dict(py::arg("n") = r.slab.n, py::arg("rows") = slab, py::arg("max_error") = r.slab.max_error,
                         py::arg("seconds") = r.slab.seconds);
    return d;
}

py::list sphere_points_list(const std::vector<experiments::polarisation::SpherePoint>& pts) {
    const auto& classes = experiments::polarisation::path_classes();
    py::list l;
    for (const auto& p : pts)
        l.append(py::dict(py::arg("n") = p.n, py::arg("theta_deg") = p.theta_deg,
                          py::arg("path") = classes[static_cast<size_t>(p.cls)].name,
                          py::arg("stokes") = py::make_tuple(p.S[0], p.S[1], p.S[2], p.S[3]), py::arg("dop") = p.dop,
                          py::arg("dop_closed") = p.dop_closed, py::arg("s1") = p.s1, py::arg("s1_closed") = p.s1_closed));
    return l;
}

}  // namespace

void bind_experiments(py::module_& m) {
    namespace ex = refract::experiments;
    m.def("experiments", [] {
        py::list l;
        for (const auto& e : ex::all()) l.append(py::dict(py::arg("name") = e.name, py::arg("description") = e.description));
        return l;
    }, "The experiment drivers, in the order `refract reproduce` runs them.");
    m.def("run_experiment", [](const std::string& name, const std::string& out_dir, int threads, bool quick) {
        const ex::Experiment& e = ex::find(name);
        ex::ExperimentOptions opt{out_dir, threads, quick};
        py::gil_scoped_release nogil;
        e.run(opt);
    }, py::arg("name"), py::arg("out_dir"), py::arg("threads") = 0, py::arg("quick") = false,
       "Runs one experiment driver, writing its CSV, figures and summary.md into out_dir.");
    m.def("optics_bench", [](bool quick, int threads) {
        ex::optics_bench::Result r;
        {
            py::gil_scoped_release nogil;
            r = ex::optics_bench::compute(ex::ExperimentOptions{"", threads, quick});
        }
        return optics_bench_dict(r);
    }, py::arg("quick") = true, py::arg("threads") = 0,
       "optics-bench measured into a dict: drop classes and bins, rainbow, prism and slab rows with closed forms.");
    m.def("polarisation", [](bool quick, int threads) {
        ex::polarisation::Result r;
        {
            py::gil_scoped_release nogil;
            r = ex::polarisation::compute(ex::ExperimentOptions{"", threads, quick});
        }
        auto image = [](const Image& img) {
            py::array_t<double> a({static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width), py::ssize_t(3)});
            std::copy(img.rgb.begin(), img.rgb.end(), a.mutable_data());
            return a;
        };
        const auto& classes = ex::polarisation::path_classes();
        py::list errors, rainbows;
        for (const auto& e : r.sphere.errors)
            errors.append(py::dict(py::arg("n") = e.n, py::arg("path") = classes[static_cast<size_t>(e.cls)].name,
                                   py::arg("points") = e.points, py::arg("max_dop_error") = e.max_dop_error,
                                   py::arg("max_signed_error") = e.max_signed_error, py::arg("max_s23") = e.max_s23));
        for (const auto& b : r.sphere.rainbows)
            rainbows.append(py::dict(py::arg("n") = b.n, py::arg("theta_deg") = b.theta_deg,
                                     py::arg("deviation_deg") = b.deviation_deg, py::arg("dop") = b.dop,
                                     py::arg("dop_closed") = b.dop_closed));
        auto comparison = [&](const ex::polarisation::Comparison& c) {
            py::list depth;
            for (const auto& d : c.depth)
                depth.append(py::dict(py::arg("depth") = d.depth, py::arg("natural") = d.natural, py::arg("exact") = d.exact));
            const py::ssize_t W = c.width, H = c.height;
            py::array_t<double> dolp({H, W});
            std::copy(c.exact_polarisation.dolp.begin(), c.exact_polarisation.dolp.end(), dolp.mutable_data());
            return py::dict(py::arg("title") = c.title, py::arg("natural") = image(c.natural), py::arg("exact") = image(c.exact),
                            py::arg("dolp") = dolp, py::arg("rmse") = c.rmse, py::arg("max_abs") = c.max_abs,
                            py::arg("delta_e_mean") = c.de_mean, py::arg("delta_e_p95") = c.de_p95,
                            py::arg("delta_e_max") = c.de_max, py::arg("light_natural") = c.light_natural,
                            py::arg("light_exact") = c.light_exact, py::arg("depth") = depth,
                            py::arg("seconds_natural") = c.seconds_natural, py::arg("seconds_exact") = c.seconds_exact);
        };
        const auto& a = r.analyser;
        py::list analyser_images;
        for (const auto& img : a.images) analyser_images.append(image(img));
        return py::dict(
            py::arg("quick") = r.quick,
            py::arg("sphere") = py::dict(py::arg("points") = sphere_points_list(r.sphere.points), py::arg("errors") = errors,
                                         py::arg("rainbows") = rainbows, py::arg("max_dop_error") = r.sphere.max_dop_error),
            py::arg("diamond") = comparison(r.diamond), py::arg("glass") = comparison(r.glass),
            py::arg("analyser") = py::dict(
                py::arg("angles") = std::vector<double>(a.angles.begin(), a.angles.end()), py::arg("images") = analyser_images,
                py::arg("light") = std::vector<double>(a.light.begin(), a.light.end()),
                py::arg("max_dev_0_90") = a.max_dev_0_90, py::arg("max_dev_45_135") = a.max_dev_45_135,
                py::arg("dolp_mean_object") = a.dolp_mean_object, py::arg("dolp_max_object") = a.dolp_max_object),
            py::arg("seconds") = r.seconds_total);
    }, py::arg("quick") = true, py::arg("threads") = 0,
       "polarisation measured into a dict: the sphere's degree of polarisation per path class against the closed "
       "forms, the 1998 diamond and a glass sphere in natural and exact polarisation (images, DoLP, ΔE, light per "
       "depth), the diamond through an analyser at 0/45/90/135°.");
    m.def("polarisation_sphere", [](double n, const std::vector<double>& angles_deg) {
        std::vector<ex::polarisation::SpherePoint> pts;
        {
            py::gil_scoped_release nogil;
            pts = ex::polarisation::sphere_points(n, angles_deg);
        }
        return sphere_points_list(pts);
    }, py::arg("n"), py::arg("angles_deg"),
       "polarisation, part 1: per incidence angle and path class the Stokes vector of natural light through a "
       "sphere of index n, its degree of polarisation and the closed form.");
    m.def("gem_geometry", [](bool quick, int threads) {
        ex::gem_geometry::Result r;
        {
            py::gil_scoped_release nogil;
            r = ex::gem_geometry::compute(ex::ExperimentOptions{"", threads, quick});
        }
        const py::object loads = py::module_::import("json").attr("loads");
        py::list presets;
        for (const auto& p : r.presets) {
            py::list rows;
            for (const auto& q : p.proportions)
                rows.append(py::dict(py::arg("quantity") = q.quantity, py::arg("unit") = q.unit, py::arg("source") = q.source,
                                     py::arg("expected") = q.expected, py::arg("measured") = q.measured));
            py::dict counts;
            for (const auto& [kind, n] : p.facet_counts) counts[py::str(kind)] = n;
            const auto& t = p.timing;
            const py::ssize_t W = p.render.image.width, H = p.render.image.height;
            py::array_t<double> rgb({H, W, py::ssize_t(3)});
            std::copy(p.render.image.rgb.begin(), p.render.image.rgb.end(), rgb.mutable_data());
            presets.append(py::dict(
                py::arg("preset") = p.preset, py::arg("proportions") = rows, py::arg("facet_counts") = counts,
                py::arg("timing") = py::dict(py::arg("planes") = t.planes, py::arg("triangles") = t.triangles,
                                             py::arg("rays") = t.rays, py::arg("hits") = t.hits, py::arg("agree") = t.agree,
                                             py::arg("plane_ns") = t.plane_ns, py::arg("mesh_ns") = t.mesh_ns),
                py::arg("scene") = loads(p.scene.dump()), py::arg("rgb") = rgb,
                py::arg("render_seconds") = p.render.stats.seconds));
        }
        return py::dict(py::arg("quick") = r.quick, py::arg("worst") = r.worst, py::arg("presets") = presets);
    }, py::arg("quick") = true, py::arg("threads") = 0,
       "gem-geometry measured into a dict: per preset the proportions, facet counts, plane-set vs mesh timing, "
       "the rendered diamond (rgb) and its scene.");
    m.def("rtiow_dielectric", [](bool quick, int threads) {
        ex::rtiow::Result r;
        {
            py::gil_scoped_release nogil;
            r = ex::rtiow::compute(ex::ExperimentOptions{"", threads, quick});
        }
        const py::object loads = py::module_::import("json").attr("loads");
        auto image = [](const Image& img) {
            py::array_t<double> a({static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width), py::ssize_t(3)});
            std::copy(img.rgb.begin(), img.rgb.end(), a.mutable_data());
            return a;
        };
        py::list stages, schlick, convergence;
        for (const auto& s : r.stages)
            stages.append(py::dict(py::arg("id") = s.stage.id, py::arg("caption") = s.stage.caption,
                                   py::arg("scene") = loads(s.scene.dump()), py::arg("rgb") = image(s.image),
                                   py::arg("tir_nodes") = s.tir_nodes));
        for (const auto& c : r.schlick) {
            py::array_t<double> rows({static_cast<py::ssize_t>(c.rows.size()), py::ssize_t(3)});
            auto R = rows.mutable_unchecked<2>();
            for (size_t k = 0; k < c.rows.size(); ++k) {
                R(static_cast<py::ssize_t>(k), 0) = c.rows[k].angle_deg;
                R(static_cast<py::ssize_t>(k), 1) = c.rows[k].fresnel;
                R(static_cast<py::ssize_t>(k), 2) = c.rows[k].schlick;
            }
            schlick.append(py::dict(py::arg("name") = c.name, py::arg("eta") = c.eta, py::arg("use_cos_t") = c.use_cos_t,
                                    py::arg("rows") = rows, py::arg("max_error") = c.max_error,
                                    py::arg("max_error_at") = c.max_error_at, py::arg("mean_error") = c.mean_error));
        }
        for (const auto& row : r.convergence.rows)
            convergence.append(py::dict(py::arg("spp") = row.spp, py::arg("rmse") = row.rmse, py::arg("seconds") = row.seconds));
        return py::dict(py::arg("quick") = r.quick, py::arg("stages") = stages, py::arg("schlick") = schlick,
                        py::arg("convergence") = convergence, py::arg("slope") = r.convergence.fit.slope,
                        py::arg("intercept") = r.convergence.fit.intercept);
    }, py::arg("quick") = true, py::arg("threads") = 0,
       "rtiow-dielectric measured into a dict: the stages (images, TIR node counts), Schlick against Fresnel per "
       "case (rows: angle, fresnel, schlick), and the stochastic integrator's RMSE per spp with the log-log slope.");
    m.def("yasuda1984", [](bool quick, int threads) {
        ex::yasuda1984::Result r;
        {
            py::gil_scoped_release nogil;
            r = ex::yasuda1984::compute(ex::ExperimentOptions{"", threads, quick});
        }
        const py::object loads = py::module_::import("json").attr("loads");
        py::array_t<double> fig4({static_cast<py::ssize_t>(r.fig4.size()), py::ssize_t(4)});
        auto F4 = fig4.mutable_unchecked<2>();
        for (size_t k = 0; k < r.fig4.size(); ++k) {
            const auto i = static_cast<py::ssize_t>(k);
            F4(i, 0) = r.fig4[k].angle_deg, F4(i, 1) = r.fig4[k].Rs, F4(i, 2) = r.fig4[k].Rp, F4(i, 3) = r.fig4[k].R;
        }
        py::array_t<double> fig7({static_cast<py::ssize_t>(r.fig7.size()), py::ssize_t(3)});
        auto F7 = fig7.mutable_unchecked<2>();
        for (size_t k = 0; k < r.fig7.size(); ++k) {
            const auto i = static_cast<py::ssize_t>(k);
            F7(i, 0) = r.fig7[k].n, F7(i, 1) = r.fig7[k].angle_deg, F7(i, 2) = r.fig7[k].T;
        }
        py::list peaks, fig8, fig9, costs, memory;
        for (const auto& p : r.peaks)
            peaks.append(py::dict(py::arg("n") = p.n, py::arg("angle_deg") = p.angle_deg, py::arg("T") = p.T,
                                  py::arg("T0") = p.T0, py::arg("interior") = p.interior));
        auto panels = [&](const std::vector<ex::yasuda1984::RenderedPanel>& in, py::list& out) {
            for (const auto& p : in) {
                py::array_t<double> rgb({static_cast<py::ssize_t>(p.image.height), static_cast<py::ssize_t>(p.image.width),
                                         py::ssize_t(3)});
                std::copy(p.image.rgb.begin(), p.image.rgb.end(), rgb.mutable_data());
                out.append(py::dict(py::arg("file") = p.file, py::arg("caption") = p.caption, py::arg("value") = p.value,
                                    py::arg("scene") = loads(p.scene.dump()), py::arg("rgb") = rgb,
                                    py::arg("seconds") = p.stats.seconds, py::arg("segments") = p.stats.segments,
                                    py::arg("tree_nodes") = p.stats.tree_nodes, py::arg("peak_list") = p.stats.peak_list));
            }
        };
        panels(r.fig8, fig8);
        panels(r.fig9, fig9);
        const auto& c = r.cost;
        for (const auto& n : c.node_costs)
            costs.append(py::dict(py::arg("formulation") = n.formulation, py::arg("model") = n.model,
                                  py::arg("mul") = n.ops.mul, py::arg("div") = n.ops.div, py::arg("add") = n.ops.add,
                                  py::arg("sqrt") = n.ops.sqrt, py::arg("cmp") = n.ops.cmp));
        for (const auto& row : c.memory)
            memory.append(py::dict(py::arg("max_depth") = row.max_depth, py::arg("whitted_peak_nodes") = row.whitted.peak_list,
                                   py::arg("list_peak_entries_threshold0") = row.list_threshold0.peak_list,
                                   py::arg("list_peak_entries_threshold_1_255") = row.list_threshold_1_255.peak_list));
        return py::dict(
            py::arg("quick") = r.quick, py::arg("fig4") = fig4, py::arg("fig7") = fig7, py::arg("peaks") = peaks,
            py::arg("peak_onset") = r.peak_onset, py::arg("peak_beyond_70") = r.peak_beyond_70, py::arg("fig8") = fig8,
            py::arg("fig9") = fig9,
            py::arg("cost") = py::dict(
                py::arg("node_costs") = costs, py::arg("sphere_test_muldiv") = c.sphere_test.muldiv(),
                py::arg("plane_test_muldiv") = c.plane_test.muldiv(), py::arg("ns_constant") = c.ns_constant,
                py::arg("ns_fresnel") = c.ns_fresnel, py::arg("ns_schlick") = c.ns_schlick,
                py::arg("ns_search") = c.ns_search, py::arg("render_constant") = c.render_best[0],
                py::arg("render_fresnel") = c.render_best[1], py::arg("memory") = memory));
    }, py::arg("quick") = true, py::arg("threads") = 0,
       "yasuda1984 measured into a dict: Fig. 4 (angle, Rs, Rp, R) and Fig. 7 (n, angle, T) as arrays, the "
       "transmissivity peaks, the Fig. 8 and 9 panels (images, counters), the §5 cost and memory measurements.");
    m.def("ohtsuka1998", [](bool quick, int threads) {
        namespace oh = ex::ohtsuka1998;
        oh::Result r;
        {
            py::gil_scoped_release nogil;
            r = oh::compute(ex::ExperimentOptions{"", threads, quick});
        }
        auto image = [](const Image& img) {
            py::array_t<double> a({static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width), py::ssize_t(3)});
            std::copy(img.rgb.begin(), img.rgb.end(), a.mutable_data());
            return a;
        };
        auto diff = [](const oh::Diff& d) {
            return py::dict(py::arg("rmse") = d.rmse, py::arg("max") = d.max, py::arg("delta_e_mean") = d.de_mean,
                            py::arg("delta_e_max") = d.de_max);
        };
        py::list steps, thresholds, peaks, lost, by_photons, by_element;
        for (const auto& x : r.steps)
            steps.append(py::dict(py::arg("step_nm") = x.step_nm, py::arg("against_1nm") = diff(x.against_1nm),
                                  py::arg("light_s") = x.light_s, py::arg("eye_s") = x.eye_s));
        auto shortcut_rows = [&](const std::vector<oh::ShortcutRow>& in, py::list& out) {
            for (const auto& x : in)
                out.append(py::dict(py::arg("label") = x.label, py::arg("threshold") = x.threshold,
                                    py::arg("wavelengths") = py::make_tuple(x.wavelengths[0], x.wavelengths[1], x.wavelengths[2]),
                                    py::arg("taken_fraction") = x.taken_fraction, py::arg("speedup_time") = x.speedup_time,
                                    py::arg("speedup_segments") = x.speedup_segments,
                                    py::arg("against_full") = diff(x.against_full)));
        };
        shortcut_rows(r.thresholds, thresholds);
        shortcut_rows(r.peaks, peaks);
        for (const auto& x : r.lost) {
            const double n = static_cast<double>(x.stats.primary_rays);
            lost.append(py::dict(py::arg("paper_limits") = x.paper_limits, py::arg("max_depth") = x.max_depth,
                                 py::arg("threshold") = x.threshold, py::arg("lost_depth") = x.stats.lost_depth / n,
                                 py::arg("lost_limits") = x.stats.lost_limits / n,
                                 py::arg("lost_threshold") = x.stats.lost_threshold / n,
                                 py::arg("worst_pixel") = x.worst_pixel, py::arg("rmse_vs_deepest") = x.rmse_vs_deepest));
        }
        auto map_rows = [](const std::vector<oh::MapStudyRow>& in, py::list& out) {
            for (const auto& x : in)
                out.append(py::dict(py::arg("element_size") = x.element_size, py::arg("elements") = x.elements,
                                    py::arg("photons") = x.photons, py::arg("filter") = filter_name(x.filter),
                                    py::arg("deposits_per_element") = x.deposits_per_element, py::arg("error") = x.e.error,
                                    py::arg("noise") = x.e.noise, py::arg("bias") = x.e.bias));
        };
        map_rows(r.maps.by_photons, by_photons);
        map_rows(r.maps.by_element, by_element);
        const auto& fs = r.fast.stats;
        return py::dict(
            py::arg("quick") = r.quick, py::arg("full") = image(r.full.image), py::arg("shortcut") = image(r.fast.image),
            py::arg("box") = image(r.box_image), py::arg("first") = image(r.first_image), py::arg("light_s") = r.light_s,
            py::arg("eye_s") = r.eye_s, py::arg("eye_shortcut_s") = fs.seconds,
            py::arg("shortcut_taken") = fs.shortcut_taken, py::arg("shortcut_tests") = fs.shortcut_tests,
            py::arg("map_elements") = r.map_elements, py::arg("map_photons") = r.map_photons,
            py::arg("map_deposits") = r.map_deposits, py::arg("shortcut_diff") = diff(r.shortcut_diff),
            py::arg("steps") = steps, py::arg("thresholds") = thresholds, py::arg("peaks") = peaks, py::arg("lost") = lost,
            py::arg("map_by_photons") = by_photons, py::arg("map_by_element") = by_element, py::arg("seconds") = r.seconds);
    }, py::arg("quick") = true, py::arg("threads") = 0,
       "ohtsuka1998 measured into a dict: the diamond with the full split and the shortcut (images, times, difference), "
       "the wavelength-step, floor-map, shortcut-threshold and dropped-light studies.");
    m.def("gem_proportions", [](const std::string& preset) {
        const Gem gem = build_brilliant(brilliant_preset(preset));
        py::list l;
        for (const auto& r : ex::gem_geometry::proportion_rows(preset, gem))
            l.append(py::dict(py::arg("preset") = r.preset, py::arg("quantity") = r.quantity, py::arg("unit") = r.unit,
                              py::arg("source") = r.source, py::arg("expected") = r.expected,
                              py::arg("measured") = r.measured));
        return l;
    }, py::arg("preset"), "gem-geometry: the preset's proportions, expected against measured on the exact polyhedron.");
}

}  // namespace refract::python
