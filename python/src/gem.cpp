// The round brilliant cut (geometry/gem/brilliant.h).
#include <pybind11/stl.h>

#include <cmath>
#include <functional>
#include <map>

#include <refract/experiments/gem_metrics.h>
#include <refract/geometry/error.h>
#include <refract/geometry/gem/brilliant.h>
#include "python/src/bindings.h"

namespace refract::python {

namespace {

py::dict proportions(const BrilliantProportions& p) {
    py::dict d;
    d["table"] = p.table;
    d["crown_angle"] = p.crown_angle;
    d["pavilion_angle"] = p.pavilion_angle;
    d["star"] = p.star;
    d["lower_half"] = p.lower_half;
    d["girdle"] = p.girdle;
    d["culet"] = p.culet;
    d["crown_height"] = p.crown_height;
    d["pavilion_depth"] = p.pavilion_depth;
    d["total_depth"] = p.total_depth;
    return d;
}

// The parameters by name, as BrilliantCut spells them.
using Setter = std::function<void(BrilliantCut&, double, const std::string&)>;
const std::map<std::string, Setter>& cut_parameters() {
    static const std::map<std::string, Setter> p = [] {
        std::map<std::string, Setter> m;
        auto real = [](double BrilliantCut::*f) { return [f](BrilliantCut& c, double v, const std::string&) { c.*f = v; }; };
        auto integer = [](int BrilliantCut::*f) {
            return [f](BrilliantCut& c, double v, const std::string& name) {
                if (!(std::floor(v) == v && std::abs(v) < 1e9))
                    throw InputError("cut_brilliant: " + name + " = " + format_value(v) + ": must be an integer");
                c.*f = static_cast<int>(v);
            };
        };
        m["table"] = real(&BrilliantCut::table);
        m["crown_angle"] = real(&BrilliantCut::crown_angle);
        m["pavilion_angle"] = real(&BrilliantCut::pavilion_angle);
        m["star"] = real(&BrilliantCut::star);
        m["lower_half"] = real(&BrilliantCut::lower_half);
        m["girdle"] = real(&BrilliantCut::girdle);
        m["culet"] = real(&BrilliantCut::culet);
        m["girdle_facets"] = integer(&BrilliantCut::girdle_facets);
        m["bruted_planes"] = integer(&BrilliantCut::bruted_planes);
        return m;
    }();
    return p;
}

py::dict cut_dict(const BrilliantCut& c) {
    py::dict d;
    d["table"] = c.table;
    d["crown_angle"] = c.crown_angle;
    d["pavilion_angle"] = c.pavilion_angle;
    d["star"] = c.star;
    d["lower_half"] = c.lower_half;
    d["girdle"] = c.girdle;
    d["culet"] = c.culet;
    d["girdle_facets"] = c.girdle_facets;
    d["bruted_planes"] = c.bruted_planes;
    return d;
}

// A preset (None: the defaults) with parameters by name over it.
BrilliantCut parse_cut(const py::object& preset, const py::dict& params) {
    BrilliantCut cut = preset.is_none() ? BrilliantCut{} : brilliant_preset(preset.cast<std::string>());
    for (const auto& kv : params) {
        const std::string name = py::str(kv.first);
        const auto it = cut_parameters().find(name);
        if (it == cut_parameters().end()) {
            std::string known;
            for (const auto& p : cut_parameters()) known += (known.empty() ? "" : ", ") + p.first;
            throw InputError("cut_brilliant: unknown parameter '" + name + "' (known: " + known + ")");
        }
        double v = 0;
        try {
            v = kv.second.cast<double>();
        } catch (const py::cast_error&) {
            throw InputError("cut_brilliant: " + name + ": must be a number");
        }
        it->second(cut, v, name);
    }
    return cut;
}

// experiments/gem_metrics.h: the metrics of one cut, with their errors (its field list), and the cut.
py::dict measure_cut(const py::object& preset, const py::dict& params, int rays, bool exact, const std::string& material,
                     std::uint64_t seed) {
    const BrilliantCut cut = parse_cut(preset, params);
    gem_metrics::MetricOptions o;
    o.rays = rays;
    o.exact_polarisation = exact;
    o.material = material;
    o.seed = seed;
    py::dict d = to_python(without_gil([&] { return gem_metrics::measure(build_brilliant(cut), o); }));
    d["cut"] = cut_dict(cut);
    return d;
}

py::dict cut_brilliant(const py::object& preset, const py::dict& params) {
    const BrilliantCut cut = parse_cut(preset, params);
    const Gem gem = without_gil([&] { return build_brilliant(cut); });
    const auto nv = static_cast<py::ssize_t>(gem.mesh.vertices.size());
    const auto nt = static_cast<py::ssize_t>(gem.mesh.triangles.size());
    const auto nf = static_cast<py::ssize_t>(gem.facets.size());
    std::vector<double> vertices, planes;
    std::vector<std::int64_t> triangles, triangle_facet;
    for (const auto& v : gem.mesh.vertices)
        for (int k = 0; k < 3; ++k) vertices.push_back(v[k]);
    for (py::ssize_t i = 0; i < nt; ++i) {
        for (int k = 0; k < 3; ++k) triangles.push_back(gem.mesh.triangles[static_cast<size_t>(i)][k]);
        triangle_facet.push_back(gem.triangle_facet[static_cast<size_t>(i)]);
    }
    py::list facets, labels;
    for (const GemFacet& f : gem.facets) {
        for (int k = 0; k < 3; ++k) planes.push_back(f.plane.normal[k]);
        planes.push_back(f.plane.offset);
        labels.append(f.label);
        py::dict fd;
        fd["label"] = f.label;
        fd["kind"] = facet_kind(f.label);
        fd["vertex_ids"] = f.vertex_ids;
        facets.append(fd);
    }
    py::dict counts;
    for (const auto& [kind, n] : facet_counts(gem)) counts[py::str(kind)] = n;
    py::dict d;
    d["vertices"] = to_numpy(vertices, {nv, 3});
    d["triangles"] = to_numpy(triangles, {nt, 3});
    d["triangle_facet"] = to_numpy(triangle_facet, {nt});
    d["planes"] = to_numpy(planes, {nf, 4});
    d["labels"] = labels;
    d["facets"] = facets;
    d["facet_counts"] = counts;
    d["measured"] = proportions(gem.measured);
    d["closed_form"] = proportions(closed_form_proportions(cut));
    d["cut"] = cut_dict(cut);
    d["girdle_description"] = girdle_description(cut);
    return d;
}

}  // namespace

void bind_gem(py::module_& m) {
    m.def("brilliant_presets", &brilliant_preset_names, "Named brilliant-cut presets.");
    m.def("_cut_brilliant", &cut_brilliant, py::arg("preset"), py::arg("params"));
    m.def("_gem_metrics", &measure_cut, py::arg("preset"), py::arg("params"), py::arg("rays"), py::arg("exact"),
          py::arg("material"), py::arg("seed"));
}

}  // namespace refract::python
