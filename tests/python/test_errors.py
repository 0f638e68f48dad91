"""Every error path: bad shapes, dtypes and values raise massspring.Error (a ValueError) with the
library's message, and leave everything as it was."""

import numpy as np
import pytest

import massspring as ms
from conftest import scene

V = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]])
E = np.array([[0, 1], [1, 2]])


def test_error_is_a_value_error():
    assert issubclass(ms.Error, ValueError)


@pytest.mark.parametrize("args, message", [
    ((V[:, :2], E, 1.0, 1.0), r"rest positions: expected a real \(float64\) array of shape "
                              r"\(#rows, 3\), got an array of dtype float64 and shape \(3, 2\)"),
    ((V.ravel(), E, 1.0, 1.0),
     r"rest positions: .* got an array of dtype float64 and shape \(9,\)"),
    ((V.astype(str), E, 1.0, 1.0), r"rest positions: .* got an array of dtype <U32"),
    ((V.astype(complex), E, 1.0, 1.0), r"rest positions: .* got an array of dtype complex128"),
    ((V, E.astype(float), 1.0, 1.0), r"springs: expected an integer array of shape \(#rows, 2\), "
                                     r"got an array of dtype float64 and shape \(2, 2\)"),
    ((V, E[:, :1], 1.0, 1.0), r"springs: .* got an array of dtype int64 and shape \(2, 1\)"),
    ((V, np.array([[0, 2**40]]), 1.0, 1.0), r"springs: index values must fit a 32-bit int"),
    ((V, E, [1.0, 2.0], 1.0), r"masses: expected a real \(float64\) array of shape \(3,\) or a "
                              r"number, got an array of dtype float64 and shape \(2,\)"),
    ((V, E, 1.0, np.ones((2, 1))),
     r"stiffness: .* got an array of dtype float64 and shape \(2, 1\)"),
    ((V, E, 1.0, "stiff"), r"stiffness: expected a real"),
    # the library's own checks, with its messages
    ((V, np.array([[0, 1], [1, 3]]), 1.0, 1.0),
     r"^spring 1 = \(1, 3\): point index 3 out of range \[0, 3\)$"),
    ((V, np.array([[0, 1], [1, 0]]), 1.0, 1.0),
     r"^spring 1 duplicates spring 0: both join points 0 and 1$"),
    ((V, np.array([[1, 1]]), 1.0, 1.0), r"^spring 0 connects point 1 to itself$"),
    ((V, E, [1.0, -1.0, 1.0], 1.0), r"point 1"),
    ((V, E, 1.0, [1.0, np.nan]), r"spring 1"),
    ((np.array([[0, 0, 0], [1, np.inf, 0], [2, 0, 0]]), E, 1.0, 1.0), r"point 1"),
])
def test_construction_errors(args, message):
    with pytest.raises(ms.Error, match=message):
        ms.MassSpringSystem(*args)


def test_rest_lengths_and_damping_checked_at_construction():
    with pytest.raises(ms.Error, match=r"rest lengths: .* shape \(2,\), got an array of dtype "
                                       r"float64 and shape \(3,\)"):
        ms.MassSpringSystem(V, E, 1.0, 1.0, rest_lengths=[1.0, 1.0, 1.0])
    with pytest.raises(ms.Error, match="spring 0"):
        ms.MassSpringSystem(V, E, 1.0, 1.0, damping=[-1.0, 0.0])


def test_setters_refuse_and_change_nothing(chain):
    x = np.arange(9.0).reshape(3, 3)
    chain.positions = x
    bad = x.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ms.Error, match=r"^point 2: positions .*nan"):
        chain.positions = bad
    with pytest.raises(ms.Error, match=r"^positions: expected 3 by 3, got 2 by 3$"):
        chain.positions = x[:2]
    with pytest.raises(ms.Error, match=r"velocities: expected a real .* shape \(3,\)"):
        chain.velocities = np.zeros(3)
    with pytest.raises(ms.Error,
                       match=r"velocities: expected a real .* got an array of dtype bool"):
        chain.set_velocities(np.zeros((3, 3), dtype=bool))
    assert np.array_equal(chain.positions, x) and np.array_equal(chain.velocities, np.zeros((3, 3)))
    with pytest.raises(ms.Error, match="point 0"):
        chain.masses = [0.0, 1.0, 1.0]
    with pytest.raises(ms.Error, match=r"masses: .* shape \(3,\)"):
        chain.set_masses([1.0, 1.0])
    with pytest.raises(ms.Error, match="spring 1"):
        chain.rest_lengths = [1.0, -2.0]
    assert np.array_equal(chain.masses, np.ones(3)) and np.array_equal(chain.rest_lengths, [1, 1])


