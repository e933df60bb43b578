// The functions behind the command line's farfield, measure, export-pov, validate and sweep,
// for Python (refract/__init__.py wraps them with keyword arguments). Each calls the C++
// function the subcommand calls; only the conversions are here.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include <refract/core/far_field.h>
#include <refract/core/image.h>
#include <refract/core/scene.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/experiments/common.h>
#include <refract/experiments/far_field_output.h>
#include <refract/experiments/gem_metrics.h>
#include <refract/experiments/gem_sweep.h>
#include <refract/geometry/error.h>
#include <refract/validation/compare.h>
#include <refract/validation/measure.h>
#include <refract/validation/pov_export.h>
#include <refract/validation/povray_runner.h>
#include <refract/validation/suite.h>
#include "python/src/bindings.h"

namespace refract::python {

namespace {

namespace v = refract::validation;
namespace sw = refract::experiments::gem_sweep;

template <class T>
py::array_t<T> array1(const std::vector<T>& x) {
    return to_numpy(x, {static_cast<py::ssize_t>(x.size())});
}

// ---- farfield -----------------------------------------------------------------------------
py::dict far_field_run(const std::shared_ptr<Scene>& scene, const std::string& binning, const py::handle& axis,
                       const py::handle& reference, int bins, int azimuth_bins, int polar_bins, int classes,
                       std::uint64_t photons, std::uint64_t seed, const std::vector<double>& wavelengths, int threads,
                       const std::string& output, bool plot) {
    if (binning != "sphere" && binning != "axis")
        throw InputError("farfield: binning '" + binning + "': expected sphere or axis");
    const std::string src = scene->source.empty() ? std::string("scene") : scene->source;
    if (scene->lights.empty() && scene->background.kind != Background::Kind::Environment)
        throw InputError(src + ": /lights: the far-field detector needs a light or an environment background");
    FarFieldSettings s;
    s.binning = binning == "axis" ? FarFieldSettings::Binning::Axis : FarFieldSettings::Binning::Sphere;
    if (!axis.is_none()) s.axis = to_vec3(axis, "farfield: axis");
    if (!reference.is_none()) s.reference = to_vec3(reference, "farfield: reference");
    s.angle_bins = bins;
    s.azimuth_bins = azimuth_bins;
    s.polar_bins = polar_bins;
    s.classes = classes;
    s.photons = photons;
    s.seed = seed;
    s.wavelengths = wavelengths;
    experiments::FarFieldFiles files;
    files.plot = plot;
    // As the subcommand: the output checked before the work, nothing left when refused.
    const bool created = !output.empty() && experiments::ensure_dir(output);
    FarFieldResult r;
    try {
        if (!output.empty()) experiments::check_far_field_outputs(output, files);
        r = without_gil([&] { return far_field(*scene, s, threads); });
        if (!output.empty())
            without_gil([&] {
                experiments::write_far_field(output, experiments::far_field_tables(r), "far field of " + src, files);
            });
    } catch (const InputError&) {
        std::error_code ec;
        if (created) std::filesystem::remove_all(output, ec);
        throw;
    }
    py::dict d;
    const auto W = static_cast<py::ssize_t>(r.wavelengths.size());
    d["wavelengths"] = array1(r.wavelengths);
    d["power"] = to_numpy(r.power, {W, r.classes, r.components, r.bins});
    d["unscattered"] = array1(r.unscattered);
    d["absorbed"] = array1(r.absorbed);
    d["dropped"] = array1(r.dropped);
    std::vector<double> theta(static_cast<size_t>(r.bins)), solid(static_cast<size_t>(r.bins));
    for (int b = 0; b < r.bins; ++b) {
        theta[static_cast<size_t>(b)] = r.theta_deg(b);
        solid[static_cast<size_t>(b)] = r.solid_angle(b);
    }
    d["theta_deg"] = array1(theta);
    d["solid_angle"] = array1(solid);
    if (s.binning == FarFieldSettings::Binning::Sphere) {
        std::vector<double> phi(static_cast<size_t>(r.bins));
        for (int b = 0; b < r.bins; ++b) phi[static_cast<size_t>(b)] = r.phi_deg(b);
        d["phi_deg"] = array1(phi);
    }
    py::list names;
    for (int c = 0; c < r.classes; ++c) names.append(r.class_name(c));
    d["class_names"] = names;
    d["photons"] = r.photons;
    d["segments"] = r.segments;
    d["seconds"] = r.seconds;
    return d;
}

// ---- measure ------------------------------------------------------------------------------
Image image_of(const py::handle& o, const char* what) {
    if (py::isinstance<py::str>(o)) return read_image(o.cast<std::string>());
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
    if (!a || a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1) {
        PyErr_Clear();
        throw InputError(std::string("measure: ") + what + " must be a path or an array of shape (height, width, 3)");
    }
    Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    std::copy(a.data(), a.data() + a.size(), img.rgb.begin());
    return img;
}

py::dict region(const py::handle& image, const std::optional<std::vector<int>>& rect, const py::handle& mask) {
    const Image img = image_of(image, "image");
    v::PixelRect r{0, 0, img.width - 1, img.height - 1};
    if (rect) {
        if (rect->size() != 4) throw InputError("measure: region must be X0 Y0 X1 Y1");
        r = {(*rect)[0], (*rect)[1], (*rect)[2], (*rect)[3]};
    }
    std::optional<Image> m;
    if (!mask.is_none()) m = image_of(mask, "mask");
    const v::RegionStats s = v::region_stats(img, r, m ? &*m : nullptr);
    py::dict d;
    d["pixels"] = s.pixels;
    const char* names[3] = {"r", "g", "b"};
    for (size_t c = 0; c < 3; ++c) {
        const auto& ch = s.channel[c];
        d[names[c]] = py::dict(py::arg("mean") = ch.mean, py::arg("sum") = ch.sum, py::arg("min") = ch.min,
                               py::arg("max") = ch.max);
    }
    return d;
}

py::dict line(const py::handle& image, int x0, int y0, int x1, int y1) {
    const Image img = image_of(image, "image");
    const auto pixels = v::line_pixels(x0, y0, x1, y1);
    const auto values = v::values_at(img, pixels);
    std::vector<double> x, y, dist, rgb;
    for (size_t k = 0; k < pixels.size(); ++k) {
        x.push_back(pixels[k].first);
        y.push_back(pixels[k].second);
        dist.push_back(std::hypot(pixels[k].first - x0, pixels[k].second - y0));
        for (int c = 0; c < 3; ++c) rgb.push_back(values[k][c]);
    }
    py::dict d;
    d["x"] = array1(x);
    d["y"] = array1(y);
    d["distance"] = array1(dist);
    d["rgb"] = to_numpy(rgb, {static_cast<py::ssize_t>(pixels.size()), 3});
    return d;
}

py::dict radial(const py::handle& image, double cx, double cy, double radius, int bins) {
    const Image img = image_of(image, "image");
    std::vector<double> r0, r1, pixels, rgb;
    for (const auto& b : v::radial_profile(img, cx, cy, bins, radius)) {
        r0.push_back(b.r0);
        r1.push_back(b.r1);
        pixels.push_back(static_cast<double>(b.pixels));
        for (int c = 0; c < 3; ++c) rgb.push_back(b.mean[c]);
    }
    py::dict d;
    d["r0"] = array1(r0);
    d["r1"] = array1(r1);
    d["pixels"] = array1(pixels);
    d["rgb"] = to_numpy(rgb, {static_cast<py::ssize_t>(r0.size()), 3});
    return d;
}

py::dict angle_histogram(const std::string& path, int bins, const py::handle& axis) {
    std::optional<Vec3> a;
    if (!axis.is_none()) a = to_vec3(axis, "measure: axis");
    const Channels map = read_channels(path);
    const auto hist = v::angle_histogram(map, path, bins, a);
    std::vector<double> t0, t1, sr, px, power, intensity;
    for (const auto& b : hist) {
        t0.push_back(b.theta0_deg);
        t1.push_back(b.theta1_deg);
        sr.push_back(b.solid_angle);
        px.push_back(static_cast<double>(b.pixels));
        power.insert(power.end(), b.power.begin(), b.power.end());
        intensity.insert(intensity.end(), b.intensity.begin(), b.intensity.end());
    }
    const auto n = static_cast<py::ssize_t>(hist.size()), c = static_cast<py::ssize_t>(map.names.size());
    py::dict d;
    d["theta0_deg"] = array1(t0);
    d["theta1_deg"] = array1(t1);
    d["solid_angle_sr"] = array1(sr);
    d["pixels"] = array1(px);
    d["channels"] = map.names;
    d["power"] = to_numpy(power, {n, c});
    d["intensity"] = to_numpy(intensity, {n, c});
    return d;
}

// ---- validate -----------------------------------------------------------------------------
py::dict validate(const std::string& out_dir, const std::vector<std::string>& cases, const std::string& scenes,
                  int threads, const std::string& povray) {
    if (out_dir.empty()) throw InputError("validate: out_dir (report directory) is required");
    if (threads < 0) throw InputError("validate: threads must be >= 0");
    for (const auto& name : cases) v::check_case_name(name, "validate");
    if (v::find_povray(povray).empty())
        throw InputError("validate: POV-Ray executable '" + povray + "' not found (install POV-Ray 3.7 or pass povray=PATH)");
    v::SuiteOptions opt;
    opt.scenes_dir = scenes;
    opt.out_dir = out_dir;
    opt.cases = cases;
    opt.threads = threads;
    opt.povray.executable = povray;
    const v::SuiteResult r = without_gil([&] { return v::run_suite(opt); });
    py::list l;
    for (const auto& c : r.cases) {
        py::list metrics;
        for (const auto& m : c.metrics)
            metrics.append(py::dict(py::arg("name") = m.name, py::arg("value") = m.value,
                                    py::arg("tolerance") = m.tolerance, py::arg("status") = v::status_name(m.status)));
        l.append(py::dict(py::arg("name") = c.name, py::arg("status") = v::status_name(c.status),
                          py::arg("skip_reason") = c.skip_reason, py::arg("metrics") = metrics,
                          py::arg("images") = c.images));
    }
    py::dict d;
    d["cases"] = l;
    d["passed"] = r.passed;
    d["failed"] = r.failed;
    d["skipped"] = r.skipped;
    d["povray_version"] = r.povray_version;
    d["table"] = v::format_table(r);
    return d;
}

// ---- sweep --------------------------------------------------------------------------------
// The rows `refract sweep brilliant` writes: (CSV header, one CSV line per cut).
py::tuple sweep(const std::string& preset, const std::vector<std::pair<std::string, std::string>>& ranges, int rays,
                int wavelengths, const std::string& material, const std::string& polarisation, std::uint64_t seed,
                int threads) {
    sw::Sweep s;
    s.grid = sw::single_cut_grid(brilliant_preset(preset));
    for (const auto& [name, text] : ranges) {
        const auto& names = sw::parameter_names();
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            std::string known;
            for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
            throw InputError("sweep: unknown parameter '" + name + "' (one of " + known + ")");
        }
        sw::set_axis(s.grid, sw::parse_axis(name, text));
    }
    if (polarisation != "exact" && polarisation != "natural")
        throw InputError("sweep: polarisation '" + polarisation + "': expected exact or natural");
    try {
        spectrum::catalogue(material);
    } catch (const InputError& e) {
        throw InputError("sweep: material: " + std::string(e.what()));
    }
    s.metric.material = material;
    s.metric.rays = rays;
    s.metric.wavelengths = wavelengths;
    s.metric.exact_polarisation = polarisation == "exact";
    s.metric.seed = seed;
    gem_metrics::validate(s.metric);
    const auto rows = without_gil([&] { return sw::run(s, sw::all_indices(s), threads); });
    py::list lines;
    for (const auto& r : rows) lines.append(sw::csv_line(r));
    return py::make_tuple(sw::csv_header(), lines);
}

}  // namespace

