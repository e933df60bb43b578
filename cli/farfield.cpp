// refract farfield SCENE -o DIR [--binning sphere|axis] [--axis X Y Z] [--photons N] ...
// The far-field detector (core/far_field.h): the power leaving the scene's transparent
// objects binned by direction, per wavelength, event class and Stokes component.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include <refract/core/far_field.h>
#include <refract/core/scene_json.h>
#include <refract/experiments/common.h>
#include <refract/experiments/far_field_output.h>
#include <refract/experiments/plot.h>
#include <refract/geometry/error.h>

namespace farfield_command {

struct FarFieldArgs {
    std::string scene, output, binning = "sphere";
    std::vector<double> axis, reference, wavelengths;
    int bins = 180, azimuth_bins = 360, polar_bins = 180, classes = 5, threads = 0;
    std::uint64_t max_memory = 0;
    std::uint64_t photons = 1000000, seed = 7;
    bool no_plot = false;
    bool no_lanes = false;
};

// The detector's run and its files, once the output directory is checked.
void run(const FarFieldArgs* a, const refract::Scene& scene, const refract::experiments::FarFieldFiles& files) {
    using namespace refract;
    FarFieldSettings s;
    s.binning = a->binning == "axis" ? FarFieldSettings::Binning::Axis : FarFieldSettings::Binning::Sphere;
    if (!a->axis.empty()) s.axis = Vec3(a->axis[0], a->axis[1], a->axis[2]);
    if (!a->reference.empty()) s.reference = Vec3(a->reference[0], a->reference[1], a->reference[2]);
    s.angle_bins = a->bins;
    s.azimuth_bins = a->azimuth_bins;
    s.polar_bins = a->polar_bins;
    s.classes = a->classes;
    s.photons = a->photons;
    s.seed = a->seed;
    s.max_memory = a->max_memory;
    s.wavelengths = a->wavelengths;
    s.trace.packets = !a->no_lanes;
    s.progress = refract::cli::stderr_is_terminal();
    const FarFieldResult r = far_field(scene, s, a->threads);
    const auto written = experiments::write_far_field(a->output, experiments::far_field_tables(r), "far field of " + a->scene, files);
    std::cout << "far field: " << r.photons << " photons, " << r.segments << " segments, " << r.wavelengths.size()
              << " wavelength(s), " << experiments::fmt(r.seconds, 3) << " s\n";
    for (size_t w = 0; w < r.wavelengths.size(); ++w) {
        const int k = static_cast<int>(w);
        // Absorbed: inside the objects (Beer–Lambert, the rest of the balance) and where a
        // path ends on a diffuse surface or an emitter.
        if (w == 0 || w + 1 == r.wavelengths.size())
            std::cout << "  " << experiments::fmt(r.wavelengths[w]) << " nm: scattered " << experiments::fmt(r.scattered(k), 6)
                      << ", unscattered " << experiments::fmt(r.unscattered[w], 6) << ", absorbed "
                      << experiments::fmt(r.absorbed_inside(k) + r.absorbed[w], 6) << " (inside the objects "
                      << experiments::fmt(r.absorbed_inside(k), 6) << ", on surfaces " << experiments::fmt(r.absorbed[w], 6)
                      << "), dropped by the limits " << experiments::fmt(r.dropped[w], 6) << "\n";
    }
    for (const auto& f : written) std::cout << "  " << a->output << "/" << f << "\n";
}

refract::cli::Registrar reg{17, [](CLI::App& app) {
    auto a = std::make_shared<FarFieldArgs>();
    auto* sub = app.add_subcommand("farfield",
                                   "Far-field detector: the power leaving the transparent objects, binned by direction "
                                   "(CSV, EXR map and plot)");
    sub->add_option("scene", a->scene, "Scene file (JSON); its lights (point, directional, beam) shoot the photons")->required();
    sub->add_option("-o,--output", a->output, "Output directory")->required();
    sub->add_option("--binning", a->binning, "sphere (equal solid angle, azimuth x cos theta) or axis (angle to the axis)")
        ->check(CLI::IsMember({"sphere", "axis"}));
    sub->add_option("--axis", a->axis, "The axis X Y Z (default 0 0 1; for a beam's scattering angle: its direction)")->expected(3);
    sub->add_option("--reference", a->reference, "Sphere binning: the direction of azimuth 0 (default 1 0 0)")->expected(3);
    sub->add_option("--bins", a->bins, "Axis binning: bins in 0-180 degrees (180)")->check(CLI::Range(1, 1 << 20));
    sub->add_option("--azimuth-bins", a->azimuth_bins, "Sphere binning: azimuth bins (360)")->check(CLI::Range(1, 1 << 14));
    sub->add_option("--polar-bins", a->polar_bins, "Sphere binning: polar bins, uniform in cos theta (180)")->check(CLI::Range(1, 1 << 14));
    sub->add_option("--classes", a->classes, "Event classes: reflected, 0, 1, ... internal reflections, the last gathering the rest (5)")
        ->check(CLI::Range(2, 64));
    sub->add_option("--photons", a->photons, "Photons per light and wavelength, 1 to 2^31 (1000000)")
        ->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 31));  // a negative count refused, not wrapped
    sub->add_option("--wavelengths", a->wavelengths,
                    "Wavelengths in nm (default: the scene's sampling when a material is dispersive or absorbing, else 550)");
    sub->add_option("--seed", a->seed, "Random seed (7)")->check(CLI::NonNegativeNumber);
    refract::cli::add_max_memory(sub, a->max_memory);
    sub->add_option("--threads", a->threads, "Worker threads (0: all cores); the result does not depend on it")
        ->check(refract::cli::thread_range());
    sub->add_flag("--no-plot", a->no_plot, "Skip the gnuplot figure");
    sub->add_flag("--no-lanes", a->no_lanes,
                  "Walk each wavelength of a photon alone, not in packets of 8 (the same result, slower; for comparison)");
    sub->callback([a] {
        using namespace refract;
        const Scene scene = load_scene(a->scene);
        if (scene.lights.empty() && scene.background.kind != Background::Kind::Environment)
            throw InputError(a->scene + ": /lights: the far-field detector needs a light or an environment background");
        experiments::FarFieldFiles files;
        files.plot = !a->no_plot;
        const bool created = experiments::ensure_dir(a->output);  // before the work, with the files it will hold
        try {
            experiments::check_far_field_outputs(a->output, files);
            run(a.get(), scene, files);
        } catch (const InputError&) {
            std::error_code ec;
            if (created) std::filesystem::remove_all(a->output, ec);  // refused: nothing left
            throw;
        }
    });
}};

}  // namespace farfield_command
using namespace farfield_command;
