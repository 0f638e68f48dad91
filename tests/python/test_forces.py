"""Every force term from Python: accepted by add_force, listed by name, and with the energy the
formula gives (diagnostics' potential_energy against numpy)."""

import numpy as np
import pytest

import massspring as ms


@pytest.fixture
def pair():
    """Two points 2 m apart (masses 2 and 3 kg) joined by a spring at rest (k = 0)."""
    points = np.array([[0.0, 0, 0], [2, 0, 0]])
    return ms.MassSpringSystem(points, [[0, 1]], [2.0, 3.0], 0.0)


def test_every_term_is_added_and_named(pair):
    terms = [ms.Gravity([0, -9.8, 0]), ms.ConstantForce([1, 2, 3]), ms.LinearDrag(0.5),
             ms.GravitationalAttraction([[0, 1]], 1.0), ms.VortexForce([[0, 1]], 1.0, 2.0),
             ms.PenaltyForce(np.full(2, 0.1), 100.0, 0.0, planes=[([0, -1, 0], [0, 1, 0])])]
    for k, term in enumerate(terms):
        assert pair.add_force(term) == k
    assert pair.forces == ["gravity", "constant force", "linear drag", "gravitational attraction",
                           "vortex force", "penalty contact"]
    pair.clear_forces()
    assert pair.forces == []


def test_term_values_read_back():
    assert np.array_equal(ms.Gravity([0, -9.8, 0]).g, [0, -9.8, 0])
    assert np.array_equal(ms.ConstantForce([1, 2, 3]).force, [1, 2, 3])
    assert ms.LinearDrag(0.25).beta == 0.25
    assert ms.GravitationalAttraction.all_pairs(3, 1.0).pairs == [(0, 1), (0, 2), (1, 2)]
    assert ms.VortexForce([[0, 1], [1, 2]], [1.0, 2.0], 3.0).pairs == [(0, 1), (1, 2)]
    p = ms.PenaltyForce(np.zeros(2), 10.0, 0.5, edges=[[0, 1]], edge_radii=[0.1])
    assert (p.stiffness, p.thickness) == (10.0, 0.5)


def test_energies(pair):
    x = pair.positions.copy()
    m = pair.masses
    g = np.array([0, -9.8, 0])
    pair.add_force(ms.Gravity(g))
    assert ms.potential_energy(pair) == pytest.approx(-(m[:, None] * g * x).sum(), rel=1e-15)
    pair.clear_forces()
    f = np.array([1.0, 2.0, 3.0])
    pair.add_force(ms.ConstantForce(f))
    assert ms.potential_energy(pair) == pytest.approx(-(x @ f).sum(), rel=1e-15)
    pair.clear_forces()
    pair.add_force(ms.GravitationalAttraction([[0, 1]], 0.5))
    assert ms.potential_energy(pair) == pytest.approx(-0.5 * 2 * 3 / 2.0, rel=1e-15)


def test_springs_energy_and_drag_force():
    s = ms.MassSpringSystem([[0.0, 0, 0], [1.5, 0, 0]], [[0, 1]], 1.0, 40.0, rest_lengths=[1.0])
    assert ms.potential_energy(s) == pytest.approx(0.5 * 40 * 0.5**2, rel=1e-15)
    # linear drag alone: one symplectic Euler step gives v' = v - h beta v / m exactly
    d = ms.MassSpringSystem([[0.0, 0, 0], [1, 0, 0]], [[0, 1]], 2.0, 0.0)
    d.add_force(ms.LinearDrag(0.5))
    d.velocities = [[1.0, 0, 0], [0, 2.0, 0]]
    solver = ms.SymplecticEuler()
    solver.precompute(d, 0.1)
    assert solver.step(d).ok()
    assert np.array_equal(d.velocities, np.array([[1.0, 0, 0], [0, 2.0, 0]]) * (1 - 0.1 * 0.5 / 2))
