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
