"""refract.trace: the whole ray tree of core/trace_record.h, node by node."""
import math
import os

import numpy as np
import pytest

import refract
from refract import optics


def lone_sphere(ior=1.5):
    """A glass sphere in a white sky, nothing else: every leaf is background of value 1."""
    return refract.scene({
        "camera": {"location": [0, 0, -5], "look_at": [0, 0, 0], "width": 8, "height": 8},
        "background": [1, 1, 1],
        "materials": {"glass": {"type": "dielectric", "ior": ior}},
        "objects": [{"type": "sphere", "name": "ball", "center": [0, 0, 0], "radius": 1, "material": "glass"}],
        "render": {"max_depth": 60, "threshold": 0},
    })


@pytest.mark.parametrize("b", [0.0, 0.3, 0.7, 0.95])
def test_a_clear_glass_sphere_conserves_energy(b):
    tree = refract.trace(lone_sphere(), [0, b, -5], [0, 0, 1])
    leaves = [n for n in tree if n["event"] == "background"]
    assert len(leaves) > 2
    total = sum(n["weight"][0] for n in leaves)
    assert total == pytest.approx(1.0, abs=1e-12)
    assert tree.radiance[0] == pytest.approx(1.0, abs=1e-12)


def test_each_node_carries_the_fresnel_terms_of_its_hit():
    tree = refract.trace(lone_sphere(), [0, 0.5, -5], [0, 0, 1])
    first = tree[0]
    assert first["parent"] == -1 and first["depth"] == 0
    assert first["object"] == "ball" and first["entering"]
    assert first["event"] == "reflection and refraction"
    cos_i = -np.dot(first["direction"], first["normal"])
    assert first["cos_i"] == pytest.approx(cos_i, rel=1e-14)
    assert first["cos_i"] == pytest.approx(math.sqrt(1 - 0.25), rel=1e-12)  # impact parameter 0.5
    f = optics.fresnel(first["cos_i"], 1.5)
    assert (first["Rs"], first["Rp"], first["cos_t"]) == pytest.approx((f.Rs, f.Rp, f.cos_t), rel=1e-14)
    assert first["eta"] == 1.5
    assert np.allclose(first["point"], [0, 0.5, -math.sqrt(0.75)], atol=1e-12)


def test_children_weights_are_the_parents_times_r_and_one_minus_r():
    # Yasuda's eq. 7 at every node: the natural-light walk (the scene's own model, the
    # physical mode's default, is exact polarisation, where a weight is C00 of a product).
    tree = refract.trace(lone_sphere(), [0, 0.4, -5], [0, 0, 1], polarisation="natural")
    for node in tree[1:]:
        parent = tree[node["parent"]]
        R = parent["R"]
        factor = R if node["reflections"] == parent["reflections"] + 1 else 1 - R
        assert node["weight"][1] == pytest.approx(parent["weight"][1] * factor, rel=1e-13)
        assert node["depth"] == parent["depth"] + 1


def test_rays_past_the_critical_angle_inside_diamond_are_totally_reflected(source_dir):
    s = refract.scene(os.path.join(source_dir, "scenes", "examples", "ohtsuka1998-diamond.json"))
    tree = refract.trace_pixel(s, 320, 240, wavelength=550)
    assert tree.wavelength == 550
    tir = [n for n in tree if n["event"] == "total internal reflection"]
    assert tir, "a ray into the 1998 diamond meets total internal reflection"
    crit = optics.critical_angle(1 / refract.n("diamond", 550))
    for n in tir:
        assert n["Rs"] == n["Rp"] == 1.0 and n["cos_t"] == 0
        assert math.acos(n["cos_i"]) > crit
        assert n["facet_label"]
    assert {n["object"] for n in tree if n["hit"]} <= {"diamond", "floor"}


