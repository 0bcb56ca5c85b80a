# Type stubs of the compiled module clothsim (python/module.cpp), placed next to it in
# build/python/. The docstrings are the module's own: help(clothsim) shows them.
import os
from collections.abc import Mapping
from typing import Any, Literal, final

import numpy as np
import numpy.typing as npt

_Rows = npt.NDArray[np.float64]  # shape (nu*nv, 3), row k = j*nu + i

class SceneError(ValueError):
    """The scene is invalid; the same checks and message as ``clothsim run``."""

    file: str
    """The scene file, or ``"<dict>"`` for a scene given as a dict."""
    key: str
    """The key path of the offending value, e.g. ``"cloth.resolution"``; ``""`` for the whole
    document."""
    reason: str
    """What is wrong with it."""

class UnstableError(RuntimeError):
    """A step became unstable (a value not finite, a speed past max_speed, a spring strained past
    max_strain); the simulation stopped there."""

    step: int
    """The first unstable step (1-based, from the start of the simulation)."""
    last_step: int
    """``step``, or, where the backend checks every few steps (the GPU), the last step of the
    range the first bad step lies in."""
    time: float
    """The simulated time at ``step`` [s]."""
    reason: str
    """What went wrong."""
    advice: str
    """What to change, as ``clothsim run`` says it."""
    suggested_dt: float | None
    """The time step the advice suggests [s], or None where a smaller step is not the cure."""
    stable_dt: float
    """The integrator's predicted stability bound [s] (inf: any step; 0: none)."""

class GpuUnavailableError(RuntimeError):
    """``backend="gpu"`` and no OpenGL 4.3 context could be made."""

@final
class Energy:
    """The energy of a state [J]."""

    @property
    def kinetic(self) -> float: ...
    @property
    def spring(self) -> float: ...
    @property
    def gravity(self) -> float: ...
    @property
    def bending(self) -> float: ...
    @property
    def potential(self) -> float:
        """spring + gravity + bending [J]."""
    @property
    def total(self) -> float:
        """kinetic + potential [J]."""

@final
class SolveStats:
    """implicit_euler's conjugate-gradient solves (all zero for the other integrators)."""

    @property
    def solves(self) -> int: ...
    @property
    def iterations(self) -> int: ...
    @property
    def most_iterations(self) -> int: ...
    @property
    def misses(self) -> int: ...
    @property
    def first_miss_step(self) -> int: ...
    @property
    def worst_residual(self) -> float: ...
    @property
    def breakdowns(self) -> int: ...
    @property
    def first_breakdown_step(self) -> int: ...
    @property
    def last_iterations(self) -> int: ...
    @property
    def last_residual(self) -> float: ...
    @property
    def last_converged(self) -> bool: ...

@final
class StepControlStats:
    """The step control's work (all zero unless integrator.max_step_strain is set)."""

    @property
    def split(self) -> int: ...
    @property
    def rejected(self) -> int: ...
    @property
    def substeps(self) -> int: ...
    @property
    def deepest(self) -> int: ...

@final
class Simulation:
    """A cloth simulation: one scene, one solver."""

    def __init__(
        self,
        scene: str | bytes | os.PathLike[str] | os.PathLike[bytes] | Mapping[str, Any],
        *,
        backend: Literal["cpu", "gpu", "auto"] | None = None,
        precision: Literal["float", "double"] | None = None,
        integrator: str | None = None,
        threads: int | None = None,
        set: Mapping[str, Any] | None = None,
    ) -> None:
        """Loads ``scene`` (a path or a dict) with the overrides and makes its solver.

        Raises SceneError (invalid scene), ValueError (bad option), GpuUnavailableError.
        """
    def step(self, n: int = 1) -> None:
        """Advances n steps; raises UnstableError at the first unstable one."""
    @property
    def time(self) -> float:
        """Simulated time [s]."""
    @property
    def steps(self) -> int:
        """Steps done."""
    @property
    def dt(self) -> float:
        """integrator.dt [s]."""
    @property
    def shape(self) -> tuple[int, int]:
        """(nu, nv)."""
    @property
    def name(self) -> str: ...
    @property
    def integrator(self) -> str: ...
    @property
    def backend(self) -> str:
        """The solver's name, e.g. "cpu double avx512, 1 thread"."""
    @property
    def stable_dt(self) -> float:
        """The integrator's predicted stability bound [s]."""
    @property
    def positions(self) -> _Rows:
        """A new (N, 3) float64 array of the positions [m]: a copy, not a view."""
    @property
    def velocities(self) -> _Rows:
        """A new (N, 3) float64 array of the velocities [m/s]: a copy, not a view."""
    def set_positions(self, positions: npt.ArrayLike) -> None:
        """Writes the positions: shape (N, 3), real numbers, finite; else ValueError."""
    def set_velocities(self, velocities: npt.ArrayLike) -> None:
        """Writes the velocities: shape (N, 3), real numbers, finite; else ValueError."""
    def pin(self, i: int, j: int) -> None:
        """Pins vertex (i, j) where it is (negative indices count from the end)."""
    def unpin(self, i: int, j: int) -> None:
        """Releases vertex (i, j)."""
    def energy(self) -> Energy: ...
    def max_strain(self) -> float:
        """Largest (|d| - L)/L over the structural springs."""
    def largest_strain(self) -> tuple[float, tuple[int, int], tuple[int, int]]:
        """(strain, (i, j), (i, j)): the most strained spring of any family."""
    @property
    def solve_stats(self) -> SolveStats: ...
    @property
    def step_control_stats(self) -> StepControlStats: ...
