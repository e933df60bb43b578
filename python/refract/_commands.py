"""The command line's farfield, measure, export-pov, validate and sweep as Python functions.

Each calls the C++ function its subcommand calls (python/src/commands.cpp); bad input raises
refract.InputError with the subcommand's message."""
import os as _os

import numpy as _np

from . import _refract


def _scene(s):
    from . import scene
    return scene(s)


def farfield(scene, output=None, binning="sphere", axis=None, reference=None, bins=180, azimuth_bins=360,
             polar_bins=180, classes=5, photons=1000000, seed=7, wavelengths=None, threads=0, plot=True):
    """The far-field detector (`refract farfield`, docs/far-field.md) on a Scene, dict, JSON text or path.

    Returns a dict: wavelengths (W,), power (W, classes, components, bins: fractions of the
    emitted power; components 4 = S0..S3 with exact polarisation, else 1), unscattered,
    absorbed and dropped (W,), theta_deg and solid_angle per bin (phi_deg for the sphere
    binning), class_names, photons, segments, seconds. output: also write the subcommand's
    files (far_field.csv, far_field_summary.csv, far_field.exr, the plot unless plot=False)
    into that directory."""
    return _refract._far_field(_scene(scene), binning, axis, reference, bins, azimuth_bins, polar_bins, classes,
                               photons, seed, list(wavelengths or []), threads,
                               _os.fspath(output) if output is not None else "", plot)


def measure(image, region=None, mask=None, line=None, radial=None, bins=32):
    """Image measurements as `refract measure` makes them, on a path or an array (height, width, 3).

    Default and region=(x0, y0, x1, y1) (inclusive; mask: a path or array whose first channel
    > 0.5 selects pixels): {"pixels", "r"/"g"/"b": {"mean", "sum", "min", "max"}}.
    line=(x0, y0, x1, y1): {"x", "y", "distance", "rgb" (N, 3)}.
    radial=(cx, cy, radius) with bins rings: {"r0", "r1", "pixels", "rgb" (bins, 3)}."""
    if isinstance(image, _os.PathLike):
        image = _os.fspath(image)
    if isinstance(mask, _os.PathLike):
        mask = _os.fspath(mask)
    if sum(x is not None for x in (line, radial)) + (region is not None or mask is not None) > 1:
        raise _refract.InputError("measure: region/mask, line and radial exclude each other")
    if line is not None:
        return _refract._measure_line(image, *[int(v) for v in line])
    if radial is not None:
        cx, cy, r = radial
        return _refract._measure_radial(image, float(cx), float(cy), float(r), int(bins))
    return _refract._measure_region(image, None if region is None else [int(v) for v in region], mask)


def angle_histogram(path, bins=32, axis=None):
    """`refract measure --angle-histogram`: a far-field sphere map (far_field.exr) binned by
    the angle to axis (default the map's own): theta0_deg, theta1_deg, solid_angle_sr,
    pixels, channels, power and intensity (bins, channels)."""
    return _refract._measure_angles(_os.fspath(path), int(bins), axis)


def export_pov(scene, path=None):
    """The scene as POV-Ray 3.7 SDL (`refract export-pov`): written to path (with its
    environment map when it has one), or returned as text when path is None."""
    s = _scene(scene)
    if path is None:
        return _refract._export_pov(s)
    _refract._write_pov(s, _os.fspath(path))
    return None


def validate(out_dir, cases=(), scenes="scenes/validation", threads=0, povray="povray"):
    """The cross-renderer validation suite (`refract validate`) into out_dir (report.md,
    report.html, images). Returns a dict: cases (name, status, skip_reason, metrics,
    images), passed, failed, skipped, povray_version, table (the text the command prints).
    InputError when POV-Ray is missing or a case is unknown."""
    return _refract._validate(_os.fspath(out_dir), list(cases), _os.fspath(scenes), threads, povray)


def sweep(preset="gia-default", rays=4096, wavelengths=31, material="diamond", polarisation="exact", seed=1,
          threads=0, **ranges):
    """The proportion sweep (`refract sweep brilliant`, docs/gem-metrics.md): ranges as
    keyword arguments in the subcommand's form, e.g. crown_angle="23:41:0.5",
    pavilion_angle="40.75". Returns the CSV's columns by name: NumPy arrays for numbers,
    lists of strings otherwise; the same values, row for row, as the command's CSV."""
    header, lines = _refract._sweep(preset, [(k, str(v)) for k, v in ranges.items()], rays, wavelengths, material,
                                    polarisation, seed, threads)
    import csv
    names = next(csv.reader([header]))
    cells = list(csv.reader(lines))
    out = {}
    for k, name in enumerate(names):
        col = [row[k] for row in cells]
        try:
            out[name] = _np.array([float(c) if c != "" else _np.nan for c in col])
        except ValueError:
            out[name] = col
    return out
