"""svo: GPU voxelization of triangle meshes into OpenVDB grids.

    import numpy as np, svo
    grid = svo.voxelize(vertices, triangles, resolution=256)   # a pyopenvdb.BoolGrid
    ijk = svo.active_voxels(grid)                               # (K, 3) int32

Keep a ``svo.Voxelizer()`` for repeated calls: it keeps its GL context,
programs and buffers. Grids are python3-openvdb (pyopenvdb) objects, so
``pyopenvdb.write(path, [grid])`` and every grid method work on them.
"""
# pyopenvdb must be loaded (and OpenVDB initialized by it) before the compiled
# module: loading _svo first was seen to crash OpenVDB's grid registration.
try:
    import pyopenvdb  # noqa: F401
except ImportError as e:  # pragma: no cover
    raise ImportError("svo returns pyopenvdb grids: install python3-openvdb") from e

from ._svo import Octree, OutOfMemoryError, Voxelizer, active_voxels, load, read_mesh, voxelize
from ._svo import _options  # noqa: F401  (internal: each call's keywords, for the stub's test)

__all__ = ["Voxelizer", "Octree", "voxelize", "active_voxels", "read_mesh", "load", "OutOfMemoryError"]

try:  # built with SVO_WITH_VALIDATE (CGAL)
    from ._svo import validate, validate_level_set  # noqa: F401

    __all__ += ["validate", "validate_level_set"]
except ImportError:  # pragma: no cover
    pass
