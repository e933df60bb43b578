#include <refract/core/render.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/integrator.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/core/memory.h>
#include <refract/core/progress.h>
#include <refract/core/tracer.h>
#include <refract/geometry/error.h>
#include <refract/core/threads.h>

namespace refract {

namespace {

// The scene's settings that cannot be honoured, before any work: one line naming the field.
void validate(const Scene& scene) {
    const std::string& f = scene.source.empty() ? std::string("scene") : scene.source;
    if (scene.camera.width <= 0 || scene.camera.height <= 0)
        throw InputError(f + ": /camera: image size must be positive");
    for (size_t k = 0; k < scene.objects.size(); ++k)
        if (scene.objects[k].material < 0 || scene.objects[k].material >= static_cast<int>(scene.materials.size()))
            throw InputError(f + ": /objects/" + std::to_string(k) + "/material: no such material");
    const RenderSettings& s = scene.settings;
    CompatRules(s).validate(scene);
    validate_integrator(scene);
    const bool exact = polarisation_model(scene) == PolarisationModel::Exact;
    for (const Material& m : scene.materials)
        validate(m, MaterialCheck{f + ": material '" + clip_echo(m.name) + "'", exact,
                                  s.integrator == IntegratorKind::FresnelTree});
}

// The extra per-pixel images a render keeps are bounded (2^28 values, 2 GiB), and the
// spectral channels need the physical spectral pass with natural light: checked before
// any work.
void check_channels(const Scene& scene, const RenderOptions& opt) {
    const std::string f = scene.source.empty() ? std::string("scene") : scene.source;
    const RenderSettings& s = scene.settings;
    const double pixels = static_cast<double>(scene.camera.width) * scene.camera.height;
    constexpr double kMaxValues = 268435456.0;
    auto bound = [&](double per_pixel, const std::string& what) {
        if (per_pixel * pixels > kMaxValues)
            throw InputError(f + ": " + what + " of a " + std::to_string(scene.camera.width) + "x" +
                             std::to_string(scene.camera.height) + " image would hold " +
                             std::to_string(static_cast<long long>(per_pixel * pixels)) +
                             " values (at most 2^28): use a smaller image");
    };
    // The image (and the lost-energy image, 3 values too). The scene reader stops at 2^26
    // pixels; this bounds scenes built in code as well.
    bound(3, "/camera: the image");
    const bool exact = polarisation_model(scene) == PolarisationModel::Exact;
    if (exact) bound(14, "/render/polarisation: the Stokes, DoLP and AoLP images");
    if (opt.spectral_channels) {
        if (!s.spectral.enabled || s.compat == Compat::PovRay || exact)
            throw InputError(f + ": spectral channels need the spectral eye pass in the physical mode with natural light");
        const std::string where = f + ": /render/spectral";
        bound(static_cast<double>(spectrum::sample_wavelengths(s.spectral.sampling, where).size()), "the spectral channels");
    }
}

}  // namespace

StokesRGB render_pixel_stokes(const Scene& scene, int i, int j, RenderStats* stats) {
    validate(scene);
    check_memory(estimate_light_pass_memory(scene), 0, scene.source.empty() ? std::string("scene") : scene.source);
    SceneTracer tracer(scene);
    RenderStats local;
    std::optional<SpectralContext> ctx;
    std::shared_ptr<IlluminationMaps> maps;
    if (scene.settings.spectral.enabled) {
        ctx = SpectralContext::build(scene);
        if (scene.settings.light_pass.enabled) {
            maps = light_pass(scene, *ctx);
            ctx->maps = maps.get();
        }
    }
    const std::unique_ptr<Integrator> integrator = make_integrator(tracer, ctx ? &*ctx : nullptr);
    StokesRGB v = StokesRGB::Zero();
    if (polarisation_model(scene) == PolarisationModel::Exact) {
        LinearPolarisation lp{};
        v = integrator->pixel_stokes(i, j, local, lp);
    } else {
        v.row(0) = integrator->pixel(i, j, local, nullptr).transpose();
    }
    if (stats) stats->merge(local);
    return v;
}

Vec3 render_pixel(const Scene& scene, int i, int j, RenderStats* stats) {
    return render_pixel_stokes(scene, i, j, stats).row(0).transpose();
}

RenderResult render(const Scene& scene, const RenderOptions& opt) {
    // Spectral channels are natural light's: a scene that leaves the model to the default
    // is rendered with natural light for them (one that asks for exact is refused below).
    if (opt.spectral_channels && !scene.settings.requested_polarisation &&
        polarisation_model(scene) == PolarisationModel::Exact) {
        Scene natural = scene;
        natural.settings.requested_polarisation = PolarisationModel::Natural;
        return render(natural, opt);
    }
    validate(scene);
    check_channels(scene, opt);
    const auto cancelled = [&opt] { return opt.cancel && opt.cancel->load(std::memory_order_relaxed); };
    const auto t0 = std::chrono::steady_clock::now();
    const int threads = worker_threads(opt.threads);
    check_memory(estimate_render_memory(scene, opt, threads), opt.max_memory,
                 scene.source.empty() ? std::string("scene") : scene.source);
    SceneTracer tracer(scene, opt.trace);
    std::optional<SpectralContext> ctx;
    std::shared_ptr<const IlluminationMaps> maps = opt.maps;
    RenderStats light_stats;
    if (scene.settings.spectral.enabled) {
        ctx = SpectralContext::build(scene);
        if (scene.settings.light_pass.enabled) {
            if (!maps) {
                maps = light_pass(scene, *ctx, threads, opt.cancel, opt.trace);
                if (cancelled()) throw RenderCancelled();
                light_stats.light_seconds = maps->seconds;
            }
            light_stats.photons = maps->photons;
            light_stats.photon_segments = maps->segments;
            light_stats.deposits = maps->deposits;
            light_stats.facet_local = maps->facet_local;
            light_stats.facet_full = maps->facet_full;
            ctx->maps = maps.get();
        }
    }
    const SpectralContext* spectral = ctx ? &*ctx : nullptr;
    const std::unique_ptr<Integrator> integrator = make_integrator(tracer, spectral);
    const int W = scene.camera.width, H = scene.camera.height;
    RenderResult result{Image(W, H), {}, {}, {}, {}, std::nullopt};
    result.signed_colours = spectral && scene.settings.spectral.pipeline == spectrum::ColourPipeline::XyzSrgb;
    if (opt.lost_energy) result.lost.assign(3 * static_cast<size_t>(W) * H, 0.0);
    if (opt.spectral_channels) {
        result.wavelengths = spectral->wavelengths;
        result.spectral.assign(spectral->bands() * static_cast<size_t>(W) * H, 0.0);
    }
    const bool exact = tracer.exact();
    if (exact) {
        const size_t n = static_cast<size_t>(W) * H;
        result.polarisation = PolarisationImages{std::vector<double>(12 * n), std::vector<double>(n), std::vector<double>(n)};
    }
    constexpr int kTile = 16;
    const int tiles_x = (W + kTile - 1) / kTile, tiles_y = (H + kTile - 1) / kTile;
    std::vector<RenderStats> tile_stats(static_cast<size_t>(tiles_x) * tiles_y);
    const int total = tiles_x * tiles_y;
    Progress progress("render", "tiles", total, opt.progress);
    auto body = [&](const tbb::blocked_range2d<int>& r) {
        for (int ty = r.rows().begin(); ty != r.rows().end(); ++ty)
            for (int tx = r.cols().begin(); tx != r.cols().end(); ++tx) {
                if (cancelled()) return;
                RenderStats& tile = tile_stats[static_cast<size_t>(ty) * tiles_x + tx];
                for (int j = ty * kTile; j < std::min(H, (ty + 1) * kTile); ++j)
                    for (int i = tx * kTile; i < std::min(W, (tx + 1) * kTile); ++i) {
                        RenderStats st;  // this pixel's, for its lost weight
                        if (exact) {
                            LinearPolarisation lp{};
                            const StokesRGB sv = integrator->pixel_stokes(i, j, st, lp);
                            result.image.set(i, j, sv.row(0).transpose());
                            PolarisationImages& p = *result.polarisation;
                            const size_t px = static_cast<size_t>(j) * W + i;
                            for (int r = 0; r < 4; ++r)
                                for (int c = 0; c < 3; ++c) p.stokes[12 * px + 3 * r + c] = sv(r, c);
                            p.dolp[px] = lp.dolp;
                            p.aolp[px] = lp.aolp;
                        } else {
                            std::vector<double> bands(result.wavelengths.size(), 0.0);
                            result.image.set(i, j, integrator->pixel(i, j, st, opt.spectral_channels ? &bands : nullptr));
                            // Light at a wavelength is >= 0; the estimate (docs/scene-format.md,
                            // spectral channels) dips below only through RGB-weighted light-pass
                            // maps in a scene that is not colour-neutral: clipped as cie-rgb clips.
                            std::transform(bands.begin(), bands.end(),
                                           result.spectral.begin() +
                                               static_cast<std::ptrdiff_t>(bands.size() * (static_cast<size_t>(j) * W + i)),
                                           [](double b) { return std::fmax(b, 0.0); });
                        }
                        if (opt.lost_energy) {
                            const size_t px = 3 * (static_cast<size_t>(j) * W + i);
                            result.lost[px] = st.lost_depth / scene.settings.samples;
                            result.lost[px + 1] = st.lost_limits / scene.settings.samples;
                            result.lost[px + 2] = st.lost_threshold / scene.settings.samples;
                        }
                        tile.merge(st);
                    }
                progress.add(1);
            }
    };
    if (cancelled()) throw RenderCancelled();
    tbb::task_arena arena(threads);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 0, tiles_x), body); });
    progress.finish();
    if (cancelled()) throw RenderCancelled();
    for (const auto& st : tile_stats) result.stats.merge(st);
    result.stats.merge(light_stats);
    result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Finite input gives finite pixels (scene validation refuses what would overflow): a
    // non-finite one is refract's own error, reported with the pixel and never written.
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            if (!result.image.at(i, j).allFinite())
                throw std::runtime_error("internal error: " + (scene.source.empty() ? std::string("scene") : scene.source) +
                                         ": pixel (" + std::to_string(i) + ", " + std::to_string(j) +
                                         ") is not finite; please report it with the scene");
    // Colours of up to 1e30 each can still multiply past what an image file holds (a light
    // of 1e30 on a pigment of 1e30): bad input, known only now.
    const auto within_float = [&](const std::vector<double>& v, size_t per_pixel, const std::string& what) {
        for (size_t k = 0; k < v.size(); ++k)
            if (std::fabs(v[k]) > std::numeric_limits<float>::max())
                throw InputError((scene.source.empty() ? std::string("scene") : scene.source) + ": " + what + " (" +
                                 std::to_string(k / per_pixel % W) + ", " + std::to_string(k / per_pixel / W) + ") is " +
                                 format_value(v[k]) + ", past the largest value an image file holds (3.4e38): the "
                                 "scene's colours (each in [0, 1e30]) multiply beyond it");
    };
    within_float(result.image.rgb, 3, "pixel");
    if (!result.spectral.empty()) within_float(result.spectral, result.wavelengths.size(), "the spectral channels of pixel");
    if (result.polarisation) within_float(result.polarisation->stokes, 12, "the Stokes vector of pixel");
    return result;
}

}  // namespace refract
