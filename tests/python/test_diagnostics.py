"""Diagnostics from Python against closed forms: kinetic energy and momentum from numpy, the
stable time step of one spring on a pinned point (h = 2 / omega, omega = sqrt(k / m))."""

import math

import numpy as np
import pytest

import massspring as ms


def test_energies_and_momentum(chain):
    rng = np.random.default_rng(3)
    chain.masses = [1.0, 2.0, 3.0]
    v = rng.normal(size=(3, 3))
    chain.velocities = v
    m = np.array([1.0, 2.0, 3.0])
    assert ms.kinetic_energy(chain) == pytest.approx(0.5 * (m * (v**2).sum(axis=1)).sum(), 1e-15)
    assert np.allclose(ms.linear_momentum(chain), (m[:, None] * v).sum(axis=0), rtol=1e-15)
    assert ms.potential_energy(chain) == 0.0  # springs at rest, no terms
    assert ms.total_energy(chain) == ms.kinetic_energy(chain)


def test_stable_time_step_of_one_spring():
    k, m = 400.0, 4.0
    s = ms.MassSpringSystem([[0.0, 0, 0], [1, 0, 0]], [[0, 1]], m, k)
    s.pin(0)
    omega = math.sqrt(k / m)
    assert ms.frequency_bounds(s).omega_max == pytest.approx(omega, rel=1e-12)
    assert ms.stability_limit(s) == pytest.approx(2 / omega, rel=1e-12)
    assert ms.stable_time_step(s) == pytest.approx(0.5 * 2 / omega, rel=1e-12)
    assert ms.stable_time_step(s, ms.ExplicitMethod.SymplecticEuler, 1.0) == pytest.approx(
        2 / omega, rel=1e-12)
    assert ms.stability_limit(s, ms.ExplicitMethod.RK4) == pytest.approx(2.6 / omega, rel=1e-12)
    assert ms.stability_limit(s, ms.ExplicitMethod.ForwardEuler) == 0.0  # undamped: none


def test_nothing_limits_a_free_point():
    s = ms.MassSpringSystem([[0.0, 0, 0], [1, 0, 0]], [[0, 1]], 1.0, 0.0)
    assert math.isinf(ms.stable_time_step(s))


def test_divergence_guard_undoes_a_step_that_blows_up():
    """Forward Euler on an undamped spring gains energy every step (by (1 + h^2 w^2) per step);
    with a tiny growth the guard refuses the first step that passes E(0) + growth x scale and
    leaves the state as it was before that step."""
    s = ms.MassSpringSystem([[0.0, 0, 0], [1.5, 0, 0]], [[0, 1]], 1.0, 100.0, rest_lengths=[1.0])
    s.pin(0)
    solver = ms.ForwardEuler()
    solver.precompute(s, 0.05)
    guard = ms.DivergenceGuard(s, 0.01)
    assert guard.initial_energy == pytest.approx(0.5 * 100 * 0.25, rel=1e-15)
    assert guard.limit == guard.initial_energy + 0.01 * guard.scale
    for _ in range(1000):
        x, v = s.positions.copy(), s.velocities.copy()
        report = guard.step(solver, s)
        if report.blew_up:
            break
        assert report.ok() and guard.energy <= guard.limit
    assert report.blew_up and not report.ok()
    assert np.array_equal(s.positions, x) and np.array_equal(s.velocities, v)
    assert ms.total_energy(s) <= guard.limit
