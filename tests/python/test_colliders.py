"""Colliders from Python: each shape, its material and motion read back, the copy semantics of
add_collider / collider / set_collider, and a point landing on each shape stays outside it."""

import numpy as np
import pytest

import massspring as ms


def cube():
    v = np.array([[x, y, z] for x in (-1.0, 1) for y in (-1.0, 1) for z in (-1.0, 1)])
    t = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, t


SHAPES = {
    "plane": lambda: ms.Collider.plane([0, -1, 0], [0, 2, 0]),
    "sphere": lambda: ms.Collider.sphere([0, -2, 0], 1.0),
    "capsule": lambda: ms.Collider.capsule([-1, -2, 0], [1, -2, 0], 1.0),
    "box": lambda: ms.Collider.box([0, -2, 0], [1, 1, 1]),
    "mesh": lambda: ms.Collider.mesh(cube()[0] + [0, -2, 0], cube()[1]),
}


@pytest.mark.parametrize("name", SHAPES)
def test_a_falling_point_stays_outside(name):
    """A point dropped from y = 0.5 onto a surface at y = -1 comes to rest on it: its height
    never goes below -1 - 1e-9 (the response keeps it out) and ends within 1 cm of it."""
    c = SHAPES[name]()
    assert c.shape == getattr(ms.ColliderShape, name.capitalize())
    s = ms.MassSpringSystem([[0.0, 0.5, 0], [5, 5, 5]], [[0, 1]], 1.0, 0.0)
    s.pin(1)
    s.add_force(ms.Gravity([0, -9.8, 0]))
    assert s.add_collider(c) == 0 and s.num_colliders == 1
    solver = ms.SymplecticEuler()
    solver.precompute(s, 0.005)
    lowest = np.inf
    for _ in range(300):
        assert solver.step(s).ok()
        lowest = min(lowest, s.positions[0, 1])
    assert lowest >= -1 - 1e-9
    assert s.positions[0, 1] == pytest.approx(-1, abs=0.01)
    assert s.collider_impulse(0)[1] >= 0  # the surface pushes up


def test_material_and_motion_read_back():
    c = ms.Collider.box([1, 2, 3], [0.5, 0.5, 0.5], [1, 0, 0, 0])
    assert c.set_friction(0.4, 0.3) is c  # chainable
    c.set_restitution(0.25).set_thickness(0.01)
    assert (c.static_friction, c.kinetic_friction, c.restitution, c.thickness) == (
        0.4, 0.3, 0.25, 0.01)
    c.set_friction(0.2)
    assert (c.static_friction, c.kinetic_friction) == (0.2, 0.2)
    r = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    c.set_pose(r, [4, 5, 6]).set_velocity([1, 0, 0]).set_angular_velocity([0, 0, 2])
    assert np.array_equal(c.rotation, r) and np.array_equal(c.translation, [4, 5, 6])
    assert np.array_equal(c.velocity, [1, 0, 0])
    assert np.array_equal(c.angular_velocity, [0, 0, 2])
    assert ms.Collider.sphere([0, 0, 0], 0.75).radius == 0.75
    assert "box" in repr(c)


def test_the_system_keeps_copies():
    s = ms.MassSpringSystem([[0.0, 0, 0], [1, 0, 0]], [[0, 1]], 1.0, 1.0)
    c = ms.Collider.sphere([0, 0, 0], 1.0)
    s.add_collider(c)
    c.set_friction(0.9)  # the system's copy is not changed
    assert s.collider(0).static_friction == 0.0
    s.set_collider(0, c)
    assert s.collider(0).static_friction == 0.9
    s.clear_colliders()
    assert s.num_colliders == 0


def test_a_step_reports_the_energy_its_contact_added():
    """StepReport.contact_work: a point at 0.05 m above the plane y = 0 moving down at 3 m/s
    (mass 2 kg, no force) is stopped on it within one step of 0.1 s, losing its kinetic energy,
    m |v|^2 / 2 = 9 J; without the plane the work is 0."""
    for plane, expected in ((True, -9.0), (False, 0.0)):
        s = ms.MassSpringSystem([[0.0, 0.05, 0], [5, 5, 5]], [[0, 1]], 2.0, 0.0)
        s.pin(1)
        velocities = s.velocities.copy()
        velocities[0] = [0, -3, 0]
        s.velocities = velocities
        if plane:
            s.add_collider(ms.Collider.plane([0, 0, 0], [0, 1, 0]))
        solver = ms.SymplecticEuler()
        solver.precompute(s, 0.1)
        report = solver.step(s)
        assert report.ok()
        assert report.contact_work == pytest.approx(expected, abs=1e-12)


def test_a_contact_response_that_adds_more_than_half_the_scale_is_refused():
    """A point at rest at y = 0.1 on a spring at rest (k = 10^4 N/m, l0 = 0.1 m) from a pin at
    y = 0.2 (1 kg each), and the plane y = 0 rising at 0.19 m/s: one backward Euler step of 1 s
    (the contact term off) leaves everything at rest; the plane's response puts the point at
    y = 0.19 moving at 0.19 m/s, the spring 1 cm long: it adds 40.5 J, more than S / 2 + S_c =
    25 + 0.14 J (S = k l0^2 / 2 at rest, S_c = 2 M V^2), so the step is refused (blew_up) and
    the state kept; with the energy bound off (energy_growth 0) it is committed."""
    for growth, refused in ((100.0, True), (0.0, False)):
        s = ms.MassSpringSystem([[0.0, 0.2, 0], [0.0, 0.1, 0]], [[0, 1]], 1.0, 1e4)
        s.pin(0)
        s.add_collider(ms.Collider.plane([0, 0, 0], [0, 1, 0]).set_velocity([0, 0.19, 0]))
        before = s.positions.copy()
        solver = ms.BackwardEuler()
        solver.options.contact_weight = 0.0
        solver.options.energy_growth = growth
        solver.precompute(s, 1.0)
        report = solver.step(s)
        work = 0.5 * 1e4 * 0.09 ** 2 + 0.5 * 0.19 ** 2
        assert work > ms.CONTACT_LIMIT_SHARE * 0.5 * 1e4 * 0.1 ** 2 + 2 * 2 * 0.19 ** 2
        assert report.contact_work == pytest.approx(work, rel=1e-9)
        assert report.blew_up == refused and report.ok() != refused
        if refused:
            assert np.array_equal(s.positions, before)
        else:
            assert s.positions[1, 1] == pytest.approx(0.19, rel=1e-12)
