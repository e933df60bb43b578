// Gradient-index fields from Python (core/grin/grid.h): a NumPy array of samples written as
// an OpenVDB file, the form a scene's `"kind": "grid"` profile reads with "file" (and other
// volume tools read and write).
#include <array>
#include <cmath>
#include <string>

#include <refract/core/grin/grid.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include "python/src/bindings.h"

namespace refract::python {

namespace {

// values[i, j, k] (shape (n_x, n_y, n_z), along x, y, z) as the writer's samples, i fastest.
grin::GridSamples samples_of(const py::array_t<double, py::array::forcecast>& values, const py::handle& origin,
                             double spacing) {
    if (values.ndim() != 3)
        throw InputError("write_vdb: values must be a 3D array indexed [i, j, k] along x, y, z, not " +
                         std::to_string(values.ndim()) + "D");
    if (!(spacing > 0 && std::isfinite(spacing)))
        throw InputError("write_vdb: spacing " + format_value(spacing) + " must be a finite number > 0");
    grin::GridSamples s;
    for (int a = 0; a < 3; ++a) s.dims[a] = static_cast<int>(values.shape(a));
    grin::check_grid_size(values.shape(0), values.shape(1), values.shape(2), "write_vdb: values");
    s.origin = to_vec3(origin, "write_vdb: origin");
    s.spacing = grin::Vec3::Constant(spacing);
    s.values.resize(static_cast<size_t>(values.size()));
    const auto v = values.unchecked<3>();
    for (py::ssize_t k = 0; k < values.shape(2); ++k)
        for (py::ssize_t j = 0; j < values.shape(1); ++j)
            for (py::ssize_t i = 0; i < values.shape(0); ++i)
                s.values[static_cast<size_t>(i + values.shape(0) * (j + values.shape(1) * k))] = v(i, j, k);
    return s;
}

}  // namespace

void bind_grin(py::module_& m) {
    m.def(
            "write_vdb",
            [](const std::string& path, const py::array_t<double, py::array::forcecast>& values, const py::handle& origin,
               double spacing, const std::string& grid, const std::string& precision) {
                if (precision != "float" && precision != "double")
                    throw InputError("write_vdb: precision '" + clip_echo(precision) + "': expected float or double");
                grin::GridSamples s = samples_of(values, origin, spacing);
                without_gil([&] {
                    grin::write_vdb_grid(path, grid, s,
                                         precision == "double" ? grin::VdbPrecision::double_ : grin::VdbPrecision::single);
                });
            },
            py::arg("path"), py::arg("values"), py::arg("origin") = std::array<double, 3>{0, 0, 0},
            py::arg("spacing") = 1.0, py::arg("grid") = "field", py::arg("precision") = "float",
            "Writes values[i, j, k] (the sample at origin + (i, j, k)·spacing) as the OpenVDB grid `grid` "
            "of `path`, every voxel active: a float grid, or with precision='double' a double grid (an index "
            "grid's refractivity n − 1 ≈ 3e-4 keeps only about 3 digits as a float). A scene reads it with "
            "{\"kind\": \"grid\", \"file\": path, \"grid\": grid}. The file appears whole or not at all.");
}

}  // namespace refract::python
