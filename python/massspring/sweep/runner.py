"""One run of a sweep, as a worker does it (no Dask here): set up the scene, step it, return the
result as plain data (numpy arrays and numbers).

The set-up follows massspring-simulate's order, so that a run equals the tool's run with the same
options bit for bit: the scene (file or generator), its model changes, self-collision, then the
force terms (Gravity unless the scene has its own or comes from a generator function,
ConstantForce, LinearDrag), the integrator and its options, precompute, the energy guard
(DivergenceGuard, growth `guard_growth`; 0: none), and `frames` x `every` steps."""

import importlib
import math
import os
import socket
import tempfile
import time

import numpy as np

import massspring as ms

from .spec import BE, DEFAULTS, FMS, FOSSSIM_INTEGRATORS

# The per-step statistics: the StepReport fields, stored under the same names.
REPORT_FIELDS = ("iterations", "relative_decrease", "energy", "residual", "converged",
                 "convergence", "finite", "refactorized", "factorization_failed", "blew_up",
                 "contact_impulses", "contact_zone_points", "contact_resolved", "contact_work")
REPORT_TYPES = {"iterations": np.int32, "contact_impulses": np.int32,
                "contact_zone_points": np.int32, "convergence": np.int8, "relative_decrease":
                np.float64, "energy": np.float64, "residual": np.float64,
                "contact_work": np.float64}


def scene_bundle(path, files):
    """The files a scene reads, as {"main": name, "files": {name: bytes}} with names relative to
    their common folder: shipped to workers that may not see the client's files."""
    root = os.path.commonpath([os.path.dirname(os.path.abspath(f)) for f in files])
    contents = {}
    for f in files:
        with open(f, "rb") as handle:
            contents[os.path.relpath(os.path.abspath(f), root)] = handle.read()
    return {"main": os.path.relpath(os.path.abspath(path), root), "files": contents}


def _load_bundle(bundle):
    with tempfile.TemporaryDirectory(prefix="massspring-sweep-") as folder:
        for name, data in bundle["files"].items():
            target = os.path.join(folder, name)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as handle:
                handle.write(data)
        return ms.load_scene_file(os.path.join(folder, bundle["main"]))


def _generated(spec):
    """massspring-simulate's --generate KIND[:SIZE]."""
    kind, _, size = spec.partition(":")
    if kind == "chain":
        options = ms.ChainOptions()
        if size:
            options.points = int(size)
        return ms.make_system(ms.make_chain(options))
    options = ms.ClothOptions() if kind == "cloth" else ms.NetOptions()
    if size:
        options.columns, options.rows = (int(v) for v in size.split("x"))
    return ms.make_system(ms.make_cloth(options) if kind == "cloth" else ms.make_net(options))


def _call_generator(generator):
    module, _, name = generator["function"].partition(":")
    function = getattr(importlib.import_module(module), name)
    system = function(**generator.get("arguments", {}))
    if not isinstance(system, ms.MassSpringSystem):
        raise TypeError(f"generator {generator['function']} returned {type(system).__name__}, "
                        "not a MassSpringSystem")
    return system


