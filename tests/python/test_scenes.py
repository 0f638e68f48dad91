"""Generated scenes from Python: make_cloth, make_chain and make_net with their options, a
SceneDescription read and changed, and make_system."""

import numpy as np
import pytest

import massspring as ms


def test_cloth():
    o = ms.ClothOptions()
    assert (o.columns, o.rows, o.pins, o.shear, o.plane, o.mass) == (
        60, 50, ms.ClothPins.TopCorners, ms.ClothShear.Both, ms.ClothPlane.Vertical, None)
    o.columns, o.rows, o.width, o.height = 5, 4, 0.4, 0.3
    scene = ms.make_cloth(o)
    assert scene.vertices.shape == (20, 3)
    assert np.allclose(scene.vertices.max(axis=0) - scene.vertices.min(axis=0), [0.4, 0.3, 0])
    assert scene.pinned == [0, 4] and scene.stiffness == o.stiffness and scene.mass is None
    assert len(scene.faces) == 4 * 3  # quads (shear Both)
    s = ms.make_system(scene)
    assert (s.num_points, s.num_pinned) == (20, 2)
    # 3 x 4 horizontal + 5 x 3 vertical structural springs and 2 diagonals per cell
    assert s.num_springs == 4 * 4 + 5 * 3 + 2 * 12
    # Voronoi masses at 1 kg/m^2: they sum to the cloth's area
    assert (s.masses > 0).all() and s.masses.sum() == pytest.approx(0.4 * 0.3, rel=1e-12)


def test_cloth_options_change_the_scene():
    o = ms.ClothOptions()
    o.columns, o.rows = 3, 3
    o.shear, o.pins, o.plane, o.mass = ms.ClothShear.None_, ms.ClothPins.TopEdge, \
        ms.ClothPlane.Horizontal, 0.5
    scene = ms.make_cloth(o)
    assert scene.pinned == [0, 1, 2] and scene.mass == 0.5
    assert np.array_equal(scene.vertices[:, 1], np.zeros(9))  # horizontal: y = 0
    s = ms.make_system(scene)
    assert s.num_springs == 12 and np.array_equal(s.masses, np.full(9, 0.5))


def test_chain_and_net():
    c = ms.ChainOptions()
    c.points, c.length, c.pins, c.mass = 5, 2.0, ms.ChainPins.First, 0.25
    c.direction = [0, -1, 0]
    s = ms.make_system(ms.make_chain(c))
    assert (s.num_points, s.num_springs, s.pinned) == (5, 4, [0])
    assert np.allclose(s.rest_positions[-1] - s.rest_positions[0], [0, -2, 0])
    n = ms.NetOptions()
    n.columns, n.rows, n.pins = 4, 3, ms.NetPins.Border
    s = ms.make_system(ms.make_net(n))
    assert s.num_points == 12 and s.num_pinned == 10


def test_a_scene_can_be_edited():
    scene = ms.SceneDescription()
    scene.vertices = [[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]
    scene.edges = [[0, 1], [1, 2]]
    scene.pinned = [0]
    scene.stiffness = 10.0
    scene.mass = 2.0
    s = ms.make_system(scene)
    assert (s.num_points, s.num_springs, s.pinned) == (3, 2, [0])
    assert np.array_equal(s.stiffness, [10, 10]) and np.array_equal(s.masses, [2, 2, 2])
    scene.edges = [[0, 5]]
    with pytest.raises(ms.Error, match="5"):
        ms.make_system(scene)
    with pytest.raises(ms.Error, match="make_cloth: columns and rows must be >= 2, got 1 by 50"):
        o = ms.ClothOptions()
        o.columns = 1
        ms.make_cloth(o)
