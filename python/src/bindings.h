#pragma once
// Shared helpers of the Python module's translation units (python/src/): buffers to NumPy,
// long calls without the GIL, and C++ results to Python through their field lists.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <refract/core/fields.h>
#include <refract/core/image.h>
#include <refract/geometry/ray.h>

namespace refract::python {

namespace py = pybind11;

// A 3-vector from anything NumPy reads as three numbers; InputError naming `what` otherwise.
Vec3 to_vec3(const py::handle& o, const char* what);
inline py::tuple tuple3(const Vec3& v) { return py::make_tuple(v.x(), v.y(), v.z()); }
py::array_t<double> array3(const Vec3& v);

// ---- The one way a buffer becomes a NumPy array --------------------------------------------
// `data` (row-major) with `shape`: a copy, or with `owner` (an object keeping `data` alive,
// such as a capsule around the C++ result) a view of it without copying.
template <class T>
py::array_t<T> to_numpy(const std::vector<T>& data, const std::vector<py::ssize_t>& shape,
                        const py::handle& owner = py::handle()) {
    std::vector<py::ssize_t> strides(shape.size());
    py::ssize_t step = sizeof(T);
    for (size_t k = shape.size(); k-- > 0;) {
        strides[k] = step;
        step *= shape[k];
    }
    return py::array_t<T>(shape, strides, data.data(), owner);  // no owner: pybind11 copies
}
// An image: shape (height, width, 3), linear RGB.
inline py::array_t<double> to_numpy(const Image& img, const py::handle& owner = py::handle()) {
    return to_numpy(img.rgb, {static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width), 3}, owner);
}

// ---- The one way a long call runs without the GIL ------------------------------------------
// Calls f() with the GIL released and returns its result (C++ values only inside f).
template <class F>
decltype(auto) without_gil(F&& f) {
    py::gil_scoped_release nogil;
    return f();
}

// ---- C++ values to Python ------------------------------------------------------------------
// Numbers, bools and strings as themselves; a structure with a field list (core/fields.h) as
// a dict of its Python fields; vectors and std::arrays as lists (of pairs with string keys:
// a dict); C arrays, std::tuples and fixed Eigen vectors as tuples; an Image or an ArrayRef
// as a NumPy array; JSON as Python's json.loads reads it; an empty optional as None. A field
// marked `table` (a vector of rows) is one 2-D NumPy array of the rows' Python fields.
template <class T>
py::object to_python(const T& v);

namespace detail {

template <class T>
struct is_vector : std::false_type {};
template <class T, class A>
struct is_vector<std::vector<T, A>> : std::true_type {};
template <class T>
struct is_std_array : std::false_type {};
template <class T, size_t N>
struct is_std_array<std::array<T, N>> : std::true_type {};
template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};
template <class T>
struct is_tuple : std::false_type {};
template <class... T>
struct is_tuple<std::tuple<T...>> : std::true_type {};
template <class T>
struct is_keyed_list : std::false_type {};  // a vector of (string, value): a dict
template <class V, class A>
struct is_keyed_list<std::vector<std::pair<std::string, V>, A>> : std::true_type {};
template <class T>
struct is_fields_vector : std::false_type {};  // a vector of rows with a field list
template <class T, class A>
struct is_fields_vector<std::vector<T, A>> : std::bool_constant<has_fields_v<T>> {};
template <class T, class = void>
struct is_eigen_vector : std::false_type {};
template <class T>
struct is_eigen_vector<T, std::enable_if_t<std::is_base_of_v<Eigen::MatrixBase<T>, T>>>
    : std::bool_constant<T::ColsAtCompileTime == 1 && T::RowsAtCompileTime != Eigen::Dynamic> {};

// The rows' Python fields as one (rows × fields) array of doubles.
template <class Row>
py::array_t<double> table(const std::vector<Row>& rows) {
    size_t cols = 0;
    for_each_field<Row>([&](const auto& f) { cols += f.in_python ? 1 : 0; });
    std::vector<double> data;
    data.reserve(rows.size() * cols);
    for (const Row& r : rows)
        for_each_field(r, [&](const auto& f, const auto& v) {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_arithmetic_v<V>) {
                if (f.in_python) data.push_back(static_cast<double>(v));
            } else {
                throw std::logic_error(std::string("to_python: field '") + f.name + "' is not a number (table)");
            }
        });
    return to_numpy(data, {static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
}

}  // namespace detail

template <class T>
py::object to_python(const T& v) {
    using D = std::remove_cv_t<std::remove_reference_t<T>>;  // not decayed: C arrays stay arrays
    if constexpr (std::is_same_v<D, bool> || std::is_arithmetic_v<D> || std::is_same_v<D, std::string>) {
        return py::cast(v);
    } else if constexpr (std::is_convertible_v<D, const char*>) {
        return py::str(static_cast<const char*>(v));
    } else if constexpr (std::is_same_v<D, nlohmann::json>) {
        return py::module_::import("json").attr("loads")(v.dump());
    } else if constexpr (std::is_same_v<D, Image>) {
        return to_numpy(v);
    } else if constexpr (std::is_same_v<D, ArrayRef>) {
        std::vector<py::ssize_t> shape(v.shape.begin(), v.shape.end());
        return to_numpy(*v.data, shape);
    } else if constexpr (std::is_array_v<D>) {
        py::tuple t(std::extent_v<D>);
        for (size_t k = 0; k < std::extent_v<D>; ++k) t[k] = to_python(v[k]);
        return std::move(t);
    } else if constexpr (detail::is_tuple<D>::value) {
        return std::apply([](const auto&... x) { return py::object(py::make_tuple(to_python(x)...)); }, v);
    } else if constexpr (detail::is_eigen_vector<D>::value) {
        py::tuple t(static_cast<size_t>(v.size()));
        for (Eigen::Index k = 0; k < v.size(); ++k) t[static_cast<size_t>(k)] = py::float_(v[k]);
        return std::move(t);
    } else if constexpr (detail::is_optional<D>::value) {
        return v ? to_python(*v) : py::none();
    } else if constexpr (detail::is_keyed_list<D>::value) {
        py::dict d;
        for (const auto& [key, x] : v) d[py::str(key)] = to_python(x);
        return std::move(d);
    } else if constexpr (detail::is_vector<D>::value || detail::is_std_array<D>::value) {
        py::list l;
        for (const auto& x : v) l.append(to_python(x));
        return std::move(l);
    } else if constexpr (has_fields_v<D>) {
        py::dict d;
        for_each_field(v, [&](const auto& f, const auto& x) {
            if (!f.in_python) return;
            using X = std::decay_t<decltype(x)>;
            if constexpr (detail::is_fields_vector<X>::value) {
                if (f.as_table) {
                    d[f.name] = detail::table(x);
                    return;
                }
            }
            d[f.name] = to_python(x);
        });
        return std::move(d);
    } else {
        static_assert(has_fields_v<D>, "to_python: no conversion for this type (give it a field list)");
        return py::none();
    }
}

void bind_optics(py::module_& m);     // core/optics.h, core/spectrum/dispersion.h
void bind_gem(py::module_& m);        // geometry/gem/brilliant.h
void bind_experiments(py::module_& m);  // experiments/
void bind_commands(py::module_& m);     // farfield, measure, export-pov, validate, sweep
void bind_trace_rays(py::module_& m);   // core/trace_rays.h
void bind_grin(py::module_& m);        // core/grin/grid.h: write_vdb

}  // namespace refract::python
