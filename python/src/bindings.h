#pragma once
// Shared helpers of the Python module's translation units (python/src/).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "geometry/ray.h"

namespace refract::python {

namespace py = pybind11;

// A 3-vector from anything NumPy reads as three numbers; InputError naming `what` otherwise.
Vec3 to_vec3(const py::handle& o, const char* what);
inline py::tuple tuple3(const Vec3& v) { return py::make_tuple(v.x(), v.y(), v.z()); }
py::array_t<double> array3(const Vec3& v);

void bind_optics(py::module_& m);     // core/optics.h, core/spectrum/dispersion.h
void bind_gem(py::module_& m);        // geometry/gem/brilliant.h
void bind_experiments(py::module_& m);  // experiments/

}  // namespace refract::python
