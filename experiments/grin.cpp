// grin: the lenses (Luneburg, fish-eye, rods, a rod imaging a grid), the findings and the
// run (experiments/grin.h). Every ray through core/grin's advance().
#include <refract/experiments/grin.h>

#include <chrono>
#include <cmath>

#include <refract/core/grin/profile.h>
#include <refract/core/grin/ray_equation.h>
#include <refract/core/optics.h>

namespace refract::experiments::grin_media {

namespace g = refract::grin;
using g::Vec3;

namespace {
constexpr double kLambda = 0.55;  // µm

g::Settings settings(double tol, bool record) {
    g::Settings s;
    s.abs_tol = s.rel_tol = tol;
    s.record_path = record;
    return s;
}

// The ray's recorded points as (a·x, b·x), after `before` and followed by `after`.
void add_path(std::vector<PathPoint>& out, int ray, const g::Result& r, const Vec3& a, const Vec3& b) {
    for (const g::PathSample& p : r.path) out.push_back({ray, a.dot(p.x), b.dot(p.x)});
}
void add_point(std::vector<PathPoint>& out, int ray, const Vec3& x, const Vec3& a, const Vec3& b) {
    out.push_back({ray, a.dot(x), b.dot(x)});
}
}  // namespace

LuneburgStudy luneburg_study(bool quick) {
    LuneburgStudy st;
    st.tol = 1e-13;
    g::Profile lens = g::Luneburg{};
    g::Region ball = g::Sphere{};
    const int n = quick ? 11 : 21;
    double evaluations = 0;
    const Vec3 focus = Vec3::UnitZ(), z = Vec3::UnitZ(), y = Vec3::UnitY();
    for (int i = 0; i < n; ++i) {
        const double rho = -0.95 + 1.9 * i / (n - 1);
        const Vec3 x0(0, rho, -std::sqrt(1 - rho * rho));
        const g::Result r = g::advance(lens, ball, x0, z, kLambda, settings(st.tol, true));
        st.spot_radius = std::fmax(st.spot_radius, (r.exit_point - focus).norm());
        st.direction_error = std::fmax(st.direction_error, (r.exit_dir + x0).norm());
        evaluations += static_cast<double>(r.evaluations);
        add_point(st.paths, i, Vec3(0, rho, -1.5), z, y);
        add_path(st.paths, i, r, z, y);
        add_point(st.paths, i, r.exit_point + 0.8 * r.exit_dir, z, y);
    }
    st.rays = n;
    st.mean_evaluations = evaluations / n;
    return st;
}

FishEyeStudy fisheye_study(bool quick) {
    FishEyeStudy st;
    st.tol = 1e-13;
    g::Profile lens = g::MaxwellFishEye{Vec3::Zero(), {st.n0, 0.0}, st.a};
    const Vec3 P(0, 0, st.r0), image = -st.a * st.a * P / P.squaredNorm();
    st.image = image.z();
    const Vec3 z = Vec3::UnitZ(), x = Vec3::UnitX();
    int ray = 0;
    for (int side : {1, -1}) {
        for (double deg = quick ? 40 : 20; deg <= 160.5; deg += quick ? 40 : 20) {
            const Vec3 d(side * std::sin(deg * kDeg), 0, std::cos(deg * kDeg));
            const g::Region half = g::HalfSpace{-static_cast<double>(side) * x, 0.0};  // the side the ray starts into
            const g::Result r = g::advance(lens, half, P, d, kLambda, settings(st.tol, true));
            st.image_error = std::fmax(st.image_error, (r.exit_point - image).norm() / st.a);
            // The circle through P tangent to d and through the image: centre P + s m, m ⊥ d.
            const Vec3 m(d.z(), 0, -d.x());
            const double s = -(P - image).squaredNorm() / (2 * m.dot(P - image));
            const Vec3 c = P + s * m;
            for (const g::PathSample& p : r.path)
                st.circle_error = std::fmax(st.circle_error, std::abs((p.x - c).norm() - std::abs(s)) / st.a);
            add_path(st.paths, ray++, r, z, x);
        }
    }
    st.rays = ray;
    return st;
}

RodStudy rod_study(bool quick) {
    RodStudy st;
    st.tol = 1e-13;
    st.pitch = 2 * kPi / st.alpha;
    g::Profile sech = g::SechRod{Vec3::Zero(), Vec3::UnitZ(), {st.n0, 0.0}, st.alpha};
    g::Profile parabolic = g::ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {st.n0, 0.0}, st.alpha * st.alpha};
    g::Region slab = g::Slab{Vec3::UnitZ(), 0.0, st.pitch};
    g::Region box = g::Box{Vec3(-0.8, -0.8, 0.0), Vec3(0.8, 0.8, st.pitch)};
    g::validate(parabolic, box, kLambda, kLambda, "grin rods");
    const Vec3 z = Vec3::UnitZ(), x = Vec3::UnitX();
    const int n = quick ? 4 : 12;
    for (int i = 0; i < n; ++i) {
        RodRow row;
        row.angle_deg = 2.0 + 22.0 * i / (n - 1);
        const Vec3 d(std::sin(row.angle_deg * kDeg), 0, std::cos(row.angle_deg * kDeg));
        const g::Result a = g::advance(sech, slab, Vec3::Zero(), d, kLambda, settings(st.tol, true));
        const g::Result b = g::advance(parabolic, box, Vec3::Zero(), d, kLambda, settings(st.tol, true));
        row.sech_height = a.exit_point.x();
        row.sech_slope_error = (a.exit_dir - d).norm();
        row.parabolic_height = b.exit_point.x();
        st.sech_spot = std::fmax(st.sech_spot, std::abs(row.sech_height));
        st.parabolic_spot = std::fmax(st.parabolic_spot, std::abs(row.parabolic_height));
        add_path(st.sech_paths, i, a, z, x);
        add_path(st.parabolic_paths, i, b, z, x);
        st.rows.push_back(row);
    }
    return st;
}