def setup(parameters, bundle=None):
    """The system, the integrator (configured, not precomputed), dt and the number of steps of a
    run. Raises massspring.Error (or another exception) naming what is wrong."""
    p = parameters
    fosssim, scene_dt, state = None, None, False
    if "scene" in p:
        if bundle is not None:
            loaded = _load_bundle(bundle)
        else:
            loaded = ms.load_scene_file(p["scene"])
        system, fosssim, scene_dt, state = loaded.system, loaded.fosssim, loaded.dt, loaded.state
    elif isinstance(p["generate"], str):
        system = _generated(p["generate"])
    else:
        system = _call_generator(p["generate"])

    # the model
    if "stiffness" in p:
        system.stiffness = np.full(system.num_springs, p["stiffness"])
    if "stiffness_scale" in p:
        system.stiffness = system.stiffness * p["stiffness_scale"]
    if "mass" in p:
        system.masses = np.full(system.num_points, p["mass"])
    if "mass_scale" in p:
        system.masses = system.masses * p["mass_scale"]
    if "damping" in p:
        system.damping = np.full(system.num_springs, p["damping"])
    for i in range(system.num_colliders):
        if "friction" in p or "restitution" in p:
            c = system.collider(i)
            if "friction" in p:
                c.set_friction(*(p["friction"] if isinstance(p["friction"], list)
                                 else [p["friction"]]))
            if "restitution" in p:
                c.set_restitution(p["restitution"])
            system.set_collider(i, c)
    for change in p.get("colliders", []):
        i = change["index"]
        if i >= system.num_colliders:
            raise ValueError(f"colliders: index {i}: the scene has {system.num_colliders} "
                             "colliders")
        c = system.collider(i)
        if "velocity" in change:
            c.set_velocity(change["velocity"])
        if "angular_velocity" in change:
            c.set_angular_velocity(change["angular_velocity"])
        if "friction" in change:
            f = change["friction"]
            c.set_friction(*(f if isinstance(f, list) else [f]))
        if "restitution" in change:
            c.set_restitution(change["restitution"])
        system.set_collider(i, c)
    if "self_collision" in p:
        if system.surface.shape[0] == 0:
            raise ValueError("self_collision: the scene has no surface to collide (no polygons)")
        system.set_self_collision(thickness=p["self_collision"])

    # the force terms, as massspring-simulate adds them (an XML scene or a saved state has its own)
    if (fosssim is not None or state) and ("gravity" in p or "force" in p):
        raise ValueError(f"{'gravity' if 'gravity' in p else 'force'}: "
                         f"{'an XML scene' if fosssim is not None else 'a saved state'} carries "
                         "its own force terms")
    if fosssim is None and not state:
        own_gravity = "gravity" in system.forces
        if own_gravity and "gravity" in p:
            raise ValueError("gravity: the scene carries its own gravity; change it there, or "
                             "leave out \"gravity\"")
        # massspring-simulate's default gravity, for its kinds of scene only: a generator
        # function's system comes with the force terms it means to have
        from_function = isinstance(p.get("generate"), dict)
        gravity = p.get("gravity", [0.0, 0.0, 0.0] if from_function else [0.0, -9.8, 0.0])
        if any(gravity) and not own_gravity:
            system.add_force(ms.Gravity(gravity))
        if any(p.get("force", [0.0, 0.0, 0.0])):
            system.add_force(ms.ConstantForce(p["force"]))
    if p.get("drag"):
        system.add_force(ms.LinearDrag(p["drag"]))

    # the integrator
    integrator = p.get("integrator") or (FOSSSIM_INTEGRATORS[fosssim.integrator]
                                         if fosssim is not None else FMS)
    dt = p.get("dt") or (fosssim.dt if fosssim is not None else scene_dt) or 1.0 / 30
    solver = {FMS: ms.FastMassSpring, "forward-euler": ms.ForwardEuler,
              "symplectic-euler": ms.SymplecticEuler, BE: ms.BackwardEuler,
              "linearized-backward-euler": ms.BackwardEuler, "rk4": ms.RK4}[integrator]()
    if integrator == FMS:
        o = solver.options
        for key in ("iterations", "tolerance", "penalty_weight", "chebyshev_rho",
                    "chebyshev_gamma", "chebyshev_delay", "chebyshev_estimate_iterations",
                    "anderson_window", "threads"):
            if key in p:
                setattr(o, key, p[key])
        # The names are the library's (option_names.hpp), as massspring-simulate reads them.
        for key, enum in (("pins", ms.PinMode), ("acceleration", ms.Acceleration),
                          ("ordering", ms.FillOrdering), ("initial_guess", ms.InitialGuess)):
            if key in p:
                setattr(o, key, enum.from_name(p[key]))
    elif integrator in (BE, "linearized-backward-euler"):
        o = solver.options
        if integrator == "linearized-backward-euler":
            o.mode = ms.BackwardEulerMode.Linearized
        if "newton_iterations" in p:
            o.iterations = p["newton_iterations"]
        if "newton_tolerance" in p:
            o.tolerance = p["newton_tolerance"]
        if "line_search" in p:
            o.line_search = p["line_search"]
    # The energy bound of every integrator: the guard's growth, as massspring-simulate sets it.
    growth = p.get("guard_growth", DEFAULTS["guard_growth"])
    if integrator in (FMS, BE, "linearized-backward-euler"):
        solver.options.energy_growth = growth
        if "contact_weight" in p:
            solver.options.contact_weight = p["contact_weight"]
    else:
        solver.set_energy_growth(growth)
    steps = p.get("frames", DEFAULTS["frames"]) * p.get("every", DEFAULTS["every"])
    return system, solver, integrator, dt, steps