def test_bad_trace_arguments_raise_valueerror():
    s = lone_sphere()
    with pytest.raises(ValueError, match="nm is outside"):
        refract.trace(s, [0, 0, -5], [0, 0, 1], wavelength=100)
    with pytest.raises(ValueError, match="non-zero direction"):
        refract.trace(s, [0, 0, -5], [0, 0, 0])
    with pytest.raises(ValueError, match="direction: must be three numbers"):
        refract.trace(s, [0, 0, -5], [0, 1])
    with pytest.raises(ValueError, match="outside the 8x8 image"):
        refract.trace_pixel(s, 9, 0)
    with pytest.raises(ValueError, match="unknown polarisation 'exact'"):
        refract.trace(s, [0, 0, -5], [0, 0, 1], polarisation="exact")
    with pytest.raises(ValueError, match="angle"):
        refract.trace(s, [0, 0, -5], [0, 0, 1], polarisation={"type": "circular", "angle": 10})


def brewster_impact(n=1.5):
    """The height at which a ray along +z meets the unit sphere at Brewster's angle."""
    return math.sin(optics.brewster_angle(n))


def first_reflection(tree):
    return next(n for n in tree if n["parent"] == 0 and n["reflections"] == 1 and n["transmissions"] == 0)


def test_unpolarised_light_reflected_at_brewsters_angle_is_fully_polarised():
    b = brewster_impact()
    tree = refract.trace(lone_sphere(), [0, b, -5], [0, 0, 1], polarisation="unpolarised")
    assert tree[0]["stokes"] == pytest.approx((1, 0, 0, 0), abs=1e-15)
    node = first_reflection(tree)
    f = optics.fresnel(math.cos(optics.brewster_angle(1.5)), 1.5)
    S = node["stokes"]
    assert S[0] == pytest.approx((f.Rs + f.Rp) / 2, abs=1e-12)
    assert math.hypot(S[1], S[2]) / S[0] == pytest.approx(1.0, abs=1e-9)  # degree of linear polarisation
    assert node["weight"][0] == pytest.approx(S[0], abs=1e-15)
    assert node["stokes_x"] is not None and tree[0]["stokes_x"] is not None


def test_p_polarised_light_is_not_reflected_at_brewsters_angle_and_s_light_is_by_rs():
    b = brewster_impact()
    f = optics.fresnel(math.cos(optics.brewster_angle(1.5)), 1.5)
    # The plane of incidence holds the beam (z) and the height (y): E along y is p.
    p = first_reflection(refract.trace(lone_sphere(), [0, b, -5], [0, 0, 1],
                                       polarisation={"type": "linear", "angle": 0, "reference": [0, 1, 0]}))
    s = first_reflection(refract.trace(lone_sphere(), [0, b, -5], [0, 0, 1],
                                       polarisation={"type": "linear", "angle": 90, "reference": [0, 1, 0]}))
    assert p["stokes"][0] < 1e-15
    assert s["stokes"][0] == pytest.approx(f.Rs, abs=1e-12)


@pytest.mark.parametrize("state", ["unpolarised", {"type": "linear", "angle": 30}, {"type": "circular"}])
def test_a_polarised_ray_through_a_clear_sphere_conserves_energy(state):
    tree = refract.trace(lone_sphere(), [0, 0.6, -5], [0, 0, 1], polarisation=state)
    leaves = [n for n in tree if n["event"] == "background"]
    assert sum(n["stokes"][0] for n in leaves) == pytest.approx(1.0, abs=1e-12)
    assert all(n["stokes"][0] >= -1e-15 and math.sqrt(sum(x * x for x in n["stokes"][1:])) <= n["stokes"][0] + 1e-12
               for n in tree)


