"""The sweep's HDF5 file (h5py): one group per run under /runs, each committed whole.

Layout (docs/sweeps.md):

    /                      attrs: format ("massspring-sweep 1"), massspring_version, spec (the
                           JSON text of the last sweep written into the file)
    /runs/<id>/            one run; <id> is "run-" and 16 hex digits of a hash of its parameters
        attrs              index, origin, parameters (JSON text), each parameter by name
                           (numbers, strings, 3-vectors; objects as JSON text), status, message,
                           integrator, dt [s], num_points, num_springs, final_step,
                           initial_energy [J], wall_seconds [s], host, pid, command (the
                           massspring-simulate command line that runs the same, when there is
                           one)
        frames             (k,) int64: the frame numbers stored
        positions          (k, n, 3) float64 [m], velocities (k, n, 3) [m/s]
        final_positions    (n, 3) [m], final_velocities (n, 3) [m/s]: after final_step steps
        loop_seconds       (r,) [s]: the stepping loop's time (the sum of steps/time) of each
                           repetition, this run first (more with `min_time`)
        steps/<name>       (final_step,) per step: time [s], total_energy, kinetic_energy [J],
                           and the StepReport fields (iterations, relative_decrease, energy,
                           residual, converged, convergence, finite, refactorized,
                           factorization_failed, blew_up, contact_impulses,
                           contact_zone_points, contact_resolved, contact_work [J])

A run is written as /runs/<id>.partial, renamed to /runs/<id> and the file flushed: a group
without the suffix is complete. A .partial group (the writer was killed mid-write) is deleted
when the file is opened again, and the run redone."""

import json

import h5py
import numpy as np

FORMAT = "massspring-sweep 1"
PARTIAL = ".partial"


def _attribute(value):
    """A parameter as an HDF5 attribute: numbers, booleans, strings and 3-vectors as themselves,
    anything else as JSON text."""
    if isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, list) and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                       for v in value):
        return np.array(value, dtype=np.float64)
    return json.dumps(value)


class Store:
    """The open results file. Use as a context manager; writes happen in the calling process
    only (workers return their results to it)."""

    def __init__(self, path, spec_text=None, version=""):
        self.path = path
        try:
            self.file = h5py.File(path, "a")
        except OSError as e:
            raise OSError(f"{path}: cannot open it as an HDF5 file: {e}") from None
        found = self.file.attrs.get("format")
        if found != FORMAT and (found is not None or len(self.file) > 0):
            self.file.close()
            raise ValueError(f"{path}: not a sweep results file (its format is {found!r}, "
                             f"expected {FORMAT!r}); choose another --out")
        self.file.attrs["format"] = FORMAT
        if version:
            self.file.attrs["massspring_version"] = version
        if spec_text is not None:
            self.file.attrs["spec"] = spec_text
        self.runs = self.file.require_group("runs")
        for name in [n for n in self.runs if n.endswith(PARTIAL)]:
            del self.runs[name]
        self.file.flush()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self.file.id.valid:
            self.file.close()

    def status(self, run_id):
        """The recorded status of a run, or None when it is not in the file."""
        group = self.runs.get(run_id)
        return None if group is None else group.attrs["status"]

    def remove(self, run_id):
        if run_id in self.runs:
            del self.runs[run_id]
            self.file.flush()

    def write(self, run, result, command=""):
        """Commits one run's result: written under a temporary name, renamed, flushed."""
        if run.id in self.runs:
            del self.runs[run.id]
        partial = run.id + PARTIAL
        if partial in self.runs:
            del self.runs[partial]
        group = self.runs.create_group(partial)
        attrs = group.attrs
        attrs["index"] = run.index
        attrs["origin"] = run.origin
        attrs["parameters"] = json.dumps(run.parameters, sort_keys=True)
        for key, value in run.parameters.items():
            attrs[key] = _attribute(value)
        if run.scene_path:
            attrs["scene_path"] = run.scene_path
        for key in ("status", "message", "integrator", "dt", "num_points", "num_springs",
                    "final_step", "initial_energy", "wall_seconds", "host", "pid"):
            if key in result:
                attrs[key] = result[key]
        attrs["command"] = command
        for key in ("frames", "positions", "velocities", "final_positions",
                    "final_velocities", "loop_seconds"):
            if key in result:
                group.create_dataset(key, data=result[key])
        if "steps" in result:
            steps = group.create_group("steps")
            for name, values in result["steps"].items():
                steps.create_dataset(name, data=values)
        self.runs.move(partial, run.id)
        self.file.flush()