class _Shrink:
    """massspring-simulate's --shrink: before step k (1-based) the rest lengths are
    l0(0) exp(-shrink dt (k - 1)); nothing when the run has no "shrink"."""

    def __init__(self, parameters, system, dt):
        self.rate = parameters.get("shrink", 0.0)
        self.rest = system.rest_lengths.copy() if self.rate > 0 else None
        self.dt = dt

    def before(self, system, step):
        if self.rest is not None:
            system.rest_lengths = self.rest * math.exp(-self.rate * self.dt * (step - 1))


def _frames_to_save(choice, frames):
    if choice == "last":
        return [frames]
    if choice == "ends":
        return sorted({0, frames})
    if choice == "all":
        return list(range(frames + 1))
    return list(choice)


def _repeat(parameters, bundle, steps, growth, energy):
    """The time [s] of one more stepping loop of the run (a new set-up: the same trajectory),
    timed as run() times it: the sum of the step() calls' wall clock; None when a step fails (a
    loop cut short is no time for the whole run)."""
    system, solver, _, dt, _ = setup(parameters, bundle)
    solver.precompute(system, dt)
    guard = ms.DivergenceGuard(system, growth) if growth > 0 else None
    shrink = _Shrink(parameters, system, dt)
    clock = time.perf_counter
    total = 0.0
    for step in range(1, steps + 1):
        shrink.before(system, step)
        t0 = clock()
        report = guard.step(solver, system) if guard is not None else solver.step(system)
        total += clock() - t0
        if energy:
            ms.total_energy(system)
            ms.kinetic_energy(system)
        if not report.ok():
            return None
    return total


