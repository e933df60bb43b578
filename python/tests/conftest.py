"""Shared scenes for the refract Python tests (run by CTest: python3 -m pytest python/tests)."""
import os

import pytest

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def sphere_scene(width=32, height=24, ior=1.5, threshold=0.001, max_depth=12, extra_render=None, background=(0.4, 0.5, 0.8)):
    """A glass sphere over a checkered floor, lit by one point light (docs/scene-format.md)."""
    render = {"integrator": "fresnel-tree", "max_depth": max_depth, "threshold": threshold}
    render.update(extra_render or {})
    return {
        "camera": {"location": [0, 1, -6], "look_at": [0, 0.5, 0], "angle": 45, "width": width, "height": height},
        "background": list(background),
        "materials": {
            "glass": {"type": "dielectric", "ior": ior},
            "floor": {"type": "diffuse", "color": [0.9, 0.9, 0.9], "checker": {"color2": [0.1, 0.1, 0.1], "size": 1}},
        },
        "objects": [
            {"type": "sphere", "name": "ball", "center": [0, 1, 0], "radius": 1, "material": "glass"},
            {"type": "plane", "name": "floor", "normal": [0, 1, 0], "offset": 0, "material": "floor"},
        ],
        "lights": [{"position": [5, 10, -5]}],
        "render": render,
    }


@pytest.fixture
def source_dir():
    return SOURCE_DIR
