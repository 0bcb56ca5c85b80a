#!/usr/bin/python3
"""Whether a sheet holds: the largest structural or shear strain at the end of every displayed
frame (1/60 s) of a scene run at a larger resolution, as in docs/performance.md "The real-time
scene at 1024²" (1 is max_strain, a tear). CPU, through the Python module (build/python).

  bench/holds.py SCENE N SECONDS [--steps-per-frame K] [--precision float|double]
                 [--threads T] [--set KEY=JSON ...]

SCENE is a scene file; N the vertices a side (cloth.resolution); Δt is 1/(60 K). Prints the
largest strain and its frame, or the frame where the sheet tore, and the wall time; exits 1 on a
tear or an unstable step, 2 on a bad argument or scene.
"""
import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.environ.get("CLOTHSIM_PYTHON", os.path.join(HERE, "..", "build", "python")))
import clothsim  # noqa: E402

FRAME = 1.0 / 60


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("n", type=int)
    ap.add_argument("seconds", type=float)
    ap.add_argument("--steps-per-frame", type=int, default=1)
    ap.add_argument("--precision", choices=["float", "double"], default="float")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=JSON")
    a = ap.parse_args()
    sets = {"cloth.resolution": [a.n, a.n], "integrator.dt": FRAME / a.steps_per_frame,
            "duration": a.seconds}
    for kv in a.set:
        key, _, value = kv.partition("=")
        try:
            sets[key] = json.loads(value)
        except json.JSONDecodeError as e:
            sys.exit(f"holds.py: --set {kv}: the value is not JSON ({e})")
    try:
        sim = clothsim.Simulation(a.scene, backend="cpu", precision=a.precision,
                                  threads=a.threads, set=sets)
    except (clothsim.SceneError, ValueError, OSError) as e:
        print(f"holds.py: {e}", file=sys.stderr)
        sys.exit(2)
    label = f"{os.path.basename(a.scene)} {a.n}² at 1/{60 * a.steps_per_frame} s, {a.precision}"
    worst, at, start = 0.0, 0, time.monotonic()
    for frame in range(1, int(round(a.seconds / FRAME)) + 1):
        try:
            sim.step(a.steps_per_frame)
        except clothsim.UnstableError as e:
            print(f"{label}: unstable in frame {frame}: {e}")
            sys.exit(1)
        strain = sim.largest_strain()[0]
        if strain > worst:
            worst, at = strain, frame
        if strain > 1.0:
            print(f"{label}: torn in frame {frame} (largest strain {strain:.3f})")
            sys.exit(1)
    print(f"{label}: largest strain {worst:.3f} (frame {at}) over {frame} frames, "
          f"{time.monotonic() - start:.0f} s wall")


if __name__ == "__main__":
    main()
