"""The surface (triangles of point indices) and self-collision of a MassSpringSystem: set, read
back, refused with the library's message, carried by scenes, state files and copies."""

import math

import numpy as np
import pytest

import massspring as ms
from conftest import grid, scene


def cell_triangles(columns, rows):
    """Two triangles (a, b, c), (a, c, d) per cell of conftest.grid's point numbering."""
    index = np.arange(columns * rows).reshape(rows, columns)
    a, b = index[:-1, :-1].ravel(), index[:-1, 1:].ravel()
    c, d = index[1:, 1:].ravel(), index[1:, :-1].ravel()
    return np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


@pytest.fixture
def cloth():
    points, springs = grid(3, 3)
    return ms.MassSpringSystem(points, springs, 0.1, 100.0)


def test_set_surface_round_trips_and_derives_the_edges(cloth):
    assert cloth.surface.shape == (0, 3)
    assert cloth.surface_edges.shape == (0, 2)
    triangles = cell_triangles(3, 3)
    revision = cloth.revision
    cloth.set_surface(triangles)
    assert cloth.revision == revision  # not a model change
    assert cloth.surface.dtype == np.int32
    assert np.array_equal(cloth.surface, triangles)
    # 12 sides of the 4 cells and their 4 diagonals a-c, each once, (i, j) with i < j, ascending
    edges = cloth.surface_edges
    assert edges.shape == (16, 2)
    assert np.all(edges[:, 0] < edges[:, 1])
    assert [tuple(e) for e in edges] == sorted({tuple(sorted(e)) for t in triangles
                                                for e in ((t[0], t[1]), (t[1], t[2]),
                                                          (t[2], t[0]))})
    cloth.set_surface(np.zeros((0, 3), dtype=np.int64))  # removes it
    assert cloth.surface.shape == (0, 3)


@pytest.mark.parametrize("triangles, message", [
    ([[0, 1, 9]], "surface triangle 0 = (0, 1, 9): point index 9 out of range [0, 9)"),
    ([[0, 1, 4], [1, 1, 4]], "surface triangle 1 = (1, 1, 4): repeats a point"),
    ([[0, 1, 2]], "surface triangle 0 = (0, 1, 2): zero area at the rest positions"),
])
def test_set_surface_refuses_a_bad_triangle_naming_it(cloth, triangles, message):
    cloth.set_surface(cell_triangles(3, 3))
    with pytest.raises(ms.Error) as info:
        cloth.set_surface(np.array(triangles))
    assert str(info.value) == message
    assert np.array_equal(cloth.surface, cell_triangles(3, 3))  # unchanged


@pytest.mark.parametrize("bad", [np.zeros((2, 2), dtype=int), np.zeros((2, 3)), [[0, 1]], "abc"])
def test_set_surface_refuses_arrays_of_the_wrong_shape_or_type(cloth, bad):
    with pytest.raises(ms.Error, match="surface: expected an integer array of shape"):
        cloth.set_surface(bad)


def test_self_collision_on_off_and_its_parameters(cloth):
    assert cloth.self_collision is None
    with pytest.raises(ms.Error, match="self-collision: the system has no surface"):
        cloth.set_self_collision()
    cloth.set_surface(cell_triangles(3, 3))
    cloth.set_self_collision()
    p = cloth.self_collision
    assert isinstance(p, ms.SelfCollision)
    assert (p.thickness, p.friction) == (0.004, 0.2)
    assert p == ms.SelfCollision()
    assert "self-collision" in repr(cloth)
    cloth.set_self_collision(thickness=0.01, friction=0.0)
    assert (cloth.self_collision.thickness, cloth.self_collision.friction) == (0.01, 0.0)
    copy = cloth.copy()
    cloth.clear_self_collision()
    assert cloth.self_collision is None
    assert copy.self_collision == ms.SelfCollision(0.01, 0.0)  # the copy keeps its own
    assert np.array_equal(copy.surface, cloth.surface)


@pytest.mark.parametrize("kwargs, message", [
    ({"thickness": 0.0}, "self-collision: thickness must be finite and > 0, got 0"),
    ({"thickness": -1e-3}, "self-collision: thickness must be finite and > 0, got -0.001"),
    ({"thickness": math.nan}, "self-collision: thickness must be finite and > 0, got nan"),
    ({"friction": -0.5}, "self-collision: friction must be finite and >= 0, got -0.5"),
    ({"friction": math.inf}, "self-collision: friction must be finite and >= 0, got inf"),
])
def test_self_collision_refuses_parameters_out_of_range(cloth, kwargs, message):
    cloth.set_surface(cell_triangles(3, 3))
    cloth.set_self_collision(thickness=0.02)
    with pytest.raises(ms.Error) as info:
        cloth.set_self_collision(**kwargs)
    assert str(info.value) == message
    assert cloth.self_collision == ms.SelfCollision(0.02)  # unchanged
    with pytest.raises(ms.Error) as info:
        ms.SelfCollision(**kwargs)
    assert str(info.value) == message


def test_scenes_give_the_surface_and_self_collision():
    options = ms.ClothOptions()
    options.columns, options.rows = 6, 4
    description = ms.make_cloth(options)
    assert description.self_collision is None
    system = ms.make_system(description)
    assert system.surface.shape == (2 * 5 * 3, 3)  # two triangles per cell
    assert system.self_collision is None
    description.self_collision = ms.SelfCollision(thickness=0.003, friction=0.5)
    assert ms.make_system(description).self_collision == ms.SelfCollision(0.003, 0.5)
    chain = ms.make_chain()
    chain.self_collision = ms.SelfCollision()
    with pytest.raises(ms.Error, match="self_collision: the scene has no faces"):
        ms.make_system(chain)
    assert ms.load_scene(scene("drape.json")).surface.shape[0] > 0
    assert ms.load_scene(scene("chain.json")).surface.shape == (0, 3)


def test_a_state_file_keeps_the_surface_and_self_collision(tmp_path):
    system = ms.load_scene(scene("drape.json"))
    system.set_self_collision(thickness=0.01 / 3, friction=0.7 / 3)
    path = str(tmp_path / "state.json")
    ms.write_state(system, path)
    back = ms.load_scene(path)
    assert np.array_equal(back.surface, system.surface)
    assert np.array_equal(back.surface_edges, system.surface_edges)
    assert back.self_collision == system.self_collision


def test_a_step_reports_its_surface_contact():
    """The two_cloths scene (self-collision on; the upper cloth lands on the lower one) at
    dt = 1/30: each report says how many contact impulses and impact-zone points the step took,
    and that the contact was resolved."""
    system = ms.load_scene(scene("two_cloths.json"))
    assert system.self_collision == ms.SelfCollision()
    system.add_force(ms.Gravity([0, -9.81, 0]))
    solver = ms.FastMassSpring()
    solver.options.iterations = 10
    solver.precompute(system, 1 / 30)
    reports = [solver.step(system) for _ in range(12)]
    assert all(r.ok() and r.contact_resolved for r in reports)
    assert sum(r.contact_impulses + r.contact_zone_points for r in reports) > 0
    assert system.positions[:, 1].min() >= 0  # the floor
