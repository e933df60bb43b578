// refract trace SCENE.json (--pixel X Y | --ray OX OY OZ DX DY DZ) [--wavelength NM] [--polarisation STATE] [-o FILE]
// Every segment of one ray's tree as JSON (core/trace_record.h).
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include <refract/core/scene_json.h>
#include <refract/core/trace_record.h>
#include <refract/geometry/error.h>
#include <refract/validation/files.h>

namespace trace_command {

struct TraceArgs {
    std::string scene, output;
    std::vector<int> pixel;
    std::vector<double> ray;
    double wavelength = 0;
    std::string polarisation;
};

nlohmann::json vec(const refract::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The record as JSON: the writing step, separate from the tracing.
nlohmann::json to_json(const refract::TraceRecord& r, const std::string& scene) {
    using nlohmann::json;
    json segs = json::array();
    for (const auto& s : r.segments) {
        json j = {{"id", s.id}, {"parent", s.parent}, {"depth", s.depth}, {"reflections", s.reflections},
                  {"transmissions", s.transmissions}, {"origin", vec(s.ray.origin)}, {"direction", vec(s.ray.dir)},
                  {"weight", vec(s.weight)}, {"event", s.event}, {"light", vec(s.light)}};
        if (s.hit) {
            j["length"] = s.length;
            j["point"] = vec(s.point);
            j["normal"] = vec(s.normal);
            j["object"] = s.object;
            j["facet"] = s.facet;
            if (!s.facet_label.empty()) j["facet_label"] = s.facet_label;
            j["entering"] = s.entering;
            if (!s.path.empty()) {
                json pts = json::array();
                for (const auto& x : s.path) pts.push_back(vec(x));
                j["path"] = pts;
            }
            if (s.eta > 0) {
                j["eta"] = s.eta;
                j["cos_i"] = s.cos_i;
                j["cos_t"] = s.cos_t;
                j["Rs"] = s.Rs;
                j["Rp"] = s.Rp;
            }
            if (s.event != "diffuse" && s.event != "emissive") j["R"] = s.R;
        }
        if (s.polarised) {
            j["stokes"] = {s.stokes[0], s.stokes[1], s.stokes[2], s.stokes[3]};
            j["stokes_x"] = vec(s.stokes_x);
        }
        if (s.wave != refract::biref::Wave::Isotropic) {
            j["wave"] = s.wave == refract::biref::Wave::Ordinary ? "o" : "e";
            if (s.index > 0) {
                j["index"] = s.index;
                j["wave_normal"] = vec(s.wave_normal);
            }
        }
        segs.push_back(j);
    }
    json out = {{"scene", scene}, {"segments", segs}, {"radiance", vec(r.radiance)}};
    out["wavelength_nm"] = r.wavelength_nm > 0 ? json(r.wavelength_nm) : json(nullptr);
    return out;
}

refract::cli::Registrar reg{15, [](CLI::App& app) {
    auto a = std::make_shared<TraceArgs>();
    auto* sub = app.add_subcommand("trace", "Record every segment of one ray's tree (a pixel's or a given ray) as JSON");
    sub->add_option("scene", a->scene, "Scene file (JSON)")->required();
    auto* px = sub->add_option("--pixel", a->pixel, "Pixel X Y (its centre)")->expected(2);
    auto* ry = sub->add_option("--ray", a->ray, "Ray origin and direction: OX OY OZ DX DY DZ")->expected(6);
    px->excludes(ry);
    sub->add_option("--wavelength", a->wavelength, "Trace at one wavelength in nm (dispersive materials take their index there)");
    sub->add_option("--polarisation", a->polarisation,
                    "Trace the ray as light of this state, with exact polarisation and each segment's Stokes vector: "
                    "unpolarised, linear, circular, or a light's polarisation object as JSON, e.g. "
                    "'{\"type\": \"linear\", \"angle\": 30}' (docs/scene-format.md)");
    sub->add_option("-o,--output", a->output, "Write the JSON here instead of standard output");
    sub->callback([a] {
        using namespace refract;
        if (a->pixel.empty() && a->ray.empty()) throw InputError("trace: give --pixel X Y or --ray OX OY OZ DX DY DZ");
        std::optional<PolarisationState> pol;
        if (!a->polarisation.empty()) {
            nlohmann::json j;
            if (a->polarisation.front() == '{') {
                try {
                    j = nlohmann::json::parse(a->polarisation);
                } catch (const nlohmann::json::exception&) {
                    throw InputError("trace: --polarisation: not a JSON object: " + clip_echo(a->polarisation));
                }
            } else {
                j = {{"type", a->polarisation}};
            }
            pol = parse_polarisation_state(j, "--polarisation");
        }
        const Scene scene = load_scene(a->scene);
        const PolarisationState* p = pol ? &*pol : nullptr;
        const TraceRecord r = a->pixel.empty()
                                  ? trace_ray(scene, Ray{Vec3(a->ray[0], a->ray[1], a->ray[2]), Vec3(a->ray[3], a->ray[4], a->ray[5])},
                                              a->wavelength, p)
                                  : trace_pixel(scene, a->pixel[0], a->pixel[1], a->wavelength, p);
        const std::string text = to_json(r, a->scene).dump(1) + "\n";
        if (a->output.empty()) std::cout << text;
        else validation::write_text_file(a->output, text);
    });
}};

}  // namespace trace_command
using namespace trace_command;
