#pragma once
// One field list per result structure. A specialisation of Fields<T> names every value of
// T that leaves the program, once:
//
//   template <> struct Fields<Row> {
//       static auto list() {
//           return std::make_tuple(field("angle_deg", &Row::angle_deg),
//                                  field("R", &Row::R).digits(6),
//                                  derived<Row>("error", [](const Row& r) { return r.S - r.R; }).csv_only());
//       }
//   };
//
// and everything that writes T out walks that list: the CSV tables of the experiments
// (experiments/fields_csv.h: header and cells in list order), the Python module's dicts
// (python/src/bindings.h: to_python), RenderStats::merge and summary (core/render_stats.h).
// A field is a member or a value derived from T; it has one name, the Python key and the CSV
// column unless `csv` renames the column, and says where it goes (CSV, Python, or both), how
// many significant digits its CSV cell has, and how RenderStats::merge combines it.
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace refract {

template <class T>
struct Fields;  // specialised per structure: static auto list() -> std::tuple<Field<T, …>…>

// A field's value that is an array of doubles (row-major, `shape`), such as a map per pixel:
// a NumPy array in Python. `data` points into the structure the field belongs to.
struct ArrayRef {
    const std::vector<double>* data = nullptr;
    std::vector<std::ptrdiff_t> shape;
};

// How RenderStats::merge (or any merge written with merge_fields) combines a field.
enum class MergeRule { Sum, Max, None };

template <class T, class Get>
struct Field {
    using Owner = T;
    const char* name;               // the Python key, and the CSV column unless `column` is set
    Get get;                        // a pointer to a member of T, or a function of const T&
    const char* column = nullptr;   // the CSV column's name (nullptr: `name`)
    int significant = 0;            // CSV: significant digits (0: the shortest round-trip form)
    bool in_csv = true, in_python = true;
    bool as_table = false;          // Python: a vector of rows as one 2-D NumPy array (not a CSV cell)
    MergeRule merge_rule = MergeRule::Sum;
    const char* label = nullptr;    // a line of text output (RenderStats::summary); nullptr: none
    bool when_nonzero = false;      // that line only when the value is not 0

    static constexpr bool is_member = std::is_member_object_pointer_v<Get>;

    decltype(auto) value(const T& t) const {
        if constexpr (is_member) return (t.*get);
        else return get(t);
    }
    const char* csv_name() const { return column ? column : name; }

    // Builders, each returning a copy: field("x", &T::x).csv("x_deg").digits(4).
    constexpr Field csv(const char* c) const { return with([&](Field& f) { f.column = c; }); }
    constexpr Field digits(int d) const { return with([&](Field& f) { f.significant = d; }); }
    constexpr Field csv_only() const { return with([](Field& f) { f.in_python = false; }); }
    constexpr Field python_only() const { return with([](Field& f) { f.in_csv = false; }); }
    constexpr Field table() const { return with([](Field& f) { f.as_table = true, f.in_csv = false; }); }
    constexpr Field merge(MergeRule m) const { return with([&](Field& f) { f.merge_rule = m; }); }
    constexpr Field text(const char* l, bool only_nonzero = false) const {
        return with([&](Field& f) { f.label = l, f.when_nonzero = only_nonzero; });
    }

private:
    template <class F>
    constexpr Field with(F&& change) const {
        Field f = *this;
        change(f);
        return f;
    }
};

// A member of T.
template <class T, class M>
constexpr Field<T, M T::*> field(const char* name, M T::*member) {
    return Field<T, M T::*>{name, member};
}
// A value computed from T (a pure function of it: a ratio, a difference, a name).
template <class T, class F>
constexpr Field<T, F> derived(const char* name, F f) {
    return Field<T, F>{name, f};
}

// True when Fields<T> is specialised.
template <class T, class = void>
struct has_fields : std::false_type {};
template <class T>
struct has_fields<T, std::void_t<decltype(Fields<T>::list())>> : std::true_type {};
template <class T>
inline constexpr bool has_fields_v = has_fields<T>::value;

// Calls f(field) for every field of T, in list order.
template <class T, class F>
void for_each_field(F&& f) {
    std::apply([&](const auto&... fs) { (f(fs), ...); }, Fields<T>::list());
}

// Calls f(field, value) for every field of t, in list order.
template <class T, class F>
void for_each_field(const T& t, F&& f) {
    for_each_field<T>([&](const auto& fd) { f(fd, fd.value(t)); });
}

// Merges o into t by each member field's rule (derived fields are left alone).
template <class T>
void merge_fields(T& t, const T& o) {
    for_each_field<T>([&](const auto& fd) {
        using Fd = std::decay_t<decltype(fd)>;
        if constexpr (Fd::is_member) {
            auto& a = t.*fd.get;
            const auto& b = o.*fd.get;
            switch (fd.merge_rule) {
                case MergeRule::Sum: a += b; break;
                case MergeRule::Max: a = a < b ? b : a; break;
                case MergeRule::None: break;
            }
        }
    });
}

}  // namespace refract
