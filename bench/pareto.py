#!/usr/bin/python3
"""The speed-accuracy trade (docs/stability.md, "Large steps: error against cost"): on the drape
scene in cotton, every solver's error after 1 s against a converged backward Euler, against its
wall time per simulated second.

  bench/pareto.py [CLOTHSIM] [OUT] [SCENE]   (defaults build/clothsim, bench/results,
                                             scenes/drape.json)

Reference: implicit_euler at dt = 1/60 in double, its CG to |r| <= 1e-10 |b|. At dt = 1/60 the
CG runs with exactly k iterations a step (tolerance 1e-14, max_iterations k) for k = 1 ... 128,
without and with block-Jacobi; vbd with 1 ... 100 sweeps; the explicit methods at steps that
keep them stable; vbd with its translation step (once a step, the default) and no levels, without
either, and with both and 4 translation levels (the default since the levels). Runs are CPU float on 2 threads (the real-time target); an unstable run is
recorded as such. Writes pareto_SCENE.csv and, with gnuplot, pareto_SCENE.png.
"""
import csv
import os
import re
import subprocess
import sys

import math

EXE = sys.argv[1] if len(sys.argv) > 1 else "build/clothsim"
OUT = sys.argv[2] if len(sys.argv) > 2 else "bench/results"
SCENE = sys.argv[3] if len(sys.argv) > 3 else "scenes/drape.json"
LABEL = os.path.splitext(os.path.basename(SCENE))[0]
FRAME = 1.0 / 60
TIME = 1.0
os.makedirs(OUT, exist_ok=True)


def run(sets, steps, precision="float", threads=2):
    """Positions (N×3) after `steps`, wall seconds of stepping, and whether it stayed stable."""
    path = os.path.join(OUT, "pareto_state.csv")
    argv = [EXE, "run", SCENE, "--precision", precision, "--threads", str(threads), "--steps",
            str(steps), "--out-csv", path]
    for s in sets:
        argv += ["--set", s]
    p = subprocess.run(argv, capture_output=True, text=True)
    if p.returncode == 3:
        return None, None, False
    if p.returncode != 0:
        sys.exit(f"{' '.join(argv)}: exit {p.returncode}\n{p.stderr}")
    wall = float(re.search(r"([0-9.]+) s wall", p.stdout).group(1))
    with open(path) as f:
        rows = list(csv.reader(f))[1:]
    return [tuple(float(v) for v in r[2:5]) for r in rows], wall, True


implicit = ['integrator.method="implicit_euler"', f"integrator.dt={FRAME!r}"]
reference, _, ok = run(implicit + ["integrator.tolerance=1e-10", "integrator.max_iterations=100000"],
                       round(TIME / FRAME), precision="double", threads=1)
assert ok, "the reference went unstable"
first, _, _ = run([], 1, precision="double", threads=1)  # about the rest state
size = math.dist([min(p[a] for p in first) for a in range(3)],
                 [max(p[a] for p in first) for a in range(3)])  # its diagonal [m]: the error's unit

rows = []


def point(solver, knob, value, sets, dt):
    steps = round(TIME / dt)
    x, wall, stable = run(sets, steps)
    error = ""
    if stable:
        squares = [sum((a - b) ** 2 for a, b in zip(p, q)) for p, q in zip(x, reference)]
        error = math.sqrt(sum(squares) / len(squares)) / size
    rows.append({"solver": solver, "knob": knob, "value": value, "dt": dt,
                 "seconds_per_second": wall / TIME if stable else "", "error": error,
                 "stable": int(stable)})
    print(f"{solver:24s} {knob}={value:<8} dt={dt:.3g}: "
          + (f"{wall / TIME:.4g} s/s, error {error:.3g}" if stable else "unstable"), flush=True)


for preconditioner in ("none", "jacobi"):
    for k in (1, 2, 4, 8, 16, 32, 64, 128):
        point(f"implicit_euler/{preconditioner}", "iterations", k,
              implicit + [f'integrator.preconditioner="{preconditioner}"',
                          "integrator.tolerance=1e-14", f"integrator.max_iterations={k}"], FRAME)
# The translation step without levels, neither, and both with 4 translation levels (the default;
# as many as the grid holds: 3 at 24²).
for translation, levels, name in ((1, 0, "vbd"), (0, 0, "vbd/translation_0"),
                                  (1, 4, "vbd/levels_4")):
    for sweeps in (1, 2, 5, 10, 20, 50, 100):
        point(name, "sweeps", sweeps,
              ['integrator.method="vbd"', f"integrator.dt={FRAME!r}",
               f"integrator.iterations={sweeps}", f"integrator.translation_sweeps={translation}",
               f"integrator.translation_levels={levels}"],
              FRAME)
for method, steps in (("symplectic_euler", (4e-4, 2e-4, 1e-4)), ("verlet", (4e-4, 2e-4)),
                      ("rk4", (8e-4, 4e-4))):
    for dt in steps:
        point(method, "dt", dt, [f'integrator.method="{method}"', f"integrator.dt={dt!r}"], dt)

table = os.path.join(OUT, f"pareto_{LABEL}.csv")
with open(table, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)
print("wrote", table)

script = f"""
set terminal pngcairo size 1200,750 enhanced font ',11'
set output '{os.path.join(OUT, f"pareto_{LABEL}.png")}'
set datafile separator ','
set logscale xy
set format x '10^{{%L}}'
set format y '10^{{%L}}'
set xlabel 'wall time per simulated second [s/s] (CPU float, 2 threads; 1 = real time)'
set ylabel 'position RMS error after 1 s / cloth diagonal'
set title '{LABEL}: against backward Euler at 1/60 s converged to 1e-10' noenhanced
set key outside right noenhanced
set grid
set arrow from 1, graph 0 to 1, graph 1 nohead dt 2 lc rgb '#888888'
plot for [s in 'implicit_euler/none implicit_euler/jacobi vbd vbd/translation_0 vbd/levels_4 symplectic_euler verlet rk4'] \\
    '{table}' using (strcol(1) eq s && $7 == 1 ? $5 : 1/0):6 with linespoints pt 7 title s
"""
try:
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print("wrote", os.path.join(OUT, f"pareto_{LABEL}.png"))
except (OSError, subprocess.CalledProcessError) as e:
    print("no plot:", e)
