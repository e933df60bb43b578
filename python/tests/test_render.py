"""refract.render: NumPy views of the C++ buffers, statistics, determinism, Ctrl-C."""
import _thread
import gc
import threading
import time

import numpy as np
import pytest

import refract
from conftest import sphere_scene


def test_render_returns_float64_arrays_viewing_the_cpp_buffer_without_a_copy():
    r = refract.render(sphere_scene(), lost_energy=True)
    rgb = r.rgb
    assert rgb.shape == (24, 32, 3) and rgb.dtype == np.float64
    assert not rgb.flags.owndata and rgb.flags.c_contiguous
    assert type(rgb.base).__name__ == "PyCapsule"  # the capsule owns the C++ RenderResult
    assert r.lost.shape == (24, 32, 3) and r.lost.base is rgb.base
    assert rgb.max() > 0.1


def test_the_arrays_outlive_the_result_and_the_scene():
    s = refract.scene(sphere_scene())
    r = refract.render(s)
    rgb = r["rgb"]
    expected = rgb.copy()
    del r, s
    gc.collect()
    assert np.array_equal(rgb, expected)


def test_the_statistics_count_one_primary_ray_per_pixel():
    r = refract.render(sphere_scene())
    st = r.stats
    assert st["primary_rays"] == 32 * 24
    assert st["segments"] >= st["primary_rays"]
    assert st["seconds"] > 0
    assert "primary" in st["summary"]


def test_the_image_does_not_depend_on_the_thread_count():
    s = refract.scene(sphere_scene(extra_render={"samples": 4, "jitter": True}))
    assert np.array_equal(refract.render(s, threads=1).rgb, refract.render(s, threads=2).rgb)


def test_a_pixel_of_the_render_equals_the_radiance_of_its_traced_tree():
    s = refract.scene(sphere_scene())
    rgb = refract.render(s).rgb
    for (i, j) in [(16, 12), (10, 8), (2, 22)]:
        tree = refract.trace_pixel(s, i, j)
        assert rgb[j, i] == pytest.approx(tree.radiance, rel=1e-12, abs=1e-15)


def test_spectral_channels_have_one_plane_per_wavelength():
    d = sphere_scene(width=8, height=6)
    d["materials"]["glass"] = {"type": "dielectric", "dispersion": "bk7"}
    r = refract.render(d, spectral_channels=True)
    assert r.wavelengths.shape == (31,)
    assert r.wavelengths[0] == 400 and r.wavelengths[-1] == 700
    assert r.spectral.shape == (6, 8, 31) and r.spectral.base is r.rgb.base


def test_exact_polarisation_gives_stokes_images_whose_s0_is_the_image():
    r = refract.render(sphere_scene(width=16, height=12, extra_render={"polarisation": "exact"}))
    assert r.stokes.shape == (12, 16, 4, 3)
    assert np.array_equal(r.stokes[:, :, 0, :], r.rgb)
    assert r.dolp.shape == r.aolp.shape == (12, 16)
    assert np.all((r.dolp >= 0) & (r.dolp <= 1 + 1e-12))
    assert r.dolp.max() > 0.01  # reflections off the glass polarise


def test_bad_render_options_raise_valueerror():
    with pytest.raises(ValueError, match="threads"):
        refract.render(sphere_scene(), threads=-3)
    with pytest.raises(ValueError, match="spectral"):
        refract.render(sphere_scene(), spectral_channels=True)  # an RGB scene has no spectral pass


def test_ctrl_c_interrupts_a_long_render_within_a_second():
    # Natural light: the physical default, exact polarisation, first allocates the Stokes,
    # DoLP and AoLP images (14 values per pixel, 340 MB here).
    s = refract.scene(sphere_scene(width=2000, height=1500,
                                   extra_render={"samples": 16, "jitter": True, "polarisation": "natural"}))
    timer = threading.Timer(0.3, _thread.interrupt_main)
    t0 = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        refract.render(s, threads=2)
    elapsed = time.perf_counter() - t0
    timer.join()
    assert elapsed < 1.5


def test_an_exr_written_from_a_render_reads_back_bit_for_bit_in_single_precision(tmp_path):
    r = refract.render(sphere_scene())
    path = str(tmp_path / "ball.exr")
    refract.write_image(path, r.rgb)
    back = refract.read_image(path)
    assert back.shape == r.rgb.shape
    assert np.array_equal(back, r.rgb.astype(np.float32).astype(np.float64))
    with pytest.raises(ValueError, match="shape"):
        refract.write_image(str(tmp_path / "x.exr"), np.zeros((4, 4)))
    with pytest.raises(ValueError, match="x.bogus"):
        refract.write_image(str(tmp_path / "x.bogus"), r.rgb)


def test_write_image_keeps_negative_values_and_refuses_values_not_finite_as_a_float(tmp_path):
    rgb = np.full((2, 3, 3), 0.25)
    rgb[1, 2, 0] = -0.5  # an out-of-gamut colour: kept in a float file
    path = str(tmp_path / "signed.exr")
    refract.write_image(path, rgb)
    assert refract.read_image(path)[1, 2, 0] == -0.5
    for bad in (np.inf, np.nan, 1e300):
        rgb[0, 1, 2] = bad
        with pytest.raises(ValueError, match=r"\[0, 1, 2\].*not finite as a 32-bit float"):
            refract.write_image(str(tmp_path / "bad.exr"), rgb)
    assert not (tmp_path / "bad.exr").exists()
