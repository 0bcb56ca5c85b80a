"""Fixtures of the Python module's tests (run by ctest as the test `python`, label python).

The module is imported from PYTHONPATH (build/python); the command-line executable the parity
tests compare with is $CLOTH_EXE, else build/clothsim beside the sources.
"""
import os
import pathlib

import pytest

import clothsim

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT


@pytest.fixture(scope="session")
def exe() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("CLOTH_EXE", ROOT / "build" / "clothsim"))
    if not path.is_file():
        pytest.fail(f"the clothsim executable is not at {path} (build it, or set CLOTH_EXE)")
    return path


@pytest.fixture(scope="session")
def gpu() -> None:
    """Skips a GPU test where no OpenGL 4.3 context can be made, unless CLOTH_REQUIRE_GPU=1
    (as CI sets, docs/design.md §6): then it fails."""
    try:
        clothsim.Simulation(ROOT / "scenes" / "hanging.json", backend="gpu")
    except clothsim.GpuUnavailableError as e:
        if os.environ.get("CLOTH_REQUIRE_GPU") == "1":
            pytest.fail(f"CLOTH_REQUIRE_GPU=1 and the GPU backend is unavailable: {e}")
        pytest.skip(f"no GPU context: {e}")
