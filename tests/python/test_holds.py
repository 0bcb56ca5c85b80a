"""bench/holds.py: a sheet that its solver holds stays below max_strain in every frame, and one
stepped with too little work tears and says in which frame (exit status 1)."""
import re
import subprocess
import sys


def holds(root, *args):
    return subprocess.run([sys.executable, root / "bench" / "holds.py",
                           root / "scenes" / "realtime.json", *args],
                          capture_output=True, text=True, timeout=300)


def test_the_shipped_solver_holds_the_realtime_sheet(root):
    done = holds(root, "32", "1")
    assert done.returncode == 0, done.stdout + done.stderr
    found = re.search(r"largest strain ([0-9.]+) \(frame (\d+)\) over 60 frames", done.stdout)
    assert found, done.stdout
    assert 0.05 < float(found[1]) < 1.0  # it stretches as it lands, and holds


def test_one_sweep_without_its_accelerations_tears_the_sheet(root):
    done = holds(root, "64", "1.5", "--set", "integrator.iterations=1",
                 "--set", "integrator.translation_levels=0", "--set", "integrator.chebyshev_rho=0")
    assert done.returncode == 1, done.stdout + done.stderr
    assert re.search(r"(unstable|torn) in frame \d+", done.stdout), done.stdout


def test_a_bad_override_names_the_key_and_exits_2(root):
    done = holds(root, "32", "1", "--set", "integrator.iterations=0")
    assert done.returncode == 2
    assert "integrator.iterations" in done.stderr
