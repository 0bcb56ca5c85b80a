"""Making, stepping and dropping a Simulation 10,000 times leaks nothing: the resident set size
(/proc/self/statm) after the cycles is within a bound far below one solver per cycle."""
import gc
import os
import warnings

import clothsim

CYCLES = 10_000
# A 12 x 12 cloth: its solver holds ~20 kB, so one leaked per cycle grows the process by ~200 MB
# (measured by leaking it on purpose: 57 MiB before the cycles, 260 MiB after). Allocators keep
# some freed memory, hence the allowance of 16 MB; any leak of 1.7 kB or more per cycle fails.
ALLOWED_GROWTH = 16 << 20


def resident_bytes() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def cycle(path):
    sim = clothsim.Simulation(path, set={"cloth.resolution": [12, 12]})
    sim.step(3)
    sim.set_velocities(sim.velocities)
    return sim.positions[0, 1] + sim.energy().total


def test_no_leak_over_ten_thousand_cycles(root):
    path = root / "scenes/hanging.json"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning per cycle would itself grow the process
        for _ in range(500):  # the allocator's pools and Python's caches reach their size
            cycle(path)
        gc.collect()
        before = resident_bytes()
        for _ in range(CYCLES):
            cycle(path)
        gc.collect()
        after = resident_bytes()
    print(f"resident set: {before / 2**20:.1f} MiB before, {after / 2**20:.1f} MiB after "
          f"{CYCLES} cycles")
    assert after - before < ALLOWED_GROWTH, (before, after)
