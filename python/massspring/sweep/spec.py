"""A sweep's specification: reading, checking and expanding it into runs (docs/sweeps.md).

A spec is a JSON object with up to three keys:

    base   an object: parameters every run shares
    runs   a list of objects: one run each, over `base` (default: one run, `base` itself)
    grid   an object of lists: every combination of the values, crossed with each entry of `runs`

A run's parameters are those of PARAMETERS below (name, check, default, unit). Every value is
checked where it is written (`base`, `runs[3]`, `grid.dt[2]`) and every expanded run as a whole
(one scene source, options that belong to its integrator) before anything runs; the first problem
raises SpecError with a message naming the entry."""

import hashlib
import itertools
import json
import math
import numbers
import os

import massspring as ms


def _names(enum):
    """The names an option enumeration takes (option_names.hpp, the command line's), in order."""
    return [value.text for value in enum.__members__.values()]


# massspring-simulate's --integrator names, and rk4 (the accuracy reference).
INTEGRATORS = ("fast-mass-spring", "forward-euler", "symplectic-euler", "backward-euler",
               "linearized-backward-euler", "rk4")
# A FOSSSim XML scene's own integrator names, and the run's name for each.
FOSSSIM_INTEGRATORS = {
    "explicit-euler": "forward-euler",
    "symplectic-euler": "symplectic-euler",
    "forward-backward-euler": "symplectic-euler",
    "linearized-implicit-euler": "linearized-backward-euler",
    "implicit-euler": "backward-euler",
}
GENERATOR_KINDS = ("cloth", "chain", "net")


class SpecError(ValueError):
    """A spec that cannot run; the message names the entry (file: entry: problem)."""


# ---- checks of one value: each returns the value (normalised) or raises ValueError(reason) ----

def _number(value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"expected a number, got {json.dumps(value)}")
    if not math.isfinite(value):
        raise ValueError(f"expected a finite number, got {value}")
    return float(value)


def positive(value):
    v = _number(value)
    if not v > 0:
        raise ValueError(f"must be > 0, got {value}")
    return v


def non_negative(value):
    v = _number(value)
    if not v >= 0:
        raise ValueError(f"must be >= 0, got {value}")
    return v


def unit_closed(value):
    v = _number(value)
    if not 0 <= v <= 1:
        raise ValueError(f"must be in [0, 1], got {value}")
    return v


def unit_open(value):
    v = _number(value)
    if not 0 <= v < 1:
        raise ValueError(f"must be in [0, 1), got {value}")
    return v


def unit_half_open_above(value):
    v = _number(value)
    if not 0 < v <= 1:
        raise ValueError(f"must be in (0, 1], got {value}")
    return v


def integer(low, high=None):
    def check(value):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise ValueError(f"expected a whole number, got {json.dumps(value)}")
        if value < low or (high is not None and value > high):
            raise ValueError(f"must be in [{low}, {high if high is not None else 'inf'}], "
                             f"got {value}")
        return int(value)
    return check


def one_of(*names):
    def check(value):
        if value not in names:
            raise ValueError(f"expected one of {', '.join(names)}; got {json.dumps(value)}")
        return value
    return check


def boolean(value):
    if not isinstance(value, bool):
        raise ValueError(f"expected true or false, got {json.dumps(value)}")
    return value


def vector3(value):
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise ValueError(f"expected three numbers [x, y, z], got {json.dumps(value)}")
    return [_number(v) for v in value]


def text(value):
    if not isinstance(value, str) or not value:
        raise ValueError(f"expected a non-empty string, got {json.dumps(value)}")
    return value


def friction(value):
    """mu (static and kinetic), or [mu_s, mu_k] with mu_k <= mu_s."""
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise ValueError(f"expected mu or [mu_static, mu_kinetic], got {json.dumps(value)}")
        s, k = non_negative(value[0]), non_negative(value[1])
        if k > s:
            raise ValueError(f"kinetic friction {k} exceeds static friction {s}")
        return [s, k]
    return non_negative(value)


