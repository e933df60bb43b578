#pragma once
// The render's compatibility policy, chosen once per render from render.compat: the
// physical rules (the default), or POV-Ray 3.7's (core/compat/povray.h), so that refract's
// numbers can be checked against POV-Ray's images. Everything that differs between the two
// is a member here — the hits' window, the order that decides exact ties, where absorption
// is applied, the dielectric's node, the stochastic integrator's sampled branch, the
// checker pattern, shadow rays through glass, the spectral split — and the physics files
// ask the policy instead of testing the mode.
#include <string>
#include <vector>

#include <refract/core/interaction.h>
#include <refract/core/material.h>
#include <refract/core/compat/povray.h>
#include <refract/core/random.h>

namespace refract {

struct Scene;
struct Object;
struct RenderSettings;
struct RenderStats;
struct SpectralContext;
class HitSearch;
enum class Compat;

class CompatRules {
public:
    explicit CompatRules(const RenderSettings& s);

    Compat mode() const { return mode_; }
    // The mode's name in scene files ("physical", "povray"), and the mode of a name (empty:
    // none).
    static const char* name(Compat c);
    static std::optional<Compat> from_name(const std::string& name);

    // Hits are kept for t_min() <= t < t_max() (physical: beyond kEpsilon, none far away).
    double t_min() const { return t_min_; }
    double t_max() const { return t_max_; }
    static constexpr double kEpsilon = 1e-6;  // secondary rays ignore hits closer than this

    // The order in which objects are searched, which decides exact ties (a hit replaces
    // the best only when strictly nearer): the scene's, or POV-Ray's exported order (opaque
    // objects first, then the transparent ones), where a gem's facet lying in the floor
    // plane shades the floor.
    std::vector<const Object*> search_order(const Scene& scene) const;

    // Whether a ray enters or leaves a dielectric mesh as the outward normal says
    // (physical), or as POV-Ray's interior list says (POV-Ray: the list only changes at
    // refractions, so a crossing closer than t_min() is not in it; HitSearch applies it).
    bool interior_lists() const { return pov_; }
    // Whether triangle meshes are met in double (physical) or as POV-Ray's mesh2 meets
    // them, from single-precision vertices, normals and plane distances (povray::Mesh).
    bool single_precision_meshes() const { return pov_; }

    // Whether a segment inside an absorbing dielectric is attenuated by Beer–Lambert where
    // it ends (physical), or the node fades its refracted light instead (POV-Ray).
    bool absorbs_segments() const { return !pov_; }

    // A dielectric's node on one ray or a packet, at a node `at` of material m.
    template <class V>
    NodeBranches<V> dielectric(const material::Dielectric& m, const NodeAt<V>& at, const V& filter,
                               bool split) const {
        if (pov_) return povray::dielectric_branches(m, at, adc_, split);
        return physical_branches(dielectric_node(at.dir, at.normal, at.eta, m.reflectance,
                                                 typename V::Scalar(m.constant_reflectivity), filter, at.on));
    }
    // The index a dielectric's `ior` refracts with (POV-Ray: single precision).
    double nominal_index(double ior) const { return pov_ ? povray::stored_index(ior) : ior; }

    // The dielectric interaction of one ray (Mueller matrices with exact polarisation).
    Interaction dielectric(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray,
                           const InteractionContext& c) const;
    // RTIOW's dielectric sampled (stochastic integrator): physical, reflection with
    // probability R, else refraction, the chosen direction alone computed; POV-Ray's node
    // sampled (sample_branch).
    Scatter sample_dielectric(const material::Dielectric& m, const SurfaceHit& h, const Ray& ray,
                              const InteractionContext& c, Rng& rng) const;

    // Beer–Lambert over the segment that ended at h from inside an absorbing material
    // (physical mode): exp(−α t) per channel, at `wavelength_nm` (all channels alike) or,
    // when 0, with the material's RGB coefficients. Empty when nothing is absorbed (POV-Ray
    // fades in its node instead). A segment lies in the material of the object it leaves,
    // so absorbing solids must not hold other objects.
    std::optional<Vec3> segment_absorption(const SurfaceHit& h, double wavelength_nm) const;

    // The light a shadow ray carries from a lit point to a light: physical, a refracting
    // surface blocks (that light arrives as a caustic, which only a light pass computes);
    // POV-Ray, the ray goes straight on through transparent objects, each crossing
    // multiplying by its filter colour (clear glass casts no shadow).
    Vec3 light_transmittance(const HitSearch& search, const Vec3& from, const Vec3& to, RenderStats& stats) const;

    // The pigment's colour at a point (a 3D checker's cell parity).
    Vec3 pigment(const Pigment& p, const Vec3& point) const;

    // The bands a spectral pass splits into (wavelengths, weights, which materials split and
    // into which bands, the clip and the shortcut): the sampled wavelengths (physical), or
    // POV-Ray's bands per dispersion_samples.
    void spectral_bands(const Scene& scene, SpectralContext& c) const;
    // A dispersive dielectric's index at λ (nm): its dispersion's (POV-Ray's law relative to
    // its ior, stored in single precision in the compat mode).
    double dielectric_index(const material::Dielectric& m, double nm) const;

    // Render settings that the mode cannot honour: one line naming the field, as InputError.
    void validate(const Scene& scene) const;

private:
    Compat mode_;
    bool pov_;
    double adc_;
    double t_min_, t_max_;
};

}  // namespace refract
