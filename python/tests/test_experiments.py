"""The experiment drivers from Python: the list, results as data, a run into files."""
import pytest

import refract


def test_every_driver_is_listed_in_reproduce_order():
    names = [e["name"] for e in refract.experiments()]
    assert names == ["yasuda1984", "rtiow-dielectric", "gem-geometry", "gem-metrics", "ohtsuka1998", "polarisation",
                     "optics-bench", "gem-cuts", "birefringence", "grin", "grin-layers"]
    assert all(e["description"] for e in refract.experiments())


def test_the_sphere_degree_of_polarisation_matches_its_closed_form():
    pts = refract.polarisation_sphere(1.5, [10.0, 40.0, 70.0])
    assert len(pts) == 12  # 3 angles × 4 path classes
    assert {p["path"] for p in pts} == {"reflection", "transmission", "1 internal", "2 internal"}
    for p in pts:
        assert p["dop"] == pytest.approx(p["dop_closed"], abs=1e-9)


def test_gem_proportions_measured_match_expected():
    rows = refract.gem_proportions("tolkowsky")
    assert len(rows) > 5
    for r in rows:
        assert r["measured"] == pytest.approx(r["expected"], abs=1e-6), r["quantity"]


def test_an_unknown_experiment_raises_listing_the_known_ones(tmp_path):
    with pytest.raises(ValueError, match="optics-bench"):
        refract.run_experiment("rainbow", str(tmp_path))


def test_optics_bench_returns_its_measurements_beside_the_closed_forms():
    r = refract.optics_bench(quick=True, threads=2)
    assert r["quick"]
    prism = r["prism"]
    assert prism["apex_deg"] == 60 and len(prism["rows"]) > 2
    for row in prism["rows"]:
        assert abs(row["deviation"] - row["deviation_closed"]) <= prism["max_error"] + 1e-12
    assert prism["max_error"] < 0.05  # degrees
    slab = r["slab"]
    for row in slab["rows"]:
        assert row["T_s"] == pytest.approx(row["T_s_closed"], abs=slab["max_error"] + 1e-12)
        assert row["T_s"] <= row["T_p"] + 1e-12  # s is reflected more than p
    assert {c["cls"] for c in r["drop"]["classes"]} >= {0, 1, 2, 3}


def test_gem_geometry_returns_its_data_and_renders_without_writing_files():
    r = refract.gem_geometry(quick=True, threads=2)
    assert [p["preset"] for p in r["presets"]] == refract.brilliant_presets()
    assert r["worst"] < 1e-9
    for p in r["presets"]:
        assert p["timing"]["agree"] == p["timing"]["rays"]  # plane set and mesh find the same hits
        assert p["rgb"].ndim == 3 and p["rgb"].shape[2] == 3 and p["rgb"].max() > 0
        assert p["facet_counts"]["table"] == 1
        assert p["scene"]["objects"]


def test_rtiow_returns_schlick_errors_and_a_convergence_slope_near_minus_one_half():
    r = refract.rtiow_dielectric(quick=True, threads=2)
    assert [s["tir_nodes"] > 0 for s in r["stages"]] == [False, False, False, True]  # only the hollow sphere
    n15 = r["schlick"][0]
    assert n15["name"] == "n=1.5" and n15["rows"].shape == (361, 3)
    assert n15["rows"][0, 1] == pytest.approx(0.04, rel=1e-12)  # Fresnel at normal incidence
    assert n15["max_error"] == pytest.approx(0.0357, abs=5e-5) and n15["max_error_at"] == 85
    assert -0.7 < r["slope"] < -0.3


def test_polarisation_returns_the_analyser_malus_sums_and_the_sphere_closed_forms():
    r = refract.polarisation(quick=True, threads=2)
    assert r["sphere"]["max_dop_error"] < 1e-9
    d = r["diamond"]
    assert d["natural"].shape == d["exact"].shape and d["dolp"].shape == d["natural"].shape[:2]
    assert d["light_natural"] > 0 and d["light_exact"] > 0
    a = r["analyser"]
    assert a["angles"] == [0, 45, 90, 135] and len(a["images"]) == 4
    # I(0°) + I(90°) = I(45°) + I(135°) = S0: the light through crossed analysers adds up
    # (to the cie-rgb pipeline's clipping of negative channels, experiments/polarisation.h)
    assert a["light"][0] + a["light"][2] == pytest.approx(a["light"][1] + a["light"][3], rel=1e-5)


def test_yasuda1984_returns_fig4_fig7_and_the_40_percent_cost_of_fresnel():
    r = refract.yasuda1984(quick=True, threads=2)
    fig4 = r["fig4"]
    assert fig4.shape == (181, 4) and fig4[0, 3] == pytest.approx(0.04, rel=1e-12)
    assert r["peak_onset"] == pytest.approx(2 + 3 ** 0.5, abs=1e-5)  # n > 2 + √3: an interior peak
    assert len(r["fig8"]) == 10 and len(r["fig9"]) == 6
    costs = {(c["formulation"], c["model"]): c["mul"] + c["div"] for c in r["cost"]["node_costs"]}
    increase = costs[("yasuda1984", "fresnel")] / costs[("yasuda1984", "constant")] - 1
    assert 0.3 < increase < 0.5  # the paper: "about 40 %"


def test_ohtsuka1998_returns_the_diamond_and_the_shortcuts_speed_and_error():
    r = refract.ohtsuka1998(quick=True, threads=2)
    assert r["full"].shape == r["shortcut"].shape == (90, 120, 3)
    assert 0 < r["shortcut_taken"] <= r["shortcut_tests"]
    assert r["shortcut_diff"]["rmse"] < 0.05
    steps = {s["step_nm"]: s["against_1nm"]["rmse"] for s in r["steps"]}
    assert steps[1.0] == 0 and steps[5.0] < steps[50.0]  # coarser sampling, larger error
    assert [x["label"] for x in r["peaks"]] == ["paper", "measured"]
