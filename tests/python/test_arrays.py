"""The state as numpy arrays: shape, dtype, copies, writes, pins and what is measured on it."""
import numpy as np
import pytest

import clothsim


@pytest.fixture
def sim(root):
    # A 5 x 3 grid: rows k = j*nu + i tell a transposed layout from the right one.
    return clothsim.Simulation(root / "scenes/hanging.json", set={"cloth.resolution": [5, 3]})


def test_arrays_are_n_by_3_float64(sim):
    for a in (sim.positions, sim.velocities):
        assert a.shape == (15, 3)
        assert a.dtype == np.float64
        assert a.flags.c_contiguous


def test_rows_follow_the_grid_index(sim):
    """Row k = j*nu + i is vertex (i, j): at rest, i runs along the u axis (x), j along v (z)."""
    p = sim.positions.reshape(3, 5, 3)  # [j, i, xyz]
    assert np.all(np.diff(p[:, :, 0], axis=1) > 0)
    assert np.all(np.diff(p[:, :, 2], axis=0) > 0)
    np.testing.assert_allclose(p[0, :, 0], np.linspace(-0.5, 0.5, 5))


def test_arrays_are_copies(sim):
    p = sim.positions
    p[:] = 99.0
    assert not np.any(sim.positions == 99.0)
    assert sim.positions is not sim.positions


def test_set_positions_and_velocities_round_trip(sim):
    p = sim.positions + np.array([0.0, 0.25, 0.0])
    v = np.arange(45, dtype=np.float64).reshape(15, 3) * 1e-3
    sim.set_positions(p)
    sim.set_velocities(v)
    np.testing.assert_array_equal(sim.positions, p)
    np.testing.assert_array_equal(sim.velocities, v)
    assert sim.steps == 0 and sim.time == 0


def test_set_accepts_lists_and_integer_arrays(sim):
    sim.set_velocities(np.zeros((15, 3), dtype=np.int32))
    sim.set_positions(sim.positions.tolist())
    sim.set_positions(sim.positions.astype(np.float32))


@pytest.mark.parametrize("bad", [
    np.zeros((14, 3)), np.zeros((15, 2)), np.zeros(45), np.zeros((15, 3, 1)), np.zeros((3, 15)),
])
def test_wrong_shape_is_a_value_error_naming_the_expected_shape(sim, bad):
    with pytest.raises(ValueError, match=r"expected an array of shape \(15, 3\)"):
        sim.set_positions(bad)
    with pytest.raises(ValueError, match=r"velocities: expected an array of shape \(15, 3\)"):
        sim.set_velocities(bad)


@pytest.mark.parametrize("bad", [
    np.zeros((15, 3), dtype=np.complex128), np.full((15, 3), "1.0"), np.zeros((15, 3), bool),
    np.empty((15, 3), dtype=object),
])
def test_wrong_dtype_is_a_value_error(sim, bad):
    with pytest.raises(ValueError, match=r"real numbers, got dtype"):
        sim.set_positions(bad)


def test_non_finite_is_a_value_error_and_changes_nothing(sim):
    before = sim.positions
    bad = sim.positions
    bad[7, 1] = np.nan
    with pytest.raises(ValueError, match="row 7 is not finite"):
        sim.set_positions(bad)
    np.testing.assert_array_equal(sim.positions, before)


def test_not_an_array_is_a_value_error(sim):
    with pytest.raises(ValueError, match=r"shape \(15, 3\)"):
        sim.set_positions("positions")


def test_pinned_vertex_stays_and_unpinned_falls(root):
    sim = clothsim.Simulation(root / "scenes/hanging.json", set={"cloth.resolution": [6, 6]})
    sim.pin(2, -1)  # vertex (2, 5): -1 counts from the end
    k = 5 * 6 + 2
    held = sim.positions[k].copy()
    sim.step(200)
    np.testing.assert_array_equal(sim.positions[k], held)
    np.testing.assert_array_equal(sim.velocities[k], 0.0)
    sim.unpin(0, 0)  # a scene pin, released
    y0 = sim.positions[0, 1]
    sim.step(200)
    assert sim.positions[0, 1] < y0 - 1e-3
    np.testing.assert_array_equal(sim.positions[k], held)


def test_pin_outside_the_grid_is_an_index_error(sim):
    with pytest.raises(IndexError, match=r"\(5, 0\) is outside the 5 x 3 grid"):
        sim.pin(5, 0)
    with pytest.raises(IndexError):
        sim.unpin(0, -4)


def test_time_steps_and_properties(sim):
    assert (sim.steps, sim.time) == (0, 0.0)
    sim.step()
    sim.step(9)
    assert sim.steps == 10
    assert sim.time == pytest.approx(10 * sim.dt)
    assert sim.shape == (5, 3)
    assert sim.name == "hanging"
    assert sim.integrator == "symplectic_euler"
    assert sim.backend.startswith("cpu double")
    assert 0 < sim.dt < sim.stable_dt
    assert "hanging" in repr(sim)
    with pytest.raises(ValueError):
        sim.step(-1)


def test_energy_is_lost_to_damping(root):
    """docs/design.md §6: with damping and no wind the total energy does not grow."""
    sim = clothsim.Simulation(root / "scenes/hanging.json", set={"cloth.resolution": [8, 8]})
    e0 = sim.energy()
    assert e0.kinetic == 0 and e0.spring == pytest.approx(0, abs=1e-12)
    assert e0.potential == pytest.approx(e0.gravity + e0.spring + e0.bending)
    totals = [e0.total]
    for _ in range(5):
        sim.step(100)
        totals.append(sim.energy().total)
    assert all(b <= a + 1e-12 for a, b in zip(totals, totals[1:]))
    assert sim.energy().kinetic > 0


def test_strain_and_solve_stats(root):
    sim = clothsim.Simulation(root / "scenes/hanging.json", integrator="implicit_euler",
                              set={"cloth.resolution": [8, 8], "integrator.dt": 1e-3})
    assert sim.max_strain() == pytest.approx(0, abs=1e-12)
    sim.step(20)
    strain, a, b = sim.largest_strain()
    assert 0 < strain < 0.25 and sim.max_strain() <= strain
    assert all(0 <= x < 8 for x in a + b) and a != b
    stats = sim.solve_stats
    assert stats.solves == 20 and stats.iterations >= 20 and stats.misses == 0
    assert stats.breakdowns == 0 and stats.first_breakdown_step == 0
    assert stats.last_converged
    assert clothsim.Simulation(root / "scenes/hanging.json").solve_stats.solves == 0
