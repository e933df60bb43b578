"""The material catalogue and dispersion models of core/spectrum/dispersion.h."""
import numpy as np
import pytest

import refract


def test_the_catalogue_lists_its_six_materials():
    assert refract.materials() == ["diamond", "n-bk7", "fused-silica", "water", "cubic-zirconia", "moissanite"]


def test_diamond_has_index_2_417_at_the_sodium_d_line_and_disperses_normally():
    n = refract.n("diamond", [refract.fraunhofer.F, refract.fraunhofer.D, refract.fraunhofer.C])
    assert n.shape == (3,)
    assert n[1] == pytest.approx(2.4175, abs=5e-4)
    assert n[0] > n[1] > n[2]  # normal dispersion: blue bends more
    assert refract.n("diamond", 589.2938) == pytest.approx(n[1], rel=1e-15)


def test_n_bk7_has_the_catalogue_abbe_number_64_17():
    bk7 = refract.material("bk7")
    assert bk7.abbe_number == pytest.approx(64.17, abs=0.02)
    assert bk7.nominal == pytest.approx(1.5168, abs=1e-4)
    assert bk7.dispersive


def test_a_cauchy_model_from_a_dict_gives_a_plus_b_over_lambda_squared():
    d = refract.dispersion({"model": "cauchy", "A": 1.5046, "B": 0.0042})
    assert d.n(500.0) == pytest.approx(1.5046 + 0.0042 / 0.25, rel=1e-14)


def test_an_unknown_material_raises_listing_the_catalogue():
    with pytest.raises(ValueError, match="diamond"):
        refract.material("unobtainium")


def test_a_bad_dispersion_field_is_named():
    with pytest.raises(refract.InputError, match="dispersion/B"):
        refract.dispersion({"model": "cauchy", "A": 1.5, "B": "x"})