def run(parameters, bundle=None):
    """Runs one run; never raises. Returns a dict:

    status       "ok", "diverged" (a step failed or the energy guard stopped it: the last good
                 state is kept), "skipped" (projected past `budget`) or "failed" (the set-up
                 raised: `message` says why)
    message      "" when ok, else what happened
    frames       the frame numbers stored, (k,); positions, velocities (k, n, 3) [m, m/s]
    final_step   the steps done; final_positions, final_velocities: the state after them
    steps        {name: (final_step,) array}: time [s] of each step (wall clock of step()),
                 total_energy and kinetic_energy [J] after it (when `energy`), the StepReport
                 fields
    loop_seconds (r,) the stepping loop's time [s] (the sum of `time`) of each repetition, the
                 stored run first; with `min_time`, an ok run is repeated (new set-ups, the same
                 trajectory) until these add up to min_time (at most 10000)
    dt, integrator, num_points, num_springs, initial_energy [J], wall_seconds (set-up and
    stepping), host, pid"""
    start = time.perf_counter()
    result = {"status": "ok", "message": "", "host": socket.gethostname(), "pid": os.getpid()}
    try:
        system, solver, integrator, dt, steps = setup(parameters, bundle)
        result.update(integrator=integrator, dt=dt, num_points=system.num_points,
                      num_springs=system.num_springs)
        frames = parameters.get("frames", DEFAULTS["frames"])
        every = parameters.get("every", DEFAULTS["every"])
        wanted = set(_frames_to_save(parameters.get("save_frames", DEFAULTS["save_frames"]),
                                     frames))
        energy = parameters.get("energy", DEFAULTS["energy"])
        growth = parameters.get("guard_growth", DEFAULTS["guard_growth"])
        budget = parameters.get("budget")

        solver.precompute(system, dt)
        guard = ms.DivergenceGuard(system, growth) if growth > 0 else None
        shrink = _Shrink(parameters, system, dt)
        result["initial_energy"] = float(ms.total_energy(system))
        saved_frames, positions, velocities = [], [], []

        def keep(frame):
            if frame in wanted:
                saved_frames.append(frame)
                positions.append(system.positions.copy())
                velocities.append(system.velocities.copy())

        keep(0)
        times = np.zeros(steps)
        reports = {name: [] for name in REPORT_FIELDS}
        total, kinetic = [], []
        probe = min(steps, max(3, steps // 50))
        done = 0
        loop_start = time.perf_counter()
        for step in range(1, steps + 1):
            if budget is not None and step - 1 == probe and probe < steps:
                projected = (time.perf_counter() - loop_start) * steps / probe
                if projected > budget:
                    result["status"] = "skipped"
                    result["message"] = (f"projected {projected:.3g} s for {steps} steps, past "
                                         f"the budget {budget:g} s; stopped after {probe}")
                    break
            shrink.before(system, step)
            t0 = time.perf_counter()
            report = guard.step(solver, system) if guard is not None else solver.step(system)
            times[step - 1] = time.perf_counter() - t0
            for name in REPORT_FIELDS:
                value = getattr(report, name)
                reports[name].append(int(value) if name == "convergence" else value)
            if energy:
                total.append(float(ms.total_energy(system)))
                kinetic.append(float(ms.kinetic_energy(system)))
            done = step
            if not report.ok():
                result["status"] = "diverged"
                if report.blew_up:
                    result["message"] = (
                        f"step {step}: the total energy passed the divergence limit "
                        f"({guard.limit:.6g} J: the initial energy + {growth:g} x the scale "
                        f"{guard.scale:.6g} J), or the step gained more than {growth:g} x the "
                        "scale, the integrator's own bound; stopped with the last good state")
                    if report.contact_work > ms.CONTACT_LIMIT_SHARE * guard.scale:
                        result["message"] += (
                            f"; in that step the contact response added "
                            f"{report.contact_work:.6g} J, more than half the scale "
                            "(StepReport.contact_work)")
                    elif integrator == "linearized-backward-euler":
                        result["message"] += (
                            "; linearized-backward-euler also refuses a step whose one linear "
                            "solve raises the incremental potential it linearises (its linear "
                            "model failed)")
                elif not report.contact_resolved:
                    result["message"] = (f"step {step}: surface contact left a crossing its "
                                         "rounds could not remove; stopped with the last good "
                                         "state")
                elif report.factorization_failed:
                    result["message"] = (f"step {step}: the factorisation failed; stopped with "
                                         "the last good state")
                else:
                    result["message"] = (f"step {step}: the step produced a non-finite state; "
                                         "stopped with the last finite state")
                break
            if step % every == 0:
                keep(step // every)
        result["final_step"] = done
        result["frames"] = np.array(saved_frames, dtype=np.int64)
        n = system.num_points
        result["positions"] = np.array(positions).reshape(-1, n, 3)
        result["velocities"] = np.array(velocities).reshape(-1, n, 3)
        result["final_positions"] = system.positions.copy()
        result["final_velocities"] = system.velocities.copy()
        statistics = {"time": times[:done]}
        if energy:
            statistics["total_energy"] = np.array(total[:done], dtype=np.float64)
            statistics["kinetic_energy"] = np.array(kinetic[:done], dtype=np.float64)
        for name in REPORT_FIELDS:
            statistics[name] = np.array(reports[name][:done],
                                        dtype=REPORT_TYPES.get(name, np.bool_))
        result["steps"] = statistics
        loops = [float(np.sum(times[:done]))]
        min_time = parameters.get("min_time")
        if min_time is not None and result["status"] == "ok" and done > 0:
            while sum(loops) < min_time and len(loops) < 10000:
                seconds = _repeat(parameters, bundle, done, growth, energy)
                if seconds is None:
                    break
                loops.append(seconds)
        result["loop_seconds"] = np.array(loops, dtype=np.float64)
    except Exception as e:  # noqa: BLE001: every failure of a run is recorded, not raised
        result["status"] = "failed"
        result["message"] = f"{type(e).__name__}: {e}" if not isinstance(e, ms.Error) else str(e)
    result["wall_seconds"] = time.perf_counter() - start
    return result