GridStudy grid_study(bool quick) {
    GridStudy st;
    st.length = 1.2 / st.g;  // g L = 1.2 rad: a fifth of a pitch
    st.object_distance = 4.0;
    st.pupil_radius = 0.2;
    // Paraxial: the rod's ABCD matrix on (height, n·slope), free space in air on both sides.
    const double c = std::cos(st.g * st.length), s = std::sin(st.g * st.length), ng = st.n0 * st.g;
    const double A = c, B = s / ng, C = -ng * s, D = c;
    st.image_distance = -(A * st.object_distance + B) / (C * st.object_distance + D);
    st.paraxial_magnification = A + st.image_distance * C;
    g::Profile rod = g::ParabolicRod{Vec3::Zero(), Vec3::UnitZ(), {st.n0, 0.0}, st.g * st.g};
    g::Region box = g::Box{Vec3(-st.rod_radius, -st.rod_radius, 0.0), Vec3(st.rod_radius, st.rod_radius, st.length)};
    g::validate(rod, box, kLambda, kLambda, "grin grid rod");
    const double image_z = st.length + st.image_distance;
    // One ray from the object point O through the entrance face at q: its point on the
    // image plane (false when it leaves through the rod's side or is reflected).
    auto trace = [&](const Vec3& O, const Vec3& q, Vec3& hit, std::vector<PathPoint>* path, int id) {
        const Vec3 d = (q - O).normalized();
        const auto in = optics::refract(d, -Vec3::UnitZ(), g::index(rod, q, kLambda));
        if (!in) return false;
        const g::Result r = g::advance(rod, box, q, *in, kLambda, settings(1e-11, path != nullptr));
        if (r.status != g::Status::left_region || std::abs(r.exit_point.z() - st.length) > 1e-9) return false;
        const auto out = optics::refract(r.exit_dir, -Vec3::UnitZ(), 1.0 / r.exit_index);
        if (!out) return false;
        hit = r.exit_point + *out * ((image_z - r.exit_point.z()) / out->z());
        if (path) {
            add_point(*path, id, O, Vec3::UnitZ(), Vec3::UnitX());
            add_path(*path, id, r, Vec3::UnitZ(), Vec3::UnitX());
            add_point(*path, id, hit, Vec3::UnitZ(), Vec3::UnitX());
        }
        return true;
    };
    // The pupil: the centre and rings of 8 points.
    std::vector<Vec3> pupil{Vec3::Zero()};
    const int rings = quick ? 1 : 3;
    for (int k = 1; k <= rings; ++k)
        for (int j = 0; j < 8; ++j) {
            const double rr = st.pupil_radius * k / rings, phi = 2 * kPi * j / 8;
            pupil.emplace_back(rr * std::cos(phi), rr * std::sin(phi), 0.0);
        }
    st.rays_per_point = static_cast<int>(pupil.size());
    const int half = quick ? 1 : 2;
    const double step = 0.4 / half;
    double nearest = 1e300, farthest = 0;
    for (int i = -half; i <= half; ++i)
        for (int j = -half; j <= half; ++j) {
            GridPoint p;
            p.object_x = i * step;
            p.object_y = j * step;
            const Vec3 O(p.object_x, p.object_y, -st.object_distance);
            std::vector<Vec3> hits;
            for (const Vec3& q : pupil) {
                Vec3 h;
                if (trace(O, q, h, nullptr, 0)) hits.push_back(h);
            }
            Vec3 centroid = Vec3::Zero();
            for (const Vec3& h : hits) centroid += h;
            centroid /= static_cast<double>(std::max<size_t>(hits.size(), 1));
            double ss = 0;
            for (const Vec3& h : hits) ss += (h - centroid).squaredNorm();
            p.image_x = hits.empty() ? NAN : centroid.x();
            p.image_y = hits.empty() ? NAN : centroid.y();
            p.spot_rms = hits.empty() ? NAN : std::sqrt(ss / static_cast<double>(hits.size()));
            const double r2 = p.object_x * p.object_x + p.object_y * p.object_y;
            p.magnification = r2 > 0 ? (p.image_x * p.object_x + p.image_y * p.object_y) / r2 : NAN;
            st.max_spot = std::fmax(st.max_spot, p.spot_rms);
            if (r2 > 0) nearest = std::fmin(nearest, r2), farthest = std::fmax(farthest, r2);
            st.points.push_back(p);
        }
    for (const GridPoint& p : st.points) {
        const double r2 = p.object_x * p.object_x + p.object_y * p.object_y;
        if (r2 == nearest) st.axis_magnification = p.magnification;
        if (r2 == farthest) st.corner_magnification = p.magnification;
    }
    // The diagram: meridional rays from the axis point and from the edge of the grid.
    int id = 0;
    for (double ox : {0.0, 0.4})
        for (double py : {-0.2, -0.1, 0.0, 0.1, 0.2}) {
            Vec3 h;
            trace(Vec3(ox, 0, -st.object_distance), Vec3(py, 0, 0), h, &st.paths, id++);
        }
    return st;
}

