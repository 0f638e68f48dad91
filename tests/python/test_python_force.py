"""massspring.PythonForce: a force term written in Python (docs/python.md).

Oracles: the same force built in.
- gravity as a callback (F_i = m_i g) gives the trajectory of ms.Gravity, to rounding, for every
  integrator that needs no Jacobian (the explicit ones and FastMassSpring, which evaluates every
  term but drag once per step), and for BackwardEuler with its Jacobian (zero);
- a tether (a spring from point 0 to a fixed anchor) as a callback with its Jacobian gives the
  trajectory of the same spring built in (the anchor a pinned point), to rounding, for RK4 and for
  BackwardEuler, linearised and Newton; the Jacobian the test gives is checked against finite
  differences first.
Errors: a wrong shape raises massspring.Error naming the term from step(), a NaN force is a
step that is not finite; either way the system keeps its state. BackwardEuler refuses a term
without a Jacobian, naming both. Two threads stepping their own systems with Python terms (the
GIL taken for each callback) get the trajectories of one thread alone."""

import numpy as np
import pytest

import massspring as ms

G = np.array([0.0, -9.8, 0.0])
ANCHOR = np.array([0.0, 0.5, 0.0])
K_TETHER, REST_TETHER = 50.0, 0.3
H = 0.01


def chain(anchor=False):
    """Three points on the x axis, springs k = 100 N/m, masses 1, 2, 3 kg; with `anchor`, a
    fourth point at ANCHOR, pinned, tied to point 0 by the tether's spring."""
    points = [[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]
    springs, k, rest = [[0, 1], [1, 2]], [100.0, 100.0], [1.0, 1.0]
    masses = [1.0, 2.0, 3.0]
    if anchor:
        points.append(list(ANCHOR))
        springs.append([0, 3])
        k.append(K_TETHER)
        rest.append(REST_TETHER)
        masses.append(1.0)
    s = ms.MassSpringSystem(np.array(points), np.array(springs), np.array(masses), np.array(k),
                            rest_lengths=np.array(rest))
    if anchor:
        s.pin(3)
    s.velocities = np.tile([0.1, 0.3, -0.2], (len(points), 1))
    return s


def python_gravity(system):
    masses = system.masses.copy()
    return lambda x, v: masses[:, None] * G


def tether_force(x, v):
    """F_0 = -k (|d| - r) d / |d|, d = x_0 - ANCHOR; zero elsewhere."""
    f = np.zeros_like(x)
    d = x[0] - ANCHOR
    length = np.linalg.norm(d)
    f[0] = -K_TETHER * (length - REST_TETHER) * d / length
    return f


def tether_block(x):
    """dF_0/dx_0 = -k ((1 - r/l) I + (r/l) d d^T / l^2)."""
    d = x[0] - ANCHOR
    length = np.linalg.norm(d)
    return -K_TETHER * ((1 - REST_TETHER / length) * np.eye(3)
                        + REST_TETHER / length * np.outer(d, d) / length ** 2)


def tether_jacobian_dense(x, v):
    dfdx = np.zeros((3 * len(x), 3 * len(x)))
    dfdx[:3, :3] = tether_block(x)
    return dfdx, None


def tether_jacobian_sparse(x, v):
    """Point 0's whole 3 x 3 block stored, zeros included (the pattern is the first call's)."""
    sparse = pytest.importorskip("scipy.sparse")
    rows, cols = np.divmod(np.arange(9), 3)
    dim = 3 * len(x)
    dfdx = sparse.coo_matrix((tether_block(x).ravel(), (rows, cols)), shape=(dim, dim))
    return dfdx, sparse.csr_matrix((dim, dim))


def run(system, solver, steps=40):
    solver.precompute(system, H)
    for _ in range(steps):
        report = solver.step(system)
        assert report.ok(), report
    return system.positions[:3].copy(), system.velocities[:3].copy()


def explicit_solvers():
    return [ms.SymplecticEuler(), ms.ForwardEuler(), ms.RK4()]


def backward_euler(mode, line_search=False):
    solver = ms.BackwardEuler()
    solver.options.mode = mode
    solver.options.line_search = line_search
    solver.options.tolerance = 1e-13
    solver.options.iterations = 20
    return solver


def test_a_python_term_is_named_listed_and_shared():
    s = chain()
    term = ms.PythonForce(tether_force)
    assert term.name == "tether_force" and term.jacobian is None and not term.symmetric
    assert ms.PythonForce(lambda x, v: x, name="wind").name == "wind"
    assert ms.PythonForce(lambda x, v: x).name == "python force"
    assert s.add_force(term) == 0 and s.forces == ["tether_force"]
    assert "PythonForce" in repr(term)


@pytest.mark.parametrize("make", [ms.SymplecticEuler, ms.ForwardEuler, ms.RK4, ms.FastMassSpring])
def test_gravity_as_a_callback_equals_the_built_in_term(make):
    built_in, python = chain(), chain()
    built_in.add_force(ms.Gravity(G))
    python.add_force(ms.PythonForce(python_gravity(python)))
    x0, v0 = run(built_in, make())
    x1, v1 = run(python, make())
    assert np.abs(x0 - chain().positions).max() > 1e-3  # it moved
    np.testing.assert_allclose(x1, x0, rtol=0, atol=1e-13)
    np.testing.assert_allclose(v1, v0, rtol=0, atol=1e-12)


def test_gravity_with_its_zero_jacobian_under_backward_euler():
    built_in, python = chain(), chain()
    built_in.add_force(ms.Gravity(G))
    zero = lambda x, v: (None, None)  # noqa: E731
    python.add_force(ms.PythonForce(python_gravity(python), jacobian=zero))
    x0, v0 = run(built_in, backward_euler(ms.BackwardEulerMode.Newton))
    x1, v1 = run(python, backward_euler(ms.BackwardEulerMode.Newton))
    np.testing.assert_allclose(x1, x0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v1, v0, rtol=0, atol=1e-10)


def test_the_tether_jacobian_matches_finite_differences():
    rng = np.random.default_rng(5)
    x = chain().positions + rng.normal(scale=0.2, size=(3, 3))
    v = np.zeros_like(x)
    exact, _ = tether_jacobian_dense(x, v)
    step = 1e-6
    for column in range(9):
        plus, minus = x.copy(), x.copy()
        plus.flat[column] += step
        minus.flat[column] -= step
        difference = (tether_force(plus, v) - tether_force(minus, v)).ravel() / (2 * step)
        np.testing.assert_allclose(exact[:, column], difference, rtol=0, atol=1e-6)


def test_a_tether_equals_the_same_spring_built_in_for_rk4():
    x0, v0 = run(chain(anchor=True), ms.RK4())
    python = chain()
    python.add_force(ms.PythonForce(tether_force))
    x1, v1 = run(python, ms.RK4())
    np.testing.assert_allclose(x1, x0, rtol=0, atol=1e-13)
    np.testing.assert_allclose(v1, v0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("mode", [ms.BackwardEulerMode.Linearized, ms.BackwardEulerMode.Newton])
@pytest.mark.parametrize("jacobian", [tether_jacobian_dense, tether_jacobian_sparse])
@pytest.mark.parametrize("symmetric", [False, True])
def test_a_tether_with_its_jacobian_equals_the_built_in_spring_for_backward_euler(
        mode, jacobian, symmetric):
    x0, v0 = run(chain(anchor=True), backward_euler(mode))
    python = chain()
    python.add_force(ms.PythonForce(tether_force, jacobian=jacobian, symmetric=symmetric))
    x1, v1 = run(python, backward_euler(mode))
    assert np.abs(x0 - chain().positions).max() > 1e-3
    np.testing.assert_allclose(x1, x0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v1, v0, rtol=0, atol=1e-10)


def test_backward_euler_refuses_a_term_without_jacobian():
    s = chain()
    s.add_force(ms.Gravity(G))
    s.add_force(ms.PythonForce(tether_force))
    message = (r"^BackwardEuler: force term 1 \(PythonForce \"tether_force\"\) has no jacobian.*"
               r"PythonForce\(forces, jacobian=...\)")
    with pytest.raises(ms.Error, match=message):
        ms.BackwardEuler().precompute(s, H)
    # added after precompute: refused at the step, the state kept
    t = chain()
    solver = ms.BackwardEuler()
    solver.precompute(t, H)
    t.add_force(ms.PythonForce(tether_force))
    x = t.positions.copy()
    with pytest.raises(ValueError, match=message.replace("term 1", "term 0")):
        solver.step(t)
    guard = ms.DivergenceGuard(t)
    with pytest.raises(ms.Error, match="has no jacobian"):
        guard.step(solver, t)
    assert np.array_equal(t.positions, x)


def every_solver(jacobian=None):
    solvers = explicit_solvers() + [ms.FastMassSpring()]
    if jacobian is not None:
        solvers.append(backward_euler(ms.BackwardEulerMode.Newton))
    return solvers


def zero_jacobian(x, v):
    return None, None


@pytest.mark.parametrize("returned, message", [
    (lambda x, v: x[:, :2], r"expected a real \(float64\) array of shape \(#rows, 3\), got an "
                            r"array of dtype float64 and shape \(3, 2\)"),
    (lambda x, v: x[:2], r"expected a real \(float64\) array of shape \(3, 3\), one row per "
                         r"point, got 2 rows"),
    (lambda x, v: "wind", r"expected a real \(float64\) array .* got an array of dtype <U4"),
])
def test_a_wrong_shape_raises_and_keeps_the_state(returned, message):
    """From step(), or from precompute() where the solver evaluates the forces there
    (FastMassSpring and BackwardEuler: the energy bound's scale)."""
    for solver in every_solver(zero_jacobian):
        s = chain()
        s.add_force(ms.PythonForce(returned, jacobian=zero_jacobian, name="bad"))
        x, v = s.positions.copy(), s.velocities.copy()
        with pytest.raises(ms.Error, match=r'^PythonForce "bad": forces\(x, v\): ' + message):
            solver.precompute(s, H)
            solver.step(s)
        assert np.array_equal(s.positions, x) and np.array_equal(s.velocities, v)


def test_a_nan_force_is_a_step_that_is_not_finite():
    """A force that turns NaN after precompute(): the step reports it, the state is kept."""
    broken = {"nan": False}

    def nan_on_point_1(x, v):
        f = np.zeros_like(x)
        if broken["nan"]:
            f[1, 1] = np.nan
        return f

    for solver in every_solver(zero_jacobian):
        s = chain()
        s.add_force(ms.PythonForce(nan_on_point_1, jacobian=zero_jacobian))
        broken["nan"] = False
        solver.precompute(s, H)
        broken["nan"] = True
        x = s.positions.copy()
        report = solver.step(s)
        assert not report.ok() and not report.finite, (type(solver).__name__, report)
        assert np.array_equal(s.positions, x), type(solver).__name__


def test_an_exception_in_the_callback_reaches_the_caller():
    raising = {"on": False}

    def broken(x, v):
        if raising["on"]:
            return 1 / 0
        return np.zeros_like(x)

    for solver in every_solver(zero_jacobian):
        s = chain()
        s.add_force(ms.PythonForce(broken, jacobian=zero_jacobian))
        raising["on"] = False
        solver.precompute(s, H)
        raising["on"] = True
        x = s.positions.copy()
        with pytest.raises(ZeroDivisionError):
            solver.step(s)
        assert np.array_equal(s.positions, x)


def test_jacobian_errors_name_the_term():
    sparse = pytest.importorskip("scipy.sparse")
    cases = [
        (lambda x, v: np.zeros((9, 9)), r"jacobian\(x, v\): expected a pair \(dfdx, dfdv\), got "
                                        r"ndarray"),
        (lambda x, v: (None,), r"jacobian\(x, v\): expected a pair \(dfdx, dfdv\), got 1 items"),
        (lambda x, v: (np.zeros((6, 9)), None), r"jacobian\(x, v\) dfdx: expected a matrix of "
                                                r"shape \(9, 9\) .* got 6 rows"),
        (lambda x, v: (sparse.csr_matrix((9, 8)), None), r"jacobian\(x, v\) dfdx: expected a "
                                                         r"matrix of shape \(9, 9\) .* sparse one "
                                                         r"of shape \(9, 8\)"),
    ]
    for jacobian, message in cases:
        s = chain()
        s.add_force(ms.PythonForce(tether_force, jacobian=jacobian, name="j"))
        with pytest.raises(ms.Error, match=r'PythonForce "j": ' + message):
            ms.BackwardEuler().precompute(s, H)

    # a sparse pattern that grows after the first call
    calls = []

    def growing(x, v):
        calls.append(1)
        dfdx = sparse.lil_matrix((9, 9))
        dfdx[0, 0] = -1.0
        if len(calls) > 1:
            dfdx[4, 4] = -1.0
        return dfdx.tocsr(), None

    s = chain()
    s.add_force(ms.PythonForce(tether_force, jacobian=growing, name="grows"))
    solver = backward_euler(ms.BackwardEulerMode.Linearized)
    solver.precompute(s, H)
    x = s.positions.copy()
    with pytest.raises(ms.Error, match=r'"grows": jacobian\(x, v\) dfdx: nonzero entry \(4, 4\) '
                                       r"outside the pattern of its first call"):
        solver.step(s)
    assert np.array_equal(s.positions, x)


def test_construction_and_add_force_errors():
    with pytest.raises(ms.Error, match=r"^PythonForce: forces must be a callable .* got int"):
        ms.PythonForce(3)
    with pytest.raises(ms.Error, match=r"^PythonForce: jacobian must be None or a callable"):
        ms.PythonForce(tether_force, jacobian=[1])

    class Tether:
        def forces(self, x, v):
            return tether_force(x, v)

    s = chain()
    with pytest.raises(TypeError, match=r"add_force: expected a force term \(Gravity, .*"
                                        r"PythonForce\(forces, jacobian=None\) .* got Tether"):
        s.add_force(Tether())
    assert s.forces == []


def test_a_copied_system_keeps_the_term():
    s = chain()
    s.add_force(ms.PythonForce(tether_force, jacobian=tether_jacobian_dense))
    s.add_force(ms.Gravity(G))
    copy = s.copy()
    del s
    x0, _ = run(copy, backward_euler(ms.BackwardEulerMode.Linearized), steps=5)
    t = chain()
    t.add_force(ms.PythonForce(tether_force, jacobian=tether_jacobian_dense))
    t.add_force(ms.Gravity(G))
    x1, _ = run(t, backward_euler(ms.BackwardEulerMode.Linearized), steps=5)
    assert np.array_equal(x0, x1)


def test_two_threads_step_systems_with_python_terms():
    """The steps run without the GIL and take it for each callback: two threads, each stepping
    its own system, finish (no deadlock) with the trajectory of one thread alone."""
    import threading

    def stepped(results, k):
        s = chain()
        s.add_force(ms.PythonForce(tether_force, jacobian=tether_jacobian_dense))
        s.add_force(ms.PythonForce(python_gravity(s), jacobian=zero_jacobian))
        solver = ms.RK4() if k == 0 else backward_euler(ms.BackwardEulerMode.Newton)
        results[k] = run(s, solver, steps=30)[0]

    alone = [None, None]
    for k in range(2):
        stepped(alone, k)
    together = [None, None]
    threads = [threading.Thread(target=stepped, args=(together, k)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
        assert not t.is_alive()
    for k in range(2):
        assert np.array_equal(together[k], alone[k])