def generator(value):
    """"KIND[:SIZE]" as massspring-simulate's --generate, or {"function": "module:name",
    "arguments": {...}} naming a function that returns a MassSpringSystem."""
    if isinstance(value, str):
        kind, _, size = value.partition(":")
        if kind not in GENERATOR_KINDS:
            raise ValueError(f"unknown generator {json.dumps(kind)} (expected cloth, chain or net "
                             f"as \"KIND[:SIZE]\", or {{\"function\": \"module:name\"}})")
        if size:
            parts = size.split("x")
            want = 1 if kind == "chain" else 2
            if len(parts) != want or not all(p.isdigit() for p in parts):
                raise ValueError(f"{json.dumps(value)}: expected {kind}:"
                                 f"{'POINTS' if want == 1 else 'COLUMNSxROWS'} with whole numbers")
        return value
    if isinstance(value, dict):
        unknown = set(value) - {"function", "arguments"}
        if unknown:
            raise ValueError(f"unknown key {json.dumps(sorted(unknown)[0])} in a generator "
                             "(expected \"function\" and \"arguments\")")
        function = value.get("function")
        if not isinstance(function, str) or function.count(":") != 1:
            raise ValueError("a generator's \"function\" must be \"module:name\", got "
                             f"{json.dumps(function)}")
        arguments = value.get("arguments", {})
        if not isinstance(arguments, dict):
            raise ValueError(f"a generator's \"arguments\" must be an object, got "
                             f"{json.dumps(arguments)}")
        return {"function": function, "arguments": arguments}
    raise ValueError(f"expected \"KIND[:SIZE]\" or {{\"function\": ...}}, got {json.dumps(value)}")


def save_frames(value):
    if value in ("last", "all", "ends"):
        return value
    if isinstance(value, list) and value:
        return sorted({integer(0)(v) for v in value})
    raise ValueError(f"expected \"last\", \"ends\", \"all\" or a list of frame numbers, got "
                     f"{json.dumps(value)}")


COLLIDER_KEYS = {
    "index": integer(0),
    "velocity": vector3,
    "angular_velocity": vector3,
    "friction": friction,
    "restitution": unit_closed,
}


def colliders(value):
    """A list of {"index": i, "velocity": [..], "angular_velocity": [..], "friction": mu,
    "restitution": e}: changes to the scene's colliders."""
    if not isinstance(value, list):
        raise ValueError(f"expected a list of collider changes, got {json.dumps(value)}")
    out = []
    for n, entry in enumerate(value):
        if not isinstance(entry, dict) or "index" not in entry:
            raise ValueError(f"[{n}]: expected an object with \"index\", got {json.dumps(entry)}")
        changed = {}
        for key, v in entry.items():
            if key not in COLLIDER_KEYS:
                raise ValueError(f"[{n}]: unknown key {json.dumps(key)} (expected "
                                 f"{', '.join(COLLIDER_KEYS)})")
            try:
                changed[key] = COLLIDER_KEYS[key](v)
            except ValueError as e:
                raise ValueError(f"[{n}].{key}: {e}") from None
        out.append(changed)
    return out


