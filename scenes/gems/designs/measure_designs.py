#!/usr/bin/env python3
"""Measures refract's catalogue of cuts (the .asc designs beside this script) with
`refract metrics` and prints the table of docs/gems.md ("Metrics of a design"): light
return, fire, scintillation and leakage with their standard errors, the ASET shares, the
facet count and the volume at width W = 2; the round brilliant (Tolkowsky's, written as a
design by `refract cut brilliant`) first, for reference.

Run: REFRACT=build/cli/refract python3 scenes/gems/designs/measure_designs.py
(the metrics' defaults: 4096 rays, 31 wavelengths, diamond, exact polarisation, seed 1)
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CUTS = [("princess", "princess"), ("emerald", "emerald"), ("asscher", "asscher"), ("radiant", "radiant"),
        ("cushion", "cushion"), ("oval", "oval"), ("pear", "pear"), ("heart", "heart"), ("marquise", "marquise"),
        ("old-european", "old European"), ("single", "single cut")]


def metrics(refract, path):
    out = subprocess.run([refract, "metrics", path, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    refract = os.environ.get("REFRACT", "refract")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        brilliant = os.path.join(tmp, "tolkowsky.asc")
        subprocess.run([refract, "cut", "brilliant", "--preset", "tolkowsky", "-o", brilliant], check=True,
                       capture_output=True)
        rows.append(("round brilliant (Tolkowsky)", metrics(refract, brilliant)))
    for cut, name in CUTS:
        rows.append((name, metrics(refract, os.path.join(HERE, cut + ".asc"))))
    print("| cut | light return | fire | scintillation | leakage | ASET red / green / blue | facets | volume (W = 2) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, m in rows:
        def v(k):
            return "%.3f ± %.3f" % (m[k]["value"], m[k]["error"])
        a = m["aset"]
        print("| %s | %s | %s | %s | %s | %.2f / %.2f / %.2f | %d | %.4f |" % (
            name, v("light_return"), v("fire"), v("scintillation"), v("leakage"), a["red"], a["green"], a["blue"],
            m["facets"], m["volume_at_width_2"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
