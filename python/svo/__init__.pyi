"""Type stubs for svo (the compiled module has no annotations of its own).

The keywords and defaults here are checked against the module's own declarations
(svo._options()) by python/tests/test_options.py."""
from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Grid = Any  # a pyopenvdb BoolGrid, FloatGrid or Vec3SGrid
Transform = Any  # a pyopenvdb.Transform, or a 4x4 matrix

class Voxelizer:
    def __init__(self, *, device: str = "", gl_debug: bool = False, program_cache: str = "") -> None: ...
    def voxelize(
        self,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        resolution: Optional[int] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        grid: str = "bool",
        backend: str = "auto",
        mode: str = "conservative",
        conservative: str = "auto",
        attributes: Sequence[str] = (),
        gpu_memory: Optional[int] = None,
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
    ) -> Union[Grid, Dict[str, Any]]: ...
    def octree(
        self,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        resolution: Optional[int] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        backend: str = "auto",
        mode: str = "conservative",
        conservative: str = "auto",
        attributes: Sequence[str] = (),
        gpu_memory: Optional[int] = None,
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
    ) -> "Octree": ...
    def level_set(
        self,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        resolution: Optional[int] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        exterior_band: float = 3.0,
        interior_band: float = 3.0,
        unsigned: bool = False,
        closest_triangle: bool = False,
        sign: str = "auto",
        winding_accuracy: float = 1.5,
        backend: str = "auto",
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
    ) -> Union[Grid, Tuple[Grid, npt.NDArray[np.int32], npt.NDArray[np.int32]]]: ...
    def solid(
        self,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        resolution: Optional[int] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        sign: str = "auto",
        winding_accuracy: float = 1.5,
        backend: str = "auto",
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
    ) -> Grid: ...
    def device(self) -> str: ...

class Octree:
    @staticmethod
    def from_grid(grid: Grid, *, backend: str = "auto") -> "Octree": ...
    @property
    def nodes(self) -> npt.NDArray[np.uint32]: ...
    @property
    def bricks(self) -> npt.NDArray[np.uint64]: ...
    @property
    def level_start(self) -> list: ...
    @property
    def levels(self) -> int: ...
    @property
    def voxel_count(self) -> int: ...
    def voxels(self) -> npt.NDArray[np.int32]: ...
    def to_grid(self, grid: str = "bool") -> Grid: ...
    def render(
        self,
        *,
        size: Tuple[int, int] = (640, 480),
        view: str = "front",
        layers: Sequence[str] = ("voxels", "outlines"),
        levels: Optional[Tuple[int, int]] = None,
        color: str = "flat",
        ao: int = 0,
        ao_only: bool = False,
        ao_source: str = "volume",
        lighting: str = "off",
        lights: Optional[Sequence[Tuple[Any, ...]]] = None,
        albedo: Optional[Union[float, Tuple[float, float, float]]] = None,
        specular: Optional[Union[float, Tuple[float, float, float]]] = None,
        mesh: Optional[Tuple[ArrayLike, ArrayLike]] = None,
        surface: str = "auto",
        gi_emission: str = "isotropic",
        gi_clearance: bool = False,
        ao_aperture: float = 60.0,
        ao_offset: float = 2.0,
        ao_distance: float = 32.0,
        ao_step: float = 0.5,
        gi_cones: int = 5,
        gi_aperture: float = 60.0,
        gi_offset: float = 1.5,
        gi_step: float = 0.5,
        gi_distance: float = 0.0,
        light_volume: int = 256,
    ) -> npt.NDArray[np.uint8]: ...
    def save(self, path: str) -> None: ...

def load(path: str) -> Octree: ...

def voxelize(
    vertices: ArrayLike,
    triangles: ArrayLike,
    *,
    resolution: Optional[int] = None,
    voxel_size: Optional[float] = None,
    transform: Optional[Union[Transform, ArrayLike]] = None,
    grid: str = "bool",
    backend: str = "auto",
    mode: str = "conservative",
    conservative: str = "auto",
    attributes: Sequence[str] = (),
    gpu_memory: Optional[int] = None,
    region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
) -> Union[Grid, Dict[str, Any]]: ...
def active_voxels(grid: Grid) -> npt.NDArray[np.int32]: ...
def read_mesh(path: str) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.uint32]]: ...
def validate(
    vertices: ArrayLike,
    triangles: ArrayLike,
    *,
    resolution: Optional[int] = None,
    voxel_size: Optional[float] = None,
    transform: Optional[Union[Transform, ArrayLike]] = None,
    backend: str = "auto",
    conservative: str = "auto",
    holes: bool = True,
    strict: bool = False,
    worst: int = 5,
    mode: str = "conservative",
) -> Dict[str, Any]: ...
def validate_level_set(
    vertices: ArrayLike,
    triangles: ArrayLike,
    *,
    resolution: Optional[int] = None,
    voxel_size: Optional[float] = None,
    transform: Optional[Union[Transform, ArrayLike]] = None,
    exterior_band: float = 3.0,
    interior_band: float = 3.0,
    sign: str = "auto",
    winding_accuracy: float = 1.5,
    backend: str = "auto",
    worst: int = 5,
    openvdb: bool = True,
) -> Dict[str, Any]: ...