# name: (check, group, unit and meaning). group: None for every run, or the integrator (or
# acceleration) the option belongs to.
FMS = "fast-mass-spring"
BE = "backward-euler"
CONTACT = "contact"  # the options of the integrators with contact inside their solve
PARAMETERS = {
    # what runs
    "scene": (text, None, "a scene file (.json + .obj, .xml, or a saved state), relative to the "
                          "spec's folder"),
    "generate": (generator, None, "a generated scene instead of a file"),
    "name": (text, None, "a label, stored with the run"),
    "integrator": (one_of(*INTEGRATORS), None, "the integrator"),
    "dt": (positive, None, "time step [s]"),
    "frames": (integer(0, 100_000_000), None, "frames after the first"),
    "every": (integer(1, 100_000_000), None, "steps per frame"),
    "save_frames": (save_frames, None, "the frames whose positions and velocities are stored"),
    "guard_growth": (non_negative, None, "DivergenceGuard growth; 0: no energy check"),
    "energy": (boolean, None, "record the total and kinetic energy after every step"),
    "budget": (positive, None, "wall-clock seconds a run may take, projected from its first "
                               "steps"),
    "min_time": (non_negative, None, "repeat an ok run (timed only) until its stepping loops "
                                     "add up to this many seconds"),
    # the model
    "stiffness": (positive, None, "every spring's stiffness [N/m]"),
    "stiffness_scale": (positive, None, "multiplies every spring's stiffness"),
    "mass": (positive, None, "every point's mass [kg]"),
    "mass_scale": (positive, None, "multiplies every point's mass"),
    "damping": (non_negative, None, "every spring's damping [N s/m]"),
    "gravity": (vector3, None, "a Gravity term [m/s^2]"),
    "force": (vector3, None, "a ConstantForce term on every point [N]"),
    "drag": (non_negative, None, "a LinearDrag term, beta [N s/m]"),
    "friction": (friction, None, "every collider's friction"),
    "restitution": (unit_closed, None, "every collider's restitution"),
    "colliders": (colliders, None, "changes to single colliders"),
    "self_collision": (positive, None, "self-collision of the surface, thickness [m]"),
    "shrink": (non_negative, None, "rest lengths l0(t) = l0(0) exp(-shrink t) [1/s]"),
    "contact_weight": (non_negative, CONTACT, "contact and friction inside the solve, alpha"),
    # FastMassSpring
    "iterations": (integer(1, 1_000_000), FMS, "most local-global iterations per step"),
    "tolerance": (non_negative, FMS, "stop at this relative energy decrease"),
    "pins": (one_of(*_names(ms.PinMode)), FMS, "how pinned points are held"),
    "penalty_weight": (positive, FMS, "w for pins = penalty [N/m]"),
    "acceleration": (one_of(*_names(ms.Acceleration)), FMS, "the acceleration"),
    "chebyshev_rho": (unit_open, "chebyshev", "spectral radius; 0: estimated"),
    "chebyshev_gamma": (unit_half_open_above, "chebyshev", "under-relaxation"),
    "chebyshev_delay": (integer(1, 1_000_000), "chebyshev", "plain iterations first"),
    "chebyshev_estimate_iterations": (integer(4, 1_000_000), "chebyshev",
                                      "trial iterations to estimate rho"),
    "anderson_window": (integer(1, 16), "anderson", "past iterates in the fit"),
    "threads": (integer(1, 256), FMS, "threads for the substitutions"),
    "ordering": (one_of(*_names(ms.FillOrdering)), FMS, "fill-reducing order"),
    "initial_guess": (one_of(*_names(ms.InitialGuess)), FMS, "where iterations start"),
    # BackwardEuler
    "newton_iterations": (integer(1, 1_000_000), BE, "most Newton iterations per step"),
    "newton_tolerance": (non_negative, BE, "stop when max |dx| <= this (1 + max |x|)"),
    "line_search": (boolean, BE, "backtracking line search"),
}

DEFAULTS = {"frames": 30, "every": 1, "save_frames": "last", "guard_growth": 100.0,
            "energy": True}


class Run:
    """One expanded run: its parameters (as written, checked), where they came from, its index in
    the spec's order and its id (a hash of the parameters: the same run has the same id in any
    spec)."""

    def __init__(self, index, parameters, origin, folder):
        self.index = index
        self.parameters = parameters
        self.origin = origin
        canonical = json.dumps(parameters, sort_keys=True, separators=(",", ":"))
        self.id = "run-" + hashlib.sha1(canonical.encode()).hexdigest()[:16]
        # the scene file, absolute (a relative "scene" starts at the spec's folder)
        self.scene_path = (os.path.abspath(os.path.join(folder, parameters["scene"]))
                           if "scene" in parameters else None)

    def where(self):
        """The run as error messages name it."""
        return f"run {self.index} ({self.origin})"

    def get(self, key):
        return self.parameters.get(key, DEFAULTS.get(key))


def _check_entry(where, entry):
    """Checks an object of parameters; returns it normalised."""
    if not isinstance(entry, dict):
        raise SpecError(f"{where}: expected an object of parameters, got {json.dumps(entry)}")
    out = {}
    for key, value in entry.items():
        out[key] = _check_value(f"{where}.{key}", key, value)
    return out


def _check_value(where, key, value):
    if key not in PARAMETERS:
        near = [k for k in PARAMETERS if k.startswith(key[:3])]
        hint = f" (did you mean {', '.join(near)}?)" if near else ""
        raise SpecError(f"{where}: unknown parameter {json.dumps(key)}{hint}")
    try:
        return PARAMETERS[key][0](value)
    except ValueError as e:
        raise SpecError(f"{where}: {e}") from None


