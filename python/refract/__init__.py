"""refract: the physics of refraction in rendering, from Python (docs/python.md).

Scenes come from dicts in the scene-file format (docs/scene-format.md), from JSON text or
from files, with the scene reader's own checks and messages: bad input raises
refract.InputError (a ValueError) naming the file or source, the field or the parameter.
"""
import os as _os

# An installed package carries the image module beside its native part, where core looks
# for it (core/image_io.cpp); the build tree's is found by core too.

try:  # declared in pyproject.toml; checked here so that its absence is one clear message
    import numpy as _numpy  # noqa: F401
except ImportError as _e:
    raise ImportError("refract needs NumPy, which is not installed: pip install numpy "
                      "(Debian: apt install python3-numpy)") from _e

from . import _refract
from ._refract import (  # noqa: F401  (the public API)
    Dispersion,
    FresnelTerms,
    InputError,
    Scene,
    brilliant_presets,
    experiments,
    fraunhofer,
    gem_geometry,
    gem_proportions,
    load_scene,
    material,
    ohtsuka1998,
    materials,
    optics,
    optics_bench,
    polarisation,
    polarisation_sphere,
    read_image,
    rtiow_dielectric,
    run_experiment,
    write_image,
    write_vdb,
    yasuda1984,
)
from ._commands import angle_histogram, export_pov, farfield, measure, sweep, validate  # noqa: F401
from ._refract import validation_cases  # noqa: F401
import sys as _sys

# `import refract.optics` and `from refract.fraunhofer import D` work as for modules.
_sys.modules[__name__ + ".optics"] = optics
_sys.modules[__name__ + ".fraunhofer"] = fraunhofer

__all__ = [
    "Dispersion", "FresnelTerms", "InputError", "RayTree", "RenderResult", "Scene", "angle_histogram",
    "brilliant_presets", "cut_brilliant", "dispersion", "experiments", "export_pov", "farfield", "fraunhofer", "gem_geometry", "gem_metrics", "gem_proportions", "load_scene", "material",
    "materials", "measure", "n", "ohtsuka1998", "optics", "optics_bench", "polarisation", "polarisation_sphere", "read_image", "render", "rtiow_dielectric", "run_experiment", "scene",
    "sweep", "trace", "trace_pixel", "trace_rays", "validate", "validation_cases", "write_image", "write_vdb", "yasuda1984",
]
__version__ = _refract.__version__  # the project's version (CMakeLists.txt)
for _c in (Dispersion, FresnelTerms, InputError, Scene):
    _c.__module__ = "refract"


def scene(source, name=None):
    """A Scene from a dict (the scene-file format), a JSON string or a file path.

    `name` is what error messages call the source (default: the path, or "scene")."""
    if isinstance(source, Scene):
        return source
    if isinstance(source, dict):
        return _refract.parse_scene(source, name or "scene")
    if isinstance(source, (str, _os.PathLike)):
        text = _os.fspath(source)
        if text.lstrip().startswith("{"):
            return _refract.parse_scene_text(text, name or "scene")
        return load_scene(text)
    raise TypeError("refract.scene: expected a Scene, a dict, JSON text or a path, not " + type(source).__name__)


class RenderResult(dict):
    """The arrays of one render, viewing the C++ image buffers without a copy.

    rgb (height, width, 3), stats (dict), and where the scene or the options have them:
    wavelengths (nm) and spectral (height, width, bands), stokes (height, width, 4, 3:
    S0..S3 of R, G, B), dolp and aolp (height, width), lost (height, width, 3: depth, limits,
    threshold). Keys are also attributes: result.rgb."""

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None


def render(scene_, threads=0, spectral_channels=False, lost_energy=False, max_memory=0, progress=False):
    """Renders a scene (Scene, dict, JSON text or path) as `refract render` does.

    The GIL is released while it runs; Ctrl-C (KeyboardInterrupt) stops it at the next tile."""
    return RenderResult(_refract.render(scene(scene_), threads, spectral_channels, lost_energy, max_memory, progress))


class RayTree(list):
    """Every node of one ray's tree (dicts, parents before children), with the ray's value.

    Per node: id, parent (-1: the primary ray), depth, reflections, transmissions, origin,
    direction, weight (cumulative attenuation), event ("background", "diffuse", "emissive",
    "mirror", "reflection and refraction", "reflection only", "total internal reflection"),
    hit, length, point, normal (incident side), object, facet, facet_label, entering, eta,
    cos_i, cos_t, Rs, Rp, R, light (what the node brings to the root), wavelength (nm,
    None for an RGB ray), and for a polarised trace stokes and stokes_x. Fields that do not
    apply are None."""

    def __init__(self, nodes, radiance, wavelength):
        super().__init__(nodes)
        self.radiance = radiance
        self.wavelength = wavelength

    def __repr__(self):
        return "RayTree(%d nodes, radiance=%r)" % (len(self), self.radiance)


