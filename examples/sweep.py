#!/usr/bin/python3
"""Stiffness sweep: how far a sheet held along two opposite edges sags under its own weight, as
its membrane stiffness (material.stretch) goes over five decades.

A 1 m square of cotton hangs between two pinned edges, starting flat at its rest size, and is
stepped by implicit Euler until it is still. Its sag is the drop of its centre. Beside each
run's sag the plot draws the shallow cable's closed form (a strip of weight w = rho*g per unit
area and stiffness Y per unit width across a span L, its sides free): parabolic shape, tension
H = w L^2 / (8 delta), elongation 8 delta^2 / (3 L^2) per unit length, so
delta = L (3 w L / (64 Y))^(1/3): the sag falls as Y^(-1/3).

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep.py [--out docs/sweep.png]
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed: the plot goes to a PNG file
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import clothsim  # noqa: E402

G = 9.81  # [m/s^2]
SPAN = 1.0  # [m] between the pinned edges
DENSITY = 0.150  # [kg/m^2] cotton (docs/physics.md, "Presets")


def sheet(n: int, stretch: float) -> dict:
    """The scene: an n x n sheet in the x-z plane, its edges j = 0 and j = n-1 pinned."""
    return {
        "name": f"sweep_{stretch:g}",
        "cloth": {"resolution": [n, n], "size": [SPAN, SPAN], "origin": [-SPAN / 2, 1.0, 0.0],
                  "u_axis": [1, 0, 0], "v_axis": [0, 0, 1]},
        # Shear in proportion, so that the sheet's stiffness is one number; heavy air damping
        # only shortens the way to rest, where drag is zero and the sag does not depend on it.
        "material": {"preset": "cotton", "stretch": stretch, "shear": 0.4 * stretch,
                     "air_damping": 20.0},
        "pins": [[i, j] for j in (0, n - 1) for i in range(n)],
        "integrator": {"method": "implicit_euler", "dt": 0.01, "preconditioner": "multigrid",
                       "max_iterations": 400},
    }


def settled_sag(n: int, stretch: float, max_steps: int = 5000) -> float:
    """The centre's drop [m] once no vertex moves faster than 10 um/s."""
    sim = clothsim.Simulation(sheet(n, stretch))
    centre = (n // 2) * n + n // 2  # row k = j*nu + i of vertex (n/2, n/2)
    y0 = sim.positions[centre, 1]
    while sim.steps < max_steps:
        sim.step(50)
        if np.abs(sim.velocities).max() < 1e-5:
            break
    else:
        print(f"stretch {stretch:g}: not at rest after {max_steps} steps", file=sys.stderr)
    return y0 - sim.positions[centre, 1]


def cable_sag(stretch: np.ndarray) -> np.ndarray:
    return SPAN * (3 * DENSITY * G * SPAN / (64 * stretch)) ** (1 / 3)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="sweep.png", help="the PNG to write (default sweep.png)")
    parser.add_argument("--points", type=int, default=11, help="stiffnesses, log-spaced")
    parser.add_argument("--grid", type=int, default=17, help="vertices along each side (odd)")
    args = parser.parse_args()

    stretch = np.logspace(1.5, 6.5, args.points)  # [N/m]; cotton is 261
    sag = np.array([settled_sag(args.grid, y) for y in stretch])
    for y, d, c in zip(stretch, sag, cable_sag(stretch)):
        print(f"stretch {y:10.4g} N/m   sag {1e3 * d:8.3f} mm   shallow cable {1e3 * c:8.3f} mm")
    slope = np.polyfit(np.log(stretch[-4:]), np.log(sag[-4:]), 1)[0]
    print(f"log-log slope over the stiffest four: {slope:.3f} (cable: -1/3)")

    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    ax.loglog(stretch, 1e3 * sag, "o-", label=f"clothsim, {args.grid}x{args.grid} implicit Euler")
    ax.loglog(stretch, 1e3 * cable_sag(stretch), "--",
              label=r"shallow cable $L\,(3wL/64Y)^{1/3}$")
    ax.axvline(261, color="0.6", lw=0.8)
    ax.text(261 * 1.15, 1e3 * sag.min() * 1.1, "cotton", color="0.4")
    ax.set_xlabel("membrane stiffness material.stretch Y [N/m]")
    ax.set_ylabel("sag of the centre [mm]")
    ax.set_title("1 m of cotton pinned along two edges, at rest")
    ax.grid(True, which="both", lw=0.3)
    ax.legend()
    fig.tight_layout()
    out = pathlib.Path(args.out)
    fig.savefig(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
