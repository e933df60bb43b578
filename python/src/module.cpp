// refract._refract: the native part of the Python module `refract` (python/refract/ is the
// package around it). Scenes, rendering and ray trees here; the optics laws and materials
// in optics.cpp, the brilliant cut in gem.cpp, the experiments in experiments.cpp. Every
// law and check is core's: these functions only convert between Python and C++.
#include <pybind11/stl.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include <refract/core/image.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/render.h>
#include <refract/core/scene_json.h>
#include <refract/core/trace_record.h>
#include <refract/geometry/error.h>
#include <refract/geometry/input_file.h>
#include "python/src/bindings.h"

namespace refract::python {

Vec3 to_vec3(const py::handle& o, const char* what) {
    py::array_t<double, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
    } catch (const py::error_already_set&) {
    }
    if (!a || a.ndim() != 1 || a.shape(0) != 3) {
        PyErr_Clear();
        throw InputError(std::string(what) + ": must be three numbers");
    }
    return {a.at(0), a.at(1), a.at(2)};
}

py::array_t<double> array3(const Vec3& v) { return to_numpy(std::vector<double>{v.x(), v.y(), v.z()}, {3}); }

namespace {

// ---- Python values to JSON, for the scene reader --------------------------------------
// Numbers stay doubles as Python gives them (NaN and infinities too, so that the scene
// reader, not this converter, names the field); NumPy scalars and arrays are accepted.
// Nesting deeper than any scene needs is refused (a Python error, not a C++ stack overflow).
constexpr int kMaxDepth = 64;

nlohmann::json to_json(const py::handle& o, const std::string& path, const std::string& source, int depth = 0) {
    if (depth > kMaxDepth)
        throw InputError(source + ": " + path + ": nested more than " + std::to_string(kMaxDepth) + " levels deep");
    if (o.is_none()) return nullptr;
    if (PyBool_Check(o.ptr())) return o.cast<bool>();
    if (PyLong_Check(o.ptr())) {
        int overflow = 0;
        const long long v = PyLong_AsLongLongAndOverflow(o.ptr(), &overflow);
        if (overflow) return PyLong_AsDouble(o.ptr());
        return v;
    }
    if (PyFloat_Check(o.ptr())) return PyFloat_AS_DOUBLE(o.ptr());
    if (PyUnicode_Check(o.ptr())) return o.cast<std::string>();
    if (PyDict_Check(o.ptr())) {
        nlohmann::json j = nlohmann::json::object();
        for (const auto& kv : py::reinterpret_borrow<py::dict>(o)) {
            if (!PyUnicode_Check(kv.first.ptr()))
                throw InputError(source + ": " + (path.empty() ? "/" : path) + ": keys must be strings, not " +
                                 std::string(py::str(py::repr(kv.first))));
            const std::string key = kv.first.cast<std::string>();
            j[key] = to_json(kv.second, path + "/" + key, source, depth + 1);
        }
        return j;
    }
    if (PyList_Check(o.ptr()) || PyTuple_Check(o.ptr())) {
        nlohmann::json j = nlohmann::json::array();
        size_t k = 0;
        for (const auto& v : py::reinterpret_borrow<py::sequence>(o))
            j.push_back(to_json(v, path + "/" + std::to_string(k++), source, depth + 1));
        return j;
    }
    if (py::isinstance<py::array>(o) || py::hasattr(o, "tolist")) return to_json(o.attr("tolist")(), path, source, depth + 1);
    if (PyIndex_Check(o.ptr()))
        return to_json(py::reinterpret_steal<py::object>(PyNumber_Index(o.ptr())), path, source, depth + 1);
    if (PyNumber_Check(o.ptr()))
        return to_json(py::reinterpret_steal<py::object>(PyNumber_Float(o.ptr())), path, source, depth + 1);
    throw InputError(source + ": " + (path.empty() ? "/" : path) + ": cannot be written in JSON (a " +
                     std::string(py::str(o.get_type().attr("__name__"))) + ")");
}

using ScenePtr = std::shared_ptr<const Scene>;

ScenePtr scene_from_text(const std::string& text, const std::string& source) {
    check_json_depth(text, source);  // as the file reader
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {  // the file reader's wording
        std::string what = e.what();
        auto pos = what.find("] ");
        throw InputError(source + ": malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos + 2)));
    }
    return std::make_shared<Scene>(parse_scene(j, source));
}

// ---- Rendering --------------------------------------------------------------------------

// The counters of core/render_stats.h by their field list, with the --stats text and the
// warning about dropped light.
py::dict stats_dict(const RenderStats& s) {
    py::dict d = to_python(s);
    d["summary"] = s.summary();
    d["lost_warning"] = s.lost_warning();
    return d;
}

// Renders on a worker thread with the GIL released; this thread polls Python's signal
// handlers every 50 ms and cancels the render when one raises (Ctrl-C: KeyboardInterrupt).
py::dict render(const ScenePtr& scene, int threads, bool spectral_channels, bool lost_energy, std::uint64_t max_memory,
                bool progress) {
    RenderOptions opt;
    opt.threads = threads;
    opt.spectral_channels = spectral_channels;
    opt.lost_energy = lost_energy;
    opt.max_memory = max_memory;
    opt.progress = progress;
    std::atomic<bool> cancel{false};
    opt.cancel = &cancel;
    std::unique_ptr<RenderResult> result;
    std::exception_ptr error;
    bool interrupted = false;
    without_gil([&] {
        std::mutex mu;
        std::condition_variable cv;
        bool done = false;
        std::thread worker([&] {
            try {
                result = std::make_unique<RenderResult>(refract::render(*scene, opt));
            } catch (...) {
                error = std::current_exception();
            }
            std::lock_guard<std::mutex> lock(mu);
            done = true;
            cv.notify_all();
        });
        std::unique_lock<std::mutex> lock(mu);
        while (!cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
            if (interrupted) continue;
            lock.unlock();
            {
                py::gil_scoped_acquire gil;
                if (PyErr_CheckSignals() != 0) {  // the handler's exception stays set
                    interrupted = true;
                    cancel = true;
                }
            }
            lock.lock();
        }
        lock.unlock();
        worker.join();
    });
    if (interrupted) throw py::error_already_set();
    if (error) std::rethrow_exception(error);

    RenderResult* r = result.release();
    const py::capsule owner(r, [](void* p) { delete static_cast<RenderResult*>(p); });
    const py::ssize_t W = r->image.width, H = r->image.height;
    py::dict d;
    d["rgb"] = to_numpy(r->image, owner);
    d["stats"] = stats_dict(r->stats);
    if (!r->lost.empty()) d["lost"] = to_numpy(r->lost, {H, W, 3}, owner);
    if (spectral_channels) {
        d["wavelengths"] = to_numpy(r->wavelengths, {static_cast<py::ssize_t>(r->wavelengths.size())}, owner);
        d["spectral"] = to_numpy(r->spectral, {H, W, static_cast<py::ssize_t>(r->wavelengths.size())}, owner);
    }
    if (r->polarisation) {
        d["stokes"] = to_numpy(r->polarisation->stokes, {H, W, 4, 3}, owner);
        d["dolp"] = to_numpy(r->polarisation->dolp, {H, W}, owner);
        d["aolp"] = to_numpy(r->polarisation->aolp, {H, W}, owner);
    }
    return d;
}

// ---- Ray trees ----------------------------------------------------------------------------

// Interned keys: one dict per node, built as fast as Python builds its own.
struct NodeKeys {
    py::object id, parent, depth, reflections, transmissions, origin, direction, weight, event, hit, length, point,
        normal, object, facet, facet_label, entering, eta, cos_i, cos_t, Rs, Rp, R, light, wavelength, stokes, stokes_x,
        wave, index, wave_normal, path;
    NodeKeys() {
        auto k = [](const char* s) { return py::reinterpret_steal<py::object>(PyUnicode_InternFromString(s)); };
        id = k("id"), parent = k("parent"), depth = k("depth"), reflections = k("reflections");
        transmissions = k("transmissions"), origin = k("origin"), direction = k("direction"), weight = k("weight");
        event = k("event"), hit = k("hit"), length = k("length"), point = k("point"), normal = k("normal");
        object = k("object"), facet = k("facet"), facet_label = k("facet_label"), entering = k("entering");
        eta = k("eta"), cos_i = k("cos_i"), cos_t = k("cos_t"), Rs = k("Rs"), Rp = k("Rp"), R = k("R");
        light = k("light"), wavelength = k("wavelength"), stokes = k("stokes"), stokes_x = k("stokes_x");
        wave = k("wave"), index = k("index"), wave_normal = k("wave_normal");
        path = k("path");
    }
};

const NodeKeys& keys() {
    static const NodeKeys* k = new NodeKeys();  // never destroyed: Python may be gone at exit
    return *k;
}

// The C API directly (one dict presized per node, new references stolen): a node costs
// about half what item assignments through pybind11 cost.
PyObject* float3(const Vec3& v) {
    PyObject* t = PyTuple_New(3);
    for (int k = 0; k < 3; ++k) PyTuple_SET_ITEM(t, k, PyFloat_FromDouble(v[k]));
    return t;
}
PyObject* none_ref() {
    Py_INCREF(Py_None);
    return Py_None;
}
PyObject* bool_ref(bool b) {
    PyObject* o = b ? Py_True : Py_False;
    Py_INCREF(o);
    return o;
}
// A str per distinct text of a few (the events): made once, shared by every node.
PyObject* text_ref(const std::string& text) {
    static std::vector<std::pair<std::string, PyObject*>>* seen = new std::vector<std::pair<std::string, PyObject*>>();
    for (const auto& [t, o] : *seen)
        if (t == text) {
            Py_INCREF(o);
            return o;
        }
    PyObject* o = PyUnicode_FromStringAndSize(text.data(), static_cast<Py_ssize_t>(text.size()));
    if (o && seen->size() < 64) {
        Py_INCREF(o);  // the cache's reference: never released (Python may be gone at exit)
        seen->emplace_back(text, o);
    }
    return o;
}

py::tuple trace_result(const TraceRecord& rec) {
    const NodeKeys& k = keys();
    py::list nodes(rec.segments.size());
    const py::object wl = rec.wavelength_nm > 0 ? py::object(py::float_(rec.wavelength_nm)) : py::none();
    size_t n = 0;
    for (const TraceSegment& s : rec.segments) {
        py::object dict = py::reinterpret_steal<py::object>(_PyDict_NewPresized(31));
        PyObject* d = dict.ptr();
        const auto put = [&](const py::object& key, PyObject* value) {  // steals value
            if (!value || PyDict_SetItem(d, key.ptr(), value) != 0) {
                Py_XDECREF(value);
                throw py::error_already_set();
            }
            Py_DECREF(value);
        };
        const auto number = [&](bool has, double v) { return has ? PyFloat_FromDouble(v) : none_ref(); };
        put(k.id, PyLong_FromLong(s.id));
        put(k.parent, PyLong_FromLong(s.parent));
        put(k.depth, PyLong_FromLong(s.depth));
        put(k.reflections, PyLong_FromLong(s.reflections));
        put(k.transmissions, PyLong_FromLong(s.transmissions));
        put(k.origin, float3(s.ray.origin));
        put(k.direction, float3(s.ray.dir));
        put(k.weight, float3(s.weight));
        put(k.event, text_ref(s.event));
        put(k.hit, bool_ref(s.hit));
        put(k.length, number(s.hit, s.length));
        put(k.point, s.hit ? float3(s.point) : none_ref());
        put(k.normal, s.hit ? float3(s.normal) : none_ref());
        put(k.object, s.hit ? PyUnicode_FromStringAndSize(s.object.data(), static_cast<Py_ssize_t>(s.object.size()))
                            : none_ref());
        put(k.facet, PyLong_FromLong(s.facet));
        put(k.facet_label, s.facet_label.empty() ? none_ref()
                                                 : PyUnicode_FromStringAndSize(s.facet_label.data(),
                                                                               static_cast<Py_ssize_t>(s.facet_label.size())));
        put(k.entering, bool_ref(s.entering));
        const bool dielectric = s.eta > 0;
        put(k.eta, number(dielectric, s.eta));
        put(k.cos_i, number(dielectric, s.cos_i));
        put(k.cos_t, number(dielectric, s.cos_t));
        put(k.Rs, number(dielectric, s.Rs));
        put(k.Rp, number(dielectric, s.Rp));
        put(k.R, number(s.hit && s.event != "diffuse" && s.event != "emissive", s.R));
        put(k.light, float3(s.light));
        put(k.wavelength, wl.inc_ref().ptr());
        if (s.polarised) {
            PyObject* t = PyTuple_New(4);
            for (int c = 0; c < 4; ++c) PyTuple_SET_ITEM(t, c, PyFloat_FromDouble(s.stokes[c]));
            put(k.stokes, t);
            put(k.stokes_x, float3(s.stokes_x));
        } else {
            put(k.stokes, none_ref());
            put(k.stokes_x, none_ref());
        }
        const bool crystal = s.wave != biref::Wave::Isotropic;
        put(k.wave, crystal ? PyUnicode_FromString(s.wave == biref::Wave::Ordinary ? "o" : "e") : none_ref());
        put(k.index, number(crystal && s.index > 0, s.index));
        put(k.wave_normal, crystal && s.index > 0 ? float3(s.wave_normal) : none_ref());
        if (s.path.empty()) {
            put(k.path, none_ref());
        } else {
            PyObject* points = PyList_New(static_cast<Py_ssize_t>(s.path.size()));
            if (!points) throw py::error_already_set();
            for (size_t i = 0; i < s.path.size(); ++i) PyList_SET_ITEM(points, static_cast<Py_ssize_t>(i), float3(s.path[i]));
            put(k.path, points);
        }
        PyList_SET_ITEM(nodes.ptr(), static_cast<py::ssize_t>(n++), dict.release().ptr());
    }
    return py::make_tuple(nodes, tuple3(rec.radiance), wl);
}

double check_wavelength(const py::handle& w) {
    if (w.is_none()) return 0.0;
    return w.cast<double>();
}

// How a trace walks: None, the camera's walk under the scene's own model; "natural", the
// same with natural light whatever that model; a dict in the scene file's form of a
// light's "polarisation" (or its type alone, as a string): light of that state.
struct TraceModel {
    std::optional<PolarisationState> state;
    bool natural = false;
};
TraceModel check_polarisation(const py::handle& p) {
    if (p.is_none()) return {};
    if (py::isinstance<py::str>(p)) {
        const std::string t = p.cast<std::string>();
        if (t == "natural") return {std::nullopt, true};
        return {parse_polarisation_state(nlohmann::json{{"type", t}}, "trace"), false};
    }
    if (!py::isinstance<py::dict>(p))
        throw InputError("trace: polarisation must be None, \"natural\", a type name or a dict such as "
                         "{\"type\": \"linear\", \"angle\": 30}");
    return {parse_polarisation_state(to_json(p.cast<py::dict>(), "", "trace"), "trace"), false};
}


}  // namespace
}  // namespace refract::python