def trace(scene_, origin, direction, wavelength=None, polarisation=None):
    """The whole tree of one ray, as `refract trace --ray` records it (core/trace_record.h).

    wavelength (nm): every dielectric with a dispersion takes its index there; None: an RGB ray
    with each material's nominal index.
    polarisation: None or "natural" (natural light, the scene's own model); otherwise the ray is
    light of that state travelling along it, walked with exact polarisation: a light's
    "polarisation" as in a scene file, e.g. {"type": "linear", "angle": 30, "reference":
    [0, 1, 0]}, {"type": "circular", "handedness": "right"} or "unpolarised". Each node then
    has "stokes" (S0..S3, fractions of the ray's power, in the frame x = "stokes_x" across the
    node's direction, y = direction x x; docs/polarisation.md), and "weight" is the colour
    weight times S0."""
    return RayTree(*_session(scene(scene_), polarisation).ray(origin, direction, wavelength, polarisation))


def trace_rays(scene_, origins, directions, wavelengths=None, threads=0, trees=False):
    """Many rays at once: per ray what its tree (as trace() records it) sums to, as NumPy arrays.

    origins, directions: (n, 3); wavelengths: None (RGB rays), one number or (n,) in nm (0: an
    RGB ray). threads: 0 all cores (the values do not depend on it). Returns a dict:
    point (n, 3) the first hit (NaN: none), object (n,) its index in scene.objects (-1: none),
    facet (n,), radiance (n, 3) the ray's value, escaped (n, 3) the summed weight of the
    segments leaving the scene and exit_direction (n, 3) that of the strongest of them (NaN:
    none), Rs and Rp (n,) summed over the dielectric nodes, segments (n,); with trees=True also
    "trees", each ray's RayTree (as trace(), one ray at a time)."""
    s = scene(scene_)
    result = _refract.trace_rays(_session(s, None), origins, directions, wavelengths, threads)
    if trees:
        import numpy as np
        o = np.asarray(origins, dtype=float).reshape(-1, 3)
        d = np.asarray(directions, dtype=float).reshape(-1, 3)
        w = None if wavelengths is None else np.broadcast_to(np.asarray(wavelengths, dtype=float), (len(o),))
        result["trees"] = [trace(s, o[i], d[i], None if w is None or w[i] == 0 else float(w[i])) for i in range(len(o))]
    return result


def trace_pixel(scene_, x, y, wavelength=None, polarisation=None):
    """The tree of the ray through the centre of pixel (x, y) (polarisation as in trace)."""
    return RayTree(*_session(scene(scene_), polarisation).pixel(x, y, wavelength, polarisation))


def _session(s, polarisation):
    """The scene's tracers, built on its first trace and kept on the Scene: pass a Scene
    (refract.scene(...)) rather than a path or a dict to trace many rays quickly."""
    natural = isinstance(polarisation, str) and polarisation == "natural"
    key = "_trace_natural" if natural else "_trace_session"
    session = getattr(s, key, None)
    if session is None:
        session = _refract.TraceSession(s, natural)
        setattr(s, key, session)
    return session


def n(name, wavelength_nm):
    """The index of catalogue material `name` at wavelength_nm (a number or an array)."""
    return material(name).n(wavelength_nm)


def dispersion(spec, where="dispersion"):
    """A Dispersion from a scene file's value: a catalogue name, a number or a dict
    such as {"model": "cauchy", "A": 1.5046, "B": 0.0042}."""
    import json
    return _refract.dispersion_from_json(spec if isinstance(spec, str) else json.dumps(spec), where)


def cut_brilliant(preset=None, **params):
    """Builds a round brilliant exactly (CGAL) with girdle radius 1, z up.

    preset: None (the defaults), "tolkowsky" or "gia-default"; params override it: table,
    crown_angle, pavilion_angle, star, lower_half, girdle, culet (% of the diameter, degrees),
    girdle_facets, bruted_planes. Returns a dict: vertices (N, 3), triangles (M, 3),
    triangle_facet (M,), planes (K, 4: unit outward normal, offset), labels, facets,
    facet_counts, measured and closed_form proportions, cut, girdle_description."""
    return _refract._cut_brilliant(preset, params)


def gem_metrics(preset=None, rays=4096, exact_polarisation=True, material="diamond", seed=1, **params):
    """Light return, fire, leakage and scintillation of a round brilliant (docs/gem-metrics.md).

    The cut as for cut_brilliant (preset, then params over it). rays: light-return eye rays
    (fire and scintillation pixels scale with it); exact_polarisation False: natural light;
    material: a catalogue name or a constant index ("2.417"); seed: the cut's own stream.
    Returns a dict: light_return, fire, leakage, scintillation, nail_head, fish_eye, obstruction (each
    {"value", "error"}, one standard error; docs/gem-metrics.md), leakage_by_kind, balance (crown, girdle, pavilion, lost, missed),
    aset (red, green, blue, white shares),
    cut, rays, fire_pixels, scintillation_pixels. Single-threaded, deterministic."""
    return _refract._gem_metrics(preset, params, rays, exact_polarisation, material, seed)
