"""The optics functions refuse arguments outside their laws' domains (refract.InputError)."""
import math

import numpy as np
import pytest

import refract
from refract import optics


@pytest.mark.parametrize("cos_i", [-0.5, 1.5, math.nan])
def test_fresnel_refuses_a_cosine_outside_0_1(cos_i):
    with pytest.raises(refract.InputError, match=r"optics.fresnel: cos_i .* outside \[0, 1\]"):
        optics.fresnel(cos_i, 1.5)


def test_fresnel_refuses_a_non_positive_index_ratio():
    with pytest.raises(refract.InputError, match=r"optics.fresnel: eta -1.5 must be a finite number > 0"):
        optics.fresnel(0.5, -1.5)


def test_fresnel_reflectance_refuses_a_negative_cosine_scalar_and_elementwise():
    with pytest.raises(refract.InputError, match=r"optics.fresnel_reflectance: cos_i -0.5 is outside \[0, 1\]"):
        optics.fresnel_reflectance(-0.5, 1.5)
    with pytest.raises(refract.InputError, match="fresnel_reflectance"):
        optics.fresnel_reflectance(np.array([1.0, 0.5, -0.5]), 1.5)
    # the domain's ends are inside it: grazing incidence reflects everything
    assert optics.fresnel_reflectance(0.0, 1.5) == pytest.approx(1.0, abs=1e-15)
    assert optics.fresnel_reflectance(1.0, 1.5) == pytest.approx(0.04, rel=1e-14)


def test_schlick_cos_transmitted_and_angles_check_their_arguments():
    with pytest.raises(refract.InputError, match="optics.schlick: cos 2"):
        optics.schlick(2.0, 1.5)
    with pytest.raises(refract.InputError, match="optics.cos_transmitted: cos_i"):
        optics.cos_transmitted(-0.1, 1.5)
    with pytest.raises(refract.InputError, match="optics.brewster_angle: eta 0"):
        optics.brewster_angle(0.0)
    with pytest.raises(refract.InputError, match="optics.critical_angle: eta inf"):
        optics.critical_angle(math.inf)


@pytest.mark.parametrize("nm", [100, 2000, 359.9, 830.1])
def test_catalogue_index_refuses_wavelengths_outside_360_830_nm_as_trace_does(nm):
    with pytest.raises(refract.InputError, match=r"wavelength .* nm is outside \[360, 830\] nm"):
        refract.n("diamond", nm)


def test_catalogue_index_inside_the_range_scalar_and_array():
    assert refract.n("diamond", 589.29) == pytest.approx(2.4175, abs=2e-3)
    assert refract.n("diamond", 360) > refract.n("diamond", 830)
    with pytest.raises(refract.InputError, match="wavelength 100 nm"):
        refract.n("diamond", np.array([500.0, 100.0]))
