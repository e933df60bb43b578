#!/usr/bin/env python3
"""Writes refract's catalogue of cuts as GemCad designs (.asc) beside this script.

Every design is built the same way (docs/gems.md, "The catalogue"): a convex girdle outline
(a dense set of points, width 2 across x, length along y), girdle facets tangent to it, then
rows of crown and pavilion facets. A row facet at azimuth phi and angle theta passes through
the outline inset by delta (support h(phi) - delta) at the row's height; each row starts
where the one before it ends (z += (delta' - delta) tan theta), so rows meet along the
outline's parallels; the table (and a culet, if any) closes the stone. Angles decrease from
the girdle inwards, as a convex stone requires. Distances are written with 10 decimals;
gear 96, index i faces azimuth 360 i / 96 - 90 degrees (geometry/gem/gemcad.h).

Facets that a row lists but the stone does not keep (a facet through a pointed tip or a
corner that its neighbours already cut) are pruned when REFRACT names a refract executable:
each design is built once with `refract cut asc`, and only the facets of its OBJ are written.

Run: REFRACT=build/cli/refract python3 scenes/gems/designs/make_designs.py
(rewrites the .asc files; refract's tests build every one)
"""
import math
import os
import subprocess
import tempfile

GEAR = 96


def index_of(phi_deg):
    i = (phi_deg + 90.0) * GEAR / 360.0
    i = i % GEAR
    r = round(i)
    if abs(i - r) > 1e-9:
        raise ValueError("azimuth %g is not on a tooth of gear 96" % phi_deg)
    return r % GEAR


def support(points, phi_deg):
    c, s = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    return max(c * x + s * y for x, y in points)


def every(step, start=0.0):
    n = int(round(360.0 / step))
    return [start + step * k for k in range(n)]


# Outlines (x: width, half-width 1; y: length).
def polygon_outline(corners, n=400):
    pts = []
    for k in range(len(corners)):
        (x0, y0), (x1, y1) = corners[k], corners[(k + 1) % len(corners)]
        for j in range(n):
            t = j / n
            pts.append((x0 + (x1 - x0) * t, y0 + (y1 - y0) * t))
    return pts


def rectangle(half_len, corner=0.0):
    a, b, c = 1.0, half_len, corner
    if c == 0:
        return polygon_outline([(a, -b), (a, b), (-a, b), (-a, -b)])
    return polygon_outline([(a, -b + c), (a, b - c), (a - c, b), (-a + c, b), (-a, b - c), (-a, -b + c),
                            (-a + c, -b), (a - c, -b)])


def ellipse(half_len, n=4000):
    return [(math.cos(2 * math.pi * k / n), half_len * math.sin(2 * math.pi * k / n)) for k in range(n)]


def superellipse(p, n=4000):
    pts = []
    for k in range(n):
        t = 2 * math.pi * k / n
        c, s = math.cos(t), math.sin(t)
        pts.append((math.copysign(abs(c) ** (2 / p), c), math.copysign(abs(s) ** (2 / p), s)))
    return pts


def lens_half(tip, upper=True, n=2000):
    """Half of a lens of half-width 1 and half-length `tip` (two circular arcs)."""
    cx = (tip * tip - 1) / 2.0   # centre distance c with R - c = 1, R^2 = c^2 + tip^2
    R = cx + 1
    a_max = math.asin(tip / R)
    pts = []
    for k in range(n + 1):
        a = -a_max + 2 * a_max * k / n
        y = R * math.sin(a)
        if (y >= 0) == upper or abs(y) < 1e-15:
            pts.append((-cx + R * math.cos(a), y))
            pts.append((cx - R * math.cos(a), y))
    return pts


def marquise(tip):
    return lens_half(tip, True) + lens_half(tip, False)


def pear(tip):
    # Round end (a half disk of radius 1) towards -y, a lens half towards +y.
    disk = [(math.cos(t), math.sin(t)) for t in (math.pi + math.pi * k / 2000 for k in range(2001))]
    return disk + lens_half(tip, True)


