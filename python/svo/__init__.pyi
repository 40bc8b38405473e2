"""Type stubs for svo (the compiled module has no annotations of its own)."""
from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Grid = Any  # a pyopenvdb BoolGrid, FloatGrid or Vec3SGrid
Transform = Any  # a pyopenvdb.Transform, or a 4x4 matrix

class Voxelizer:
    def __init__(self, device: str = "auto") -> None: ...
    def voxelize(
        self,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        resolution: Optional[float] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        grid: str = "bool",
        backend: str = "auto",
        attributes: Sequence[str] = (),
    ) -> Union[Grid, Dict[str, Any]]: ...
    def device(self) -> str: ...

def voxelize(
    vertices: ArrayLike,
    triangles: ArrayLike,
    *,
    resolution: Optional[float] = None,
    voxel_size: Optional[float] = None,
    transform: Optional[Union[Transform, ArrayLike]] = None,
    grid: str = "bool",
    backend: str = "auto",
    attributes: Sequence[str] = (),
) -> Union[Grid, Dict[str, Any]]: ...
def active_voxels(grid: Grid) -> npt.NDArray[np.int32]: ...
def read_mesh(path: str) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.uint32]]: ...
