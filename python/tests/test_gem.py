"""refract.cut_brilliant: the exact round brilliant as NumPy arrays."""
import numpy as np
import pytest

import refract


def test_the_tolkowsky_cut_measures_back_its_proportions():
    g = refract.cut_brilliant("tolkowsky")
    m, c = g["measured"], g["closed_form"]
    for key in ("table", "crown_angle", "pavilion_angle", "crown_height", "pavilion_depth"):
        assert m[key] == pytest.approx(c[key], abs=1e-9), key
    assert m["pavilion_angle"] == pytest.approx(40.75, abs=1e-9)


def test_every_vertex_lies_inside_every_plane_and_on_its_own_facets():
    g = refract.cut_brilliant(pavilion_angle=41.5, girdle_facets=32)
    v, planes = g["vertices"], g["planes"]
    assert np.allclose(np.linalg.norm(planes[:, :3], axis=1), 1.0, atol=1e-14)
    assert np.all(v @ planes[:, :3].T - planes[:, 3] <= 1e-9)
    for k, f in enumerate(g["facets"]):
        assert np.allclose(v[f["vertex_ids"]] @ planes[k, :3], planes[k, 3], atol=1e-9)
    assert g["facet_counts"]["girdle"] == 32
    assert g["cut"]["pavilion_angle"] == 41.5


def test_the_triangle_mesh_is_a_closed_surface_with_euler_characteristic_2():
    g = refract.cut_brilliant("gia-default")
    t = g["triangles"]
    edges = {tuple(sorted((int(a), int(b)))) for tri in t for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0]))}
    assert len(g["vertices"]) - len(edges) + len(t) == 2
    assert g["triangle_facet"].shape == (len(t),)


def test_bad_cut_parameters_are_named():
    with pytest.raises(ValueError, match="unknown parameter 'pavillion_angle'"):
        refract.cut_brilliant(pavillion_angle=41)
    with pytest.raises(ValueError, match="pavilion angle = 80 deg is outside"):
        refract.cut_brilliant(pavilion_angle=80)
    with pytest.raises(ValueError, match="girdle_facets = 16.5: must be an integer"):
        refract.cut_brilliant(girdle_facets=16.5)
    with pytest.raises(ValueError, match="tolkowsky"):
        refract.cut_brilliant("round")


def test_gem_metrics_carry_errors_and_a_shallow_pavilion_leaks_more():
    t = refract.gem_metrics("tolkowsky", rays=1984)
    s = refract.gem_metrics("tolkowsky", rays=1984, pavilion_angle=37.5)
    for key in ("light_return", "fire", "leakage", "scintillation"):
        assert t[key]["error"] > 0, key
    b = t["balance"]
    assert b["crown"] + b["girdle"] + b["pavilion"] + b["lost"] + b["missed"] == pytest.approx(1.0, abs=1e-12)
    assert s["leakage"]["value"] > t["leakage"]["value"] + 5 * np.hypot(s["leakage"]["error"], t["leakage"]["error"])
    assert refract.gem_metrics("tolkowsky", rays=1984) == t  # deterministic
    assert refract.gem_metrics("tolkowsky", rays=496, material="2.417")["fire"]["value"] == 0.0
    with pytest.raises(ValueError, match="rays = 8"):
        refract.gem_metrics("tolkowsky", rays=8)
