#pragma once
// The integrators as one abstraction: what a render asks of one — the light of a pixel
// (its samples averaged and finished), its per-wavelength light, its Stokes vectors under
// exact polarisation — chosen once per render from render.integrator and the spectral pass
// (render.spectral, on when a material is dispersive), with every combination it cannot
// honour refused by one line naming the setting, never replaced by another.
//
// Adding an integrator: core/integrators/NAME.cpp (a subclass of Integrator and its
// factory), its value in IntegratorKind (core/scene.h), and its row in the table of
// core/integrators/integrator.cpp (name, factory, what it supports).
#include <memory>
#include <string>
#include <vector>

#include <refract/core/polarisation_state.h>
#include <refract/core/random.h>
#include <refract/core/tracer.h>

namespace refract {

struct SpectralContext;

class Integrator {
public:
    explicit Integrator(const SceneTracer& tracer) : tracer_(tracer) {}
    virtual ~Integrator() = default;

    // The light of pixel (i, j): its samples averaged and finished. `bands` (the spectral
    // pass's wavelengths, when asked for): each wavelength's light, the samples averaged.
    virtual Vec3 pixel(int i, int j, RenderStats& stats, std::vector<double>* bands) const = 0;
    // Exact polarisation: the Stokes vectors of pixel (i, j) per colour channel, the samples
    // averaged, S0 finished as the image is; `lp` from the sum of the channels before that
    // finish. Only the integrators whose table row says so.
    virtual StokesRGB pixel_stokes(int i, int j, RenderStats& stats, LinearPolarisation& lp) const;

protected:
    // The primary ray of sample k of pixel (i, j): through its centre, or jittered with the
    // sample's own random stream `rng` (which a stochastic integrator then continues).
    Ray sample_ray(int i, int j, int k, Rng& rng) const;
    // The mean over pixel (i, j)'s samples of `light(ray)` (T: Vec3 or StokesRGB), each
    // sample's primary ray counted, the sum in sample order divided by their number.
    template <class T, class Light>
    T sample_mean(int i, int j, RenderStats& stats, Light&& light) const {
        const int n = tracer_.settings().samples;
        T sum = T::Zero();
        for (int k = 0; k < n; ++k) {
            Rng rng;
            const Ray ray = sample_ray(i, j, k, rng);
            ++stats.primary_rays;
            sum += light(ray);
        }
        return T(sum / n);
    }
    const SceneTracer& tracer_;
};

// The integrator of the tracer's scene (render.integrator; the spectral pass when
// `spectral` is given), after validate_integrator.
std::unique_ptr<Integrator> make_integrator(const SceneTracer& tracer, const SpectralContext* spectral);
// Throws InputError, one line naming the setting, for a combination of integrator, spectral
// pass and polarisation that cannot be honoured.
void validate_integrator(const Scene& scene);
// The polarisation model a render of `scene` uses (docs/polarisation.md): render.polarisation
// when the scene gives it; else exact in the physical mode wherever it is supported (an
// integrator whose table row carries Stokes vectors: the fresnel-tree and the spectral eye
// pass; every material able to pass it: carries_stokes), natural light elsewhere (compat
// "povray", POV-Ray's model; Whitted, stochastic; a non-Fresnel reflectance).
PolarisationModel polarisation_model(const Scene& scene);
// The integrators' names in scene files, in the table's order; the kind of a name.
std::vector<std::string> integrator_names();
std::optional<IntegratorKind> integrator_of(const std::string& name);
const char* integrator_name(IntegratorKind kind);

// The factories of the table (one per integrator file).
std::unique_ptr<Integrator> whitted_integrator(const SceneTracer& tracer, const SpectralContext* spectral);
std::unique_ptr<Integrator> fresnel_tree_integrator(const SceneTracer& tracer, const SpectralContext* spectral);
std::unique_ptr<Integrator> stochastic_integrator(const SceneTracer& tracer, const SpectralContext* spectral);
// The spectral eye pass (core/integrators/spectral.h) under the tree integrators' rules.
std::unique_ptr<Integrator> spectral_integrator(const SceneTracer& tracer, const SpectralContext& ctx);

}  // namespace refract
