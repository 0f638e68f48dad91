"""The integrators from Python: options with the C++ names reach the solver, the report carries
the C++ fields, and steps match closed forms (free fall, a symplectic Euler step)."""

import math

import numpy as np
import pytest

import massspring as ms
from conftest import grid


def test_fast_mass_spring_options_reach_the_solver():
    points, springs = grid(5, 4)
    s = ms.MassSpringSystem(points, springs, 0.1, 500.0)
    s.pin([0, 4])
    s.add_force(ms.Gravity([0, -9.8, 0]))
    solver = ms.FastMassSpring()
    o = solver.options
    assert (o.iterations, o.tolerance, o.pins, o.acceleration, o.initial_guess,
            o.contact_weight, o.energy_growth) == (
        10, 0.0, ms.PinMode.Exact, ms.Acceleration.Anderson, ms.InitialGuess.Inertial, 1.0, 100.0)
    r = ms.FastMassSpringOptions.reference()
    assert (r.iterations, r.acceleration, r.initial_guess, r.contact_weight) == (
        50, ms.Acceleration.None_, ms.InitialGuess.Current, 0.0)
    solver.options.iterations = 7  # the solver's own options, changed in place
    assert solver.options.iterations == 7 and o.iterations == 7
    solver.precompute(s, 1 / 30)
    r = solver.step(s)
    assert r.ok() and r.iterations == 7 and r.finite and not r.blew_up
    assert r.refactorized is False or r.refactorized is True
    assert "iterations=7" in repr(r)
    solver.options.acceleration = ms.Acceleration.Chebyshev
    solver.options.tolerance = 1e-12
    assert solver.step(s).ok()
    assert solver.chebyshev_rho > 0
    assert solver.dt == 1 / 30
    opts = ms.FastMassSpringOptions()
    opts.iterations = 3
    opts.initial_guess = ms.InitialGuess.Inertial
    opts.ordering = ms.FillOrdering.NestedDissection
    other = ms.FastMassSpring(opts)
    other.precompute(s, 1 / 30)
    assert other.step(s).iterations == 3


def test_free_fall_is_exact_for_every_integrator():
    """A free point under gravity: x(t) = x0 + v0 t + g t^2 / 2 is each method's fixed point up to
    its order (symplectic Euler: x_n = g h^2 n (n + 1) / 2; RK4 and the implicit ones: exact for
    a constant force up to their own discretisation, checked at 1e-9)."""
    g, h, n = -9.8, 0.01, 100
    for make, expect in ((ms.SymplecticEuler, g * h * h * n * (n + 1) / 2),
                         (ms.ForwardEuler, g * h * h * n * (n - 1) / 2),
                         (ms.RK4, g * (h * n) ** 2 / 2)):
        s = ms.MassSpringSystem([[0.0, 0, 0], [10, 0, 0]], [[0, 1]], 1.0, 0.0)
        s.add_force(ms.Gravity([0, g, 0]))
        solver = make()
        solver.precompute(s, h)
        for _ in range(n):
            assert solver.step(s).ok()
        assert s.positions[0, 1] == pytest.approx(expect, rel=1e-9), make.__name__


def test_backward_euler_options_and_spring():
    """One spring, one end pinned: implicit Euler damps the oscillation (amplitude shrinks)."""
    k, m, h = 100.0, 1.0, 0.01
    s = ms.MassSpringSystem([[0.0, 0, 0], [1.2, 0, 0]], [[0, 1]], m, k, rest_lengths=[1.0])
    s.pin(0)
    solver = ms.BackwardEuler()
    assert solver.options.mode == ms.BackwardEulerMode.Newton
    assert solver.options.contact_weight == 1.0  # contact inside the solve, as FastMassSpring's
    solver.options.iterations = 30
    solver.options.tolerance = 1e-12
    solver.options.line_search = False
    assert (solver.options.iterations, solver.options.line_search) == (30, False)
    solver.precompute(s, h)
    period = 2 * math.pi / math.sqrt(k / m)
    for _ in range(int(round(period / h))):
        r = solver.step(s)
        assert r.ok() and r.converged
    assert 1.0 < s.positions[1, 0] < 1.2  # back near the start, with less amplitude
    lin = ms.BackwardEulerOptions()
    lin.mode = ms.BackwardEulerMode.Linearized
    assert ms.BackwardEuler(lin).options.mode == ms.BackwardEulerMode.Linearized


