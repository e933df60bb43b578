#include <refract/core/integrators/fresnel_tree.h>

#include <refract/core/integrators/integrator.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/ray_tree.h>

namespace refract {

namespace {

// Where a branch ends: the light there, as the camera sees it along the branch, is added
// to the pixel.
template <class P>
struct PixelEnds {
    using Entry = TreeEntryT<P>;
    const SceneTracer& tracer;
    RenderStats& stats;
    decltype(seen(P{}, Vec3(), Vec3())) pixel;  // the shading accumulator, 0 at the start

    void background(const Entry& e) { pixel += seen(e.pol, e.weight, tracer.background(e.ray.dir)); }
    void leaf(const Entry& e, const SurfaceHit& h) { pixel += seen(e.pol, e.weight, tracer.local_light(h, stats)); }
    bool intercept(RayTreeWalkerT<P>&, const Entry&, const SurfaceHit&, typename RayTreeWalkerT<P>::List&) {
        return false;
    }
    double band_ior(const Entry&, const SurfaceHit&) const { return 0.0; }
    double wavelength(const Entry&) const { return 0.0; }
};

template <class P>
auto walk_pixel(const SceneTracer& tracer, const Ray& primary, const P& start, RenderStats& stats) {
    RayTreeWalkerT<P> walker(tracer, tree_limits(tracer.settings()), stats);
    PixelEnds<P> ends{tracer, stats, {}};
    ends.pixel.setZero();
    // ① the primary ray, weight 1.
    typename RayTreeWalkerT<P>::List list{TreeEntryT<P>{primary, Vec3(1, 1, 1)}};
    list.front().pol = start;
    walker.walk(list, ends);
    return ends.pixel;
}

}  // namespace

Vec3 fresnel_tree_radiance(const SceneTracer& tracer, const Ray& primary, RenderStats& stats) {
    return walk_pixel(tracer, primary, NaturalLight{}, stats);
}

StokesRGB fresnel_tree_stokes(const SceneTracer& tracer, const Ray& primary, const EyeStokes& start,
                              RenderStats& stats) {
    return walk_pixel(tracer, primary, start, stats);
}

namespace {

// Yasuda's tree per sample, the samples averaged; exact polarisation: Stokes vectors.
class FresnelTree : public Integrator {
public:
    using Integrator::Integrator;
    Vec3 pixel(int i, int j, RenderStats& stats, std::vector<double>*) const override {
        return sample_mean<Vec3>(i, j, stats, [&](const Ray& ray) { return fresnel_tree_radiance(tracer_, ray, stats); });
    }
    StokesRGB pixel_stokes(int i, int j, RenderStats& stats, LinearPolarisation& lp) const override {
        const StokesRGB sum = sample_mean<StokesRGB>(i, j, stats, [&](const Ray& ray) {
            return fresnel_tree_stokes(tracer_, ray, camera_stokes(tracer_.scene(), ray), stats);
        });
        lp = linear_polarisation(sum, tracer_.scene(), tracer_.camera_ray(i + 0.5, j + 0.5));
        return sum;
    }
};

}  // namespace

std::unique_ptr<Integrator> fresnel_tree_integrator(const SceneTracer& tracer, const SpectralContext* spectral) {
    if (spectral) return spectral_integrator(tracer, *spectral);
    return std::make_unique<FresnelTree>(tracer);
}

}  // namespace refract
