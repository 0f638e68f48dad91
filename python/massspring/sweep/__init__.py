"""massspring.sweep: grids of runs on a Dask cluster, results in one HDF5 file (docs/sweeps.md).

    python3 -m massspring.sweep SPEC.json --out results.h5 [--scheduler tcp://HOST:8786]

From Python: `massspring.sweep.sweep(spec_path, out, ...)` (driver.py); one run without Dask:
`massspring.sweep.run_one(parameters)` (runner.py). A sweep needs Dask (python3-dask,
python3-distributed) and h5py (python3-h5py) for its file; checking a spec
(`massspring.sweep.check`, `--check`) and run_one need neither."""

from .runner import run as run_one
from .spec import PARAMETERS, SpecError, expand


def sweep(*args, **kwargs):
    """driver.sweep (imported on first use: it needs h5py)."""
    from .driver import sweep as run_sweep  # noqa: PLC0415

    return run_sweep(*args, **kwargs)


def check(spec_path):
    """The checked runs of a spec file (driver.check); raises SpecError naming the entry."""
    from .driver import check as check_spec  # noqa: PLC0415

    return check_spec(spec_path)[0]


__all__ = ["sweep", "check", "run_one", "expand", "SpecError", "PARAMETERS"]
