"""Errors reach Python as exceptions carrying what the command line prints: SceneError with the
file, key path and reason; UnstableError with the step and the suggested time step."""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import clothsim


def scene_doc(root, name="hanging"):
    with open(root / "scenes" / f"{name}.json") as f:
        return json.load(f)


def test_missing_file(root):
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes" / "no_such.json")
    assert e.value.file.endswith("no_such.json")
    assert e.value.key == ""
    assert e.value.reason == "no such file"
    assert isinstance(e.value, ValueError)


def test_any_path_the_file_system_takes_loads(root, tmp_path):
    """A path is its bytes (os.fsencode): str, bytes or PathLike, UTF-8 or not. A non-UTF-8 name
    raised a bare RuntimeError (the path was cast to a C++ string as UTF-8)."""
    raw = bytes(tmp_path) + b"/sc\xe9ne.json"
    with open(root / "scenes" / "spring.json", "rb") as f, open(raw, "wb") as out:
        out.write(f.read())
    for path in (raw, os.fsdecode(raw), type(tmp_path)(os.fsdecode(raw))):
        assert clothsim.Simulation(path).steps == 0
    missing = bytes(tmp_path) + b"/no\xff.json"
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(missing)
    assert os.fsencode(e.value.file) == missing  # the file as os.fsdecode gives it
    assert "no\\xff.json" in str(e.value)  # the message writes the byte as Python does
    assert e.value.reason == "no such file"


def test_an_embedded_null_byte_is_refused_as_open_refuses_it(root):
    """The path was cut at the NUL and the error named another file ("sc")."""
    for path in ("sc\x00ene.json", b"sc\x00ene.json"):
        with pytest.raises(ValueError, match="embedded null byte") as e:
            clothsim.Simulation(path)
        assert not isinstance(e.value, clothsim.SceneError)


def test_bad_value_in_a_dict_names_its_key_path(root):
    doc = scene_doc(root)
    doc["cloth"]["size"] = [1.0, -2.0]
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(doc)
    assert e.value.file == "<dict>"
    assert e.value.key.startswith("cloth.size")
    assert "> 0" in e.value.reason
    assert str(e.value) == f"<dict>: {e.value.key}: {e.value.reason}"


def test_unknown_key_is_an_error(root):
    doc = scene_doc(root)
    doc["integrator"]["dtt"] = 0.1
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(doc)
    assert e.value.key == "integrator.dtt"


def test_the_same_message_as_validate(root, exe, tmp_path):
    """The message is the command line's (stderr of `clothsim validate`) word for word."""
    doc = scene_doc(root)
    doc["material"]["stretch"] = -5
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(path)
    cli = subprocess.run([exe, "validate", path], capture_output=True, text=True, timeout=60)
    assert cli.returncode == 2
    assert str(e.value) in cli.stderr
    assert (e.value.file, e.value.key) == (str(path), "material.stretch")


def test_override_is_validated_like_the_file(root):
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes/hanging.json", set={"integrator.dt": -1})
    assert e.value.key == "integrator.dt"
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes/hanging.json", integrator="leapfrog")
    assert e.value.key == "integrator.method"
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes/hanging.json", set={"cloth.colour": "red"})
    assert e.value.key == "cloth.colour"
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes/hanging.json", set={"springs.bend": math.nan})
    assert e.value.key == "springs.bend" and "JSON" in e.value.reason
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes/hanging.json", set={"": 1})
    assert e.value.key == "set" and "empty key" in e.value.reason


def test_overrides_apply(root):
    sim = clothsim.Simulation(root / "scenes/hanging.json", integrator="vbd",
                              set={"cloth.resolution": [7, 4], "integrator.dt": 1e-3})
    assert sim.shape == (7, 4) and sim.dt == 1e-3 and sim.integrator == "vbd"
    # numpy's scalars and arrays are values too
    sim = clothsim.Simulation(root / "scenes/hanging.json",
                              set={"cloth.resolution": np.array([5, 6]), "integrator.dt": np.float32(1e-4),
                                   "material.bend": np.int64(0)})
    assert sim.shape == (5, 6) and sim.dt == float(np.float32(1e-4))
    with pytest.raises(clothsim.SceneError) as e:
        clothsim.Simulation(root / "scenes/hanging.json", set={"integrator.dt": object()})
    assert e.value.key == "integrator.dt" and "not a JSON value" in e.value.reason


def test_a_key_set_twice_keeps_the_later_and_warns(root):
    with pytest.warns(UserWarning, match="integrator.method"):
        sim = clothsim.Simulation(root / "scenes/hanging.json", integrator="vbd",
                                  set={"integrator.method": "verlet"})
    assert sim.integrator == "verlet"


@pytest.mark.parametrize("kwargs,key", [
    ({"backend": "cuda"}, "backend"), ({"precision": "half"}, "precision"),
    ({"threads": 0}, "threads"), ({"backend": "gpu", "precision": "double"}, "--precision"),
])
def test_bad_options_are_value_errors(root, kwargs, key):
    with pytest.raises(ValueError, match=key) as e:
        clothsim.Simulation(root / "scenes/hanging.json", **kwargs)
    assert not isinstance(e.value, clothsim.SceneError)


def test_bad_environment_variables_are_value_errors(root, monkeypatch):
    monkeypatch.setenv("CLOTH_CPU_ISA", "sse9")
    with pytest.raises(ValueError, match="CLOTH_CPU_ISA: expected") as e:
        clothsim.Simulation(root / "scenes/hanging.json")
    assert not isinstance(e.value, clothsim.SceneError)


