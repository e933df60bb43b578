#pragma once
// CSV tables from a field list (core/fields.h): the columns of a row structure are its
// fields' CSV names in list order, its cells the values formatted by type — a double with
// the field's significant digits (or the shortest round-trip form), an integer in full, a
// bool as 1 or 0, a string as it is, an empty optional as an empty cell. An experiment
// declares Fields<Row> beside Row and writes `csv_table(rows)`; the same list gives the
// Python module its dict keys, so a column and a key cannot drift apart.
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <refract/core/fields.h>
#include <refract/experiments/plot.h>

namespace refract::experiments {

namespace field_csv_detail {

template <class V>
struct is_optional : std::false_type {};
template <class V>
struct is_optional<std::optional<V>> : std::true_type {};

template <class V>
std::string cell(const V& v, int significant) {
    using D = std::decay_t<V>;
    if constexpr (std::is_same_v<D, bool>) return v ? "1" : "0";
    else if constexpr (std::is_integral_v<D>) return std::to_string(v);
    else if constexpr (std::is_floating_point_v<D>) return significant > 0 ? fmt(v, significant) : fmt(v);
    else if constexpr (std::is_same_v<D, std::string>) return v;
    else if constexpr (std::is_convertible_v<D, const char*>) return std::string(v);
    else if constexpr (is_optional<D>::value) return v ? cell(*v, significant) : std::string();
    else {
        (void)v, (void)significant;
        throw std::logic_error("csv: a field without a CSV form (mark it python_only)");
    }
}

// Where each of `columns` is among T's CSV fields (all of them, in list order, when empty);
// std::logic_error naming a column T does not have.
template <class T>
std::vector<std::string> chosen(const std::vector<std::string>& columns) {
    std::vector<std::string> all;
    for_each_field<T>([&](const auto& f) {
        if (f.in_csv) all.push_back(f.csv_name());
    });
    if (columns.empty()) return all;
    for (const auto& c : columns) {
        bool known = false;
        for (const auto& a : all) known = known || a == c;
        if (!known) throw std::logic_error("csv: no column '" + c + "' in the field list");
    }
    return columns;
}

}  // namespace field_csv_detail

// The CSV columns of T (or `columns`, a selection in their own order).
template <class T>
std::vector<std::string> csv_header(const std::vector<std::string>& columns = {}) {
    return field_csv_detail::chosen<T>(columns);
}

// The cells of one row, in the order of csv_header<T>(columns).
template <class T>
std::vector<std::string> csv_cells(const T& row, const std::vector<std::string>& columns = {}) {
    std::vector<std::string> names, cells;
    for_each_field(row, [&](const auto& f, const auto& v) {
        if (!f.in_csv) return;
        names.push_back(f.csv_name());
        cells.push_back(field_csv_detail::cell(v, f.significant));
    });
    if (columns.empty()) return cells;
    std::vector<std::string> out;
    for (const auto& c : field_csv_detail::chosen<T>(columns))
        for (size_t k = 0; k < names.size(); ++k)
            if (names[k] == c) out.push_back(cells[k]);
    return out;
}

// A whole table of rows; `columns` as above.
template <class T>
Csv csv_table(const std::vector<T>& rows, const std::vector<std::string>& columns = {}) {
    Csv t{csv_header<T>(columns), {}};
    for (const T& r : rows) t.add(csv_cells(r, columns));
    return t;
}

// `a` followed by `b` (leading columns from an enclosing structure: csv_join({"case"}, csv_header<Row>())).
inline std::vector<std::string> csv_join(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

}  // namespace refract::experiments
