"""examples/sweep.py runs and writes its plot (a small sweep: 3 stiffnesses on a 9 x 9 sheet)."""
import os
import subprocess
import sys


def test_sweep_writes_a_png(root, tmp_path):
    out = tmp_path / "sweep.png"
    done = subprocess.run(
        [sys.executable, root / "examples" / "sweep.py", "--out", out, "--points", "3",
         "--grid", "9"], capture_output=True, text=True, timeout=120,
        env={**os.environ, "MPLCONFIGDIR": str(tmp_path)})
    assert done.returncode == 0, done.stderr
    assert "slope" in done.stdout and "not at rest" not in done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
