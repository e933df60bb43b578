"""The subcommands' functions from Python: farfield, measure, export_pov, validate, sweep.

Each is the C++ function the command line calls; where cheap, the test compares with the
command's own output."""
import csv
import os
import subprocess

import numpy as np
import pytest

import refract
from conftest import sphere_scene

CLI = os.path.normpath(os.path.join(os.path.dirname(refract.__file__), "..", "..", "cli", "refract"))


def beam_sphere():
    """A glass sphere of index 1.5 in a beam along +z, nothing else: all light leaves it."""
    s = sphere_scene(ior=1.5)
    s["objects"] = s["objects"][:1]
    s["lights"] = [{"type": "beam", "position": [0, 1, -3], "direction": [0, 0, 1], "radius": 1.0}]
    s["render"]["threshold"] = 0
    s["render"]["max_depth"] = 40
    return s


def test_farfield_conserves_the_beams_power_and_writes_the_subcommands_files(tmp_path):
    r = refract.farfield(beam_sphere(), output=tmp_path / "ff", binning="axis", bins=18, photons=1000, threads=1,
                         plot=False)
    assert r["wavelengths"].tolist() == [550.0]
    assert r["power"].shape == (1, 5, 4, 18)  # exact polarisation: S0..S3
    total = r["power"][0, :, 0].sum() + r["unscattered"][0] + r["absorbed"][0] + r["dropped"][0]
    assert total == pytest.approx(1.0, abs=1e-9)
    assert r["absorbed"][0] == 0.0  # a clear sphere absorbs nothing
    # reflected at the first surface: the sphere-averaged Fresnel reflectance of n = 1.5, 0.092
    assert r["power"][0, 0, 0].sum() == pytest.approx(0.092, abs=0.01)
    assert r["photons"] == 1000 and len(r["class_names"]) == 5
    for f in ("far_field.csv", "far_field_summary.csv", "far_field.exr"):  # plot=False: no figure
        assert (tmp_path / "ff" / f).exists()


def test_farfield_refuses_a_scene_without_lights_and_leaves_no_directory(tmp_path):
    s = beam_sphere()
    del s["lights"]
    with pytest.raises(refract.InputError, match="/lights: the far-field detector needs a light"):
        refract.farfield(s, output=tmp_path / "ff", photons=10)
    assert not (tmp_path / "ff").exists()


def test_measure_region_line_and_radial_on_an_array_match_numpy():
    img = np.zeros((6, 8, 3))
    img[:, :, 0] = np.arange(8)[None, :]  # red = x
    img[:, :, 1] = np.arange(6)[:, None]  # green = y
    full = refract.measure(img)
    assert full["pixels"] == 48
    assert full["r"]["mean"] == pytest.approx(3.5) and full["g"]["max"] == 5.0
    box = refract.measure(img, region=(2, 1, 4, 3))
    assert box["pixels"] == 9 and box["r"]["sum"] == pytest.approx(27.0) and box["g"]["min"] == 1.0
    line = refract.measure(img, line=(0, 2, 7, 2))
    assert line["x"].tolist() == list(range(8)) and line["rgb"][:, 0].tolist() == list(range(8))
    assert line["distance"][-1] == 7.0
    radial = refract.measure(img, radial=(4, 3, 3), bins=3)
    assert radial["rgb"].shape == (3, 3) and radial["pixels"].sum() > 0
    with pytest.raises(refract.InputError, match="exclude each other"):
        refract.measure(img, region=(0, 0, 1, 1), line=(0, 0, 1, 1))


def test_measure_reads_an_image_file_as_the_command_does(tmp_path):
    img = np.full((4, 5, 3), 0.25)
    refract.write_image(str(tmp_path / "a.exr"), img)
    assert refract.measure(tmp_path / "a.exr")["b"]["mean"] == pytest.approx(0.25)


def test_export_pov_returns_the_sdl_and_writes_the_file(tmp_path):
    s = sphere_scene()
    s["render"]["compat"] = "povray"
    text = refract.export_pov(s)
    assert "camera" in text and "sphere" in text
    refract.export_pov(s, tmp_path / "s.pov")
    assert (tmp_path / "s.pov").read_text() == text


def test_validation_lists_the_suite_and_refuses_unknown_cases_and_a_missing_povray(source_dir, tmp_path):
    scenes = os.path.join(source_dir, "scenes", "validation")
    cases = refract.validation_cases(scenes)
    assert "fresnel-sphere" in cases and not any(c.endswith(".tol") for c in cases)
    with pytest.raises(refract.InputError, match="not found"):
        refract.validate(tmp_path / "v", ["fresnel-sphere"], scenes=scenes, povray="no-such-povray")
    with pytest.raises(refract.InputError):
        refract.validate(tmp_path / "v", ["../x"], scenes=scenes)


def test_sweep_gives_the_rows_of_the_commands_csv(tmp_path):
    rows = refract.sweep(crown_angle="34:35:1", rays=16, wavelengths=2, threads=1)
    assert rows["crown_angle"].tolist() == [34.0, 35.0]
    assert rows["status"] == ["ok", "ok"]
    assert np.all((rows["light_return"] > 0) & (rows["light_return"] < 1))
    if not os.access(CLI, os.X_OK):
        pytest.skip("no refract executable beside the module")
    out = tmp_path / "s.csv"
    subprocess.run([CLI, "sweep", "brilliant", "--crown-angle", "34:35:1", "--rays", "16", "--wavelengths", "2",
                    "--threads", "1", "--quiet", "-o", str(out)], check=True, capture_output=True)
    with open(out, newline="") as f:
        table = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, body = table[0], table[1:]
    for k, name in enumerate(header):
        col = [r[k] for r in body]
        if isinstance(rows[name], np.ndarray):
            assert rows[name].tolist() == [float(c) if c else pytest.approx(np.nan, nan_ok=True) for c in col], name
        else:
            assert rows[name] == col, name


def test_sweep_refuses_an_unknown_parameter():
    with pytest.raises(refract.InputError, match="unknown parameter 'crown'"):
        refract.sweep(crown="30")


def test_version_is_the_projects(source_dir):
    import re
    with open(os.path.join(source_dir, "CMakeLists.txt")) as f:
        assert refract.__version__ == re.search(r"project\(refract VERSION ([0-9.]+)", f.read()).group(1)


def test_import_without_numpy_fails_with_one_clear_message(source_dir):
    code = ("import sys\n"
            "class Block:\n"
            "    def find_spec(self, name, path=None, target=None):\n"
            "        if name == 'numpy' or name.startswith('numpy.'):\n"
            "            raise ImportError('blocked')\n"
            "sys.meta_path.insert(0, Block())\n"
            "import refract\n")
    r = subprocess.run([os.sys.executable, "-c", code], capture_output=True, text=True,
                       env=dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(refract.__file__))))
    assert r.returncode == 1
    assert "ImportError: refract needs NumPy, which is not installed" in r.stderr