Findings judge(const Result& r) {
    Findings f;
    f.luneburg_focus = r.luneburg.spot_radius <= 1e-9;
    f.fisheye_image = r.fisheye.image_error <= 1e-8 && r.fisheye.circle_error <= 1e-8;
    f.sech_refocus = r.rods.sech_spot <= 1e-9 && r.rods.parabolic_spot >= 1000 * r.rods.sech_spot;
    f.grid_inverted_as_paraxial =
        std::abs(r.grid.axis_magnification / r.grid.paraxial_magnification - 1) <= 0.01;
    auto has = [](const MirageStudy& m, bool inverted) {
        for (const MirageBranch& b : m.branches)
            if (b.inverted() == inverted) return true;
        return false;
    };
    f.road_inverted = has(r.road, true) && has(r.road, false);
    f.sea_inverted = has(r.sea, true);
    f.sea_looming = r.sea.lowest_seen < r.sea.lowest_seen_standard;
    const auto& rows = r.sun.rows;
    f.sun_flattened = !rows.empty() && rows.front().ratio >= 0.75 && rows.front().ratio <= 0.9;
    for (size_t k = 1; k < rows.size(); ++k) f.sun_flattened = f.sun_flattened && rows[k].ratio > rows[k - 1].ratio;
    f.green_above_red = !r.sun.limbs.empty();
    for (const LimbRow& l : r.sun.limbs)
        f.green_above_red = f.green_above_red && l.traced_arcsec > 0 && std::abs(l.traced_arcsec - l.integral_arcsec) <= 0.01;
    f.traced_is_integral = !r.refraction.rows.empty() && r.refraction.max_traced_integral_arcsec <= 0.01;
    f.bennett_within = !r.refraction.rows.empty();
    for (const RefractionRow& row : r.refraction.rows)
        if (row.apparent_deg >= 5)
            f.bennett_within = f.bennett_within && std::abs(row.bennett_corrected_arcmin - row.integral_arcmin) <= 0.07;
    f.tolerance_proportional = f.fifth_order = !r.convergence.curves.empty();
    for (const ConvergenceCurve& c : r.convergence.curves) {
        f.tolerance_proportional = f.tolerance_proportional && c.tol_slope >= 0.8 && c.tol_slope <= 1.2;
        f.fifth_order = f.fifth_order && c.step_order >= 4.5 && c.step_order <= 5.5;
    }
    f.views_complete = !r.views.empty();
    for (const ViewStudy& v : r.views) {
        f.views_complete = f.views_complete && v.finite && v.grin_exhausted == 0;
        if (v.name == "sunset_limb_view") f.limb = sunset_limb(v);
        if (v.name == "sea_view") f.ship = ship_image(v);
    }
    f.sea_view_inverted = f.ship.inverted;
    f.limb_blue_on_top = f.limb.found && f.limb.blue_on_top && f.limb.rim_arcsec > 0;
    f.shimmer_linear = !r.shimmer.rows.empty() && std::abs(r.shimmer.exponent - 1.0) <= 0.05;
    f.shimmer_vdb_same = r.shimmer.vdb_dims_match && r.shimmer.vdb_max_index_difference <= 1e-9;
    return f;
}

