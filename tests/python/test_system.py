"""MassSpringSystem from numpy and back: every array round trips exactly, positions and velocities
are views of the system's own state (no copy), tied to its lifetime."""

import copy
import gc

import numpy as np
import pytest

import massspring as ms
from conftest import grid


def test_construction_round_trips_every_array():
    rng = np.random.default_rng(1)
    points, springs = grid(4, 3)
    n, m = len(points), len(springs)
    masses = rng.uniform(0.5, 2, n)
    stiffness = rng.uniform(10, 1000, m)
    rest = rng.uniform(0.05, 0.2, m)
    damping = rng.uniform(0, 1, m)
    s = ms.MassSpringSystem(points, springs, masses, stiffness, rest_lengths=rest,
                            damping=damping)
    assert (s.num_points, s.num_springs, s.num_pinned) == (n, m, 0)
    for got, want in ((s.rest_positions, points), (s.positions, points), (s.masses, masses),
                      (s.stiffness, stiffness), (s.rest_lengths, rest), (s.damping, damping)):
        assert got.dtype == np.float64
        assert np.array_equal(got, want)
    assert np.array_equal(s.springs, springs)
    assert np.array_equal(s.velocities, np.zeros((n, 3)))
    assert s.has_spring_damping


def test_scalar_mass_and_stiffness_and_default_rest_lengths(chain):
    assert np.array_equal(chain.masses, [1, 1, 1])
    assert np.array_equal(chain.stiffness, [100, 100])
    assert np.array_equal(chain.rest_lengths, [1, 1])  # the distances between rest positions
    assert np.array_equal(chain.damping, [0, 0]) and not chain.has_spring_damping


@pytest.mark.parametrize("dtype", [np.int8, np.int32, np.int64, np.uint16, np.uint64])
def test_any_integer_dtype_for_springs(dtype):
    s = ms.MassSpringSystem(np.eye(3), np.array([[0, 1], [1, 2]], dtype=dtype), 1.0, 1.0)
    assert np.array_equal(s.springs, [[0, 1], [1, 2]])


def test_lists_and_float32_convert_exactly():
    points32 = np.array([[0.1, 0, 0], [1, 0.3, 0]], dtype=np.float32)
    s = ms.MassSpringSystem(points32, [[0, 1]], [1, 2], [5])
    assert np.array_equal(s.positions, points32.astype(np.float64))
    assert np.array_equal(s.masses, [1.0, 2.0]) and np.array_equal(s.stiffness, [5.0])


def test_positions_and_velocities_assign_exactly(chain):
    rng = np.random.default_rng(2)
    x, v = rng.normal(size=(3, 3)), rng.normal(size=(3, 3))
    chain.positions = x
    chain.velocities = v
    assert np.array_equal(chain.positions, x) and np.array_equal(chain.velocities, v)
    chain.set_positions(x + 1)
    chain.set_velocities(v + 1)
    assert np.array_equal(chain.positions, x + 1) and np.array_equal(chain.velocities, v + 1)
    # Fortran order and strided input are read by value
    chain.positions = np.asfortranarray(x)
    assert np.array_equal(chain.positions, x)
    chain.positions = np.hstack([x, x])[:, ::2]
    assert np.array_equal(chain.positions, np.hstack([x, x])[:, ::2])


def test_positions_are_a_view_without_copy(chain):
    a, b = chain.positions, chain.velocities
    assert a.shape == (3, 3) and a.dtype == np.float64 and a.flags.c_contiguous
    assert np.shares_memory(a, chain.positions)  # both read the system's one buffer
    assert np.shares_memory(b, chain.velocities)
    assert not a.flags.owndata and not a.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        a[0, 0] = 5.0
    # the view follows the state
    chain.positions = np.full((3, 3), 7.0)
    assert np.array_equal(a, np.full((3, 3), 7.0))


@pytest.mark.parametrize("make", [ms.FastMassSpring, ms.SymplecticEuler, ms.ForwardEuler, ms.RK4,
                                  ms.BackwardEuler])
