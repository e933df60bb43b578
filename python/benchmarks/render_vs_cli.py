"""Paired whole-process timings: `refract render SCENE` against refract.render(SCENE) in a
fresh Python process, alternating, N pairs; prints each pair and the medians: wall time of
the process, its CPU time (user + system: steadier than wall time on a shared machine),
and the render's own stats seconds.
Usage: PYTHONPATH=build/python python3 python/benchmarks/render_vs_cli.py build/cli/refract SCENE [PAIRS] [THREADS]"""
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

exe, scene = sys.argv[1], sys.argv[2]
pairs = int(sys.argv[3]) if len(sys.argv) > 3 else 5
threads = sys.argv[4] if len(sys.argv) > 4 else "0"
py = ("import sys, refract\n"
      "r = refract.render(sys.argv[1], threads=int(sys.argv[2]))\n"
      "print('render seconds', r.stats['seconds'])\n")


def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd):
    c0, t0 = cpu(), time.perf_counter()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    wall, used = time.perf_counter() - t0, cpu() - c0
    m = re.search(r"(?:wall time \(s\)|render seconds)\s+([0-9.eE+-]+)", out)
    return wall, used, float(m.group(1))


with tempfile.TemporaryDirectory() as tmp:
    image = os.path.join(tmp, "image.exr")
    cli, pyt = [], []
    for k in range(pairs):
        a = timed([exe, "render", scene, "-o", image, "--threads", threads, "--stats"])
        b = timed([sys.executable, "-c", py, scene, threads])
        cli.append(a)
        pyt.append(b)
        print("pair %d: refract render %.3f s (CPU %.3f s, render %.3f s), python %.3f s (CPU %.3f s, render %.3f s)"
              % (k, *a, *b))
for name, col in (("whole process, wall", 0), ("whole process, CPU", 1), ("render alone, wall", 2)):
    c, p = statistics.median(x[col] for x in cli), statistics.median(x[col] for x in pyt)
    print("median %s: refract render %.3f s, python %.3f s, python/cli = %.4f" % (name, c, p, p / c))
