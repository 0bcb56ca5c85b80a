// The Python module's docstrings, longer than a line: what `help(clothsim)` shows.
#pragma once

namespace cloth::python::doc {

inline constexpr const char* kModule = R"doc(clothsim: the cloth simulator's solvers from Python.

A ``Simulation`` loads a scene (a JSON file, or the same document as a dict) with the checks and
overrides of ``clothsim run``, makes a CPU or GPU solver for it and steps it; its state comes out
and goes in as ``(N, 3)`` float64 numpy arrays, one row per vertex ``k = j*nu + i``.

    import clothsim
    sim = clothsim.Simulation("scenes/hanging.json", set={"material.stretch": 1e4})
    sim.step(1000)
    sag = sim.positions[:, 1].min()

The physics is the executable's, bit for bit: ``sim.step(n)`` then ``sim.positions`` gives the
numbers ``clothsim run SCENE --steps n --out-csv FILE`` writes, on the same backend and precision.

Errors: ``SceneError`` (a ``ValueError``) for an invalid scene, with ``.file``, ``.key`` and
``.reason``; ``UnstableError`` when a step leaves physics, with ``.step`` and ``.suggested_dt``;
``GpuUnavailableError`` when ``backend="gpu"`` has no OpenGL 4.3 context. The environment
variables of ``clothsim`` (``CLOTH_CPU_ISA``, ``CLOTH_WORKGROUP``, ``CLOTH_SHADER_DIR``,
``CLOTH_EGL_DEVICE``) tune the backends here as they do there.)doc";

inline constexpr const char* kSimulation = R"doc(A cloth simulation: one scene, one solver.

The Python object owns the solver; it is freed (with its GPU buffers) when the object is. A
``Simulation`` is not thread-safe: use each from one thread, and a GPU one from the thread that
made it (its OpenGL context is current there).)doc";

inline constexpr const char* kInit = R"doc(Loads ``scene`` and makes its solver.

Args:
    scene: a scene file's path (``str``, ``bytes`` or ``os.PathLike``: its ``os.fsencode``
        bytes, UTF-8 or not; a NUL in it is a ``ValueError``), or the scene document as a dict
        (the JSON file's content, e.g. ``json.load``'s result). Validated as ``clothsim run``
        validates a file (docs/design.md §4): unknown keys, out-of-range values and missing ones
        raise ``SceneError``.
    backend: ``"cpu"`` (the default), ``"gpu"`` (OpenGL compute shaders, in float) or
        ``"auto"`` (the GPU on a hardware OpenGL device, else the CPU).
    precision: ``"double"`` (the CPU's default) or ``"float"``; the GPU computes in float, so
        ``backend="gpu", precision="double"`` is refused.
    integrator: an integrator method, e.g. ``"vbd"``: the same as
        ``set={"integrator.method": "vbd"}``, applied before ``set``.
    threads: CPU threads (default: one per core for cloths of 4096+ vertices, else 1).
    set: overrides ``{"KEY.PATH": value}``, each ``clothsim run --set KEY.PATH=JSON`` with the
        value written as JSON: ``{"material.stretch": 1e6, "cloth.resolution": [32, 32],
        "colliders.1.radius": 0.4}``. Applied in order, and validated with the file.

Raises:
    SceneError: the scene or an override is invalid (``.file``, ``.key``, ``.reason``).
    ValueError: a bad ``backend``, ``precision`` or ``threads``, or a bad value of one of the
        environment variables.
    GpuUnavailableError: ``backend="gpu"`` and no OpenGL 4.3 context could be made.

Warns:
    RuntimeWarning: ``integrator.dt`` is beyond the integrator's predicted stability bound
        (``clothsim run`` prints the same warning).
    UserWarning: a key set twice (by ``integrator`` and ``set``, or in both spellings
        ``colliders.1`` and ``colliders[1]``); the later value is kept.)doc";

inline constexpr const char* kStep = R"doc(Advances ``n`` steps of ``dt`` (default 1).

Checked as ``clothsim run`` checks a run (docs/design.md §2): every step by the solver (the GPU's
every few steps), and the springs' strain against ``max_strain`` every 1000 steps and at the end
of the call, which reads the state (``positions``'s cost): many small calls cost more than one
large one. Ctrl+C stops a long call between runs of 1000 steps.

Raises:
    UnstableError: a step became unstable; the simulation stopped there (``.step``).
    ValueError: ``n`` < 0.)doc";