PYBIND11_MODULE(_refract, m) {
    namespace py = pybind11;
    using namespace refract;
    using namespace refract::python;
    m.doc() = "refract: the physics of refraction in rendering (native part; import refract)";

    // Bad input: refract.InputError, a ValueError, with core's one-line message.
    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

    py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", py::dynamic_attr(), "A validated scene (docs/scene-format.md)")
        .def_property_readonly("source", [](const Scene& s) { return s.source; })
        .def_property_readonly("width", [](const Scene& s) { return s.camera.width; })
        .def_property_readonly("height", [](const Scene& s) { return s.camera.height; })
        .def_property_readonly("objects",
                               [](const Scene& s) {
                                   std::vector<std::string> n;
                                   for (const auto& o : s.objects) n.push_back(o.name);
                                   return n;
                               })
        .def_property_readonly("spectral", [](const Scene& s) { return s.settings.spectral.enabled; })
        .def_property_readonly("polarisation", [](const Scene& s) {
            return polarisation_model(s) == PolarisationModel::Exact ? "exact" : "natural";
        })
        .def("__repr__", [](const Scene& s) {
            return "<refract.Scene " + s.source + " " + std::to_string(s.camera.width) + "x" +
                   std::to_string(s.camera.height) + ", " + std::to_string(s.objects.size()) + " objects>";
        });

    m.def("load_scene", [](const std::string& path) { return std::const_pointer_cast<Scene>(std::make_shared<Scene>(load_scene(path))); },
          py::arg("path"), "Reads and validates a scene file (JSON).");
    m.def("parse_scene_text",
          [](const std::string& text, const std::string& source) {
              return std::const_pointer_cast<Scene>(scene_from_text(text, source));
          },
          py::arg("text"), py::arg("source") = "scene", "A scene from JSON text; errors name `source`.");
    m.def("parse_scene",
          [](const py::dict& d, const std::string& source) {
              return std::make_shared<Scene>(parse_scene(to_json(d, "", source), source));
          },
          py::arg("scene"), py::arg("source") = "scene",
          "A scene from a dict in the scene file's format; errors name `source` and the field.");

    m.def("render",
          [](const std::shared_ptr<Scene>& s, int threads, bool spectral_channels, bool lost_energy,
             std::uint64_t max_memory, bool progress) {
              return render(s, threads, spectral_channels, lost_energy, max_memory, progress);
          },
          py::arg("scene"), py::arg("threads") = 0, py::arg("spectral_channels") = false, py::arg("lost_energy") = false,
          py::arg("max_memory") = 0, py::arg("progress") = false);

    // A scene's tracers built once for many traces (core/trace_record.h TraceSession);
    // `natural`: the walk with natural light whatever the scene's model.
    py::class_<TraceSession, std::shared_ptr<TraceSession>>(m, "TraceSession")
        .def(py::init([](const std::shared_ptr<Scene>& s, bool natural) {
                 if (!natural || polarisation_model(*s) == PolarisationModel::Natural)
                     return std::make_shared<TraceSession>(s);
                 auto copy = std::make_shared<Scene>(*s);
                 copy->settings.requested_polarisation = PolarisationModel::Natural;
                 return std::make_shared<TraceSession>(copy);
             }),
             py::arg("scene"), py::arg("natural") = false)
        .def("ray",
             [](const TraceSession& t, const py::handle& origin, const py::handle& direction, const py::handle& wavelength,
                const py::handle& polarisation) {
                 const Vec3 o = to_vec3(origin, "trace: origin"), d = to_vec3(direction, "trace: direction");
                 const double nm = check_wavelength(wavelength);
                 const TraceModel pol = check_polarisation(polarisation);
                 const PolarisationState* state = pol.state ? &*pol.state : nullptr;
                 return trace_result(without_gil([&] { return t.ray(Ray{o, d}, nm, state); }));
             },
             py::arg("origin"), py::arg("direction"), py::arg("wavelength") = py::none(),
             py::arg("polarisation") = py::none())
        .def("pixel",
             [](const TraceSession& t, int i, int j, const py::handle& wavelength, const py::handle& polarisation) {
                 const double nm = check_wavelength(wavelength);
                 const TraceModel pol = check_polarisation(polarisation);
                 const PolarisationState* state = pol.state ? &*pol.state : nullptr;
                 return trace_result(without_gil([&] { return t.pixel(i, j, nm, state); }));
             },
             py::arg("x"), py::arg("y"), py::arg("wavelength") = py::none(), py::arg("polarisation") = py::none());

    m.def("write_image",
          [](const std::string& path, const py::array_t<double, py::array::c_style | py::array::forcecast>& rgb,
             bool linear16) {
              if (rgb.ndim() != 3 || rgb.shape(2) != 3 || rgb.shape(0) < 1 || rgb.shape(1) < 1)
                  throw InputError(path + ": write_image needs an array of shape (height, width, 3)");
              Image img(static_cast<int>(rgb.shape(1)), static_cast<int>(rgb.shape(0)));
              std::copy(rgb.data(), rgb.data() + rgb.size(), img.rgb.begin());
              // The caller's values: any sign, but each must be finite as a float (bad input,
              // not the writer's internal error).
              for (size_t k = 0; k < img.rgb.size(); ++k)
                  if (!(std::fabs(img.rgb[k]) <= std::numeric_limits<float>::max()))
                      throw InputError(path + ": write_image: the value at [" + std::to_string(k / 3 / img.width) +
                                       ", " + std::to_string(k / 3 % img.width) + ", " + std::to_string(k % 3) +
                                       "] is " + format_value(img.rgb[k]) + ", not finite as a 32-bit float");
              without_gil([&] { write_image(path, img, WriteOptions{linear16, true}); });
          },
          py::arg("path"), py::arg("rgb"), py::arg("linear16") = false,
          "Writes linear RGB (height, width, 3) as `refract render` does: .exr/.hdr/.tif linear, .png/.jpg sRGB "
          "(16-bit linear PNG with linear16); atomically. Every value must be finite as a 32-bit float "
          "(ValueError otherwise); negative ones are kept in the float formats.");
    m.def("read_image",
          [](const std::string& path) {
              return to_numpy(without_gil([&] { return read_image(path); }));
          },
          py::arg("path"), "Reads an image as stored (linear for EXR), shape (height, width, 3).");

    bind_optics(m);
    bind_gem(m);
    bind_experiments(m);
    bind_commands(m);
    m.attr("__version__") = REFRACT_VERSION;
    bind_trace_rays(m);
    bind_grin(m);
}
