"""svo: GPU voxelization of triangle meshes into OpenVDB grids.

    import numpy as np, svo
    result = svo.voxelize(vertices, triangles, resolution=256)
    grid = result.grid                       # a BoolGrid "surface"
    ijk = svo.active_voxels(grid)            # (K, 3) int32

Every call that makes grids returns an svo.Result (the grid, every grid by
name, the per-voxel arrays and the report asked for). Grids are
python3-openvdb (pyopenvdb) objects where pyopenvdb imports (Debian's
/usr/bin/python3), so ``pyopenvdb.write(path, [grid])`` and every grid
method work on them; in any other CPython they are svo.Grid, with the voxels
and values as numpy arrays, ``write(path)`` (.vdb, .nvdb) and
``to_pyopenvdb()``. ``svo.write(path, grids)`` writes either kind.

Keep a ``svo.Voxelizer()`` for repeated calls: it keeps its GL context,
programs and buffers.
"""
import sys as _sys

from . import _build


def _refuse(problem):
    raise ImportError(f"svo cannot load in {_sys.executable} (CPython {_sys.version.split()[0]}): {problem}. "
                      f"It was built for CPython {_build.PYTHON_VERSION} ({_build.PYTHON}); use that interpreter, "
                      f"or any CPython {_build.PYTHON_VERSION} with numpy below 2, or rebuild svo with this one "
                      f"(pip install <svo source folder>)")


if _sys.implementation.name != "cpython" or "%d.%d" % _sys.version_info[:2] != _build.PYTHON_VERSION:
    _refuse("its compiled module is for another Python")
try:
    import numpy as _numpy
except ImportError:
    _refuse("numpy does not import (pip install 'numpy<2')")
# pybind11 2.10 (Debian 12's), which the module is built with, predates numpy 2's ABI.
if int(_numpy.__version__.split(".")[0]) >= 2:
    _refuse(f"numpy {_numpy.__version__} is newer than the module's pybind11 reads (pip install 'numpy<2')")

# pyopenvdb, where it imports, must be loaded (and OpenVDB initialized by it)
# before the compiled module: loading _svo first was seen to crash OpenVDB's
# grid registration. Without it, grids come as svo.Grid.
try:
    import pyopenvdb  # noqa: F401
except Exception:  # ImportError, or a pyopenvdb that fails to load here
    pass

from ._svo import (Grid, Octree, OutOfMemoryError, Voxelizer, __version__, active_voxels, load, read_mesh,  # noqa: E402
                   voxelize, write)
from ._svo import _options  # noqa: F401,E402  (internal: each call's keywords, for the stub's test)
from ._result import Result  # noqa: E402

__all__ = ["Voxelizer", "Octree", "Grid", "Result", "voxelize", "active_voxels", "read_mesh", "load", "write",
           "OutOfMemoryError", "__version__"]

try:  # built with SVO_WITH_VALIDATE (CGAL)
    from ._svo import validate, validate_level_set  # noqa: F401

    __all__ += ["validate", "validate_level_set"]
except ImportError:  # pragma: no cover
    pass
