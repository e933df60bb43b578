"""A sampled gradient-index field (docs/grin.md, "Sampled fields") given as a NumPy array."""
import numpy as np
import pytest

import refract


def sampled_luneburg(n=12):
    """A Luneburg-like index sampled on an n³ grid over [-1.1, 1.1]³, as a NumPy array."""
    x = np.linspace(-1.1, 1.1, n)
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    r2 = np.minimum(X**2 + Y**2 + Z**2, 1.2)
    return np.sqrt(2.0 - r2), float(x[1] - x[0])


def grid_scene(values, spacing):
    return {
        "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 40, "width": 12, "height": 9},
        "background": {"type": "gradient"},
        "materials": {"lens": {"type": "grin", "profile": {
            "kind": "grid", "origin": [-1.1, -1.1, -1.1], "spacing": spacing, "values": values}}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lens"}],
        "lights": [{"position": [2, 3, -4]}],
    }


def test_a_numpy_field_renders_and_traces_as_the_same_field_in_nested_lists():
    values, h = sampled_luneburg()
    from_numpy = refract.scene(grid_scene(values, h))
    from_lists = refract.scene(grid_scene(values.tolist(), h))
    a = refract.render(from_numpy, threads=1).rgb
    b = refract.render(from_lists, threads=1).rgb
    assert np.array_equal(a, b)
    assert a.max() > 0
    ta = refract.trace(from_numpy, [0.4, 0.1, -3], [0, 0, 1])
    tb = refract.trace(from_lists, [0.4, 0.1, -3], [0, 0, 1])
    assert len(ta) == len(tb) >= 2
    for p, q in zip(ta, tb):
        assert p["point"] == q["point"]
    # The curved ray inside leaves near the antipode (0, 0, 1) of the sampled lens.
    inside = [node for node in ta if node.get("parent") == 0 and node.get("transmissions") == 1]
    assert inside and np.linalg.norm(np.array(inside[0]["point"]) - [0, 0, 1]) < 0.05


def test_a_temperature_field_with_a_zero_is_refused_naming_the_sample():
    T = np.full((4, 4, 4), 300.0)
    T[1, 2, 3] = 0.0
    s = grid_scene(T, 0.8)
    s["materials"]["lens"]["profile"]["quantity"] = "temperature"
    with pytest.raises(Exception, match=r"/materials/lens/profile/values/1/2/3: the temperature 0 must be finite"):
        refract.render(refract.scene(s, "t.json"))


def file_scene(path, spacing, grid):
    s = grid_scene(None, spacing)
    p = s["materials"]["lens"]["profile"]
    del p["values"], p["origin"], p["spacing"]
    p["file"], p["grid"] = str(path), grid
    return s


@pytest.mark.parametrize("precision,as_stored", [("double", np.float64), ("float", np.float32)])
def test_write_vdb_gives_a_file_the_scene_reads_back_as_the_same_field(tmp_path, precision, as_stored):
    values, h = sampled_luneburg()
    path = tmp_path / "lens.vdb"
    refract.write_vdb(str(path), values, origin=[-1.1, -1.1, -1.1], spacing=h, grid="n", precision=precision)
    # What the file holds: the samples as a float or a double, so the inline field of the
    # same stored numbers renders and traces identically.
    stored = values.astype(as_stored).astype(np.float64)
    from_file = refract.scene(file_scene(path, h, "n"), str(tmp_path / "s.json"))
    inline = refract.scene(grid_scene(stored, h))
    assert np.array_equal(refract.render(from_file, threads=1).rgb, refract.render(inline, threads=1).rgb)
    ta = refract.trace(from_file, [0.4, 0.1, -3], [0, 0, 1])
    tb = refract.trace(inline, [0.4, 0.1, -3], [0, 0, 1])
    assert [p["point"] for p in ta] == [q["point"] for q in tb]
    if precision == "float":
        # A float keeps n to about 1e-7: 6e-8 is the largest rounding of these samples.
        assert 0 < np.abs(stored - values).max() < 1.2e-7


def test_write_vdb_refuses_bad_input_in_one_line_and_writes_nothing(tmp_path):
    path = tmp_path / "bad.vdb"
    with pytest.raises(refract.InputError, match=r"write_vdb: values must be a 3D array"):
        refract.write_vdb(str(path), np.ones((3, 3)))
    bad = np.ones((3, 3, 3))
    bad[1, 1, 1] = np.nan
    with pytest.raises(refract.InputError, match=r"bad.vdb: sample 13 is nan"):
        refract.write_vdb(str(path), bad)
    with pytest.raises(refract.InputError, match=r"write_vdb: precision 'half': expected float or double"):
        refract.write_vdb(str(path), np.ones((2, 2, 2)), precision="half")
    with pytest.raises(refract.InputError, match=r"spacing -1 must be a finite number > 0"):
        refract.write_vdb(str(path), np.ones((2, 2, 2)), spacing=-1)
    assert list(tmp_path.iterdir()) == []