def test_a_bad_gpu_device_is_a_value_error(gpu, root):
    # The process's GPU settings are read once, at its first Simulation: a new process.
    code = ("import clothsim\n"
            "try:\n"
            f"    clothsim.Simulation({str(root / 'scenes/hanging.json')!r}, backend='gpu')\n"
            "except clothsim.SceneError:\n"
            "    print('SceneError')\n"
            "except ValueError as e:\n"
            "    print('ValueError', e)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                          env={**os.environ, "CLOTH_EGL_DEVICE": "999"})
    assert done.stdout.startswith("ValueError CLOTH_EGL_DEVICE: "), done.stdout + done.stderr


def test_wrong_argument_types(root):
    with pytest.raises(TypeError):
        clothsim.Simulation(42)
    with pytest.raises(TypeError):
        clothsim.Simulation(root / "scenes/hanging.json", set=[("integrator.dt", 1e-3)])


UNSTABLE = {"cloth.resolution": [8, 8], "integrator.dt": 0.01}  # 7x the bound


def test_instability_raises_with_the_step_and_a_stable_dt(root, exe):
    with pytest.warns(RuntimeWarning, match="beyond"):
        sim = clothsim.Simulation(root / "scenes/hanging.json", set=UNSTABLE)
    with pytest.raises(clothsim.UnstableError) as e:
        sim.step(500)
    err = e.value
    assert 1 <= err.step <= err.last_step == sim.steps < 500
    assert err.time == pytest.approx(err.step * 0.01)
    assert err.reason
    assert err.suggested_dt == pytest.approx(err.stable_dt / 2)
    assert 0 < err.suggested_dt < 0.01
    assert err.stable_dt == sim.stable_dt
    assert "integrator.dt" in err.advice
    # The command line says the same.
    cli = subprocess.run([exe, "run", root / "scenes/hanging.json", "--steps", "500", "--quiet"]
                         + [a for k, v in UNSTABLE.items() for a in ("--set", f"{k}={json.dumps(v)}")],
                         capture_output=True, text=True, timeout=60)
    assert cli.returncode == 3
    assert f"unstable at step {err.step} " in cli.stderr
    assert err.reason in cli.stderr and err.advice in cli.stderr


def test_a_torn_vbd_sheet_suggests_the_step_its_sweeps_need(root):
    """vbd without the translation's levels tears where its sweeps do not carry the landing's
    tension across the sheet: the suggested step gives it iterations / (13 N) s, the rate at
    which dropped sheets held."""
    sim = clothsim.Simulation(root / "scenes/drape.json", precision="float", set={
        "integrator": {"method": "vbd", "dt": 1 / 60, "iterations": 10, "translation_levels": 0},
        "cloth.resolution": [128, 128]})
    with pytest.raises(clothsim.UnstableError) as e:
        sim.step(60)
    assert "strain" in e.value.reason
    assert e.value.suggested_dt == pytest.approx(10 / (13 * 128))
    assert "sweeps" in e.value.advice and "integrator.iterations" in e.value.advice


@pytest.mark.filterwarnings("ignore:.*beyond")
def test_instability_on_the_gpu_names_a_step_range(gpu, root):
    sim = clothsim.Simulation(root / "scenes/hanging.json", backend="gpu", set=UNSTABLE)
    with pytest.raises(clothsim.UnstableError) as e:
        sim.step(2000)
    assert 1 <= e.value.step <= e.value.last_step <= sim.steps
    assert e.value.suggested_dt < 0.01


@pytest.mark.filterwarnings("ignore:.*beyond")
def test_writing_a_state_goes_on_after_instability(root):
    sim = clothsim.Simulation(root / "scenes/hanging.json", set=UNSTABLE)
    start = sim.positions
    with pytest.raises(clothsim.UnstableError):
        sim.step(500)
    sim.set_positions(start)
    sim.set_velocities(0 * start)
    sim.step(1)


def test_a_signal_stops_a_long_step_between_its_runs_of_steps(root):
    """step() holds the interpreter's lock, but checks for signals between runs of at most
    0.1 s simulated: a SIGALRM whose handler raises (as Ctrl+C's does) ends step(10**9) with the
    steps done so far kept."""
    import signal
    import time

    def interrupt(signum, frame):
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGALRM, interrupt)
    s = clothsim.Simulation(root / "scenes" / "hanging.json")
    start = time.monotonic()
    signal.setitimer(signal.ITIMER_REAL, 0.3)
    try:
        with pytest.raises(KeyboardInterrupt):
            s.step(10**9)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert time.monotonic() - start < 10
    assert 0 < s.steps < 10**9
    run = min(1000, math.floor(0.1 / s.dt * (1 + 1e-9)))  # solver/instability.h strainCheckSteps
    assert s.steps % run == 0


def test_a_gpu_simulation_called_from_another_thread_says_which_thread(gpu, root):
    """EGL binds a context to one thread: a GPU Simulation called from another thread raises a
    RuntimeError that says so (not GpuUnavailableError: the GPU is there), and goes on working on
    the thread that made it."""
    import threading

    sim = clothsim.Simulation(root / "scenes/spring.json", backend="gpu")
    sim.step(1)
    raised = []

    def other():
        try:
            sim.step(1)
        except Exception as e:  # the assertion runs on the main thread
            raised.append(e)

    t = threading.Thread(target=other)
    t.start()
    t.join()
    assert len(raised) == 1 and type(raised[0]) is RuntimeError, raised
    assert "thread" in str(raised[0])
    sim.step(1)
    assert sim.steps == 2


def test_a_step_count_past_the_counter_is_a_value_error(root):
    """step(n) adds n to the steps done: n that would count past 2^63 - 1 is refused, not
    wrapped round to a negative end that returns at once."""
    sim = clothsim.Simulation(root / "scenes/spring.json")
    sim.step(1)
    with pytest.raises(ValueError, match="2\\^63"):
        sim.step(2**63 - 1)
    assert sim.steps == 1
