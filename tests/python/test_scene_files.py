"""Scene files from Python: JSON+OBJ and FOSSSim XML load with what they hold, a saved state
reads back exactly, an OBJ is written."""

import numpy as np

import massspring as ms
from conftest import scene


def test_json_scene():
    loaded = ms.load_scene_file(scene("flag.json"))
    s = loaded.system
    assert s.num_points > 0 and s.num_springs > 0 and s.num_pinned > 0
    assert loaded.fosssim is None and not loaded.state
    assert len(loaded.faces) > 0 and all(len(f) >= 3 for f in loaded.faces)
    assert any(str(f).endswith("flag.obj") for f in loaded.files)
    assert s.forces == []  # a JSON+OBJ scene brings no force terms
    same = ms.load_scene(scene("flag.json"))
    assert np.array_equal(same.positions, s.positions)
    x = s.positions
    del loaded  # the view keeps the system, which keeps the loaded scene
    assert np.array_equal(x, same.positions)


def test_xml_scene():
    loaded = ms.load_scene_file(scene("orbit.xml"))
    run = loaded.fosssim
    assert run is not None and run.dt > 0 and run.duration > 0 and run.steps > 0
    assert run.integrator in ("explicit-euler", "symplectic-euler", "linearized-implicit-euler",
                              "implicit-euler")
    assert "gravitational attraction" in loaded.system.forces


def test_state_scene_round_trip(tmp_path):
    s = ms.load_scene(scene("chain.json"))
    s.add_force(ms.Gravity([0, -9.8, 0]))
    solver = ms.FastMassSpring()
    solver.precompute(s, 1 / 30)
    for _ in range(5):
        solver.step(s)
    path = str(tmp_path / "state.json")
    ms.write_state(s, path)
    back = ms.load_scene_file(path)
    assert back.state
    t = back.system
    for name in ("positions", "velocities", "masses", "stiffness", "rest_lengths", "pin_targets"):
        assert np.array_equal(getattr(t, name), getattr(s, name)), name
    assert t.forces == ["gravity"]


def test_write_obj(tmp_path):
    path = tmp_path / "tri.obj"
    ms.write_obj(str(path), np.eye(3), faces=[[0, 1, 2]], edges=[[0, 1]])
    text = path.read_text()
    assert text.count("\nv ") + text.startswith("v ") == 3
    assert "f 1 2 3" in text
