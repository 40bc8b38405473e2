"""svo.Result: what every call that makes grids returns, whatever was asked."""
from dataclasses import dataclass
from typing import Any, Dict, Optional


@dataclass(frozen=True)
class Result:
    """The grids a call made, the per-voxel arrays and the report asked for.

    grid: the main grid: "surface" (voxelize; "density" with grid="fog"),
        "level_set" or "distance" (level_set), "solid" (solid). A pyopenvdb
        grid where pyopenvdb imports, else an svo.Grid.
    grids: every grid by name, the main one first ("normal" and "color" with
        those attributes).
    ijk: (K, 3) int32 index coordinates of the voxels the arrays below
        describe, in their order; None when no array was asked for.
    normal, color: (K, 3) float32 (attributes "normal", "color"); else None.
    triangle: (K,) int32: voxelize's smallest triangle id per voxel
        (attributes "triangle"), level_set's nearest triangle per band voxel
        (closest_triangle=True); else None.
    report: with report=True, what the call did (backend, mode, sign method,
        voxels, GPU memory, stage times); else None.
    """

    grid: Any
    grids: Dict[str, Any]
    ijk: Optional[Any] = None
    normal: Optional[Any] = None
    color: Optional[Any] = None
    triangle: Optional[Any] = None
    report: Optional[Dict[str, Any]] = None
