// refract._refract.trace_rays: many rays through a TraceSession at once (core/trace_rays.h),
// the sums of each ray's tree as NumPy arrays.
#include <algorithm>
#include <string>

#include <refract/core/trace_rays.h>
#include <refract/geometry/error.h>
#include "python/src/bindings.h"

namespace refract::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An (n, 3) array of `what`, or InputError naming it.
Array rows3(const py::handle& o, const char* what) {
    Array a;
    try {
        a = Array::ensure(o);
    } catch (const py::error_already_set&) {
    }
    if (!a || (a.ndim() == 1 && a.shape(0) == 3)) {
        if (a) a = a.reshape({py::ssize_t{1}, py::ssize_t{3}});
    }
    if (!a || a.ndim() != 2 || a.shape(1) != 3) {
        PyErr_Clear();
        throw InputError(std::string("trace_rays: ") + what + ": must be an array of shape (n, 3)");
    }
    return a;
}

py::dict trace_rays_py(const TraceSession& session, const py::handle& origins, const py::handle& directions,
                       const py::handle& wavelengths, int threads) {
    const Array o = rows3(origins, "origins"), d = rows3(directions, "directions");
    const py::ssize_t n = o.shape(0);
    if (d.shape(0) != n)
        throw InputError("trace_rays: directions: " + std::to_string(d.shape(0)) + " rows for " + std::to_string(n) +
                         " origins");
    Array w;
    const bool has_w = !wavelengths.is_none();
    if (has_w) {
        try {
            w = Array::ensure(wavelengths);
        } catch (const py::error_already_set&) {
        }
        if (w && w.ndim() == 0) {  // one wavelength for every ray
            const double nm = *w.data();
            w = Array(n);
            std::fill(w.mutable_data(), w.mutable_data() + n, nm);
        }
        if (!w || w.ndim() != 1 || w.shape(0) != n) {
            PyErr_Clear();
            throw InputError("trace_rays: wavelengths: must be None, a number or an array of shape (n,)");
        }
    }
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
    const auto* op = reinterpret_cast<const Vec3*>(o.data());
    const auto* dp = reinterpret_cast<const Vec3*>(d.data());
    const double* wp = has_w ? w.data() : nullptr;
    auto* b = new RayBatch(
        without_gil([&] { return trace_rays(session, op, dp, wp, static_cast<std::size_t>(n), threads); }));
    const py::capsule owner(b, [](void* p) { delete static_cast<RayBatch*>(p); });  // the arrays view b
    py::dict r;
    const py::ssize_t rows = n;
    r["point"] = to_numpy(b->point, {rows, 3}, owner);
    r["object"] = to_numpy(b->object, {rows}, owner);
    r["facet"] = to_numpy(b->facet, {rows}, owner);
    r["radiance"] = to_numpy(b->radiance, {rows, 3}, owner);
    r["escaped"] = to_numpy(b->escaped, {rows, 3}, owner);
    r["exit_direction"] = to_numpy(b->exit_direction, {rows, 3}, owner);
    r["Rs"] = to_numpy(b->Rs, {rows}, owner);
    r["Rp"] = to_numpy(b->Rp, {rows}, owner);
    r["segments"] = to_numpy(b->segments, {rows}, owner);
    return r;
}

}  // namespace

void bind_trace_rays(py::module_& m) {
    m.def("trace_rays", &trace_rays_py, py::arg("session"), py::arg("origins"), py::arg("directions"),
          py::arg("wavelengths") = py::none(), py::arg("threads") = 0,
          "The sums of many rays' trees (core/trace_rays.h) as NumPy arrays; the GIL is released.");
}

}  // namespace refract::python
