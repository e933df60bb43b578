// Double refraction at a uniaxial crystal's surface (see birefringence.h, docs/birefringence.md).
#include <refract/core/birefringence.h>

#include <cmath>

namespace refract::biref {

namespace {

// Bilinear (not Hermitian) products: the wave equation holds for complex k with k·k = n².
cplx bdot(const Vec3c& a, const Vec3c& b) { return a.transpose() * b; }
Vec3c cplx_of(const Vec3& v) { return v.cast<cplx>(); }
// a × b without conjugation (Eigen's cross conjugates complex results).
Vec3c bcross(const Vec3c& a, const Vec3c& b) {
    return Vec3c(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

// |v| (Hermitian) without the overflow-safe hypot of Eigen's complex norm.
double hnorm(const Vec3c& v) { return std::sqrt(v.squaredNorm()); }
Vec3c unit_hermitian(const Vec3c& v) { return v / hnorm(v); }

// A unit vector ⟂ k (the fallback ŝ at normal incidence): the axis least aligned with k,
// projected.
Vec3 any_perpendicular(const Vec3& k) {
    const Vec3 a = std::abs(k.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return (a - a.dot(k) * k).normalized();
}

// ε and ε⁻¹ of a uniaxial medium applied to a (complex) vector.
Vec3c eps_inverse(const Medium& m, const Vec3c& d) {
    const Vec3c a = cplx_of(m.axis);
    return d / (m.n_o * m.n_o) + (1.0 / (m.n_e * m.n_e) - 1.0 / (m.n_o * m.n_o)) * a * bdot(a, d);
}

// q of k = t + qN for |k|² = n² (isotropic or ordinary): real when propagating, else iγ
// with γ > 0, decaying along +N (e^{i k·r}).
cplx normal_component(double n, double t2) {
    const double d = n * n - t2;
    return d >= 0 ? cplx(std::sqrt(d), 0) : cplx(0, std::sqrt(-d));
}

// A propagating wave: real k and field; the ray along E × H, the flux ½ (E × H)·N.
PlaneWave real_wave(Wave w, bool s_like, const Vec3& k, const Vec3& E_dir, const Vec3& N) {
    const Vec3 E = E_dir.normalized(), H = k.cross(E), S = E.cross(H);
    return PlaneWave{w, s_like, cplx_of(k), cplx_of(E), cplx_of(H), false, S.normalized(), 0.5 * S.dot(N)};
}

// An evanescent wave (complex k): unit (Hermitian) field, no ray, no flux across N.
PlaneWave evanescent_wave(Wave w, bool s_like, const Vec3c& k, const Vec3c& E_dir) {
    const Vec3c E = unit_hermitian(E_dir);
    return PlaneWave{w, s_like, k, E, bcross(k, E), true, Vec3::Zero(), 0.0};
}

// Solves A X = B in place (B becomes X) by Gaussian elimination with partial pivoting on
// |a|² (no hypot, no complex division but one reciprocal per pivot). A is the 4×4 system
// of the boundary conditions, which is regular for any pair of media.
void solve4(Eigen::Matrix4cd& A, Eigen::Matrix<cplx, 4, 2>& B) {
    const auto abs2 = [](cplx z) { return z.real() * z.real() + z.imag() * z.imag(); };
    for (int c = 0; c < 4; ++c) {
        int p = c;
        for (int r = c + 1; r < 4; ++r)
            if (abs2(A(r, c)) > abs2(A(p, c))) p = r;
        if (p != c) {
            A.row(c).swap(A.row(p));
            B.row(c).swap(B.row(p));
        }
        const cplx inv = std::conj(A(c, c)) / abs2(A(c, c));
        for (int r = c + 1; r < 4; ++r) {
            const cplx f = A(r, c) * inv;
            for (int k = c + 1; k < 4; ++k) A(r, k) -= f * A(c, k);
            B.row(r) -= f * B.row(c);
        }
    }
    for (int c = 3; c >= 0; --c) {
        for (int k = c + 1; k < 4; ++k) B.row(c) -= A(c, k) * B.row(k);
        B.row(c) *= std::conj(A(c, c)) / abs2(A(c, c));
    }
}

}  // namespace

double extraordinary_index(double n_o, double n_e, double cos_theta) {
    const double c2 = cos_theta * cos_theta;
    return 1.0 / std::sqrt(c2 / (n_o * n_o) + (1.0 - c2) / (n_e * n_e));
}

double walk_off_angle(double n_o, double n_e, double theta) {
    const double r = (n_o * n_o) / (n_e * n_e), t = std::tan(theta);
    return std::atan((r - 1.0) * t / (1.0 + r * t * t));
}

Vec3 wave_vector_of_ray(const Medium& m, Wave w, const Vec3& ray) {
    if (!m.uniaxial() || w != Wave::Extraordinary) return m.n_o * ray;
    // The ray is along ε k (Born & Wolf §15.2.2: s ∝ E × (k × E) ∝ ε k for the e wave).
    const Vec3 k = eps_inverse(m, cplx_of(ray)).real().normalized();
    return extraordinary_index(m.n_o, m.n_e, k.dot(m.axis)) * k;
}

std::array<PlaneWave, 2> plane_waves(const Medium& m, const Vec3& t, const Vec3& N, const Vec3& s) {
    const Vec3c tc = cplx_of(t), Nc = cplx_of(N), sc = cplx_of(s);
    // Propagating waves (real q) are built in real arithmetic, evanescent ones in complex.
    if (!m.uniaxial()) {
        const cplx q = normal_component(m.n_o, t.squaredNorm());
        if (q.imag() == 0) {
            const Vec3 k = t + q.real() * N;
            return {real_wave(Wave::Isotropic, true, k, s, N), real_wave(Wave::Isotropic, false, k, k.cross(s), N)};
        }
        const Vec3c k = tc + q * Nc;
        return {evanescent_wave(Wave::Isotropic, true, k, sc), evanescent_wave(Wave::Isotropic, false, k, bcross(k, sc))};
    }
    const Vec3& a = m.axis;
    std::array<PlaneWave, 2> w;
    // Ordinary: |k| = n_o, E ∥ k × â (the s direction when k ∥ â).
    const cplx qo = normal_component(m.n_o, t.squaredNorm());
    Vec3 o_dir = s;  // the o field's direction when propagating (the e fallback uses it)
    if (qo.imag() == 0) {
        const Vec3 ko = t + qo.real() * N;
        const Vec3 Eo = ko.cross(a);
        if (Eo.norm() > 1e-12 * m.n_o) o_dir = Eo.normalized();
        w[0] = real_wave(Wave::Ordinary, false, ko, o_dir, N);
    } else {
        const Vec3c ko = tc + qo * Nc;
        Vec3c Eo = bcross(ko, cplx_of(a));
        if (hnorm(Eo) <= 1e-12 * m.n_o) Eo = sc;
        w[0] = evanescent_wave(Wave::Ordinary, false, ko, Eo);
    }
    // Extraordinary: kᵀAk = 1 with A = I/n_e² + (1/n_o² − 1/n_e²) â âᵀ; the root whose ray
    // A k has A k · N = b + q c = +sqrt(disc) > 0.
    const double ie = 1.0 / (m.n_e * m.n_e), d = 1.0 / (m.n_o * m.n_o) - ie;
    const double ta = t.dot(a), na = N.dot(a);
    const double b = ie * t.dot(N) + d * ta * na;
    const double c = ie + d * na * na;
    const double cc = ie * t.squaredNorm() + d * ta * ta - 1.0;
    const double disc = b * b - c * cc;
    // D ⟂ k in the plane of k and â: D = â (k·k) − k (k·â); E = ε⁻¹ D.
    if (disc >= 0) {
        const Vec3 ke = t + ((-b + std::sqrt(disc)) / c) * N;
        Vec3 De = a * ke.squaredNorm() - ke * ke.dot(a);
        if (De.norm() <= 1e-12 * ke.squaredNorm()) De = ke.cross(o_dir);
        const Vec3 Ee = De / (m.n_o * m.n_o) + (1.0 / (m.n_e * m.n_e) - 1.0 / (m.n_o * m.n_o)) * a.dot(De) * a;  // ε⁻¹ D
        w[1] = real_wave(Wave::Extraordinary, false, ke, Ee, N);
    } else {
        const Vec3c ke = tc + cplx(-b / c, std::sqrt(-disc) / c) * Nc;
        Vec3c De = cplx_of(a) * bdot(ke, ke) - ke * bdot(ke, cplx_of(a));
        if (hnorm(De) <= 1e-12 * std::abs(bdot(ke, ke))) De = bcross(ke, unit_hermitian(w[0].E));
        w[1] = evanescent_wave(Wave::Extraordinary, false, ke, eps_inverse(m, De));
    }
    return w;
}

InterfaceSplit split_at_interface(const Medium& from, Wave wave, const Medium& to, const Vec3& dir,
                                  const Vec3& normal) {
    const Vec3 N = -normal;  // into `to`
    const Vec3 k_in = wave_vector_of_ray(from, from.uniaxial() ? wave : Wave::Isotropic, dir);
    const Vec3 t = k_in - k_in.dot(N) * N;
    const Vec3 s = polar::s_axis(normal, k_in.normalized(), any_perpendicular(k_in.normalized()));
    const auto incident = plane_waves(from, t, N, s);
    const auto reflected = plane_waves(from, t, -N, s);
    const auto transmitted = plane_waves(to, t, N, s);

    // Tangential E and H continuous (Born & Wolf §1.1.3): rows E·u1, E·u2, H·u1, H·u2 with
    // u1 = ŝ, u2 = N × ŝ; unknowns the amplitudes of the two reflected and two transmitted waves.
    const Vec3c u1 = cplx_of(s), u2 = cplx_of(N.cross(s));
    const auto rows = [&](const PlaneWave& w) {
        return Eigen::Vector4cd(bdot(w.E, u1), bdot(w.E, u2), bdot(w.H, u1), bdot(w.H, u2));
    };
    Eigen::Matrix4cd A;
    A.col(0) = rows(reflected[0]);
    A.col(1) = rows(reflected[1]);
    A.col(2) = -rows(transmitted[0]);
    A.col(3) = -rows(transmitted[1]);

    // Incident basis: the s and p waves (isotropic), or the one crystal wave.
    const bool iso_in = !from.uniaxial();
    const int n_in = iso_in ? 2 : 1;
    const PlaneWave* in[2] = {&incident[0], &incident[1]};
    if (!iso_in) in[0] = &incident[wave == Wave::Ordinary ? 0 : 1];
    Eigen::Matrix<cplx, 4, 2> amp = Eigen::Matrix<cplx, 4, 2>::Zero();
    double f_in[2] = {1.0, 1.0};
    for (int b = 0; b < n_in; ++b) {
        amp.col(b) = -rows(*in[b]);
        f_in[b] = in[b]->flux;
    }
    solve4(A, amp);

    InterfaceSplit out;
    out.x_in = polar::s_axis(normal, dir, s);
    // The incident crystal wave's components in its frame (x̂_in, dir × x̂_in): J's row.
    Eigen::Vector2d c_in(1, 0);
    if (!iso_in) {
        const Vec3 e = in[0]->E.real();
        c_in = Eigen::Vector2d(e.dot(out.x_in), e.dot(dir.cross(out.x_in)));
    }
    const auto add_beam = [&](const std::array<PlaneWave, 2>& waves, int first, bool trans, const Medium& m) {
        const auto beam_of = [&](const Vec3& d, Wave w, const auto& field_of) {
            Beam bm{d, w, trans, polar::s_axis(normal, d, s), Jones::Zero(), 0.0};
            const Vec3 y = d.cross(bm.x);
            Eigen::Vector2cd col[2];
            for (int b = 0; b < n_in; ++b) {
                const Vec3c F = field_of(b);
                col[b] = Eigen::Vector2cd(bdot(F, cplx_of(bm.x)), bdot(F, cplx_of(y)));
            }
            if (iso_in) {
                bm.J.col(0) = col[0];
                bm.J.col(1) = col[1];
                bm.power = 0.5 * bm.J.squaredNorm();
            } else {
                bm.J = col[0] * c_in.transpose().cast<cplx>();
                bm.power = col[0].squaredNorm();
            }
            out.beam[static_cast<size_t>(out.count++)] = bm;
        };
        if (!m.uniaxial()) {  // the s and p waves: one beam
            if (waves[0].evanescent) return;
            beam_of(waves[0].ray, Wave::Isotropic, [&](int b) {
                return Vec3c((amp(first, b) * waves[0].E + amp(first + 1, b) * waves[1].E) *
                             std::sqrt(std::abs(waves[0].flux) / f_in[b]));
            });
            return;
        }
        for (int w = 0; w < 2; ++w) {
            if (waves[static_cast<size_t>(w)].evanescent) continue;
            const PlaneWave& pw = waves[static_cast<size_t>(w)];
            beam_of(pw.ray, pw.wave, [&](int b) {
                return Vec3c(amp(first + w, b) * pw.E * std::sqrt(std::abs(pw.flux) / f_in[b]));
            });
        }
    };
    add_beam(reflected, 0, false, from);
    add_beam(transmitted, 2, true, to);
    return out;
}

Jones reversed(const Jones& J) {
    Jones R = J.transpose();
    R(0, 1) = -R(0, 1);
    R(1, 0) = -R(1, 0);
    return R;
}

}  // namespace refract::biref
