"""The three studies in examples/python/ run and write their figures."""
import os
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

EXAMPLES = os.path.join(SOURCE_DIR, "examples", "python")


@pytest.mark.parametrize("script", ["prism_deviation", "brilliant_light_return", "diamond_facet_reflectance"])
def test_the_example_script_writes_its_figure(script, tmp_path):
    path = os.path.join(EXAMPLES, script + ".py")
    with open(path) as f:
        assert len(f.read().splitlines()) < 60
    run = subprocess.run([sys.executable, path, str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    png = tmp_path / (script + ".png")
    assert png.stat().st_size > 10000
    with open(png, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
