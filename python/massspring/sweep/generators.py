"""Scene generators a spec can name as {"function": "massspring.sweep.generators:NAME",
"arguments": {...}}: each returns a MassSpringSystem with its force terms.

`pareto` builds benchmarks/pareto.cpp's five scenes exactly as it does (the recipes of
scene/recipes.hpp, changed as it changes them), so that benchmarks/pareto_sweep.json reproduces
its study."""

import math

import numpy as np

import massspring as ms


def _enum(enum, value):
    return getattr(enum, value) if isinstance(value, str) else value


def cloth(**fields):
    """make_cloth(ClothOptions(**fields)) with a Gravity term of 9.8 m/s^2 unless `gravity`
    [m/s^2] says otherwise; enums by name ("TopCorners")."""
    gravity = fields.pop("gravity", [0.0, -9.8, 0.0])
    for key, enum in (("shear", ms.ClothShear), ("pins", ms.ClothPins),
                      ("plane", ms.ClothPlane)):
        if key in fields:
            fields[key] = _enum(enum, fields[key])
    system = ms.make_system(ms.make_cloth(ms.ClothOptions(**fields)))
    if any(gravity) and "gravity" not in system.forces:
        system.add_force(ms.Gravity(gravity))
    return system


def _under_gravity(description):
    system = ms.make_system(description)
    system.add_force(ms.Gravity([0.0, -9.81, 0.0]))
    return system


def pareto(scene, stiffness=50.0):
    """benchmarks/pareto.cpp's scene `scene`: chain, net, orbit, cloth32 or cloth64 (`stiffness`
    [N/m] for the cloths; the study's is 50). End times: 1 s, orbit 1.5 pi s."""
    if scene == "chain":
        options = ms.chain_recipe()
        options.points = 20
        options.mass = 0.05
        return _under_gravity(ms.make_chain(options))
    if scene == "net":
        options = ms.net_recipe()
        options.mass = 1.0 / 64
        return _under_gravity(ms.make_net(options))
    if scene in ("cloth32", "cloth64"):
        options = ms.hanging_cloth_recipe(int(scene[5:]))
        options.stiffness = stiffness
        return _under_gravity(ms.make_cloth(options))
    if scene == "orbit":
        system = ms.MassSpringSystem(np.array([[0.0, 0, 0], [1, 0, 0]]),
                                     np.zeros((0, 2), dtype=np.int64), 1.0, 0.0)
        system.pin(0)
        system.velocities = np.array([[0.0, 0, 0], [0, 1, 0]])
        system.add_force(ms.GravitationalAttraction(np.array([[0, 1]]), 1.0))
        return system
    raise ValueError(f"pareto: unknown scene {scene!r} (expected chain, net, orbit, cloth32 or "
                     "cloth64)")


PARETO_END_TIMES = {"chain": 1.0, "net": 1.0, "cloth32": 1.0, "cloth64": 1.0,
                    "orbit": 1.5 * math.pi}
