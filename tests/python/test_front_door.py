"""What a new user meets first, from Python: messages that quote numbers as written and name what
was expected, options built by keyword and checked when set, a report that does not call a step
without a tolerance a failure, generators placed where asked, and JSON scenes that carry their own
gravity and step."""

import json
import re
import shutil

import numpy as np
import pytest

import massspring as ms
from conftest import scene


def test_numbers_in_messages_are_the_shortest_that_read_back():
    with pytest.raises(ms.Error) as error:
        ms.Collider.sphere([0, 0, 0], -0.3)
    assert "-0.3" in str(error.value)
    assert "-0.29999" not in str(error.value)


def test_pin_of_a_float_says_what_pin_takes():
    system = ms.make_system(ms.make_chain())
    with pytest.raises(ms.Error, match=re.escape(
            "pin: expected a point index (an int) or a list of them, got 1.0 (float)")):
        system.pin(1.0)
    with pytest.raises(ms.Error, match=re.escape("got 2.0 (float64)")):
        system.pin(np.float64(2.0))
    system.pin(1)  # an int and a list still work
    system.pin([2, 3])
    assert system.pinned == [0, 1, 2, 3, 9]


def test_generator_options_by_keyword():
    options = ms.ClothOptions(columns=30, rows=20, center=[0, 1, 0])
    assert (options.columns, options.rows) == (30, 20)
    assert ms.ChainOptions(points=12).points == 12
    assert ms.NetOptions(columns=6, rows=5, width=2.0).width == 2.0
    assert ms.ClothOptions().columns == 60  # no keyword: the defaults
    with pytest.raises(TypeError, match='ClothOptions\\(\\) has no field "colums" '
                                        '\\(fields: .*columns.*\\)'):
        ms.ClothOptions(colums=30)
    with pytest.raises(TypeError):  # a field's own type check, as for an assignment
        ms.ClothOptions(columns="thirty")


def test_generators_place_the_scene_at_origin_or_center():
    cloth = ms.make_cloth(ms.ClothOptions(columns=5, rows=4, plane=ms.ClothPlane.Horizontal,
                                          center=[0.25, 1.5, -0.75]))
    v = cloth.vertices
    assert np.allclose((v.min(axis=0) + v.max(axis=0)) / 2, [0.25, 1.5, -0.75], atol=1e-15)
    chain = ms.make_chain(ms.ChainOptions(origin=[1, 2, 3]))
    assert list(chain.vertices[0]) == [1, 2, 3]
    options = ms.NetOptions(origin=[0, 0, 0], center=[1, 1, 1])
    with pytest.raises(ms.Error, match="make_net: give origin .* or center .*, not both"):
        ms.make_net(options)
    options.origin = None
    assert options.origin is None
    assert np.allclose(ms.make_net(options).vertices.mean(axis=0), [1, 1, 1])


def test_options_are_checked_when_set():
    solver = ms.FastMassSpring()
    with pytest.raises(ms.Error, match=re.escape(
            "FastMassSpring: options.iterations must be >= 1, got -1")):
        solver.options.iterations = -1
    assert solver.options.iterations == ms.FastMassSpringOptions().iterations  # unchanged
    solver.options.iterations = 3
    assert solver.options.iterations == 3


def test_the_removed_options_name_their_force_terms():
    solver = ms.FastMassSpring()
    with pytest.raises(AttributeError, match="add massspring.Gravity"):
        solver.options.gravity = [0, -9.8, 0]
    with pytest.raises(AttributeError, match="add massspring.ConstantForce"):
        solver.options.external_force
    assert solver.options.iterations == ms.FastMassSpringOptions().iterations  # unchanged


def test_help_names_array_arguments():
    signature = ms.Collider.sphere.__doc__.splitlines()[0]
    assert "center: ArrayLike" in signature and "handle" not in signature


def test_a_step_without_a_tolerance_is_not_called_unconverged():
    system = ms.make_system(ms.make_cloth(ms.ClothOptions(columns=6, rows=5)))
    system.add_force(ms.Gravity([0, -9.8, 0]))
    solver = ms.FastMassSpring()
    solver.precompute(system, 1.0 / 30)
    report = solver.step(system)
    assert report.ok() and not report.converged
    assert report.convergence == ms.Convergence.NotTested
    assert "convergence=NotTested" in repr(report) and "converged=False" not in repr(report)
    solver.options.tolerance = 1e-30
    solver.options.iterations = 2
    assert solver.step(system).convergence == ms.Convergence.NotConverged
    solver.options.tolerance = 1e-2
    solver.options.iterations = 50
    assert solver.step(system).convergence == ms.Convergence.Converged


def test_a_json_scene_carries_its_gravity_and_dt(tmp_path):
    loaded = ms.load_scene_file(scene("drape.json"))
    assert loaded.dt == 0.005
    assert loaded.system.forces == ["gravity"]
    shutil.copy(scene("chain.obj"), tmp_path / "chain.obj")
    with open(scene("chain.json")) as f:
        keys = json.load(f)
    for bad, message in (({"dt": 0}, 'key "dt": expected a finite number > 0, got 0'),
                         ({"gravity": [0, "down", 0]},
                          'key "gravity": expected [gx, gy, gz] (three finite numbers, m/s^2)'),
                         ({"gravity": [0, -9.8]},
                          'key "gravity": expected [gx, gy, gz] (three numbers, m/s^2)')):
        path = tmp_path / "bad.json"
        path.write_text(json.dumps({**keys, **bad}))
        with pytest.raises(ms.Error, match=re.escape(message)):
            ms.load_scene(str(path))
    assert ms.load_scene_file(scene("chain.json")).dt is None


def test_option_enums_read_and_write_the_command_lines_names():
    assert ms.Acceleration.from_name("chebyshev") == ms.Acceleration.Chebyshev
    assert ms.Acceleration.None_.text == "none"
    assert ms.FillOrdering.from_name("nested-dissection") == ms.FillOrdering.NestedDissection
    assert [ms.PinMode.from_name(p.text) for p in (ms.PinMode.Exact, ms.PinMode.Penalty)] == [
        ms.PinMode.Exact, ms.PinMode.Penalty]
    with pytest.raises(ms.Error, match=r'^acceleration: unknown value "fast" \(expected none, '
                                       r'chebyshev or anderson\)$'):
        ms.Acceleration.from_name("fast")
