#include <refract/core/polarisation.h>

#include <algorithm>
#include <cmath>

#include <refract/core/optics.h>

namespace refract::polar {

FresnelAmplitudes fresnel_amplitudes(double cos_i, double eta) {
    if (const auto cos_t = optics::cos_transmitted(cos_i, eta)) {
        // The laws of core/optics.h, so rs², rp² are optics::fresnel's Rs, Rp exactly.
        const auto r = optics::generic::fresnel_reflection_amplitudes(cos_i, *cos_t, eta);
        const auto t = optics::generic::fresnel_transmission_amplitudes(cos_i, *cos_t, eta);
        return FresnelAmplitudes{r.s, r.p, t.s, t.p, *cos_t, false};
    }
    // TIR: cos θt = iγ; rs = (c − iηγ)/(c + iηγ), rp = (ηc − iγ)/(ηc + iγ), written as
    // exact unit-modulus phasors. ηγ = sqrt(sin²θi − η²) is computed as in
    // tir_phase_difference: near the critical angle δ ∝ sqrt(θi − θc), so the rounding of
    // sin²θi − η² is what both see.
    const double w = std::sqrt(std::max(0.0, (1.0 - cos_i * cos_i) - eta * eta));  // ηγ
    const auto rs = std::polar(1.0, -2.0 * std::atan2(w, cos_i));
    const auto rp = std::polar(1.0, -2.0 * std::atan2(w, eta * eta * cos_i));
    return FresnelAmplitudes{rs, rp, 0.0, 0.0, w / eta, true};
}

Mueller jones_diagonal_to_mueller(std::complex<double> a, std::complex<double> b) {
    // (Ex, Ey) → (a Ex, b Ey): |a Ex|² ± |b Ey|² mixes S0, S1; 2 conj(a Ex)(b Ey) =
    // z · 2 Ex* Ey, so S2 + i S3 is multiplied by z = conj(a) b.
    const double A = std::norm(a), B = std::norm(b);
    const std::complex<double> z = std::conj(a) * b;
    Mueller M = Mueller::Zero();
    M(0, 0) = M(1, 1) = 0.5 * (A + B);
    M(0, 1) = M(1, 0) = 0.5 * (A - B);
    M(2, 2) = M(3, 3) = z.real();
    M(2, 3) = -z.imag();
    M(3, 2) = z.imag();
    return M;
}

Mueller jones_to_mueller(const Eigen::Matrix2cd& J) {
    // Φ' = J Φ J† for Φ = ½ Σ_j S_j σ_j (σ0 = I, σ1 = diag(1, −1), σ2 = [[0, 1], [1, 0]],
    // σ3 = [[0, −i], [i, 0]]): column j is read off K_j = J σ_j J† as
    // (½(K00 + K11), ½(K00 − K11), Re K10, Im K10), K Hermitian. Written out per σ_j.
    using c = std::complex<double>;
    const c a = J(0, 0), b = J(0, 1), cc = J(1, 0), d = J(1, 1);
    // |z|² as re² + im² (libstdc++'s std::norm goes through hypot).
    const auto abs2 = [](c z) { return z.real() * z.real() + z.imag() * z.imag(); };
    const double A = abs2(a), B = abs2(b), C = abs2(cc), D = abs2(d);
    const c ab = a * std::conj(b), cd = cc * std::conj(d);
    Mueller M;
    const auto column = [&M](int j, double k00, double k11, c k10) {
        M(0, j) = 0.5 * (k00 + k11);
        M(1, j) = 0.5 * (k00 - k11);
        M(2, j) = k10.real();
        M(3, j) = k10.imag();
    };
    column(0, A + B, C + D, cc * std::conj(a) + d * std::conj(b));
    column(1, A - B, C - D, cc * std::conj(a) - d * std::conj(b));
    column(2, 2.0 * ab.real(), 2.0 * cd.real(), cc * std::conj(b) + d * std::conj(a));
    column(3, 2.0 * ab.imag(), 2.0 * cd.imag(), c(0, 1) * (d * std::conj(a) - cc * std::conj(b)));
    return M;
}

Mueller mueller_reflection(double cos_i, double eta) {
    const auto f = fresnel_amplitudes(cos_i, eta);
    return jones_diagonal_to_mueller(f.rs, f.rp);
}

std::optional<Mueller> mueller_transmission(double cos_i, double eta) {
    const auto f = fresnel_amplitudes(cos_i, eta);
    if (f.tir) return std::nullopt;
    return Mueller(eta * f.cos_t / cos_i * jones_diagonal_to_mueller(f.ts, f.tp));
}

double tir_phase_difference(double cos_i, double eta) {
    if (eta >= 1.0 || optics::cos_transmitted(cos_i, eta)) return 0.0;  // no TIR
    const double sin2 = 1.0 - cos_i * cos_i;
    return 2.0 * std::atan2(cos_i * std::sqrt(std::max(0.0, sin2 - eta * eta)), sin2);
}

Mueller rotator(double angle) {
    const double c = std::cos(2.0 * angle), s = std::sin(2.0 * angle);
    Mueller R = Mueller::Identity();
    R(1, 1) = c;
    R(1, 2) = s;
    R(2, 1) = -s;
    R(2, 2) = c;
    return R;
}

double frame_angle(const Vec3& x_from, const Vec3& x_to, const Vec3& k) {
    return std::atan2(k.dot(x_from.cross(x_to)), x_from.dot(x_to));
}

Vec3 s_axis(const Vec3& normal, const Vec3& k, const Vec3& fallback) {
    const Vec3 s = normal.cross(k);
    const double len = s.norm();
    if (len > 1e-12) return s / len;
    return (fallback - fallback.dot(k) * k).normalized();
}

Mueller linear_polariser(double angle) {
    const double c = std::cos(2.0 * angle), s = std::sin(2.0 * angle);
    Mueller M;
    M << 1, c, s, 0,  //
        c, c * c, c * s, 0,  //
        s, c * s, s * s, 0,  //
        0, 0, 0, 0;
    return 0.5 * M;
}

Mueller circular_polariser(int handedness) {
    const double h = handedness > 0 ? 1.0 : -1.0;
    Mueller M = Mueller::Zero();
    M(0, 0) = M(3, 3) = 0.5;
    M(0, 3) = M(3, 0) = 0.5 * h;
    return M;
}

Stokes unpolarised(double I) { return Stokes(I, 0.0, 0.0, 0.0); }

Stokes linear(double I, double angle) {
    return Stokes(I, I * std::cos(2.0 * angle), I * std::sin(2.0 * angle), 0.0);
}

Stokes circular(double I, int handedness) { return Stokes(I, 0.0, 0.0, handedness > 0 ? I : -I); }

double degree_of_polarisation(const Stokes& S) {
    if (!(S[0] > 0.0)) return 0.0;
    return S.tail<3>().norm() / S[0];
}

double degree_of_linear_polarisation(const Stokes& S) {
    if (!(S[0] > 0.0)) return 0.0;
    return std::hypot(S[1], S[2]) / S[0];
}

double angle_of_linear_polarisation(const Stokes& S) { return 0.5 * std::atan2(S[2], S[1]); }

}  // namespace refract::polar
