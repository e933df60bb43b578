#include <refract/experiments/ohtsuka1998_maps.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include <refract/core/illumination_map.h>
#include <refract/core/integrators/spectral.h>
#include <refract/core/light_pass.h>
#include <refract/experiments/common.h>

namespace refract::experiments::ohtsuka1998 {

namespace {

constexpr int kFloor = 0;  // the scene's first object

struct Run {
    std::shared_ptr<const IlluminationMaps> maps;
    double seconds = 0;
    const IlluminationMap& floor() const { return *maps->by_object[kFloor]; }
};

// Light passes by (element size, photons, seed), each run once.
class Runs {
public:
    Runs(const SceneParams& base, int threads) : base_(base), threads_(threads) {}

    void add(double element, std::uint64_t photons, std::uint64_t seed, std::shared_ptr<const IlluminationMaps> maps) {
        Run r;
        r.seconds = maps->seconds;
        r.maps = std::move(maps);
        runs_.emplace(std::make_tuple(element, photons, seed), std::move(r));
    }

    const Run& get(double element, std::uint64_t photons, std::uint64_t seed) {
        const auto key = std::make_tuple(element, photons, seed);
        const auto it = runs_.find(key);
        if (it != runs_.end()) return it->second;
        SceneParams p = base_;
        p.element_size = element;
        p.photons = photons;
        p.seed = seed;
        const Scene s = scene_from_json(scene_json(p), "map-study");
        const SpectralContext ctx = SpectralContext::build(s);
        Run r;
        r.maps = light_pass(s, ctx, threads_);
        r.seconds = r.maps->seconds;
        traced += photons;
        return runs_.emplace(key, std::move(r)).first->second;
    }

    std::uint64_t traced = 0;

private:
    SceneParams base_;
    int threads_;
    std::map<std::tuple<double, std::uint64_t, std::uint64_t>, Run> runs_;
};

Vec3 at(const IlluminationMap& m, const Vec3& p, MapFilter f) {
    Hit h;
    h.point = p;
    return m.value(h, f);
}

// The comparison grid and the reference's values there.
struct Reference {
    std::vector<Vec3> points, value;  // value: (R1 + R2)/2
    double norm2 = 0;                 // Σ|E_ref|²
    double noise = 0;                 // σ_ref
};

Reference make_reference(const IlluminationMap& r1, const IlluminationMap& r2) {
    Reference ref;
    const int n = r1.cells();
    double diff2 = 0;
    for (int j = 0; j < 2 * n; ++j)
        for (int i = 0; i < 2 * n; ++i) {
            const Vec3 p = r1.grid_point(0.5 * i + 0.25, 0.5 * j + 0.25);
            const Vec3 a = at(r1, p, MapFilter::Bilinear), b = at(r2, p, MapFilter::Bilinear);
            ref.points.push_back(p);
            ref.value.push_back(0.5 * (a + b));
            ref.norm2 += ref.value.back().squaredNorm();
            diff2 += (a - b).squaredNorm();
        }
    ref.noise = std::sqrt(diff2 / 4 / ref.norm2);
    return ref;
}

MapError measure(const Reference& ref, const IlluminationMap& a, const IlluminationMap& b, MapFilter f) {
    double ea = 0, dab = 0, emean = 0;
    for (size_t k = 0; k < ref.points.size(); ++k) {
        const Vec3 va = at(a, ref.points[k], f), vb = at(b, ref.points[k], f);
        ea += (va - ref.value[k]).squaredNorm();
        dab += (va - vb).squaredNorm();
        emean += (0.5 * (va + vb) - ref.value[k]).squaredNorm();
    }
    MapError e;
    e.error = std::sqrt(ea / ref.norm2);
    const double noise2 = dab / 2 / ref.norm2;
    e.noise = std::sqrt(noise2);
    e.bias = std::sqrt(std::fmax(0.0, emean / ref.norm2 - noise2 / 2 - ref.noise * ref.noise));
    return e;
}

double deposits_per_element(const Run& r) {
    const IlluminationMap& m = r.floor();
    int lit = 0;
    for (const Vec3& v : m.irradiance) lit += v.squaredNorm() > 0 ? 1 : 0;
    return lit ? static_cast<double>(r.maps->deposits) / lit : 0.0;
}

void add_rows(std::vector<MapStudyRow>& rows, const Reference& ref, Runs& runs, const MapStudyPlan& plan,
              double element, std::uint64_t photons) {
    const Run& a = runs.get(element, photons, plan.seeds[0]);
    const Run& b = runs.get(element, photons, plan.seeds[1]);
    for (const MapFilter f : {MapFilter::Box, MapFilter::Bilinear}) {
        MapStudyRow row;
        row.element_size = element;
        row.photons = photons;
        row.filter = f;
        row.elements = a.floor().elements();
        row.deposits_per_element = deposits_per_element(a);
        row.e = measure(ref, a.floor(), b.floor(), f);
        row.light_s = a.seconds;
        rows.push_back(row);
    }
}

}  // namespace

MapStudies run_map_studies(const SceneParams& base, const MapStudyPlan& plan, int threads,
                           std::shared_ptr<const IlluminationMaps> known) {
    const auto t0 = std::chrono::steady_clock::now();
    Runs runs(base, threads);
    if (known) runs.add(base.element_size, base.photons, base.seed, std::move(known));
    MapStudies st;
    st.reference_element = plan.reference_element;
    st.reference_photons = 2 * plan.reference_photons;
    const Run& r1 = runs.get(plan.reference_element, plan.reference_photons, plan.reference_seeds[0]);
    const Run& r2 = runs.get(plan.reference_element, plan.reference_photons, plan.reference_seeds[1]);
    st.reference_light_s = r1.seconds + r2.seconds;
    const Reference ref = make_reference(r1.floor(), r2.floor());
    st.reference_noise = ref.noise;
    for (const std::uint64_t n : plan.photons) add_rows(st.by_photons, ref, runs, plan, plan.photon_element, n);
    for (const double h : plan.elements) {
        const double scale = (plan.density_element / h) * (plan.density_element / h);
        const auto n = static_cast<std::uint64_t>(std::llround(static_cast<double>(plan.density_photons) * scale));
        add_rows(st.by_element, ref, runs, plan, h, n);
    }
    st.photons_traced = runs.traced;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return st;
}

}  // namespace refract::experiments::ohtsuka1998