def heart(lobe_r, lobe_x, lobe_y, tip, n=2000):
    """The heart's convex preform outline: the hull of two lobes (disks of radius lobe_r at
    (+-lobe_x, lobe_y), lobe_x + lobe_r = 1) and the point (0, -tip); the cleft between the
    lobes is ground in afterwards (cleft tiers, see design())."""
    pts = [(0.0, -tip)]
    for sx in (-1.0, 1.0):
        for k in range(n):
            t = 2 * math.pi * k / n
            pts.append((sx * lobe_x + lobe_r * math.cos(t), lobe_y + lobe_r * math.sin(t)))
    return pts


def round_outline():
    return ellipse(1.0)


def surviving(text):
    """The (name, index) of the facets refract keeps, or None without REFRACT."""
    exe = os.environ.get("REFRACT")
    if not exe:
        return None
    with tempfile.TemporaryDirectory() as d:
        asc, obj = os.path.join(d, "x.asc"), os.path.join(d, "x.obj")
        with open(asc, "w") as f:
            f.write(text)
        subprocess.run([exe, "cut", "asc", asc, "-o", obj], check=True, stdout=subprocess.DEVNULL)
        kept = set()
        for line in open(obj):
            if line.startswith("g "):
                name, index = line[2:].strip().rsplit("_", 1)
                kept.add((name, int(index)))
        return kept


