// The optics laws of core/optics.h, one Python function per C++ function, and the material
// catalogue of core/spectrum/dispersion.h. Scalar laws accept NumPy arrays (elementwise).
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include <refract/core/optics.h>
#include <refract/core/spectrum/dispersion.h>
#include <refract/core/spectrum/wavelengths.h>
#include <refract/geometry/error.h>
#include "python/src/bindings.h"

namespace refract::python {

namespace {

py::object vec_or_none(const std::optional<Vec3>& v) { return v ? py::object(array3(*v)) : py::object(py::none()); }
py::object num_or_none(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

// The laws' domains: a cosine of the incident side in [0, 1], a relative index finite and
// > 0, a wavelength inside the range the colour tables (and `trace`) accept. InputError
// naming the function and the argument otherwise.
double check_cos(const char* fn, const char* arg, double c) {
    if (!(c >= 0.0 && c <= 1.0))
        throw InputError(std::string("optics.") + fn + ": " + arg + " " + format_value(c) +
                         " is outside [0, 1] (the cosine on the incident side)");
    return c;
}
double check_eta(const char* fn, double eta) {
    if (!(eta > 0.0 && std::isfinite(eta)))
        throw InputError(std::string("optics.") + fn + ": eta " + format_value(eta) + " must be a finite number > 0");
    return eta;
}
double check_nm(const std::string& label, double nm) {
    if (!(nm >= spectrum::kMinWavelength && nm <= spectrum::kMaxWavelength))
        throw InputError(label + ": wavelength " + format_value(nm) + " nm is outside [" +
                         format_value(spectrum::kMinWavelength) + ", " + format_value(spectrum::kMaxWavelength) + "] nm");
    return nm;
}

}  // namespace

void bind_optics(py::module_& m) {
    using namespace refract::optics;

    py::class_<FresnelTerms>(m, "FresnelTerms", "Rs (s, TE), Rp (p, TM), cos_t; R = (Rs + Rp)/2, T = 1 − R")
        .def_readonly("Rs", &FresnelTerms::Rs)
        .def_readonly("Rp", &FresnelTerms::Rp)
        .def_readonly("cos_t", &FresnelTerms::cos_t)
        .def_property_readonly("R", &FresnelTerms::R)
        .def_property_readonly("T", &FresnelTerms::T)
        .def("__repr__", [](const FresnelTerms& f) {
            return "FresnelTerms(Rs=" + format_value(f.Rs) + ", Rp=" + format_value(f.Rp) + ", cos_t=" +
                   format_value(f.cos_t) + ")";
        });

    py::module_ o = m.def_submodule("optics", "The laws of core/optics.h; eta = n_t / n_i, cosines on the incident side");
    o.def("reflect", [](const py::handle& d, const py::handle& n) {
        return array3(optics::reflect(to_vec3(d, "reflect: d"), to_vec3(n, "reflect: n")));
    }, py::arg("d"), py::arg("n"), "Mirror reflection of direction d about the unit normal n.");
    o.def("refract", [](const py::handle& d, const py::handle& n, double eta) {
        return vec_or_none(optics::refract(to_vec3(d, "refract: d"), to_vec3(n, "refract: n"), eta));
    }, py::arg("d"), py::arg("n"), py::arg("eta"),
       "Refracted unit direction (d unit, n on the incident side); None on total internal reflection.");
    o.def("whitted_directions", [](const py::handle& v, const py::handle& n, double eta) {
        const auto w = whitted_directions(to_vec3(v, "whitted_directions: V"), to_vec3(n, "whitted_directions: N"), eta);
        return py::make_tuple(array3(w.reflected), vec_or_none(w.transmitted));
    }, py::arg("V"), py::arg("N"), py::arg("eta"), "Yasuda 1984 eq. 2–5: (R, P), P None on total internal reflection.");
    o.def("cos_transmitted", [](double cos_i, double eta) {
        return num_or_none(cos_transmitted(check_cos("cos_transmitted", "cos_i", cos_i), check_eta("cos_transmitted", eta)));
    },
          py::arg("cos_i"), py::arg("eta"), "Snell's law: cos θt, None on total internal reflection.");
    o.def("fresnel", [](double cos_i, double eta) -> py::object {
        const auto f = fresnel(check_cos("fresnel", "cos_i", cos_i), check_eta("fresnel", eta));
        return f ? py::cast(*f) : py::object(py::none());
    }, py::arg("cos_i"), py::arg("eta"), "Exact Fresnel terms (Rs, Rp, cos_t); None on total internal reflection.");
    o.def("fresnel_reflection_amplitudes", [](double cos_i, double cos_t, double eta) {
        const auto a = generic::fresnel_reflection_amplitudes(cos_i, cos_t, eta);
        return py::make_tuple(a.s, a.p);
    }, py::arg("cos_i"), py::arg("cos_t"), py::arg("eta"), "(rs, rp), Hecht §4.6.2.");
    o.def("fresnel_transmission_amplitudes", [](double cos_i, double cos_t, double eta) {
        const auto a = generic::fresnel_transmission_amplitudes(cos_i, cos_t, eta);
        return py::make_tuple(a.s, a.p);
    }, py::arg("cos_i"), py::arg("cos_t"), py::arg("eta"), "(ts, tp), Hecht §4.6.2.");
    o.def("fresnel_reflectance", py::vectorize([](double cos_i, double eta) {
              return fresnel_reflectance(check_cos("fresnel_reflectance", "cos_i", cos_i), check_eta("fresnel_reflectance", eta));
          }),
          py::arg("cos_i"), py::arg("eta"), "Natural-light reflectance, 1 on total internal reflection (elementwise).");
    o.def("schlick", py::vectorize([](double c, double eta) { return schlick(check_cos("schlick", "cos", c), check_eta("schlick", eta)); }), py::arg("cos"), py::arg("eta"),
          "Schlick's approximation R0 + (1 − R0)(1 − cos)^5 (elementwise).");
    o.def("critical_angle", [](double eta) { return num_or_none(critical_angle(check_eta("critical_angle", eta))); }, py::arg("eta"),
          "Critical angle in radians for eta < 1; None when eta >= 1.");
    o.def("brewster_angle", py::vectorize([](double eta) { return brewster_angle(check_eta("brewster_angle", eta)); }), py::arg("eta"),
          "Brewster's angle in radians: tan θB = eta (elementwise).");
    o.def("beer_lambert", py::vectorize([](double alpha, double d) { return beer_lambert(alpha, d); }),
          py::arg("alpha"), py::arg("distance"), "Fraction left after a path: exp(−α d) (elementwise).");
    o.def("absorption_coefficient", [](double t, double d) { return num_or_none(absorption_coefficient(t, d)); },
          py::arg("transmittance"), py::arg("thickness"), "α = −ln(T)/d; None unless 0 < T <= 1 and d > 0.");

    // ---- Materials ----
    using spectrum::Dispersion;
    py::class_<Dispersion>(m, "Dispersion", "An index of refraction as a function of wavelength (docs/spectra.md)")
        .def_readonly("label", &Dispersion::label)
        .def("n", [](const Dispersion& d, const py::object& nm) -> py::object {
            if (PyFloat_Check(nm.ptr()) || PyLong_Check(nm.ptr())) return py::float_(d.n(check_nm(d.label, nm.cast<double>())));
            return py::vectorize([&d](double x) { return d.n(check_nm(d.label, x)); })(nm.cast<py::array_t<double>>());
        }, py::arg("wavelength_nm"), "n(λ), λ in nm within [360, 830] (elementwise over an array); InputError outside.")
        .def_property_readonly("nominal", &Dispersion::nominal)
        .def_property_readonly("dispersive", &Dispersion::dispersive)
        .def_property_readonly("abbe_number", &Dispersion::abbe_number)
        .def("__repr__", [](const Dispersion& d) { return "<refract.Dispersion " + d.label + ">"; });
    m.def("materials", &spectrum::catalogue_names, "The names of the material catalogue.");
    m.def("material", [](const std::string& name) { return spectrum::catalogue(name); }, py::arg("name"),
          "A catalogue material (diamond, n-bk7, fused-silica, water, cubic-zirconia, moissanite).");
    m.def("dispersion_from_json", [](const std::string& text, const std::string& where) {
        return spectrum::parse_dispersion_text(text, where);
    }, py::arg("text"), py::arg("where") = "dispersion",
       "A dispersion from a catalogue name or the scene file's JSON form; errors name `where`.");

    py::module_ f = m.def_submodule("fraunhofer", "Fraunhofer and helium lines, nm");
    f.attr("B") = spectrum::fraunhofer::B;
    f.attr("C") = spectrum::fraunhofer::C;
    f.attr("D") = spectrum::fraunhofer::D;
    f.attr("d") = spectrum::fraunhofer::d;
    f.attr("F") = spectrum::fraunhofer::F;
    f.attr("G") = spectrum::fraunhofer::G;
}

}  // namespace refract::python