void bind_commands(py::module_& m) {
    m.def("_far_field", &far_field_run, py::arg("scene"), py::arg("binning"), py::arg("axis"), py::arg("reference"),
          py::arg("bins"), py::arg("azimuth_bins"), py::arg("polar_bins"), py::arg("classes"), py::arg("photons"),
          py::arg("seed"), py::arg("wavelengths"), py::arg("threads"), py::arg("output"), py::arg("plot"));
    m.def("_measure_region", &region, py::arg("image"), py::arg("region"), py::arg("mask"));
    m.def("_measure_line", &line, py::arg("image"), py::arg("x0"), py::arg("y0"), py::arg("x1"), py::arg("y1"));
    m.def("_measure_radial", &radial, py::arg("image"), py::arg("cx"), py::arg("cy"), py::arg("radius"), py::arg("bins"));
    m.def("_measure_angles", &angle_histogram, py::arg("path"), py::arg("bins"), py::arg("axis"));
    m.def("_export_pov", [](const std::shared_ptr<Scene>& s) { return v::export_pov(*s); }, py::arg("scene"));
    m.def("_write_pov", [](const std::shared_ptr<Scene>& s, const std::string& path) { v::write_pov(*s, path); },
          py::arg("scene"), py::arg("path"));
    m.def("validation_cases", &v::list_cases, py::arg("scenes") = "scenes/validation",
          "The validation suite's case names in a scenes directory (refract validate --list).");
    m.def("_validate", &validate, py::arg("out_dir"), py::arg("cases"), py::arg("scenes"), py::arg("threads"),
          py::arg("povray"));
    m.def("_sweep", &sweep, py::arg("preset"), py::arg("ranges"), py::arg("rays"), py::arg("wavelengths"),
          py::arg("material"), py::arg("polarisation"), py::arg("seed"), py::arg("threads"));
}

}  // namespace refract::python