def design(name, outline, girdle_az, girdle_half, crown, table_inset, pavilion, culet_inset=None,
           headings=(), symmetry=(1, True), index=2.417, cleft=()):
    """crown/pavilion: lists of (angle, inset, azimuths), from the girdle inwards.

    cleft: (angle, distance, index) of facets ground in after the convex preform the other
    tiers cut (tier CL, geometry/gem/gemcad.h): the notch removed is the part of the preform
    outside every cleft facet. The preform alone is pruned; the cleft is written as given.

    Tiers are named as the trade names them: G the girdle, C1, C2, ... the crown's rows and
    P1, P2, ... the pavilion's from the girdle inwards (their angles decrease), T the table,
    CU the culet."""
    tiers = []  # (angle_text, distance, [(index, name)])

    def add(angle_text, facets):
        # one tier per distinct distance, facets in azimuth order
        groups = {}
        for phi, d in facets:
            key = round(d, 10)
            groups.setdefault(key, []).append(index_of(phi))
        for key in sorted(groups):
            tiers.append((angle_text, key, sorted(set(groups[key]))))

    labels = []
    # girdle
    g = {}
    for phi in girdle_az:
        g.setdefault(round(support(outline, phi), 10), []).append(index_of(phi))
    for d in sorted(g):
        tiers.append(("-90", d, sorted(set(g[d]))))
        labels.append("G")
    z = girdle_half
    last = None
    for row, (angle, inset, azimuths) in enumerate(crown):
        label = "C%d" % (row + 1)
        if last is not None:
            z += (inset - last[1]) * math.tan(math.radians(last[0]))
        t = math.radians(angle)
        n0 = len(tiers)
        add("%g" % angle, [(phi, math.sin(t) * (support(outline, phi) - inset) + math.cos(t) * z)
                                 for phi in azimuths])
        labels += [label] * (len(tiers) - n0)
        last = (angle, inset)
    z += (table_inset - last[1]) * math.tan(math.radians(last[0]))
    tiers.append(("0", round(z, 10), [0]))
    labels.append("T")
    z = girdle_half  # depth below the girdle plane
    last = None
    for row, (angle, inset, azimuths) in enumerate(pavilion):
        label = "P%d" % (row + 1)
        if last is not None:
            z += (inset - last[1]) * math.tan(math.radians(last[0]))
        t = math.radians(angle)
        n0 = len(tiers)
        add("-%g" % angle, [(phi, math.sin(t) * (support(outline, phi) - inset) + math.cos(t) * z)
                                  for phi in azimuths])
        labels += [label] * (len(tiers) - n0)
        last = (angle, inset)
    if culet_inset is not None:
        z += (culet_inset - last[1]) * math.tan(math.radians(last[0]))
        tiers.append(("-0", round(z, 10), [0]))
        labels.append("CU")
    def text(keep):
        out = []
        for (angle, d, idx), label in zip(tiers, labels):
            idx = [i for i in idx if keep is None or (label, i) in keep]
            if idx:
                out.append("a %s %.10f %d n %s%s" % (angle, d, idx[0], label, "".join(" %d" % i for i in idx[1:])))
        return out

    body = text(None)
    lines = ["GemCad 5.0", "g %d 0.0" % GEAR, "y %d %s" % (symmetry[0], "y" if symmetry[1] else "n"),
             "I %g" % index]
    lines += ["H " + h for h in (name,) + tuple(headings)]
    head, foot = lines, ["F written by scenes/gems/designs/make_designs.py (refract)"]
    keep = surviving("\n".join(head + body + foot) + "\n")
    cl = {}
    for angle, d, i in cleft:
        cl.setdefault((angle, round(d, 10)), []).append(i)
    cleft_lines = ["a %s %.10f %d n CL%s" % (angle, d, idx[0], "".join(" %d" % i for i in idx[1:]))
                   for (angle, d), idx in cl.items()]
    return "\n".join(head + text(keep) + cleft_lines + foot) + "\n"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    sq8 = every(45)          # sides and corners
    r16 = every(22.5)
    r8o = every(45, 22.5)
    cat = {}
    sides = every(90)
    chevrons = [a + o for a in sides for o in (-15.0, 15.0)]
    cat["princess"] = design(
        "Princess (square modified brilliant)", rectangle(1.0), sides, 0.02,
        [(40, 0.0, sides), (30, 0.0, every(90, 45)), (28, 0.15, sides)], 0.3,
        [(42, 0.0, chevrons), (40, 0.35, sides), (38, 0.7, chevrons)],
        headings=("Source: the square modified brilliant sold as the 'princess' since about 1980, chevron pavilion;",
                  "reference proportions: L/W 1.00, table ~70 %, crown 40/28 deg (corners 30), pavilion 42/40/38 deg"),
        symmetry=(4, True))
    cat["emerald"] = design(
        "Emerald (rectangular step cut, cut corners)", rectangle(1.4, 0.25), sq8, 0.02,
        [(45, 0.0, sq8), (38, 0.1, sq8), (30, 0.2, sq8)], 0.32,
        [(52, 0.0, sq8), (46, 0.25, sq8), (40, 0.5, sq8)],
        headings=("Source: the step cut of rectangular outline with cut corners (the trade's 'emerald cut');",
                  "reference proportions: L/W 1.40, table ~65 %, three crown and three pavilion steps"),
        symmetry=(2, True))
    cat["asscher"] = design(
        "Asscher (square step cut, large cut corners)", rectangle(1.0, 0.35), sq8, 0.02,
        [(45, 0.0, sq8), (38, 0.1, sq8), (30, 0.2, sq8)], 0.38,
        [(52, 0.0, sq8), (46, 0.25, sq8), (40, 0.5, sq8)],
        headings=("Source: J. Asscher's square step cut (Amsterdam, 1902): square outline, large cut corners;",
                  "reference proportions: L/W 1.00, table ~60 %, three crown and three pavilion steps"),
        symmetry=(4, True))
    cat["radiant"] = design(
        "Radiant (rectangular modified brilliant, cut corners)", rectangle(1.25, 0.2), sq8, 0.02,
        [(40, 0.0, sq8), (30, 0.15, sq8)], 0.35,
        [(43, 0.0, r16), (41, 0.4, chevrons)],
        headings=("Source: H. Grossbard's radiant (1977): cut-cornered rectangle, brilliant-style facets below;",
                  "reference proportions: L/W 1.25, table ~65 %, crown 40/30 deg, pavilion 43/41 deg"),
        symmetry=(2, True))
    cat["cushion"] = design(
        "Cushion (rounded square modified brilliant)", superellipse(4), r16, 0.02,
        [(38, 0.0, r16), (28, 0.15, r8o)], 0.38,
        [(42, 0.0, r16), (40, 0.4, r8o)],
        headings=("Source: the rounded-square 'cushion' outline (old mine cut's modern descendant);",
                  "reference proportions: L/W 1.00, table ~62 %, crown 38/28 deg, pavilion 42/40 deg"),
        symmetry=(4, True))
    cat["oval"] = design(
        "Oval (elliptical modified brilliant)", ellipse(1.35), every(11.25), 0.02,
        [(36, 0.0, r16), (25, 0.15, r8o)], 0.45,
        [(42, 0.0, r16), (40, 0.3, r8o)],
        headings=("Source: elliptical outline with brilliant-style facets (the trade's oval brilliant);",
                  "reference proportions: L/W 1.35, table ~55 %, crown 36/25 deg, pavilion 42/40 deg"),
        symmetry=(2, True))
    cat["pear"] = design(
        "Pear (teardrop modified brilliant)", pear(1.6), every(11.25), 0.02,
        [(36, 0.0, r16), (25, 0.15, r8o)], 0.45,
        [(42, 0.0, r16), (40, 0.3, r8o)],
        headings=("Source: half round, half marquise outline with brilliant-style facets (the trade's pear);",
                  "reference proportions: L/W 1.30, table ~55 %, crown 36/25 deg, pavilion 42/40 deg"),
        symmetry=(1, True))
    # The heart: the convex preform (two lobes and a point, crown and pavilion rows as the
    # pear's), then the cleft, a V-shaped notch between the lobes ground in with three
    # vertical facets: two walls facing each other at 33.75 deg either side of the axis
    # (indices 33 and 63) meeting the axis at y = apex, and a short flat (index 48) at y = floor.
    apex, floor, wall = 0.25, 0.30, 33.75
    cat["heart"] = design(
        "Heart (modified brilliant with a cleft)", heart(0.55, 0.45, 0.15, 1.3), every(11.25), 0.02,
        [(36, 0.0, r16), (25, 0.15, r8o)], 0.45,
        [(42, 0.0, r16), (40, 0.3, r8o)],
        headings=("Source: the trade's heart shape: two round lobes, a point and a cleft between the lobes, cut as a",
                  "convex preform with the cleft ground in last (tier CL); reference proportions: L/W 1.00,",
                  "table ~55 %, crown 36/25 deg, pavilion 42/40 deg, cleft ~20 % of the length deep"),
        symmetry=(1, True),
        cleft=[("90", math.sin(math.radians(wall)) * apex, 33), ("90", math.sin(math.radians(wall)) * apex, 63),
               ("90", floor, 48)])
    cat["marquise"] = design(
        "Marquise (navette modified brilliant)", marquise(2.0), every(11.25), 0.02,
        [(36, 0.0, r16), (25, 0.15, r8o)], 0.45,
        [(42, 0.0, r16), (40, 0.3, r8o)],
        headings=("Source: the lens (two circular arcs) outline with brilliant-style facets (navette);",
                  "reference proportions: L/W 2.00, table ~55 %, crown 36/25 deg, pavilion 42/40 deg"),
        symmetry=(2, True))
    cat["old-european"] = design(
        "Old European (round, small table, high crown, open culet)", round_outline(), every(11.25), 0.02,
        [(42, 0.0, r16), (36, 0.12, every(45)), (22, 0.35, r8o)], 0.55,
        [(43, 0.0, r16), (41, 0.3, every(45))], culet_inset=0.93,
        headings=("Source: the round cut of c. 1870-1930 (before Tolkowsky, 1919): small table, high crown, open culet;",
                  "reference proportions: table ~45 %, crown 42/36/22 deg, pavilion 43/41 deg, culet ~7 %"),
        symmetry=(8, True))
    cat["single"] = design(
        "Single cut (table, 8 crown and 8 pavilion facets)", round_outline(), r16, 0.02,
        [(35, 0.0, every(45))], 0.5,
        [(41, 0.0, every(45))],
        headings=("Source: the single cut (8/8 facets and a table), used for small melee;",
                  "reference proportions: table ~50 %, crown 35 deg, pavilion 41 deg, 16 girdle facets"),
        symmetry=(8, True))
    for name, text in cat.items():
        with open(os.path.join(here, name + ".asc"), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
