"""The physics through Python is the command line's, bit for bit: the same scene, overrides,
steps, backend and precision give the numbers `clothsim run --out-csv` writes.

The CSV prints each number so that it round-trips (%.17g from double solvers, %.9g from float
ones, docs/design.md §5): parsed back (through float32 for a float solver) it is the solver's
value exactly, so the comparison is exact, not to a tolerance.
"""
import csv
import json
import subprocess

import numpy as np
import pytest

import clothsim

# (scene, overrides, steps): a material under symplectic Euler; the seed's per-vertex cloth with
# wind, a plane and a sphere under explicit Euler; an implicit Euler drape over a sphere.
CASES = [
    ("scenes/hanging.json", {}, 300),
    ("tests/data/good_scene.json", {"integrator.dt": 2e-4}, 250),
    ("scenes/drape.json",
     {"cloth.resolution": [12, 10], "integrator.method": "implicit_euler", "integrator.dt": 4e-3},
     40),
]


def run_cli(exe, root, tmp_path, scene, overrides, steps, backend, precision):
    out = tmp_path / "state.csv"
    args = [exe, "run", root / scene, "--steps", str(steps), "--backend", backend,
            "--out-csv", out, "--quiet"]
    if precision:
        args += ["--precision", precision]
    for key, value in overrides.items():
        args += ["--set", f"{key}={json.dumps(value)}"]
    done = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["i", "j", "x", "y", "z", "vx", "vy", "vz"]
    return rows[1:]


def parsed(rows, single: bool):
    values = np.array([[float(v) for v in row[2:]] for row in rows])
    # %.9g round-trips a float, not a double: the nearest float is the solver's value.
    return values.astype(np.float32).astype(np.float64) if single else values


def check_parity(exe, root, tmp_path, scene, overrides, steps, backend, precision):
    rows = run_cli(exe, root, tmp_path, scene, overrides, steps, backend, precision)
    sim = clothsim.Simulation(root / scene, backend=backend, precision=precision, set=overrides)
    sim.step(steps)
    nu, nv = sim.shape
    assert [(int(r[0]), int(r[1])) for r in rows] == [(i, j) for j in range(nv) for i in range(nu)]
    single = backend == "gpu" or precision == "float"
    expected = parsed(rows, single)
    np.testing.assert_array_equal(sim.positions, expected[:, :3])
    np.testing.assert_array_equal(sim.velocities, expected[:, 3:])
    assert sim.steps == steps


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("scene,overrides,steps", CASES)
def test_cpu_matches_cli(exe, root, tmp_path, scene, overrides, steps, precision):
    check_parity(exe, root, tmp_path, scene, overrides, steps, "cpu", precision)


@pytest.mark.parametrize("scene,overrides,steps", CASES)
def test_gpu_matches_cli(gpu, exe, root, tmp_path, scene, overrides, steps):
    check_parity(exe, root, tmp_path, scene, overrides, steps, "gpu", None)


def test_steps_in_pieces_equal_one_call(root):
    """step(n) in several calls takes the same steps as one call."""
    whole = clothsim.Simulation(root / "scenes/hanging.json")
    whole.step(120)
    pieces = clothsim.Simulation(root / "scenes/hanging.json")
    for n in (1, 19, 0, 100):
        pieces.step(n)
    assert pieces.steps == whole.steps == 120
    assert pieces.time == whole.time == pytest.approx(120 * whole.dt)
    np.testing.assert_array_equal(pieces.positions, whole.positions)


def test_dict_scene_equals_file(root):
    """A scene given as a dict is the file's scene."""
    with open(root / "scenes/hanging.json") as f:
        doc = json.load(f)
    a = clothsim.Simulation(doc)
    b = clothsim.Simulation(root / "scenes/hanging.json")
    a.step(50)
    b.step(50)
    np.testing.assert_array_equal(a.positions, b.positions)
    assert a.name == b.name == "hanging"


def test_cli_and_module_find_the_same_instability(exe, root):
    """Both check the strain every 0.1 s of simulated time (333 steps of hanging.json): the same
    run is unstable in both, between the same steps. run used to check at its progress chunks'
    ends (every 360 steps here) and found this sheet, whose strain passes 0.25 for a while near
    step 1400, stable."""
    args = [str(exe), "run", str(root / "scenes" / "hanging.json"), "--steps", "3000",
            "--set", "max_strain=0.25"]
    done = subprocess.run(args, capture_output=True, text=True, timeout=120)
    assert done.returncode == 3, done.stderr
    s = clothsim.Simulation(root / "scenes" / "hanging.json", set={"max_strain": 0.25})
    with pytest.raises(clothsim.UnstableError) as e:
        s.step(3000)
    assert "unstable between steps 1333 and 1665" in str(e.value)
    assert "unstable between steps 1333 and 1665" in done.stderr