def test_views_follow_every_integrators_steps(make):
    points, springs = grid(3, 3)
    s = ms.MassSpringSystem(points, springs, 1.0, 100.0)
    s.pin(0)
    s.add_force(ms.Gravity([0, -9.8, 0]))
    x, v = s.positions, s.velocities
    solver = make()
    solver.precompute(s, 0.001)
    for _ in range(3):
        before = x.copy(), v.copy()
        assert solver.step(s).ok()
        assert np.shares_memory(x, s.positions) and np.shares_memory(v, s.velocities)
        assert np.array_equal(x, s.positions.copy())
        # the views taken before the steps see each step's state
        assert not (np.array_equal(x, before[0]) and np.array_equal(v, before[1]))
    del solver  # the views belong to the system, not to the integrator
    gc.collect()
    assert np.isfinite(x).all() and x[8, 1] < points[8, 1]


def test_a_view_keeps_its_system_alive():
    points, springs = grid(3, 2)
    s = ms.MassSpringSystem(points, springs, 1.0, 10.0)
    s.positions = points + 1
    x = s.positions
    del s
    gc.collect()
    assert np.array_equal(x, points + 1)


def test_pins_and_targets(chain):
    chain.pin(0)
    chain.pin(2, [2.0, 1.0, 0.0])
    assert chain.pinned == [0, 2] and chain.num_pinned == 2
    assert chain.is_pinned(2) and not chain.is_pinned(1) and chain.pin_row(2) == 1
    assert np.array_equal(chain.pin_targets, [[0, 0, 0], [2, 1, 0]])
    revision = chain.revision
    chain.set_pin_target(2, np.array([3.0, 0.5, -1.0]))
    assert chain.revision == revision  # free: no new revision
    assert np.array_equal(chain.pin_targets[1], [3, 0.5, -1])
    chain.unpin(0)
    assert chain.pinned == [2] and chain.revision != revision
    chain.pin(np.array([0, 1]))
    assert chain.pinned == [0, 1, 2]


def test_inverse_masses_are_zero_at_pins(chain):
    chain.masses = [1.0, 2.0, 4.0]
    assert np.array_equal(chain.inverse_masses, [1.0, 0.5, 0.25])
    chain.pin(1)
    assert np.array_equal(chain.inverse_masses, [1.0, 0.0, 0.25])
    chain.unpin(1)
    assert np.array_equal(chain.inverse_masses, [1.0, 0.5, 0.25])


def test_setters_round_trip(chain):
    chain.masses = [2.0, 3.0, 4.0]
    chain.stiffness = 50.0
    chain.rest_lengths = np.array([0.5, 0.25])
    chain.damping = [0.0, 1.5]
    assert np.array_equal(chain.masses, [2, 3, 4]) and np.array_equal(chain.stiffness, [50, 50])
    assert np.array_equal(chain.rest_lengths, [0.5, 0.25])
    assert np.array_equal(chain.damping, [0, 1.5]) and chain.has_spring_damping
    chain.set_masses(np.ones(3))
    chain.set_stiffness([1.0, 2.0])
    chain.set_rest_lengths([1.0, 1.0])
    chain.set_damping([0.0, 0.0])
    assert np.array_equal(chain.masses, np.ones(3)) and np.array_equal(chain.stiffness, [1, 2])
    assert not chain.has_spring_damping


def test_copies_are_copies(chain):
    m = chain.masses
    m[0] = 99
    assert chain.masses[0] == 1.0
    assert "3 points, 2 springs" in repr(chain)


def test_copies_are_independent_and_step_identically():
    points, springs = grid(5, 4)
    s = ms.MassSpringSystem(points, springs, 0.1, 200.0)
    s.pin([0, 4])
    s.add_force(ms.Gravity([0, -9.8, 0]))
    s.add_collider(ms.Collider.plane([0, -0.2, 0], [0, 1, 0]))
    a = ms.FastMassSpring()
    a.precompute(s, 1 / 60)
    for _ in range(5):
        a.step(s)
    t = s.copy()
    u = copy.deepcopy(s)
    for other in (t, u, copy.copy(s)):
        assert not np.shares_memory(other.positions, s.positions)
        assert np.array_equal(other.positions, s.positions)
        assert np.array_equal(other.velocities, s.velocities)
        assert other.forces == ["gravity"] and other.num_colliders == 1 and other.pinned == [0, 4]
    b = ms.FastMassSpring()
    b.precompute(t, 1 / 60)
    for _ in range(10):  # the same state, the same solver settings: the same bits
        a.step(s)
        b.step(t)
    assert np.array_equal(s.positions, t.positions) and np.array_equal(s.velocities, t.velocities)
    assert np.array_equal(u.positions, copy.deepcopy(u).positions)
    u.positions = np.zeros((20, 3))  # changing a copy leaves the original
    assert not np.array_equal(s.positions, u.positions)