def test_pin_errors(chain):
    with pytest.raises(ms.Error, match=r"^pin: point index 3 out of range \[0, 3\)$"):
        chain.pin(3)
    with pytest.raises(ms.Error, match=r"^pin: point index -1 out of range"):
        chain.pin([0, -1])
    assert chain.pinned == []  # nothing pinned: the list is checked first
    with pytest.raises(ms.Error, match=r"^pin target: point 1 is not pinned$"):
        chain.set_pin_target(1, [0, 0, 0])
    with pytest.raises(ms.Error, match=r"pin target: expected a real .* shape \(3,\)"):
        chain.pin(1, [0.0, 1.0])
    with pytest.raises(ms.Error, match=r"^pin 1: target must be finite"):
        chain.pin(1, [0.0, np.inf, 0.0])
    with pytest.raises(ms.Error, match=r"pin: expected a one-dimensional integer array"):
        chain.pin([0.5, 1.5])
    with pytest.raises(ms.Error, match=r"^unpin: point index 7"):
        chain.unpin(7)
    assert chain.pinned == []


def test_force_errors(chain):
    with pytest.raises(ms.Error, match=r"^gravity: acceleration must be finite"):
        ms.Gravity([0, np.nan, 0])
    with pytest.raises(ms.Error, match=r"gravity: expected a real .* shape \(3,\)"):
        ms.Gravity([0, -9.8])
    with pytest.raises(ms.Error, match="linear drag"):
        ms.LinearDrag(-1.0)
    with pytest.raises(ms.Error, match="attracts point 1 to itself"):
        ms.GravitationalAttraction([[1, 1]], 1.0)
    with pytest.raises(ms.Error, match=r"gravitational attraction: G: .* shape \(1,\)"):
        ms.GravitationalAttraction([[0, 1]], [1.0, 2.0])
    with pytest.raises(ms.Error, match=r"^gravitational attraction: point index 5 out of range"):
        chain.add_force(ms.GravitationalAttraction([[0, 5]], 1.0))
    with pytest.raises(ms.Error, match="vortex force 0 acts between point 2 and itself"):
        ms.VortexForce([[2, 2]], 1.0, 1.0)
    with pytest.raises(ms.Error, match="penalty force: planes"):
        ms.PenaltyForce(np.zeros(3), 1.0, 0.0, planes=[[0, 1, 0]])
    assert chain.forces == []
    with pytest.raises(TypeError):
        chain.add_force("gravity")


def test_integrator_errors(chain):
    for make in (ms.FastMassSpring, ms.BackwardEuler):
        with pytest.raises(ms.Error, match=r"step\(\) before precompute\(\)"):
            make().step(chain)
    for make, name in ((ms.ForwardEuler, "ForwardEuler"), (ms.SymplecticEuler, "SymplecticEuler"),
                       (ms.RK4, "RK4")):
        with pytest.raises(ms.Error, match=rf"^{name}: step\(\) before precompute\(\)$"):
            make().step(chain)
        with pytest.raises(ms.Error, match=rf"^{name}: dt"):
            make().precompute(chain, -1.0)
    assert np.array_equal(chain.positions, [[0, 0, 0], [1, 0, 0], [2, 0, 0]])
    solver = ms.FastMassSpring()
    # refused when set, with the message precompute() and step() give
    with pytest.raises(ms.Error, match=r"^FastMassSpring: options.iterations must be >= 1, got 0$"):
        solver.options.iterations = 0
    solver.options.iterations = 5
    solver.precompute(chain, 0.01)
    solver.options.chebyshev_rho = 1.5
    with pytest.raises(ms.Error, match=r"options.chebyshev_rho must be in \[0, 1\), got 1.5"):
        solver.step(chain)
    with pytest.raises(AttributeError, match=r"options.gravity was removed: add massspring.Gravity"):
        solver.options.gravity = [1.0]
    with pytest.raises(TypeError):
        solver.options.iterations = "ten"
    assert np.array_equal(chain.positions, [[0, 0, 0], [1, 0, 0], [2, 0, 0]])
    explicit = ms.SymplecticEuler()
    explicit.precompute(chain, 0.01)
    bigger = ms.MassSpringSystem(np.eye(4)[:, :3], [[0, 1]], 1.0, 1.0)
    with pytest.raises(ms.Error, match=r"the system has 4 points, precompute\(\) saw 3"):
        explicit.step(bigger)
    assert np.array_equal(bigger.positions, np.eye(4)[:, :3])  # left as it was


