"""massspring: mass-spring simulation (MassSpringSystem<double, Sparse>) with the C++ library's
names; see docs/python.md.

Every name of the compiled module `massspring._core` is re-exported here, so `massspring.X` is the
C++ `massspring::X`. The subpackage `massspring.sweep` runs grids of runs on a Dask cluster
(docs/sweeps.md); it is imported on demand, so `import massspring` needs neither Dask nor h5py."""

from . import _core
from ._core import *  # noqa: F401,F403: the module's public names are the package's

__doc__ = _core.__doc__ + "\n\n" + __doc__.split("\n\n", 1)[1]
__version__ = _core.__version__
__all__ = [name for name in dir(_core) if not name.startswith("_")]

# The classes, enums and the exception print as massspring.X (where they are used), not
# massspring._core.X.
for _name in __all__:
    _value = getattr(_core, _name)
    if isinstance(_value, type) and getattr(_value, "__module__", "") == _core.__name__:
        try:
            _value.__module__ = __name__
        except (AttributeError, TypeError):
            pass
del _name, _value
