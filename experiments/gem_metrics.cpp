// The gem metrics of one round brilliant (docs/gem-metrics.md): eye rays from a distant
// viewer above the table, traced through the exact cut at the options' wavelengths, and
// the light their trees return under each observation set-up (experiments/gem_observation.h).
#include <refract/experiments/gem_metrics.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include <refract/core/random.h>
#include <refract/experiments/gem_detectors.h>
#include <refract/experiments/gem_observation.h>
#include <refract/experiments/gem_observer.h>
#include <refract/geometry/error.h>

namespace refract::gem_metrics {

namespace {

// The eye ray of sample i of a metric (stream): the viewer's direction v drawn uniformly
// over the cap of directions within `cone_deg` of the axis; a distant viewer, so parallel
// rays along −v through points drawn uniformly over the stone's outline seen from v
// (rejection from the disk of radius 1.1·frame across v about the stone's centre).
struct EyeSample {
    Ray ray;
    Vec3 viewer;  // unit, from the stone towards the eye
    Rng rng;      // the sample's stream, continued (spot-layout rotations)
};
// `turn` (the stone tilted, world = turn · stone frame): the viewer drawn in the world and
// the ray built in the stone's frame, so that it meets the tilted stone.
EyeSample eye_sample(const Shape& stone, std::uint64_t seed, std::uint64_t stream, int i, double cone_deg, double frame,
                     const Eigen::Matrix3d* turn = nullptr) {
    Rng rng(seed, stream, static_cast<std::uint64_t>(i));
    Vec3 v(0, 0, 1);
    if (cone_deg > 0) {
        const double c = 1 - rng.uniform() * (1 - std::cos(cone_deg * M_PI / 180)), phi = 2 * M_PI * rng.uniform();
        const double sn = std::sqrt(std::max(0.0, 1 - c * c));
        v = Vec3(sn * std::cos(phi), sn * std::sin(phi), c);
    }
    if (turn) v = turn->transpose() * v;
    const Vec3 a = (std::abs(v.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(v).normalized(), b = v.cross(a);
    for (;;) {
        const double r = 1.1 * frame * std::sqrt(rng.uniform()), phi = 2 * M_PI * rng.uniform();
        const Ray ray{r * std::cos(phi) * a + r * std::sin(phi) * b + 4.0 * frame * v, -v};
        if (intersect(stone, ray, 0.0, 1e30)) return {ray, v, rng};
    }
}

const Vec3 kUp(0, 0, 1);

// The golden-ratio sequence frac(0.5 + i/φ): a low-discrepancy point of [0, 1) per ray.
double golden(int i) {
    const double g = 0.5 + 0.6180339887498949 * i;
    return g - std::floor(g);
}

// Exits of one trace as spot probes (only those near a ring of spots) with their weights.
struct Probes {
    std::vector<std::pair<double, SpotProbe>> items;
    void fill(const std::vector<GemTracer::Exit>& exits, const Eigen::Matrix3d& to_world) {
        items.clear();
        for (const auto& e : exits) {
            if (e.weight <= 0) continue;
            const SpotProbe p(to_world * e.dir, kUp);
            if (p.near_ring()) items.emplace_back(e.weight, p);
        }
    }
    double radiance(double rotation_deg) const {
        double s = 0;
        for (const auto& [w, p] : items) s += w * p.lit(rotation_deg);
        return s;
    }
};

// The layout rotations of one pixel: K stratified angles over the full turn.
std::vector<double> rotations(Rng& rng, int K) {
    const double u = rng.uniform();
    std::vector<double> r;
    for (int k = 0; k < K; ++k) r.push_back(360.0 * (k + u) / K);
    return r;
}

}  // namespace

GemMetrics measure(const Gem& gem, const MetricOptions& o) {
    GemTracer t(gem, o);  // validates the options
    const Shape stone = tracing_shape(gem);  // what an eye ray must meet
    GemMetrics m;
    const int W = t.bands();
    std::vector<GemTracer::Exit> exits;

    // Light return, leakage and the energy balance: one band per eye ray, drawn by
    // luminance along a golden-ratio sequence (every prefix of the rays spreads evenly).
    const int N = o.rays;
    const Observer& observer = find_observer(o.observer);
    const double cos_head = head_cosine(observer);
    m.observer = observer.name;
    Mean lr, leak;
    Detectors detectors(gem);
    // The further face-up models on the same rays.
    std::vector<double> cos_also;
    for (const std::string& name : o.also_observers) {
        const Observer& x = find_observer(name);
        if (traces_own_rays(x))
            throw InputError("also_observers: '" + name +
                             "' traces eye rays of its own (tilts, two eyes); only one-eye face-up models can share the rays");
        cos_also.push_back(head_cosine(x));
    }
    const size_t NA = cos_also.size();
    std::vector<Mean> lr_also(NA);
    std::vector<Detectors> det_also(NA, Detectors(gem));
    std::vector<double> ret_also(NA), head_also(NA);
    std::vector<double> by_kind(t.kinds().size(), 0.0);
    for (int i = 0; i < N; ++i) {
        const int band = t.band_by_luminance(golden(i));
        const EyeSample eye = eye_sample(stone, o.seed, 1, i, o.viewer_cone_deg, o.frame);
        const auto tr = t.trace(eye.ray, band, exits);
        double returned = 0, pav = 0, girdle = 0, head = 0;
        std::fill(ret_also.begin(), ret_also.end(), 0.0);
        std::fill(head_also.begin(), head_also.end(), 0.0);
        for (const auto& e : exits) {
            if (e.kind < 0) {
                m.balance.missed += e.weight;
                continue;
            }
            by_kind[static_cast<size_t>(e.kind)] += e.weight;
            switch (aset_zone(e.dir, eye.viewer)) {
                case AsetZone::Red: m.aset.red += e.weight; break;
                case AsetZone::Green: m.aset.green += e.weight; break;
                case AsetZone::Blue: m.aset.blue += e.weight; break;
                case AsetZone::Leak: m.aset.white += e.weight; break;
            }
            switch (t.kind_regions()[static_cast<size_t>(e.kind)]) {
                case Region::Crown:
                    m.balance.crown += e.weight;
                    returned += e.weight * observer_radiance(e.dir, kUp, eye.viewer, cos_head);
                    head += e.dir.dot(kUp) > 0.0 && e.dir.dot(eye.viewer) >= cos_head ? e.weight : 0.0;
                    for (size_t j = 0; j < NA; ++j) {
                        ret_also[j] += e.weight * observer_radiance(e.dir, kUp, eye.viewer, cos_also[j]);
                        head_also[j] += e.dir.dot(kUp) > 0.0 && e.dir.dot(eye.viewer) >= cos_also[j] ? e.weight : 0.0;
                    }
                    break;
                case Region::Girdle:
                    m.balance.girdle += e.weight;
                    girdle += e.weight;
                    break;
                case Region::Pavilion:
                    m.balance.pavilion += e.weight;
                    pav += e.weight;
                    break;
            }
        }
        m.balance.lost += tr.lost;
        detectors.add(eye.ray, head, girdle);  // face-up (gem_detectors.h)
        for (size_t j = 0; j < NA; ++j) {
            lr_also[j].add(ret_also[j]);
            det_also[j].add(eye.ray, head_also[j], girdle);
        }
        // The observer's further tilts of the stone (gem_observer.h): the same light return
        // from an eye sample of its own per tilt, the lights and the eye fixed in the world.
        for (size_t k = 1; k < observer.tilts_deg.size(); ++k) {
            Rng axis_rng(o.seed, 16 + k, static_cast<std::uint64_t>(i));
            const double az = 2 * M_PI * axis_rng.uniform();
            const Eigen::Matrix3d turn =
                Eigen::AngleAxisd(observer.tilts_deg[k] * M_PI / 180.0, Vec3(std::cos(az), std::sin(az), 0))
                    .toRotationMatrix();
            const Vec3 up = turn.transpose() * kUp;  // the world's vertical in the stone's frame
            const EyeSample te = eye_sample(stone, o.seed, 8 + k, i, o.viewer_cone_deg, o.frame, &turn);
            t.trace(te.ray, band, exits);
            for (const auto& e : exits)
                if (e.kind >= 0 && t.kind_regions()[static_cast<size_t>(e.kind)] == Region::Crown)
                    returned += e.weight * observer_radiance(e.dir, up, te.viewer, cos_head);
        }
        // Two eyes (gem_observer.h): the light return of an eye ray from each eye, each eye's
        // sample of its own (streams 24, 25), the eyes side by side along the stone's x axis;
        // the cyclopean ray above gives the rest (leakage, balance, detectors).
        if (observer.eye_half_angle_deg > 0) {
            returned = 0;
            const double half = observer.eye_half_angle_deg * M_PI / 180.0;
            for (const int side : {-1, 1}) {
                // eye_sample turns the drawn viewer v by turnᵀ: the eye at R(side·half)·v.
                const Eigen::Matrix3d turn = Eigen::AngleAxisd(-side * half, Vec3::UnitY()).toRotationMatrix();
                const EyeSample eye_k = eye_sample(stone, o.seed, side < 0 ? 24 : 25, i, o.viewer_cone_deg, o.frame, &turn);
                const Vec3 other = Eigen::AngleAxisd(-2.0 * side * half, Vec3::UnitY()) * eye_k.viewer;
                t.trace(eye_k.ray, band, exits);
                for (const auto& e : exits)
                    if (e.kind >= 0 && t.kind_regions()[static_cast<size_t>(e.kind)] == Region::Crown)
                        returned += 0.5 * e.weight * observer_radiance(e.dir, kUp, eye_k.viewer, other, cos_head);
            }
        }
        lr.add(returned / static_cast<double>(observer.tilts_deg.size()));
        leak.add(pav);
    }
    // The nail-head's central zone: eye rays of its own (stream 4), centre_share as many as
    // the light return's (a quarter by default), each viewer drawn as theirs, face-up
    // (gem_detectors.h).
    const int NC = std::max(4, static_cast<int>(N * o.centre_share));  // N / 4 by default
    if (detectors.has_table())
        for (int i = 0; i < NC; ++i) {
            Rng rng(o.seed, 4, static_cast<std::uint64_t>(i));
            Vec3 v(0, 0, 1);
            if (o.viewer_cone_deg > 0) {
                const double c = 1 - rng.uniform() * (1 - std::cos(o.viewer_cone_deg * M_PI / 180)),
                             phi = 2 * M_PI * rng.uniform();
                const double sn = std::sqrt(std::max(0.0, 1 - c * c));
                v = Vec3(sn * std::cos(phi), sn * std::sin(phi), c);
            }
            const double u1 = rng.uniform(), u2 = rng.uniform();
            t.trace(detectors.central_ray(v, u1, u2, 4.0 * o.frame), t.band_by_luminance(golden(i)), exits);
            double head = 0;
            std::fill(head_also.begin(), head_also.end(), 0.0);
            for (const auto& e : exits) {
                if (e.kind < 0 || t.kind_regions()[static_cast<size_t>(e.kind)] != Region::Crown || e.dir.dot(kUp) <= 0.0)
                    continue;
                head += e.dir.dot(v) >= cos_head ? e.weight : 0.0;
                for (size_t j = 0; j < NA; ++j) head_also[j] += e.dir.dot(v) >= cos_also[j] ? e.weight : 0.0;
            }
            detectors.add_centre(head);
            for (size_t j = 0; j < NA; ++j) det_also[j].add_centre(head_also[j]);
        }
    m.light_return = lr.metric();
    m.leakage = leak.metric();
    m.nail_head = detectors.nail_head();
    m.fish_eye = detectors.fish_eye();
    m.obstruction = detectors.obstruction();
    for (size_t j = 0; j < NA; ++j)
        m.also.push_back({o.also_observers[j], lr_also[j].metric(), det_also[j].nail_head(), det_also[j].obstruction()});
    for (double* v : {&m.balance.crown, &m.balance.girdle, &m.balance.pavilion, &m.balance.lost, &m.balance.missed,
                      &m.aset.red, &m.aset.green, &m.aset.blue, &m.aset.white})
        *v /= N;
    for (const std::string& kind : leakage_kinds()) {
        const auto it = std::find(t.kinds().begin(), t.kinds().end(), kind);
        const double v = it == t.kinds().end() ? 0.0 : by_kind[static_cast<size_t>(it - t.kinds().begin())];
        m.leakage_by_kind.emplace_back(kind, v / N);
    }
    m.light_return_rays = N;

    // Fire: each pixel's eye ray at every band under spot lighting; the pixel's dispersed
    // coloured light is the luminance of its returned spectrum above the spectrum's
    // minimum (the white part), averaged over turns of the spot layout.
    const int K = o.spot_rotations;
    const int NF = std::max(4, N / o.fire_divisor);
    Mean fire;
    std::vector<Probes> band_probes(static_cast<size_t>(W));
    std::vector<double> r(static_cast<size_t>(W)), coloured(static_cast<size_t>(W), 0.0);
    const Eigen::Matrix3d none = Eigen::Matrix3d::Identity();
    for (int i = 0; i < NF; ++i) {
        EyeSample eye = eye_sample(stone, o.seed, 2, i, o.viewer_cone_deg, o.frame);
        for (int b = 0; b < W; ++b) {
            t.trace(eye.ray, b, exits);
            band_probes[static_cast<size_t>(b)].fill(exits, none);
        }
        double pixel = 0;
        for (const double rot : rotations(eye.rng, K)) {
            for (int b = 0; b < W; ++b) r[static_cast<size_t>(b)] = band_probes[static_cast<size_t>(b)].radiance(rot);
            const double lo = *std::min_element(r.begin(), r.end());
            double c = 0;
            for (int b = 0; b < W; ++b) {
                c += t.luminance_weight(b) * (r[static_cast<size_t>(b)] - lo);
                coloured[static_cast<size_t>(b)] += r[static_cast<size_t>(b)] - lo;
            }
            pixel += c / W;
        }
        fire.add(pixel / K);
    }
    m.fire = fire.metric();
    m.fire_pixels = NF;
    for (int b = 0; b < W; ++b)
        m.fire_spectrum.emplace_back(t.wavelength(b), coloured[static_cast<size_t>(b)] / (static_cast<double>(NF) * K));

    // Scintillation: a pixel's luminance under spot lighting changes as the stone tilts by
    // tilt_deg about x and about y; the mean absolute change of the two, averaged over
    // turns of the spot layout.
    const int NS = std::max(4, N / o.scintillation_divisor);
    const double a = o.tilt_deg * M_PI / 180.0;
    const std::array<Eigen::Matrix3d, 3> tilts{none, Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(),
                                               Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix()};
    std::array<Probes, 3> tilt_probes;
    Mean scint;
    for (int i = 0; i < NS; ++i) {
        EyeSample eye = eye_sample(stone, o.seed, 3, i, o.viewer_cone_deg, o.frame);
        const int band = t.band_by_luminance(golden(i));
        for (size_t k = 0; k < 3; ++k) {
            // The stone turned by tilts[k], viewer and lights fixed: in the stone's frame the
            // eye ray turns back, and its exits turn forward into the world.
            const Ray in_gem{tilts[k].transpose() * eye.ray.origin, tilts[k].transpose() * eye.ray.dir};
            t.trace(in_gem, band, exits);
            tilt_probes[k].fill(exits, tilts[k]);
        }
        double pixel = 0;
        for (const double rot : rotations(eye.rng, K)) {
            const double i0 = tilt_probes[0].radiance(rot);
            pixel += 0.5 * (std::abs(tilt_probes[1].radiance(rot) - i0) + std::abs(tilt_probes[2].radiance(rot) - i0));
        }
        scint.add(pixel / K);
    }
    m.scintillation = scint.metric();
    m.scintillation_pixels = NS;
    return m;
}

}  // namespace refract::gem_metrics
