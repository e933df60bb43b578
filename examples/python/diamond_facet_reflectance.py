"""Reflectance of diamond's facets for s and p light: Rs, Rp against the angle of incidence,
outside (air to diamond) and inside (diamond to air: Brewster, then total internal
reflection past the critical angle), at 450, 550 and 650 nm; on top, the angles and Rs/Rp
that vertical rays actually meet on the facets of a Tolkowsky brilliant, with a table per
facet kind.  Usage: python3 diamond_facet_reflectance.py OUT_DIR"""
import collections
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import refract

out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out_dir, exist_ok=True)
fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
theta = np.linspace(0, 89.9, 400)
for nm, ls in [(450, ":"), (550, "-"), (650, "--")]:
    n = refract.n("diamond", nm)
    for ax, eta in [(axes[0], n), (axes[1], 1 / n)]:
        terms = [refract.optics.fresnel(math.cos(math.radians(t)), eta) for t in theta]
        ax.plot(theta, [f.Rs if f else 1 for f in terms], "b" + ls, lw=1, label="Rs %d nm" % nm)
        ax.plot(theta, [f.Rp if f else 1 for f in terms], "r" + ls, lw=1, label="Rp %d nm" % nm)
    print("%d nm: n = %.4f, Brewster %.2f deg outside, %.2f inside; critical angle %.2f deg" % (
        nm, n, math.degrees(refract.optics.brewster_angle(n)), math.degrees(refract.optics.brewster_angle(1 / n)),
        math.degrees(refract.optics.critical_angle(1 / n))))

# What vertical light meets on a Tolkowsky brilliant's facets, inside and out.
gem = refract.scene({
    "camera": {"location": [0, 4, -0.01], "look_at": [0, 0, 0], "width": 4, "height": 4},
    "background": [1, 1, 1], "materials": {"d": {"type": "dielectric", "dispersion": "diamond"}},
    "objects": [{"type": "brilliant", "name": "gem", "preset": "tolkowsky", "material": "d"}],
    "render": {"max_depth": 12, "threshold": 1e-4}})
hits = collections.defaultdict(list)
for x in np.linspace(-0.9, 0.9, 19):
    for z in np.linspace(-0.9, 0.9, 19):
        for s in refract.trace(gem, [x, 3, z], [0, -1, 0], wavelength=550):
            if s["eta"] is not None:
                angle = math.degrees(math.acos(s["cos_i"]))
                kind = s["facet_label"].rstrip("+-0123456789 ")
                hits[(kind, s["entering"])].append((angle, s["Rs"], s["Rp"]))
                axes[0 if s["entering"] else 1].plot(angle, s["Rp"], "k.", ms=2)
print("%-14s %-7s %6s %8s %7s %7s %6s" % ("facet", "side", "hits", "angle", "Rs", "Rp", "TIR"))
for (kind, entering), v in sorted(hits.items()):
    a = np.array(v)
    print("%-14s %-7s %6d %8.2f %7.3f %7.3f %5.0f%%" % (kind, "outside" if entering else "inside", len(a),
                                                       *a.mean(axis=0), 100 * np.mean(a[:, 1] == 1)))
for ax, title in zip(axes, ["air → diamond", "diamond → air"]):
    ax.set_title(title + " (dots: Rp of traced hits, 550 nm)")
    ax.set_xlabel("angle of incidence (deg)")
axes[0].set_ylabel("reflectance")
axes[1].legend(fontsize=7, loc="center left")
fig.tight_layout()
fig.savefig(os.path.join(out_dir, "diamond_facet_reflectance.png"), dpi=120)
