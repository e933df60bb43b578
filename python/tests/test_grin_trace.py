"""A trace through a gradient-index medium records its curved ray's points (docs/python.md, `path`)."""
import numpy as np

import refract


def test_the_curved_segment_in_a_luneburg_lens_records_points_on_the_circle_of_its_ray_and_straight_ones_none():
    scene = refract.scene({
        "camera": {"location": [0, 0, -4], "look_at": [0, 0, 0], "angle": 40, "width": 8, "height": 6},
        "background": {"type": "gradient"},
        "materials": {"lens": {"type": "grin", "profile": {"kind": "luneburg", "centre": [0, 0, 0], "radius": 1}}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lens"}],
        "lights": [{"position": [2, 3, -4]}],
    })
    nodes = refract.trace(scene, [0.5, 0, -3], [0, 0, 1])
    assert nodes[0]["path"] is None  # the camera ray to the lens is straight
    inside = [n for n in nodes if n["path"] is not None]
    assert len(inside) == 1
    path = np.array(inside[0]["path"])
    assert path.shape[1] == 3 and len(path) >= 3
    # From the entry point to the exit at the antipode of the ray's direction, (0, 0, 1).
    assert np.allclose(path[0], nodes[0]["point"], atol=1e-12)
    assert np.allclose(path[-1], inside[0]["point"], atol=1e-12)
    assert np.linalg.norm(path[-1] - [0, 0, 1]) < 1e-6
    # Inside the lens, in the plane y = 0 of the ray, and curved: off the chord between its ends.
    assert np.all(np.linalg.norm(path, axis=1) <= 1 + 1e-9)
    assert np.all(np.abs(path[:, 1]) < 1e-12)
    chord = path[-1] - path[0]
    off = np.abs(np.cross(path - path[0], chord)[:, 1]) / np.linalg.norm(chord)
    assert off.max() > 0.05