def test_symplectic_euler_step_matches_the_formula():
    k, m, h = 50.0, 2.0, 0.02
    s = ms.MassSpringSystem([[0.0, 0, 0], [1.5, 0, 0]], [[0, 1]], m, k, rest_lengths=[1.0])
    s.velocities = [[0, 0.5, 0], [0.1, 0, 0]]
    solver = ms.SymplecticEuler()
    solver.precompute(s, h)
    x0, v0 = s.positions.copy(), s.velocities.copy()
    solver.step(s)
    d = x0[1] - x0[0]
    l = np.linalg.norm(d)
    f0 = k * (l - 1.0) / l * d  # on point 0, towards point 1
    v = v0 + h / m * np.array([f0, -f0])
    assert np.allclose(s.velocities, v, rtol=0, atol=1e-15)
    assert np.allclose(s.positions, x0 + h * v, rtol=0, atol=1e-15)


def test_a_failed_step_leaves_the_state():
    s = ms.MassSpringSystem([[0.0, 0, 0], [1, 0, 0]], [[0, 1]], 1.0, 1e300)
    s.positions = [[0.0, 0, 0], [1e10, 0, 0]]
    x = s.positions.copy()
    solver = ms.ForwardEuler()
    solver.precompute(s, 1.0)
    r = solver.step(s)
    assert not r.ok() and not r.finite
    assert np.array_equal(s.positions, x)


@pytest.mark.parametrize("integrator", ["FastMassSpring", "BackwardEuler"])
def test_contact_duals_resume_a_run_bit_for_bit(integrator):
    """FastMassSpring and BackwardEuler with contact_weight > 0 carry the contact term's dual
    variables from step to step: a run continued by a new solver from a copy of the system and
    the duals gives the uninterrupted run's steps exactly, and one without the duals does not."""
    import copy
    points, springs = grid(6, 6)
    points = points[:, [0, 2, 1]]  # horizontal, at y = 0
    s = ms.MassSpringSystem(points, springs, 0.01, 500.0)
    s.add_force(ms.Gravity([0, -9.8, 0]))
    ball = ms.Collider.sphere([0.25, -0.52, -0.25], 0.5).set_friction(0.5)
    s.add_collider(ball.set_angular_velocity([0, 1, 0]))
    if integrator == "FastMassSpring":
        opts = ms.FastMassSpringOptions()
        opts.iterations = 10
        opts.initial_guess = ms.InitialGuess.Inertial
        opts.acceleration = ms.Acceleration.Anderson
        opts.contact_weight = 1
    else:
        opts = ms.BackwardEulerOptions()
        opts.contact_weight = 1
    make = getattr(ms, integrator)
    first = make(opts)
    first.precompute(s, 1 / 30)
    for _ in range(10):
        assert first.step(s).ok()
    duals = first.contact_duals
    assert duals.shape == (36, 3) and np.abs(duals).max() > 0
    resumed, without = copy.copy(s), copy.copy(s)
    for _ in range(10):
        assert first.step(s).ok()
    second, third = make(opts), make(opts)
    second.precompute(resumed, 1 / 30)
    third.precompute(without, 1 / 30)
    with pytest.raises(ms.Error,
                       match=r"set_contact_duals: expected one value per point \(36\), got 3"):
        second.contact_duals = np.zeros((3, 3))
    second.contact_duals = duals
    for _ in range(10):
        assert second.step(resumed).ok() and third.step(without).ok()
    assert np.array_equal(resumed.positions, s.positions)
    assert not np.array_equal(without.positions, s.positions)
