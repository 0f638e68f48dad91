"""Keeps Dask's own output off the terminal during a sweep (driver.sweep without verbose): the
sweep's messages, progress and results say what happened; Dask's log lines
(`distributed.nanny - WARNING - Restarting worker`, a worker's traceback on Ctrl-C) only repeat it
in Dask's words.

- In this process: `dask_logs_silenced()` raises the level of the `distributed` loggers above
  CRITICAL while the sweep's cluster lives, and restores each logger's own level afterwards.
- In a worker process of the sweep's own local cluster: the same block sets
  DASK_LOGGING__DISTRIBUTED=critical in the environment the worker processes are started with
  (Dask configures their logging from it as they import it; restored afterwards), and this module
  is the workers' Dask preload (LocalCluster(preload=[...])): `dask_setup` then sends the worker
  process's stderr (file descriptor 2: multiprocessing's tracebacks of a worker stopped by Ctrl-C
  or failing to close) to os.devnull. Its stdout is kept."""

import contextlib
import logging
import os

# A level no record reaches (CRITICAL is the highest standard level).
SILENT = logging.CRITICAL + 1
# Dask's configuration of the `distributed` logger's level, read by a process that imports Dask.
WORKER_LOGGING = ("DASK_LOGGING__DISTRIBUTED", "critical")


@contextlib.contextmanager
def dask_logs_silenced():
    """The `distributed` logger and each of its descendants that has a level of its own (Dask
    sets `distributed.client` to WARNING) at SILENT inside the block, and WORKER_LOGGING in the
    environment; their levels and the environment's value back after."""
    names = ["distributed"] + sorted(n for n in logging.root.manager.loggerDict
                                     if n.startswith("distributed."))
    saved = {}
    for name in names:
        logger = logging.getLogger(name)
        if name == "distributed" or logger.level != logging.NOTSET:
            saved[name] = logger.level
            logger.setLevel(SILENT)
    variable, value = WORKER_LOGGING
    environment = os.environ.get(variable)
    os.environ[variable] = value
    try:
        yield
    finally:
        for name, level in saved.items():
            logging.getLogger(name).setLevel(level)
        if environment is None:
            os.environ.pop(variable, None)
        else:
            os.environ[variable] = environment


def dask_setup(worker):  # noqa: ARG001: Dask's preload interface
    """Dask calls this in each worker process as it starts (and in a worker restarted after a
    crash): the process's stderr goes to os.devnull from then on."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 2)
    os.close(devnull)
