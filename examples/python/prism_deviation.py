"""Deviation of a 60° N-BK7 prism against the angle of incidence, traced ray by ray at three
wavelengths, beside the closed form δ(i) = i + arcsin(n sin(A − arcsin(sin i / n))) − A and
its minimum δmin = 2 arcsin(n sin(A/2)) − A.  Usage: python3 prism_deviation.py OUT_DIR"""
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import refract

A = math.radians(60)
n1 = np.array([math.sin(A / 2), 0, -math.cos(A / 2)])  # entrance face, outward
t1 = np.array([math.cos(A / 2), 0, math.sin(A / 2)])   # along it, towards the apex
prism = refract.scene({
    "camera": {"location": [0, 0, -5], "look_at": [0, 0, 0], "width": 4, "height": 4},
    "background": [1, 1, 1],
    "materials": {"glass": {"type": "dielectric", "dispersion": "n-bk7"}},
    "objects": [{"type": "polyhedron", "name": "prism", "material": "glass",
                 "planes": [[*n1, 0], [n1[0], 0, -n1[2], 0], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1]]}],
    "render": {"max_depth": 4, "threshold": 0}})
mid = np.array([-0.5, 0, -0.5 * math.tan(A / 2)])  # middle of the entrance face


def deviation(i, nm):
    """Angle (deg) between the incoming ray and the ray leaving through the second face."""
    d = math.cos(i) * -n1 + math.sin(i) * t1
    tree = refract.trace(prism, mid - 2 * d, d, wavelength=nm)
    out = [s for s in tree if s["transmissions"] == 2 and s["reflections"] == 0]
    return math.degrees(math.acos(np.clip(np.dot(out[0]["direction"], d), -1, 1))) if out else math.nan


out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out_dir, exist_ok=True)
angles = np.linspace(30, 89, 120)
fig, ax = plt.subplots(figsize=(6.5, 4.2))
for nm, colour in [(450, "tab:blue"), (550, "tab:green"), (650, "tab:red")]:
    n = refract.n("n-bk7", nm)
    traced = [deviation(math.radians(a), nm) for a in angles]
    i = np.radians(angles)
    closed = np.degrees(i + np.arcsin(n * np.sin(A - np.arcsin(np.sin(i) / n))) - A)
    dmin = math.degrees(2 * math.asin(n * math.sin(A / 2)) - A)
    assert np.nanmax(np.abs(np.array(traced) - closed)) < 1e-9, nm
    assert abs(np.nanmin(traced) - dmin) < 0.05, nm
    ax.plot(angles, traced, color=colour, label="%d nm traced (n = %.4f)" % (nm, n))
    ax.plot(angles[::8], closed[::8], "o", color=colour, ms=3, mfc="none")
    ax.axhline(dmin, color=colour, lw=0.6, ls=":")
    print("%d nm: n = %.5f, minimum deviation %.4f deg (closed form %.4f)" % (nm, n, np.nanmin(traced), dmin))
ax.set_xlabel("angle of incidence (deg)")
ax.set_ylabel("deviation (deg)")
ax.set_title("60° N-BK7 prism: traced (lines), closed form (circles), δmin (dotted)")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(out_dir, "prism_deviation.png"), dpi=120)