def test_collider_errors(chain):
    with pytest.raises(ms.Error, match="plane collider: the normal must not be zero"):
        ms.Collider.plane([0, 0, 0], [0, 0, 0])
    with pytest.raises(ms.Error, match="sphere collider: radius"):
        ms.Collider.sphere([0, 0, 0], -1.0)
    with pytest.raises(ms.Error, match="box collider: rotation must be a finite, non-zero"):
        ms.Collider.box([0, 0, 0], [1, 1, 1], [0, 0, 0, 0])
    with pytest.raises(ms.Error, match="mesh collider: no vertices"):
        ms.Collider.mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))
    with pytest.raises(ms.Error, match=r"mesh collider: triangles: expected an integer array"):
        ms.Collider.mesh(np.eye(3), [[0.0, 1.0, 2.0]])
    sphere = ms.Collider.sphere([0, 0, 0], 1.0)
    with pytest.raises(ms.Error, match="kinetic friction 0.5 exceeds static friction 0.2"):
        sphere.set_friction(0.2, 0.5)
    with pytest.raises(ms.Error, match=r"restitution must be in \[0, 1\], got 2"):
        sphere.set_restitution(2.0)
    with pytest.raises(ms.Error, match="thickness must be finite and >= 0"):
        sphere.set_thickness(-0.1)
    with pytest.raises(ms.Error, match="pose rotation must be a rotation matrix"):
        sphere.set_pose(2 * np.eye(3), [0, 0, 0])
    with pytest.raises(ms.Error, match=r"pose: rotation: expected a real .* shape \(3, 3\)"):
        sphere.set_pose(np.eye(2), [0, 0, 0])
    assert (sphere.static_friction, sphere.restitution, sphere.thickness) == (0.0, 0.0, 0.0)
    with pytest.raises(ms.Error, match=r"^collider index 0 out of range \[0, 0\)$"):
        chain.collider(0)
    with pytest.raises(ms.Error, match=r"^collider index 1 out of range"):
        chain.set_collider(1, sphere)


def test_scene_file_errors(tmp_path):
    with pytest.raises(ms.Error, match="nope.json"):
        ms.load_scene(str(tmp_path / "nope.json"))
    with pytest.raises(ms.Error, match=r'unsupported scene format "\.txt": supported are \.json'):
        ms.load_scene(str(tmp_path / "scene.txt"))
    bad = tmp_path / "bad.json"
    bad.write_text('{"obj": "missing.obj"}')
    with pytest.raises(ms.Error, match="bad.json"):
        ms.load_scene(str(bad))
    with pytest.raises(ms.Error, match="positions: expected a real"):
        ms.write_obj(str(tmp_path / "x.obj"), np.zeros(3))
    s = ms.load_scene(scene("chain.json"))
    with pytest.raises(ms.Error, match=r"faces: expected a list of lists of point indices"):
        ms.write_state(s, str(tmp_path / "state.json"), faces="abc")
    with pytest.raises(ms.Error, match=r"y.obj: vertex 0: position must be finite"):
        ms.write_obj(str(tmp_path / "y.obj"), np.full((2, 3), np.nan))
    assert not (tmp_path / "state.json").exists() and not (tmp_path / "y.obj").exists()


def test_diagnostics_errors(chain):
    with pytest.raises(ms.Error, match=r"^stable_time_step: safety must be in \(0, 1\], got 2$"):
        ms.stable_time_step(chain, ms.ExplicitMethod.SymplecticEuler, 2.0)
