"""The laws of core/optics.h through the Python module, against their closed forms."""
import math

import numpy as np
import pytest

import refract
from refract import optics


@pytest.mark.parametrize("n", [1.333, 1.5, 2.417])
def test_fresnel_at_normal_incidence_is_the_square_of_n_minus_1_over_n_plus_1(n):
    f = optics.fresnel(1.0, n)
    expected = ((n - 1) / (n + 1)) ** 2
    assert f.Rs == pytest.approx(expected, rel=1e-14)
    assert f.Rp == pytest.approx(expected, rel=1e-14)
    assert f.R == pytest.approx(expected, rel=1e-14)
    assert f.T == pytest.approx(1 - expected, rel=1e-14)
    assert f.cos_t == 1.0


@pytest.mark.parametrize("eta", [1.5, 1 / 1.5, 2.417])
def test_rp_vanishes_at_brewsters_angle(eta):
    theta_b = optics.brewster_angle(eta)
    assert math.tan(theta_b) == pytest.approx(eta, rel=1e-14)
    f = optics.fresnel(math.cos(theta_b), eta)
    assert f.Rp < 1e-28
    assert f.Rs > 0.01


def test_refract_obeys_snells_law_and_stays_in_the_plane_of_incidence():
    theta = math.radians(40)
    d = np.array([math.sin(theta), -math.cos(theta), 0.0])
    t = optics.refract(d, [0, 1, 0], 1.5)
    assert np.linalg.norm(t) == pytest.approx(1.0, abs=1e-15)
    assert t[0] == pytest.approx(math.sin(theta) / 1.5, rel=1e-14)  # sin θt = sin θi / η
    assert t[2] == 0.0
    assert -t[1] == pytest.approx(optics.cos_transmitted(math.cos(theta), 1.5), rel=1e-14)


def test_total_internal_reflection_beyond_the_critical_angle():
    eta = 1 / 1.5
    theta_c = optics.critical_angle(eta)
    assert math.sin(theta_c) == pytest.approx(eta, rel=1e-14)
    assert optics.critical_angle(1.5) is None
    cos_i = math.cos(theta_c + 0.01)
    assert optics.fresnel(cos_i, eta) is None
    assert optics.cos_transmitted(cos_i, eta) is None
    assert optics.fresnel_reflectance(cos_i, eta) == 1.0
    d = np.array([math.sin(theta_c + 0.01), -cos_i, 0.0])
    assert optics.refract(d, [0, 1, 0], eta) is None
    r, p = optics.whitted_directions(d, np.array([0.0, 1.0, 0.0]), eta)
    assert p is None
    assert np.allclose(optics.reflect(d, [0, 1, 0]), [d[0], cos_i, 0], atol=1e-15)


def test_reflectance_plus_transmittance_is_one_from_the_amplitudes():
    # T = η cos θt / cos θi · t², energy: r² + T = 1 for s and p.
    for deg in (0, 20, 45, 70, 89):
        ci = math.cos(math.radians(deg))
        ct = optics.cos_transmitted(ci, 1.5)
        rs, rp = optics.fresnel_reflection_amplitudes(ci, ct, 1.5)
        ts, tp = optics.fresnel_transmission_amplitudes(ci, ct, 1.5)
        k = 1.5 * ct / ci
        assert rs * rs + k * ts * ts == pytest.approx(1.0, abs=1e-14)
        assert rp * rp + k * tp * tp == pytest.approx(1.0, abs=1e-14)


def test_schlick_is_exact_at_normal_and_grazing_incidence_and_works_on_arrays():
    cos = np.array([1.0, 0.5, 0.0])
    r = optics.schlick(cos, 1.5)
    assert r.shape == (3,)
    assert r[0] == pytest.approx(0.04, rel=1e-14)
    assert r[2] == pytest.approx(1.0, rel=1e-14)
    assert r[1] == pytest.approx(0.04 + 0.96 * 0.5 ** 5, rel=1e-14)
    assert optics.fresnel_reflectance(cos, 1.5)[0] == pytest.approx(0.04, rel=1e-14)


def test_beer_lambert_and_the_absorption_coefficient_are_inverse():
    alpha = optics.absorption_coefficient(0.5, 2.0)
    assert alpha == pytest.approx(math.log(2) / 2, rel=1e-14)
    assert optics.beer_lambert(alpha, 2.0) == pytest.approx(0.5, rel=1e-14)
    assert optics.absorption_coefficient(0.0, 1.0) is None
    assert optics.absorption_coefficient(0.5, -1.0) is None


def test_a_vector_argument_that_is_not_three_numbers_raises():
    with pytest.raises(refract.InputError, match="reflect: d: must be three numbers"):
        optics.reflect([1, 2], [0, 1, 0])