Result compute(const ExperimentOptions& opt) {
    const auto t0 = std::chrono::steady_clock::now();
    Result r;
    r.quick = opt.quick;
    r.lambda_um = kLambda;
    auto timed = [&](const char* name, auto&& study) {
        const auto t = std::chrono::steady_clock::now();
        study();
        r.study_seconds.emplace_back(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
    };
    timed("Luneburg lens", [&] { r.luneburg = luneburg_study(opt.quick); });
    timed("fish-eye", [&] { r.fisheye = fisheye_study(opt.quick); });
    timed("rods", [&] { r.rods = rod_study(opt.quick); });
    timed("rod imaging a grid", [&] { r.grid = grid_study(opt.quick); });
    timed("hot road", [&] { r.road = mirage_study(true, opt.quick); });
    timed("cold sea", [&] { r.sea = mirage_study(false, opt.quick); });
    timed("setting sun", [&] { r.sun = sun_study(opt.quick); });
    timed("refraction", [&] { r.refraction = refraction_study(opt.quick); });
    timed("convergence", [&] { r.convergence = convergence_study(opt.quick); });
    timed("rendered views", [&] { r.views = view_study(opt.quick, opt.threads); });
    timed("heat shimmer", [&] { r.shimmer = shimmer_study(opt.quick, opt.threads); });
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.findings = judge(r);
    return r;
}

void run(const ExperimentOptions& opt) { write(compute(opt), opt.out_dir); }

}  // namespace refract::experiments::grin_media