def test_segments_inside_calcite_name_their_wave_and_index():
    a = math.radians(45)
    s = refract.scene({
        "camera": {"location": [0, 3, -3], "look_at": [0, 0.3, 0], "width": 4, "height": 3},
        "materials": {"calcite": {"type": "uniaxial", "crystal": "calcite", "optic_axis": [math.sin(a), math.cos(a), 0]}},
        "objects": [{"type": "polyhedron", "name": "slab", "material": "calcite",
                     "planes": [[1, 0, 0, 1], [-1, 0, 0, 1], [0, 0, 1, 1], [0, 0, -1, 1], [0, 1, 0, 0.55], [0, -1, 0, -0.05]]}],
        "render": {"spectral": False, "max_depth": 3},
    })
    tree = refract.trace(s, [0.1, 2, 0.2], [0, -1, 0])
    inside = {n["wave"]: n for n in tree if n["parent"] == 0 and n["wave"] is not None}
    assert set(inside) == {"o", "e"}
    no, ne = inside["o"]["index"], 1.48613  # calcite at the D line (Ghosh 1999): n_o 1.65834
    assert no == pytest.approx(1.65834, abs=2e-5)
    # Normal incidence: the e wave's normal is the slab's, at 45 degrees to the optic axis.
    ne45 = no * ne / math.sqrt(ne ** 2 * math.cos(a) ** 2 + no ** 2 * math.sin(a) ** 2)
    assert inside["e"]["index"] == pytest.approx(ne45, abs=2e-5)
    assert inside["e"]["wave_normal"] == pytest.approx((0, -1, 0), abs=1e-12)
    assert all(n["wave"] is None and n["index"] is None for n in tree if n["parent"] == -1)


def test_trace_rays_gives_each_ray_its_trees_sums(source_dir):
    scene = refract.scene(os.path.join(source_dir, "scenes", "examples", "ohtsuka1998-diamond.json"))
    trees = [refract.trace_pixel(scene, x, y) for x, y in [(320, 200), (300, 260), (10, 10), (330, 420)]]
    o = np.array([t[0]["origin"] for t in trees])
    d = np.array([t[0]["direction"] for t in trees])
    w = np.array([450.0, 0.0, 600.0, 700.0])
    r = refract.trace_rays(scene, o, d, w, threads=2, trees=True)
    assert r["radiance"].shape == (4, 3) and r["segments"].dtype == np.int32
    for i, tree in enumerate(r["trees"]):
        assert tree == refract.trace(scene, o[i], d[i], None if w[i] == 0 else w[i])
        assert r["segments"][i] == len(tree)
        assert tuple(r["radiance"][i]) == tree.radiance
        first = tree[0]
        assert r["object"][i] == (scene.objects.index(first["object"]) if first["hit"] else -1)
        if first["hit"]:
            assert tuple(r["point"][i]) == first["point"]
        assert r["Rs"][i] == sum(n["Rs"] or 0.0 for n in tree)
        leaves = [n for n in tree if n["event"] == "background"]
        assert tuple(r["escaped"][i]) == tuple(sum(np.array(n["weight"]) for n in leaves)) if leaves else True
    assert r["object"][0] == 1 and r["segments"][0] > 10  # the table of the gem
    with pytest.raises(refract.InputError, match="trace_rays: ray 1 needs a finite origin"):
        refract.trace_rays(scene, [[0, 0, 0], [0, 0, math.nan]], [[0, 0, 1], [0, 0, 1]])
    with pytest.raises(refract.InputError, match=r"directions: must be an array of shape \(n, 3\)"):
        refract.trace_rays(scene, o, [1, 2])


def test_documented_trace_figures_are_within_2x_of_the_benchmark(source_dir):
    """docs/python.md quotes python/benchmarks/trace_speed.py; a short run of it (thread CPU
    time, the best of its rounds) stays within 2x of those figures."""
    import importlib.util
    import re
    spec = importlib.util.spec_from_file_location(
        "trace_speed", os.path.join(source_dir, "python", "benchmarks", "trace_speed.py"))
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    with open(os.path.join(source_dir, "docs", "python.md")) as f:
        doc = f.read()

    def best(text, label):
        m = re.search(re.escape(label) + r"[^\n]*best ([0-9.]+)", text)
        assert m, (label, text)
        return float(m.group(1))
    labels = ("refract.trace, one ray:", "refract.trace_rays, one thread:")

    def within(run):
        return all(0.5 * best(doc, l) <= best(run, l) <= 2 * best(doc, l) for l in labels)
    # A loaded machine (ctest -j, other processes) can slow one short run past 2x: the
    # figures count as kept when one of three runs is within 2x.
    for _ in range(3):
        lines = []
        bench.main(quick=True, rounds=3, out=lines.append)
        run = "\n".join(lines)
        if within(run):
            break
    for label in labels:
        documented, measured = best(doc, label), best(run, label)
        assert 0.5 * documented <= measured <= 2 * documented, (label, documented, measured, run)
