"""Type stubs for svo (the compiled module has no annotations of its own).

The keywords and defaults here are checked against the module's own declarations
(svo._options()) by python/tests/test_options.py."""
import os
from typing import Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
PathLike = Union[str, "os.PathLike[str]"]
Transform = Any  # a pyopenvdb.Transform, or a 4x4 matrix
AnyGrid = Any  # a pyopenvdb BoolGrid, FloatGrid or Vec3SGrid (where pyopenvdb imports), or an svo.Grid

__version__: str

class Grid:
    """A grid svo made where pyopenvdb does not import (or lacks its type)."""
    name: str
    @property
    def type(self) -> str: ...
    @property
    def grid_class(self) -> str: ...
    @property
    def transform(self) -> npt.NDArray[np.float64]: ...
    @property
    def voxel_size(self) -> Tuple[float, float, float]: ...
    @property
    def background(self) -> Any: ...
    @property
    def active_voxel_count(self) -> int: ...
    @property
    def ijk(self) -> npt.NDArray[np.int32]: ...
    @property
    def values(self) -> npt.NDArray[Any]: ...
    @property
    def metadata(self) -> Dict[str, str]: ...
    def write(self, path: PathLike, *, codec: str = "none") -> None: ...
    def to_pyopenvdb(self) -> Any: ...

class Result:
    """What voxelize(), level_set() and solid() return (svo/_result.py)."""
    grid: AnyGrid
    grids: Dict[str, AnyGrid]
    ijk: Optional[npt.NDArray[np.int32]]
    normal: Optional[npt.NDArray[np.float32]]
    color: Optional[npt.NDArray[np.float32]]
    triangle: Optional[npt.NDArray[np.int32]]
    report: Optional[Dict[str, Any]]

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
        report: bool = False,
    ) -> Result: ...
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
        part_of_closed_mesh: bool = False,
        backend: str = "auto",
        gpu_memory: Optional[int] = None,
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
        report: bool = False,
    ) -> Result: ...
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
        part_of_closed_mesh: bool = False,
        backend: str = "auto",
        gpu_memory: Optional[int] = None,
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
        report: bool = False,
    ) -> Result: ...
    def band(
        self,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        resolution: Optional[int] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        exterior_band: float = 3.0,
        backend: str = "auto",
        gpu_memory: Optional[int] = None,
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
        report: bool = False,
    ) -> Result: ...
    def write_nanovdb(
        self,
        path: PathLike,
        vertices: ArrayLike,
        triangles: ArrayLike,
        *,
        kind: str = "surface",
        resolution: Optional[int] = None,
        voxel_size: Optional[float] = None,
        transform: Optional[Union[Transform, ArrayLike]] = None,
        exterior_band: float = 3.0,
        interior_band: float = 3.0,
        closest_triangle: bool = False,
        sign: str = "auto",
        winding_accuracy: float = 1.5,
        part_of_closed_mesh: bool = False,
        backend: str = "auto",
        mode: str = "conservative",
        conservative: str = "auto",
        attributes: Sequence[str] = (),
        gpu_memory: Optional[int] = None,
        region: Optional[Tuple[Tuple[int, int, int], Tuple[int, int, int]]] = None,
        topology: str = "mask",
        fog: bool = False,
        codec: str = "none",
    ) -> int: ...
    def device(self) -> str: ...

class Octree:
    @staticmethod
    def from_grid(grid: AnyGrid, *, backend: str = "auto") -> "Octree": ...
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
    def to_grid(self, grid: str = "bool") -> AnyGrid: ...
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
    def save(self, path: PathLike) -> None: ...

def load(path: PathLike) -> Octree: ...

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
    report: bool = False,
) -> Result: ...
def active_voxels(grid: AnyGrid) -> npt.NDArray[np.int32]: ...
def read_mesh(path: PathLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.uint32]]: ...
def write(path: PathLike, grids: Iterable[AnyGrid], *, codec: str = "none") -> None: ...
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
