// grin: the air (mirages, the setting sun, astronomical refraction) and the integrator's
// convergence (experiments/grin.h). Every ray through core/grin's advance().
#include <refract/experiments/grin.h>

#include <cmath>
#include <functional>

#include <refract/core/grin/air_index.h>
#include <refract/core/grin/atmosphere.h>
#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/grin/refraction_integral.h>
#include <refract/experiments/common.h>

namespace refract::experiments::grin_media {

namespace g = refract::grin;
using g::Vec3;

namespace {
constexpr double kArcmin = kDeg / 60.0;
constexpr double kArcsec = kDeg / 3600.0;
constexpr double kR = g::kEarthRadius_m;
constexpr double kTop = 150e3;        // m: the top of the air for the sky's rays
constexpr double kAirTol = 1e-13;     // relative to coordinates of 6 371 km: 0.6 µm a step
constexpr double kMirageTol = 1e-12;  // 6 µm a step, along rays of at most 25 km
constexpr double kSunSemidiameter_arcsec = 959.63;  // at 1 au (IAU 2015 nominal solar radius)

// ---- mirages: the Earth's centre at (0, −R, 0), the eye above the origin, +x ahead, +y up.

const Vec3 kCentre(0, -kR, 0);
double height(const Vec3& x) { return (x - kCentre).norm() - kR; }
double along_ground(const Vec3& x) { return kR * std::atan2(x.x(), x.y() + kR); }

struct MirageSpec {
    double T0, dT, hs, eye, D, e_lo, e_hi;
};

MirageSpec mirage_spec(bool inferior) {
    // Hot road: 30 °C air, the asphalt's layer 20 K hotter with an e-folding height of
    // 0.2 m (the atmosphere's surface layer), an eye at 1.5 m, an object 600 m away.
    // Cold sea: 5 °C at the sea, an inversion of ΔT centred at height hs (a logistic step
    // 2 m wide, up to 1.25 K/m, past the 0.11 K/m that bends rays with the Earth), an eye at
    // 3 m, a ship 25 km away.
    if (inferior) return {303.15, 20.0, 0.2, 1.5, 600.0, -0.6, 0.1};
    return {278.15, 10.0, 20.0, 3.0, 25000.0, -0.15, 0.35};
}

// The cold sea's air: T(h) = T₀ − 6.5 K/km · h + ΔT / (1 + exp(−(h − h_i)/w)), the pressure
// by hydrostatic equilibrium (dp/dh = −p g₀ M₀ / (R* T), the 1976 standard's constants),
// the index Ciddor's (core/grin/air_index.h), tabulated over 0–500 m as a spherically
// symmetric profile about the Earth's centre (a natural cubic spline, TabulatedRadial).
g::Profile inversion_air(const MirageSpec& m, double dT, double lambda, const std::string& where) {
    const double w = 2.0;
    auto T = [&](double h) { return m.T0 - 0.0065 * h + dT / (1 + std::exp(-(h - m.hs) / w)); };
    std::vector<double> r, n;
    double h_prev = 0, log_p = std::log(101325.0);
    for (double h = 0; h <= 500.0 + 1e-9; h += (h < 60 ? 0.25 : 5.0)) {
        const int sub = 20;  // the trapezoid rule on 1/T between the nodes
        for (int k = 0; k < sub; ++k) {
            const double a = h_prev + (h - h_prev) * k / sub, b = h_prev + (h - h_prev) * (k + 1) / sub;
            log_p -= g::kStandardGravity * g::kStandardAirMolarMass / g::kStandardGasConstant * 0.5 *
                     (1 / T(a) + 1 / T(b)) * (b - a);
        }
        h_prev = h;
        g::AirState s;
        s.temperature_K = T(h);
        s.pressure_Pa = std::exp(log_p);
        r.push_back(kR + h);
        n.push_back(g::ciddor_index(lambda, s));
    }
    return g::tabulated_radial(kCentre, r, n, where);
}

}  // namespace

SeaAir sea_air(double lambda_um) {
    const MirageSpec m = mirage_spec(false);
    const g::Profile p = inversion_air(m, m.dT, lambda_um, "grin superior mirage");
    const auto& t = std::get<g::TabulatedRadial>(p);
    return SeaAir{kCentre, t.r, t.n, m.eye, m.D, m.dT, m.hs};
}

namespace {

// The first point where the ray from (x, d) meets the ground sphere, by tangent planes: the
// ray advanced to the plane tangent at the last estimate, three times.
Vec3 ground_point(const g::Profile& air, Vec3 estimate, const Vec3& x, const Vec3& d, double lambda) {
    for (int k = 0; k < 3; ++k) {
        const Vec3 up = (estimate - kCentre).normalized();
        const g::Region above = g::HalfSpace{-up, -up.dot(kCentre + kR * up)};
        g::Settings s;
        s.abs_tol = s.rel_tol = kMirageTol;
        s.max_steps = 20000;
        const g::Result r = g::advance(air, above, x, d, lambda, s);
        if (r.status != g::Status::left_region) break;
        estimate = r.exit_point;
    }
    return estimate;
}

// One ray from the eye at `elevation` to the radial plane at the object's distance or the ground.
MirageRay mirage_ray(const g::Profile& air, const MirageSpec& m, double elevation_deg, double lambda,
                     std::vector<PathPoint>* paths, int id) {
    const double th = m.D / kR;
    const Vec3 n(std::cos(th), -std::sin(th), 0);
    const g::Region before = g::HalfSpace{n, n.dot(kCentre)};
    const Vec3 eye(0, m.eye, 0), d(std::cos(elevation_deg * kDeg), std::sin(elevation_deg * kDeg), 0);
    g::Settings s;
    s.abs_tol = s.rel_tol = kMirageTol;
    s.record_path = true;
    const g::Result r = g::advance(air, before, eye, d, lambda, s);
    MirageRay out;
    out.elevation_deg = elevation_deg;
    size_t end = r.path.size();
    for (size_t i = 1; i < r.path.size(); ++i)
        if (height(r.path[i].x) < 0) {
            end = i;
            break;
        }
    Vec3 last = r.exit_point;
    if (end < r.path.size()) {
        out.hits_ground = true;
        last = ground_point(air, r.path[end].x, r.path[end - 1].x, r.path[end - 1].dir, lambda);
        out.ground_distance = along_ground(last);
        out.height_at_object = NAN;
    } else {
        out.height_at_object = height(r.exit_point);
    }
    if (paths) {
        for (size_t i = 0; i < end; ++i) paths->push_back({id, along_ground(r.path[i].x), height(r.path[i].x)});
        if (end < r.path.size() || r.path.empty() || (r.path.back().x - last).norm() > 0)
            paths->push_back({id, along_ground(last), std::fmax(height(last), 0.0)});
    }
    return out;
}

// The monotonic runs of height at D against elevation over consecutive rays that reach D.
void find_branches(MirageStudy& st) {
    MirageBranch b;
    int dir = 0;
    bool open = false;
    auto close = [&] {
        if (open && b.elevation_hi_deg > b.elevation_lo_deg) st.branches.push_back(b);
        open = false;
    };
    for (const MirageRay& a : st.rays) {
        if (a.hits_ground) {
            close();
            continue;
        }
        if (open) {
            const double dh = a.height_at_object - b.height_hi;
            const int s = dh > 0 ? 1 : (dh < 0 ? -1 : 0);
            if (dir != 0 && s != 0 && s != dir) {  // a fold: the last ray ends one run and starts the next
                close();
                b = {b.elevation_hi_deg, b.elevation_hi_deg, b.height_hi, b.height_hi};
                open = true;
            }
            if (s != 0) dir = s;
            b.elevation_hi_deg = a.elevation_deg;
            b.height_hi = a.height_at_object;
            continue;
        }
        b = {a.elevation_deg, a.elevation_deg, a.height_at_object, a.height_at_object};
        open = true;
        dir = 0;
    }
    close();
}

double lowest(const std::vector<MirageRay>& rays) {
    double m = NAN;
    for (const MirageRay& r : rays)
        if (!r.hits_ground && !(r.height_at_object >= m)) m = r.height_at_object;
    return m;
}

// ---- the sky: the observer at (0, R, 0) on the ground, the air to 150 km.

// The angle the ray from the observer at apparent altitude `alt` turns by to the top of the air.
double traced_refraction(const g::Profile& air, double alt, double lambda) {
    const g::Region top = g::Sphere{Vec3::Zero(), kR + kTop};
    const Vec3 d0(std::cos(alt), std::sin(alt), 0.0);
    g::Settings s;
    s.abs_tol = s.rel_tol = kAirTol;
    const g::Result r = g::advance(air, top, Vec3(0.0, kR, 0.0), d0, lambda, s);
    return std::atan2(d0.cross(r.exit_dir).norm(), d0.dot(r.exit_dir));
}

// The apparent altitude whose true altitude a − R(a) is `true_alt` (secant method from `guess`).
double apparent_of(const std::function<double(double)>& R, double true_alt, double guess) {
    double a0 = guess, f0 = a0 - R(a0) - true_alt;
    double a1 = guess + 1e-4, f1 = a1 - R(a1) - true_alt;
    for (int k = 0; k < 40 && std::abs(f1) > 1e-13; ++k) {
        const double a2 = a1 - f1 * (a1 - a0) / (f1 - f0);
        a0 = a1, f0 = f1;
        a1 = a2, f1 = a1 - R(a1) - true_alt;
    }
    return a1;
}

// Vertical and horizontal diameters of the sun whose lower limb is seen at `lower` (rad).
void flattening(const std::function<double(double)>& R, double lower, double S, double& upper, double& vertical,
                double& horizontal) {
    const double t_lo = lower - R(lower);
    upper = apparent_of(R, t_lo + 2 * S, lower + 2 * S);
    vertical = upper - lower;
    const double t_c = t_lo + S, a_c = apparent_of(R, t_c, lower + S);
    horizontal = 2 * S * std::cos(a_c) / std::cos(t_c);  // the same azimuths, raised to a_c
}
}  // namespace

MirageStudy mirage_study(bool inferior, bool quick) {
    const MirageSpec m = mirage_spec(inferior);
    MirageStudy st;
    st.name = inferior ? "inferior" : "superior";
    st.sea_level_temperature_K = m.T0;
    st.delta_T = m.dT;
    st.surface_height = m.hs;
    st.eye_height = m.eye;
    st.distance = m.D;
    const double lambda = 0.55;
    const std::string where = "grin " + st.name + " mirage";
    g::Profile air, standard;
    if (inferior) {
        g::AtmosphereSpec spec;
        spec.sea_level_temperature_K = m.T0;
        spec.surface_delta_T_K = m.dT;
        spec.surface_height_m = m.hs;
        g::AtmosphereSpec plain = spec;
        plain.surface_delta_T_K = 0;
        air = g::EarthAtmosphere{kCentre, g::Atmosphere(spec, where)};
        standard = g::EarthAtmosphere{kCentre, g::Atmosphere(plain, where)};
    } else {
        air = inversion_air(m, m.dT, lambda, where);
        standard = inversion_air(m, 0.0, lambda, where);
    }
    const int n = quick ? 24 : 160, every = quick ? 3 : 8;
    for (int i = 0; i <= n; ++i) {
        const double e = m.e_lo + (m.e_hi - m.e_lo) * i / n;
        st.rays.push_back(mirage_ray(air, m, e, lambda, i % every == 0 ? &st.paths : nullptr, i / every));
        st.standard_rays.push_back(mirage_ray(standard, m, e, lambda, nullptr, i));
    }
    find_branches(st);
    st.ground_onset_deg = NAN;
    for (const MirageRay& r : st.rays)
        if (r.hits_ground && !(r.elevation_deg <= st.ground_onset_deg)) st.ground_onset_deg = r.elevation_deg;
    st.lowest_seen = lowest(st.rays);
    st.lowest_seen_standard = lowest(st.standard_rays);
    return st;
}

SunStudy sun_study(bool quick) {
    SunStudy st;
    st.semidiameter_arcmin = kSunSemidiameter_arcsec / 60.0;
    const double S = kSunSemidiameter_arcsec * kArcsec;
    g::Profile air = g::EarthAtmosphere{};  // the standard atmosphere, 15 °C, 101 325 Pa, dry
    const g::Atmosphere& atm = std::get<g::EarthAtmosphere>(air).air;
    const std::function<double(double)> traced = [&](double a) { return traced_refraction(air, std::fmax(a, 0.0), 0.55); };
    const std::function<double(double)> bennett = [&](double a) {
        return g::bennett_refraction_arcmin(std::fmax(a, 0.0) / kDeg, 101325.0, 288.15) * kArcmin;
    };
    const std::vector<double> lows = quick ? std::vector<double>{0, 1, 5} : std::vector<double>{0, 0.5, 1, 2, 3, 4, 5};
    for (double lo : lows) {
        SunRow row;
        row.lower_apparent_deg = lo;
        double up, v, h;
        flattening(traced, lo * kDeg, S, up, v, h);
        row.upper_apparent_deg = up / kDeg;
        row.vertical_arcmin = v / kArcmin;
        row.horizontal_arcmin = h / kArcmin;
        row.ratio = v / h;
        flattening(bennett, lo * kDeg, S, up, v, h);
        row.ratio_bennett = v / h;
        st.rows.push_back(row);
    }
    const std::vector<double> alts = quick ? std::vector<double>{0, 5} : std::vector<double>{0, 0.5, 1, 2, 5, 10};
    for (double a : alts) {
        LimbRow l;
        l.apparent_deg = a;
        l.traced_arcsec = (traced_refraction(air, a * kDeg, 0.52) - traced_refraction(air, a * kDeg, 0.65)) / kArcsec;
        l.integral_arcsec =
            (g::refraction_integral(atm, 0.52, a * kDeg) - g::refraction_integral(atm, 0.65, a * kDeg)) / kArcsec;
        st.limbs.push_back(l);
    }
    return st;
}

RefractionStudy refraction_study(bool quick) {
    RefractionStudy st;
    g::AtmosphereSpec spec;  // Bennett's conditions: 10 °C, 101.0 kPa at sea level, dry
    spec.sea_level_temperature_K = 283.15;
    spec.sea_level_pressure_Pa = 101000.0;
    g::Profile air = g::EarthAtmosphere{Vec3::Zero(), g::Atmosphere(spec, "grin refraction")};
    const g::Atmosphere& atm = std::get<g::EarthAtmosphere>(air).air;
    const std::vector<double> alts =
        quick ? std::vector<double>{0, 1, 5, 10, 45, 90}
              : std::vector<double>{0, 0.25, 0.5, 1, 1.5, 2, 3, 4, 5, 7, 10, 15, 20, 30, 45, 60, 75, 90};
    for (double a : alts) {
        RefractionRow row;
        row.apparent_deg = a;
        const double R = traced_refraction(air, a * kDeg, 0.55);
        row.traced_arcmin = R / kArcmin;
        row.true_deg = a - R / kDeg;
        row.integral_arcmin = g::refraction_integral(atm, 0.55, a * kDeg) / kArcmin;
        row.bennett_arcmin = g::bennett_refraction_arcmin(a);
        row.bennett_corrected_arcmin = g::bennett_corrected_refraction_arcmin(a);
        row.saemundsson_arcmin = g::saemundsson_refraction_arcmin(row.true_deg);
        st.max_traced_integral_arcsec =
            std::fmax(st.max_traced_integral_arcsec, std::abs(row.traced_arcmin - row.integral_arcmin) * 60);
        st.max_bennett_arcmin = std::fmax(st.max_bennett_arcmin, std::abs(row.bennett_arcmin - row.integral_arcmin));
        st.max_saemundsson_arcmin =
            std::fmax(st.max_saemundsson_arcmin, std::abs(row.saemundsson_arcmin - row.integral_arcmin));
        st.rows.push_back(row);
    }
    return st;
}

ConvergenceStudy convergence_study(bool quick) {
    ConvergenceStudy st;
    const double rho = 0.7;
    const Vec3 r0(0, 0, 0.5), image = -r0 / r0.squaredNorm();
    const std::vector<std::pair<std::string, g::KnownRay>> rays = {
        {"Luneburg impact 0.7",
         {g::Luneburg{}, g::Sphere{}, Vec3(rho, 0, -std::sqrt(1 - rho * rho)), Vec3::UnitZ(), Vec3::UnitZ(), 0.55}},
        {"fish-eye 20 deg off the axis",
         {g::MaxwellFishEye{Vec3::Zero(), {2.0, 0.0}, 1.0}, g::HalfSpace{-Vec3::UnitX(), 0.0}, r0,
          Vec3(std::sin(20 * kDeg), 0, std::cos(20 * kDeg)), image, 0.55}},
    };
    for (const auto& [name, ray] : rays) {
        ConvergenceCurve c;
        c.ray = name;
        const double per_decade = quick ? 1 : 2;
        for (double e = 4; e <= 13.01; e += 1 / per_decade) c.adaptive.push_back(g::adaptive_point(ray, std::pow(10.0, -e)));
        for (int k = 0; k <= (quick ? 5 : 8); ++k)  // a budget for the coarse steps that do not reach the exit
            c.fixed.push_back(g::fixed_point(ray, 0.4 / std::pow(2.0, k), quick ? 50000 : 250000));
        std::vector<double> x, y;
        for (const g::StepPoint& p : c.adaptive)
            if (p.setting >= 1e-12 && p.error > 0) x.push_back(p.setting), y.push_back(p.error);
        c.tol_slope = loglog_fit(x, y).slope;
        x.clear(), y.clear();
        // The fit over the steps whose error is between 1e-3 and 100× the sweep's smallest
        // (the rounding floor, reached as the steps grow many).
        double floor = 1.0;
        for (const g::StepPoint& p : c.fixed) floor = std::fmin(floor, p.error);
        for (const g::StepPoint& p : c.fixed)
            if (p.error > 100 * floor && p.error < 1e-3) x.push_back(p.setting), y.push_back(p.error);
        c.step_order = x.size() >= 2 ? loglog_fit(x, y).slope : NAN;
        const g::StepPoint a = g::adaptive_point(ray, 1e-11);
        c.matched_ratio = static_cast<double>(g::fixed_steps_to_match(ray, a.error).evaluations) /
                          static_cast<double>(a.evaluations);
        st.curves.push_back(c);
    }
    return st;
}

}  // namespace refract::experiments::grin_media