inline constexpr const char* kPositions = R"doc(The vertices' positions [m], a new ``(N, 3)``
float64 array, row ``k = j*nu + i`` for vertex ``(i, j)``, N = nu*nv.

A copy, not a view: each backend keeps its state in its own layout (the CPU in separate x, y and z
arrays in float or double, the GPU in vec4 buffers on the device), so every read copies it out
into a new array that the simulation never touches again. Changing the array changes nothing:
write with ``set_positions``. ``float`` solvers' values are their floats, exactly.)doc";

inline constexpr const char* kVelocities = R"doc(The vertices' velocities [m/s], a new
``(N, 3)`` float64 array laid out as ``positions``: a copy, read from the solver each time.)doc";

inline constexpr const char* kSetPositions = R"doc(Replaces every vertex's position [m].

Args:
    positions: an array (or nested lists) of shape ``(N, 3)``, N = nu*nv, rows ``k = j*nu + i``,
        of any float or integer dtype (taken as float64; a float solver rounds to float).

The velocities and the time stay. A pinned vertex is held where it is written. Like the viewer's
backend switch, a written state starts afresh: implicit Euler's solver and VBD start from it
without their last step's history.

Raises:
    ValueError: another shape (the message names the expected one), a non-real dtype, or a value
        that is not finite.)doc";

inline constexpr const char* kSetVelocities = R"doc(Replaces every vertex's velocity [m/s].

Args:
    velocities: as ``set_positions``'s ``positions``: shape ``(N, 3)``, real numbers.

Raises:
    ValueError: another shape (the message names the expected one), a non-real dtype, or a value
        that is not finite.)doc";

inline constexpr const char* kPin = R"doc(Pins vertex ``(i, j)`` where it is now, at rest.

Negative indices count from the end, as in a scene's ``pins`` (``-1``: the last). From the next
step on, the vertex stays there. Raises ``IndexError`` outside the grid.)doc";

inline constexpr const char* kUnpin = R"doc(Releases vertex ``(i, j)``: it moves on from where it
is (a scene's pin included). Negative indices count from the end. Raises ``IndexError`` outside
the grid; a vertex not pinned stays free.)doc";

inline constexpr const char* kEnergy = R"doc(The energy of a state [J], with the masses and the
stiffnesses the solvers use (read-only). ``total`` stays constant or falls without wind and with
damping (docs/design.md §6).)doc";

inline constexpr const char* kEnergyMethod = R"doc(The energy of the state now: an ``Energy``
(kinetic, spring, gravity, bending, potential, total) [J].)doc";

inline constexpr const char* kMaxStrain = R"doc(The largest relative stretch ``(|d| - L)/L`` over
the structural springs now (0 without structural springs).)doc";

inline constexpr const char* kLargestStrain = R"doc(The spring of largest ``||d| - L|/L`` over
every modelled family now, as ``(strain, (i, j), (i, j))``: the strain and its two vertices.
This is what ``max_strain`` limits.)doc";

inline constexpr const char* kSolveStats = R"doc(implicit_euler's conjugate-gradient solves since
the simulation was made (all zero for the other integrators). A solve that reaches
``integrator.max_iterations`` is a miss: the step goes on with its last iterate.)doc";

inline constexpr const char* kSolveStatsProperty = R"doc(implicit_euler's linear solves so far,
a ``SolveStats`` copy (``clothsim run`` warns when ``misses`` > 0).)doc";

inline constexpr const char* kStepControlStats = R"doc(The step control's work since the
simulation was made (all zero unless the scene sets ``integrator.max_step_strain``): a step that
stretches a structural spring by more than that fraction of its rest length is taken again as
two of half the step, down to ``dt / 16``.)doc";

inline constexpr const char* kStepControlStatsProperty = R"doc(The step control's work so far, a
``StepControlStats`` copy.)doc";

inline constexpr const char* kStableDt = R"doc(The integrator's predicted stability bound for the
scene [s] (``clothsim validate`` prints it): ``inf`` where any step is stable, ``0`` where none
is (explicit Euler without damping).)doc";

}  // namespace cloth::python::doc
