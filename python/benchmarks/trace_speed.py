"""Ray queries on the 1998 diamond from Python: refract.trace of one ray (the whole tree as
dicts, the scene's tracers kept on the Scene) and refract.trace_rays over the camera's rays
that meet the diamond, one thread and all. CPU time of the calling thread for the
one-thread figures (steadier than wall time on a shared machine), the best and the median
of the rounds; prints the load average. docs/python.md quotes its output.
Usage: PYTHONPATH=build/python python3 python/benchmarks/trace_speed.py [--quick] [--rounds N]"""
import argparse
import os
import statistics
import time

import numpy as np

import refract

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "examples",
                     "ohtsuka1998-diamond.json")


def rounds_of(rounds, f):
    """Thread-CPU and wall seconds of f(), `rounds` times."""
    cpu, wall = [], []
    for _ in range(rounds):
        c0, w0 = time.thread_time(), time.perf_counter()
        f()
        cpu.append(time.thread_time() - c0)
        wall.append(time.perf_counter() - w0)
    return cpu, wall


def diamond_rays(scene, step):
    """The camera's rays through every step-th pixel's centre whose first hit is the diamond,
    at 400, 410, ..., 700 nm in turn."""
    o, d = [], []
    for y in range(0, scene.height, step):
        for x in range(0, scene.width, step):
            first = refract.trace_pixel(scene, x, y)[0]
            if first["object"] == "diamond":
                o.append(first["origin"])
                d.append(first["direction"])
    w = 400.0 + 10.0 * (np.arange(len(o)) % 31)
    return np.array(o), np.array(d), w


def main(quick=False, rounds=5, out=print):
    scene = refract.scene(SCENE)
    out("Ray queries from Python, the 1998 diamond; load average before: %.2f %.2f %.2f" % os.getloadavg())
    first = refract.trace_pixel(scene, 320, 200)
    origin, direction = first[0]["origin"], first[0]["direction"]
    out("  one ray, pixel (320, 200): %d nodes" % len(first))
    calls = 200 if quick else 2000

    def one():
        for _ in range(calls):
            refract.trace(scene, origin, direction)
    cpu, wall = rounds_of(rounds, one)
    out("  refract.trace, one ray: %.2f us CPU (median; best %.2f), wall %.2f us" % (
        statistics.median(cpu) / calls * 1e6, min(cpu) / calls * 1e6, statistics.median(wall) / calls * 1e6))

    o, d, w = diamond_rays(scene, 8 if quick else 2)
    n = len(o)
    segments = refract.trace_rays(scene, o, d, w, threads=1)["segments"]
    out("  refract.trace_rays: %d camera rays on the diamond at 400-700 nm, %.1f segments per ray" % (
        n, segments.mean()))
    cpu, wall = rounds_of(rounds, lambda: refract.trace_rays(scene, o, d, w, threads=1))
    out("  refract.trace_rays, one thread: %.3f M rays/s CPU (median; best %.3f), wall %.3f M rays/s" % (
        n / statistics.median(cpu) / 1e6, n / min(cpu) / 1e6, n / statistics.median(wall) / 1e6))
    cpu, wall = rounds_of(rounds, lambda: refract.trace_rays(scene, o, d, w, threads=0))
    out("  refract.trace_rays, all threads: %.3f M rays/s wall (median)" % (n / statistics.median(wall) / 1e6))
    out("  load average after: %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer calls and rays")
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    main(args.quick, args.rounds)
