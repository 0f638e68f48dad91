"""Shared set-up of the Python module's tests (run by ctest, tests/python/CMakeLists.txt, or by
hand: PYTHONPATH=build/python python3 -m pytest tests/python).

Environment (ctest sets each):
  MASSSPRING_SOURCE_DIR  the checkout (default: two folders up from here)
  MASSSPRING_SIMULATE    massspring-simulate, for the bit-for-bit test (unset or empty: skipped)
Scratch files go to pytest's tmp_path."""

import os

import numpy as np
import pytest

import massspring as ms

SOURCE_DIR = os.environ.get("MASSSPRING_SOURCE_DIR") or os.path.abspath(
    os.path.join(os.path.dirname(__file__), "..", ".."))


def scene(name):
    """A scene file shipped with the project (examples/scenes or examples/scenes_xml)."""
    for folder in ("scenes", "scenes_xml"):
        path = os.path.join(SOURCE_DIR, "examples", folder, name)
        if os.path.exists(path):
            return path
    raise FileNotFoundError(name)


def grid(columns, rows, spacing=0.1):
    """A flat cloth: columns x rows points in the x-y plane, structural and shear springs."""
    index = np.arange(columns * rows).reshape(rows, columns)
    x, y = np.meshgrid(np.arange(columns) * spacing, -np.arange(rows) * spacing)
    points = np.column_stack([x.ravel(), y.ravel(), np.zeros(columns * rows)])
    springs = np.concatenate([
        np.column_stack([index[:, :-1].ravel(), index[:, 1:].ravel()]),
        np.column_stack([index[:-1, :].ravel(), index[1:, :].ravel()]),
        np.column_stack([index[:-1, :-1].ravel(), index[1:, 1:].ravel()]),
        np.column_stack([index[:-1, 1:].ravel(), index[1:, :-1].ravel()]),
    ])
    return points, springs


@pytest.fixture
def chain():
    """Three points on the x axis, two springs (k = 100 N/m, m = 1 kg), nothing pinned."""
    points = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]])
    springs = np.array([[0, 1], [1, 2]])
    return ms.MassSpringSystem(points, springs, 1.0, 100.0)