def _check_run(run, integrator_of_scene):
    """Checks a whole run: one scene source, options of its integrator only, frames in range."""
    p = run.parameters
    where = run.where()
    if ("scene" in p) == ("generate" in p):
        raise SpecError(f"{where}: give either \"scene\" or \"generate\"")
    own = integrator_of_scene(run)  # also loads (checks) the scene file
    integrator = p.get("integrator") or own or FMS
    acceleration = p.get("acceleration", ms.FastMassSpringOptions().acceleration.text)
    for key in p:
        group = PARAMETERS[key][1]
        if group is None:
            continue
        applies = (integrator == FMS if group == FMS
                   else integrator == BE if group == BE
                   else integrator in (FMS, BE, "linearized-backward-euler") if group == CONTACT
                   else integrator == FMS and acceleration == group)
        if not applies:
            needs = ("integrator " + group if group in (FMS, BE)
                     else "integrators fast-mass-spring, backward-euler and "
                     "linearized-backward-euler" if group == CONTACT
                     else "acceleration " + group)
            raise SpecError(f"{where}: \"{key}\" applies to {needs} only (this run: {integrator}"
                            f"{', acceleration ' + acceleration if integrator == FMS else ''})")
    frames = run.get("frames")
    if frames * run.get("every") > 100_000_000:
        raise SpecError(f"{where}: frames x every = {frames * run.get('every')} steps: more than "
                        "10^8")
    saved = run.get("save_frames")
    if isinstance(saved, list) and saved[-1] > frames:
        raise SpecError(f"{where}: save_frames names frame {saved[-1]}, past the last frame "
                        f"{frames}")
    for key in ("stiffness", "stiffness_scale"), ("mass", "mass_scale"):
        if all(k in p for k in key):
            raise SpecError(f"{where}: give \"{key[0]}\" or \"{key[1]}\", not both")


def load(path, integrator_of_scene=None):
    """Reads and checks a spec file; returns (spec, runs). Relative scene paths start at the
    spec's folder."""
    try:
        with open(path) as handle:
            spec = json.load(handle)
    except OSError as e:
        raise SpecError(f"{path}: cannot read it: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise SpecError(f"{path}: not JSON: {e}") from None
    return spec, expand(spec, name=path, folder=os.path.dirname(os.path.abspath(path)),
                        integrator_of_scene=integrator_of_scene)


def expand(spec, name="spec", folder=None, integrator_of_scene=None):
    """The runs of a spec (a dict), checked, in order: each entry of `runs` (over `base`), crossed
    with each combination of `grid` (its keys in order, the last changing fastest).

    @param folder  where relative scene paths start (default: the current folder)
    @param integrator_of_scene  a function giving an XML scene's own integrator for a Run (None for
        other scenes; it may raise SpecError for a scene that cannot be read), or None (then the
        options are checked against fast-mass-spring when the run names no integrator)"""
    def fail(message):
        raise SpecError(f"{name}: {message}")

    if not isinstance(spec, dict):
        fail(f"expected an object with \"base\", \"runs\" and/or \"grid\", got {json.dumps(spec)}")
    unknown = set(spec) - {"base", "runs", "grid", "description"}
    if unknown:
        fail(f"unknown key {json.dumps(sorted(unknown)[0])} (expected base, runs, grid, "
             "description)")
    try:
        base = _check_entry("base", spec.get("base", {}))
        runs = spec.get("runs", [{}])
        if not isinstance(runs, list) or not runs:
            raise SpecError(f"runs: expected a non-empty list of objects, got {json.dumps(runs)}")
        runs = [_check_entry(f"runs[{i}]", r) for i, r in enumerate(runs)]
        grid = spec.get("grid", {})
        if not isinstance(grid, dict):
            raise SpecError(f"grid: expected an object of lists, got {json.dumps(grid)}")
        axes = []
        for key, values in grid.items():
            if not isinstance(values, list) or not values:
                raise SpecError(f"grid.{key}: expected a non-empty list of values, got "
                                f"{json.dumps(values)}")
            axes.append([(key, _check_value(f"grid.{key}[{j}]", key, v))
                         for j, v in enumerate(values)])
        for i, r in enumerate(runs):
            for key in grid:
                if key in r:
                    raise SpecError(f"runs[{i}].{key}: also a key of grid; give it in one place")
        expanded = []
        seen = {}
        for i, r in enumerate(runs):
            for combination in itertools.product(*axes):
                parameters = {**base, **r, **dict(combination)}
                origin = f"runs[{i}]" if len(runs) > 1 or "runs" in spec else "base"
                if combination:
                    origin += " x grid " + json.dumps(dict(combination))
                run = Run(len(expanded), parameters, origin, folder or os.getcwd())
                if run.id in seen:
                    raise SpecError(f"run {run.index} ({origin}): the same parameters as run "
                                    f"{seen[run.id]}")
                seen[run.id] = run.index
                _check_run(run, integrator_of_scene or (lambda p: None))
                expanded.append(run)
    except SpecError as e:
        fail(str(e))
    return expanded
