"""svo on a Dask cluster: one grid voxelized in tiles, one Dask task per tile.

    import svo.distributed
    grid = svo.distributed.voxelize("city.obj", kind="sdf", resolution=1024)   # a LocalCluster
    grid = svo.distributed.voxelize((vertices, triangles), client=Client("tcp://host:8786"), tile=256)

Each tile is a region of the grid (svo's ``region=``, docs/design.md "Regions"),
which computes exactly the whole grid's result inside its box, so the tiles
joined are the single-process grid: same voxels, same values, same inactive
values. Tiles are boxes of whole leaves, so no two share a leaf and joining
them moves nodes (svo._svo._join_region).

Tiles are planned by the surface they hold (plan_tiles) on a lattice
aligned to the tile size; a surface or unsigned field of arrays is cut to
the tiles on the workers, so each task gets only its triangles; with
output_dir, the workers write one .vdb per tile and the client an
index.json (write_index) instead of joining; local_cluster(devices=...)
gives each worker its own EGL device (SVO_EGL_DEVICE). A worker lost in a
task costs only that task, which Dask runs again (tasks are placed so that
Dask's scheduler never queues them: see _placement), and every wait is
bounded (timeout=, JobTimeout).

Command line: ``python3 -m svo.distributed voxelize MESH -r N [--sdf|--udf|--fill solid]
[--tile N] [--timeout S] [--workers N | --devices 0,1 | --scheduler ADDRESS] (-o OUT.vdb | --tiles-dir DIR)``.

A surface's attributes and a level set's closest triangles are joined too:
their grids by name, their per-voxel arrays with rows sorted by (i, j, k),
returned as an svo.Result.

Level sets and solids of arrays signed by parity are partitioned too: each
tile gets the triangles of its z columns, top to bottom. Those signed by
winding numbers (open meshes) give every tile the whole mesh, over which
the numbers sum.

The city benchmark: bench/distributed_city.py.
read_tiles joins a tile folder back into one grid.
"""
import argparse
import json
import math
import os
import inspect
import sys
import time
import warnings

import numpy as np

import svo
from svo._svo import _grid_bytes, _grid_from_bytes, _join_region

KINDS = ("surface", "sdf", "udf", "solid", "band")


class TileError(RuntimeError):
    """A tile's call failed; the message names the tile's box and the call's error."""


# --- what runs on a worker ---------------------------------------------------

# One Voxelizer per worker process: it keeps its GL context, programs and
# buffers across the tiles the worker runs.
_worker_voxelizer = None


def _voxelizer():
    global _worker_voxelizer
    if _worker_voxelizer is None:
        _worker_voxelizer = svo.Voxelizer()
    return _worker_voxelizer


def _mesh_arrays(mesh):
    """A path read with svo's readers, a tile's part of the mesh (a dict, see
    _partitioned), or the (vertices, triangles) pair itself."""
    if isinstance(mesh, (str, os.PathLike)):
        return svo.read_mesh(os.fspath(mesh))
    if isinstance(mesh, dict):
        return _tile_mesh(mesh["pieces"], mesh["bounding"])
    return mesh


def _call(mesh, kind, keywords, region=None):
    """The call's svo.Result."""
    vertices, triangles = _mesh_arrays(mesh)
    v = _voxelizer()
    if region is not None:
        keywords = dict(keywords, region=region)
    if kind == "surface":
        return v.voxelize(vertices, triangles, **keywords)
    if kind == "sdf":
        return v.level_set(vertices, triangles, **keywords)
    if kind == "udf":
        return v.level_set(vertices, triangles, unsigned=True, **keywords)
    if kind == "band":
        return v.band(vertices, triangles, **keywords)
    return v.solid(vertices, triangles, **keywords)


def _wants_arrays(kind, keywords):
    """Whether the call gives per-voxel arrays (svo.Result's ijk and the
    rest): a surface's attributes, a level set's closest triangles."""
    if kind == "surface":
        return bool(keywords.get("attributes"))
    return kind in ("sdf", "udf") and bool(keywords.get("closest_triangle"))


ARRAYS = ("ijk", "normal", "color", "triangle")


def _arrays_of(result, mesh):
    """The result's per-voxel arrays by name (those it has), its triangle ids
    in the whole mesh's numbering where the tile had a part of it."""
    arrays = {name: getattr(result, name) for name in ARRAYS if getattr(result, name) is not None}
    if isinstance(mesh, dict) and "triangle" in arrays:
        # A part's triangles are the whole mesh's in its order (_tile_mesh),
        # so the smallest id of a voxel stays the smallest.
        ids, _ = _tile_triangles(mesh["pieces"], mesh["bounding"], corners=False)
        arrays["triangle"] = ids[arrays["triangle"]].astype(np.int32)
    return arrays


def _joined_arrays(parts):
    """The tiles' arrays as one, rows sorted by (i, j, k)."""
    arrays = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    ijk = arrays["ijk"]
    order = np.lexsort((ijk[:, 2], ijk[:, 1], ijk[:, 0]))
    return {name: a[order] for name, a in arrays.items()}


# An index box no grid reaches (OpenVDB coordinates are int32; svo keeps
# indices well inside them): a region there computes nothing but still gives
# the grid's transform, class, name and metadata.
_NOWHERE = ((2**30, 2**30, 2**30), (2**30 + 8, 2**30 + 8, 2**30 + 8))


def _box_task(mesh, kind, keywords):
    """The index box that holds every value of the whole grid that is not
    background, and the call's grids by name, empty, with their transform
    and metadata (the main grid first)."""
    vertices, triangles = _mesh_arrays(mesh)
    empty = _call((vertices, triangles), kind, keywords, region=_NOWHERE).grids
    xform = next(iter(empty.values())).transform
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    # The mesh's world box, its 8 corners to index space: holds the mesh under
    # any affine transform.
    wlo, whi = vertices.min(axis=0), vertices.max(axis=0)
    for cx in (wlo[0], whi[0]):
        for cy in (wlo[1], whi[1]):
            for cz in (wlo[2], whi[2]):
                p = xform.worldToIndex((float(cx), float(cy), float(cz)))
                lo = [min(lo[a], p[a]) for a in range(3)]
                hi = [max(hi[a], p[a]) for a in range(3)]
    # What a grid holds beyond the mesh: a surface's voxels touch it (one
    # voxel); a level set's band leaves reach its band and one leaf further.
    margin = 2
    if kind in ("sdf", "udf", "band"):
        margin += _band(keywords) + 8
    box_lo = tuple(_floor8(math.floor(lo[a]) - margin) for a in range(3))
    box_hi = tuple(_ceil8(math.ceil(hi[a]) + margin + 1) for a in range(3))
    return (box_lo, box_hi), dict(empty)


def _band(keywords):
    return math.ceil(max(keywords.get("exterior_band", 3.0), keywords.get("interior_band", 3.0)))


def _plan_task(mesh, kind, keywords, tile=None, workers=1):
    """The tiles: boxes of whole leaves that cover every value of the whole
    grid that is not background (see plan_tiles); the box they cover; the
    call's grids by name, empty (see _box_task)."""
    vertices, triangles = mesh = _mesh_arrays(mesh)
    box, empty = _box_task(mesh, kind, keywords)
    if tile is not None:
        return tiles(box, tile), box, empty
    if workers <= 1:
        return [box], box, empty
    leaves, weights = surface_weights(vertices, triangles, _matrix(next(iter(empty.values())).transform))
    return _balanced(box, workers, leaves, weights), box, empty


def _balanced(box, workers, leaves, weights):
    """The default plan for several workers. Each region call has a fixed
    cost (on the 2-core machine's CPU backend 40-100 ms: the whole mesh's
    triangles culled, the octree and grid made), so a worker gets about 4
    tiles, enough for Dask to even out their costs; one worker gets the
    whole box (see _plan_task), or without output_dir one task and no plan
    at all (_run)."""
    return plan_tiles(box, default_tile(box, workers), leaves, weights, parts=4 * workers)


def _tile_task(mesh, kind, keywords, box, output_dir=None, metadata=None):
    """The tile's main grid; with per-voxel arrays, its grids by name and its
    arrays (_arrays_of); with output_dir, its index entry (_write_tile).
    Grids come back as bytes (_grid_bytes). box None: the whole grid, no
    region (a job of one tile)."""
    try:
        result = _call(mesh, kind, keywords, region=box)
        for grid in result.grids.values():
            for key, value in (metadata or {}).items():  # what a part of the mesh says of the whole
                grid[key] = value
        if output_dir is not None:
            return _write_tile(result.grid, output_dir, box)
        if _wants_arrays(kind, keywords):
            return {name: _grid_bytes(g) for name, g in result.grids.items()}, _arrays_of(result, mesh)
        return _grid_bytes(result.grid)
    except Exception as e:  # the job's error must say which tile
        where = "the whole grid" if box is None else f"tile {box[0]}..{box[1]}"
        raise TileError(f"{where}: {type(e).__name__}: {e}") from e


def _joined(into, part):
    """into with part's region joined (svo._svo._join_region); part itself
    when there is nothing yet to join it to."""
    if into is None:
        return part
    _join_region(into, part)
    return into


def tile_file_name(box):
    """The file of the tile whose box starts at box[0]: tile_X_Y_Z.vdb (index coordinates)."""
    return "tile_{}_{}_{}.vdb".format(*box[0])


def _write_tile(grid, output_dir, box):
    """The tile's grid to its own .vdb in output_dir (svo's writer: a temporary
    file renamed into place, so a killed task leaves no partial file), or no
    file when the grid holds nothing but background. Its entry in the index."""
    entry = {"box": [list(box[0]), list(box[1])], "file": None, "active_voxels": int(grid.activeVoxelCount())}
    if not grid.empty():
        os.makedirs(output_dir, exist_ok=True)  # a worker on another host may see the folder first
        entry["file"] = tile_file_name(box)
        svo.write(os.path.join(output_dir, entry["file"]), [grid])
    return entry


# --- planning ----------------------------------------------------------------


def _floor8(i):
    return i // 8 * 8


def _ceil8(i):
    return -(-i // 8) * 8


def default_tile(box, workers):
    """About 4 tiles per worker: a cube of that many voxels, a multiple of 8
    (of 128 from 128 up, so large tiles hold whole OpenVDB internal nodes)."""
    volume = math.prod(box[1][a] - box[0][a] for a in range(3))
    side = (volume / (4 * max(1, workers))) ** (1 / 3)
    step = 128 if side >= 128 else 8
    return max(step, math.ceil(side / step) * step)


def tiles(box, tile):
    """The box cut by the lattice of `tile` voxels a side, cells clipped to
    the box. A tile that is a multiple of 128 starts its cells at a multiple
    of 128, so they are whole OpenVDB internal nodes (and the box is cut
    into few cells); any other at a multiple of `tile`."""
    if tile <= 0 or tile % 8:
        raise ValueError(f"tile must be a positive multiple of 8, got {tile}")
    lo, hi = box
    align = 128 if tile % 128 == 0 else tile
    starts = [range(lo[a] // align * align, hi[a], tile) for a in range(3)]
    return [(tuple(max(c[a], lo[a]) for a in range(3)), tuple(min(c[a] + tile, hi[a]) for a in range(3)))
            for c in ((x, y, z) for x in starts[0] for y in starts[1] for z in starts[2])]


def _matrix(xform):
    """A pyopenvdb transform's 4x4 matrix (row vectors), or svo.Grid's own."""
    if hasattr(xform, "indexToWorld"):
        return np.array(_transform_matrix(xform))
    return np.asarray(xform, dtype=np.float64)


def surface_weights(vertices, triangles, matrix, chunk=1 << 20):
    """How much work each leaf's part of the surface makes: the origins of the
    leaves (8³ voxels, (L, 3) int64) that hold a triangle's centroid in index
    space, and per leaf the sum over those triangles of 1 + the triangle's
    area in voxels (the per-triangle work and about the voxels it covers).
    matrix: the grid's 4x4 index-to-world matrix (row vectors)."""
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles)
    to_index = np.linalg.inv(matrix[:3, :3])
    leaves, weights = [], []
    for start in range(0, len(triangles), chunk):  # bounded memory for large meshes
        corners = (vertices[triangles[start:start + chunk]] - matrix[3, :3]) @ to_index  # (n, 3, 3)
        area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
        keys, inverse = np.unique(np.floor(corners.mean(axis=1) / 8).astype(np.int64), axis=0,
                                  return_inverse=True)
        leaves.append(keys)
        weights.append(np.bincount(inverse.ravel(), weights=1.0 + area, minlength=len(keys)))
    if not leaves:
        return np.zeros((0, 3), dtype=np.int64), np.zeros(0)
    keys, inverse = np.unique(np.concatenate(leaves), axis=0, return_inverse=True)
    return keys * 8, np.bincount(inverse.ravel(), weights=np.concatenate(weights), minlength=len(keys))


def plan_tiles(box, tile, leaves, weights, parts, levels=3):
    """Tiles balanced by the surface they hold: the lattice of `tile` (see
    tiles), each cell whose leaves weigh more than 1/parts of the whole split
    in eight (halves of whole leaves), recursively, at most `levels` times.
    leaves, weights: see surface_weights. The tiles cover the box once; a
    tile with no surface stays whole (its call is cheap: the region culls
    the triangles away, or only fills an inside)."""
    leaves = np.asarray(leaves, dtype=np.int64).reshape(-1, 3)
    weights = np.asarray(weights, dtype=np.float64)
    target = weights.sum() / max(1, parts)
    out = []

    def split(b, sel, level):
        lo, hi = b
        if level >= levels or weights[sel].sum() <= target or all(hi[a] - lo[a] <= 8 for a in range(3)):
            out.append(b)
            return
        cuts = [(lo[a], lo[a] + _ceil8((hi[a] - lo[a]) // 2), hi[a]) if hi[a] - lo[a] > 8 else (lo[a], hi[a])
                for a in range(3)]
        for x0, x1 in zip(cuts[0], cuts[0][1:]):
            for y0, y1 in zip(cuts[1], cuts[1][1:]):
                for z0, z1 in zip(cuts[2], cuts[2][1:]):
                    c = ((x0, y0, z0), (x1, y1, z1))
                    p = leaves[sel]
                    inside = np.all((p >= c[0]) & (p < c[1]), axis=1)
                    split(c, sel[inside], level + 1)

    for b in tiles(box, tile):
        inside = np.all((leaves >= b[0]) & (leaves < b[1]), axis=1)
        split(b, np.flatnonzero(inside), 0)
    return sorted(out)


# --- the mesh partitioned to tiles -------------------------------------------
#
# Kinds whose value at a voxel depends only on the triangles near it: a
# surface's (the triangles that touch the voxel's cube, grown by the guard
# band) and an unsigned field's (the triangles within the band). A level set's
# and a solid's signs depend on triangles far away (design §7e), so those
# tasks keep the whole mesh. The rest of a call that depends on the whole
# mesh is its box: the voxel size (from resolution), the local frame and the
# guard band (svo/core/grid.h). Each tile's part therefore also holds the
# triangles that hold the lowest and highest vertex along each axis (at most
# six, "bounding"): the part's box is the mesh's, and those triangles are
# the mesh's own, so where the region reaches them they are right too.
# svo:triangles, the one piece of metadata that counts the mesh, is set to
# the whole mesh's count.

PARTITIONED_KINDS = ("surface", "udf", "sdf", "solid", "band")
# Level sets and solids are partitioned where their signs come from parity:
# a tile then gets its columns' triangles (see _partitioned).
SIGNED_KINDS = ("sdf", "solid")


def _bounding_triangles(vertices, triangles, chunk=1 << 20):
    """The (sorted, unique) indices of triangles that hold the lowest and the
    highest vertex along each axis of those the triangles use."""
    best = [[math.inf, -1], [-math.inf, -1]] * 3  # per axis: lowest, highest (value, triangle)
    for start in range(0, len(triangles), chunk):
        corners = vertices[triangles[start:start + chunk]]  # (n, 3, 3)
        for a in range(3):
            c = corners[:, :, a]
            i, j = np.unravel_index(np.argmin(c), c.shape)[0], np.unravel_index(np.argmax(c), c.shape)[0]
            if c[i].min() < best[2 * a][0]:
                best[2 * a] = [c[i].min(), start + i]
            if c[j].max() > best[2 * a + 1][0]:
                best[2 * a + 1] = [c[j].max(), start + j]
    return np.unique([t for _, t in best])


def _chunk_of(vertices, triangles, first, end):
    """Triangles first..end of a mesh as a chunk to send: their first index,
    the vertices they use and their corners as indices into those (int32).
    Sent and kept by the scheduler (see _hold), so small: 12 bytes a
    triangle and 24 a vertex, where corners would be 72 a triangle."""
    used, local = np.unique(triangles[first:end], return_inverse=True)
    return first, vertices[used], local.reshape(-1, 3).astype(np.int32)


def _chunk_corners(chunk):
    """A chunk's triangles: their indices in the mesh and their corners, (n, 3, 3)."""
    first, vertices, local = chunk
    return np.arange(first, first + len(local)), vertices[local]


def _chunk_weights(chunk, matrix):
    _, vertices, local = chunk
    return surface_weights(vertices, local, matrix)


def _partition_task(chunk, matrix, boxes, margin, columns=False):
    """Per tile box, the chunk's triangles whose index-space box grown by
    `margin` voxels meets the tile's voxels (with columns, the tile's z
    columns: x and y only): (their indices in the mesh, their corners), or None."""
    index, corners = _chunk_corners(chunk)
    ijk = (corners - matrix[3, :3]) @ np.linalg.inv(matrix[:3, :3])
    lo, hi = ijk.min(axis=1) - margin, ijk.max(axis=1) + margin
    axes = 2 if columns else 3
    out = []
    for b_lo, b_hi in boxes:
        meets = np.all((hi[:, :axes] >= np.array(b_lo[:axes])) & (lo[:, :axes] <= np.array(b_hi[:axes]) - 1), axis=1)
        out.append((index[meets], corners[meets]) if meets.any() else None)
    return out


def _hold(data):
    """Arrays as a task's result. Scattered data has no recipe: lost with the
    workers that hold it (Dask's memory manager keeps one replica of what no
    task needs where it is), it fails every task that needs it. A task's
    result is made again from its arguments, which the scheduler keeps."""
    return data


def _metadata_settable():
    """Whether grids are pyopenvdb's, whose metadata a part's call can correct
    (svo.Grid's is read-only): elsewhere tasks get the whole mesh."""
    try:
        import pyopenvdb  # noqa: F401
    except ImportError:
        return False
    return True


def _placement(client):
    """Where the job's tasks may run: the hosts of the workers the cluster has
    now, loosely (allow_other_workers: a worker on another host that joins
    later runs them too, by stealing or when no such host is left).

    Why any restriction: Dask's scheduler queues "root-ish" tasks (a large
    group whose few dependencies are under 5 keys: svo's tiles of a mesh held
    in one task, a partitioned mesh's picks), and when the only worker
    holding such a dependency dies, Dask (2022.11 up to 2024.6.0, fixed by
    dask/distributed#8703) leaves the queued tasks queued on a dependency no
    longer in memory: they are later sent to a worker that cannot get it, and
    the job waits forever (issue 43: a worker killed in a tile task). Dask
    never queues a task that has worker restrictions, so these tasks are
    scheduled as Dask did before queuing (placed at once, balanced by work
    stealing), the path a lost dependency is recomputed on.

    Hosts, not worker addresses: a task Dask left without a worker (all
    workers gone at once, as a one-worker cluster's restart) runs again only
    on a worker its restriction names (the scheduler does not apply
    allow_other_workers there), and a restarted worker has a new address but
    the same host."""
    from distributed.comm import get_address_host

    hosts = sorted({get_address_host(a) for a in client.scheduler_info()["workers"]})
    return {"workers": hosts, "allow_other_workers": True}


def _submit(client, place, fn, *args):
    return client.submit(fn, *args, pure=False, **place)


def _submit_held(client, place, data):
    with warnings.catch_warnings():
        # Dask's advice to scatter large arguments instead: see _hold for why not.
        warnings.filterwarnings("ignore", message="Large object of size")
        return _submit(client, place, _hold, data)


def _is_future(x):
    from distributed import Future

    return isinstance(x, Future)


def _pick(parts, i):
    return parts[i]


def _tile_triangles(pieces, bounding, corners=True):
    """A tile's triangles from its pieces and the bounding triangles, each
    once, in the mesh's order: their indices in the whole mesh and (with
    corners) their corners, (n, 3, 3)."""
    pieces = [p for p in pieces if p is not None] + [bounding]
    index, first = np.unique(np.concatenate([i for i, _ in pieces]), return_index=True)
    return index, (np.concatenate([c for _, c in pieces])[first] if corners else None)


def _tile_mesh(pieces, bounding):
    """A tile's mesh (_tile_triangles) as a soup."""
    index, corners = _tile_triangles(pieces, bounding)
    return corners.reshape(-1, 3), np.arange(3 * len(index), dtype=np.int64).reshape(-1, 3)


def _sign_task(mesh, kind, keywords):
    """The sign method a level set or solid of the whole mesh takes, as its
    grid's svo:sign says ("parity: ...", "winding: ...")."""
    return _call(mesh, kind, keywords, region=_NOWHERE).grid["svo:sign"]


def _partitioned(client, vertices, triangles, kind, tile, workers, keywords, place=None, timeout=None, sign=None):
    """Plan and partition a mesh of arrays: the tiles, the box, the plan's
    grids (see _box_task), each tile's mesh (a dict of futures), the
    metadata to set and the keywords of the tiles' calls. sign: a level
    set's or solid's method, as _sign_task gives it for the whole mesh; only
    "parity: ..." can be partitioned (winding numbers sum over the whole mesh).
    place: see _placement; timeout: seconds to wait for the plan."""
    if place is None:
        place = _placement(client)
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    count = len(triangles)
    metadata = {"svo:triangles": str(count)}
    if kind in SIGNED_KINDS:
        if not (sign or "").startswith("parity"):
            raise ValueError(f"a {kind} is partitioned only when signed by parity, not {sign!r}")
        # What the whole mesh decided (sign="auto" asks whether it is closed;
        # a part looks open where it is cut), and its record in the grids.
        metadata["svo:sign"] = sign
        keywords = dict(keywords, part_of_closed_mesh=True)
    bound = _bounding_triangles(vertices, triangles)
    bounding = (bound, vertices[triangles[bound]])
    # The plan's call sees only the bounding triangles: the same box, so the
    # same transform and frame.
    box, grids = _wait_result(_submit(client, place, _box_task, _tile_mesh([], bounding), kind, keywords),
                              timeout, "the plan (the grid's box)")
    for grid in grids.values():
        for key, value in metadata.items():
            grid[key] = value
    matrix = _matrix(next(iter(grids.values())).transform)
    # One chunk per worker; each a task's result, not scattered data, so that
    # the scheduler can make it again when its worker is lost (see _hold).
    n = max(1, min(workers, count))
    bounds = np.linspace(0, count, n + 1).astype(np.int64)
    chunks = [_submit_held(client, place, _chunk_of(vertices, triangles, a, b)) for a, b in zip(bounds, bounds[1:])]
    if tile is not None:
        boxes = tiles(box, tile)
    elif workers <= 1:
        boxes = [box]
    else:
        parts = [_wait_result(_submit(client, place, _chunk_weights, c, matrix), timeout, "the plan (weights)")
                 for c in chunks]
        keys, inverse = np.unique(np.concatenate([p[0] for p in parts]), axis=0, return_inverse=True)
        weights = np.bincount(inverse.ravel(), weights=np.concatenate([p[1] for p in parts]), minlength=len(keys))
        boxes = _balanced(box, workers, keys, weights)
    # A surface voxel depends on the triangles that touch its cube grown by
    # the guard band (half a voxel and a little); a distance within the band
    # on those within the band of its centre (bricksNearTriangles' reach), a
    # value beyond it is the background whatever lies there. A parity sign
    # depends on the crossings of the voxel's z column below it: a signed
    # tile gets its columns' triangles, top to bottom (docs/design.md, "Regions").
    margin = 2 + (_band(keywords) if kind in ("udf", "sdf", "band") else 0)
    columns = kind in SIGNED_KINDS
    split = [_submit(client, place, _partition_task, c, matrix, boxes, margin, columns) for c in chunks]
    meshes = [{"pieces": [_submit(client, place, _pick, s, i) for s in split], "bounding": bounding}
              for i in range(len(boxes))]
    return boxes, box, grids, meshes, metadata, keywords


# --- the call ------------------------------------------------------------------


def local_cluster(workers=2, devices=None):
    """A Dask cluster on this machine for svo: one-thread worker processes
    (one GL context each), the dashboard on a free port.

    devices: one worker per entry, each with SVO_EGL_DEVICE set to it (an
    EGL device index, or auto/hardware/software, as Voxelizer(device=...)
    takes), so that each worker voxelizes on its own GPU; workers is then
    ignored. None: `workers` workers on the device svo picks by default.
    Use it as a context manager, or close() it.
    """
    from distributed import LocalCluster, Nanny, Scheduler, SpecCluster

    if devices is None:
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0")
    devices = [str(d) for d in devices]
    if not devices:
        raise ValueError("devices: give at least one EGL device")
    # The library reads SVO_EGL_DEVICE where the Voxelizer is given no device
    # (svo/gl/device_options.h); the nanny sets it in the worker's process.
    spec = {i: {"cls": Nanny, "options": {"nthreads": 1, "env": {"SVO_EGL_DEVICE": d}}}
            for i, d in enumerate(devices)}
    return SpecCluster(workers=spec, scheduler={"cls": Scheduler, "options": {"dashboard_address": ":0"}})


DEFAULT_TIMEOUT = 3600


def voxelize(mesh, *, client=None, tile=None, kind="surface", progress=None, output_dir=None, devices=None,
             partition=True, timeout=DEFAULT_TIMEOUT, **keywords):
    """Voxelize a mesh on a Dask cluster: exactly the single-process grid (the
    main grid of the call's svo.Result, returned as the grid itself).

    mesh: a path every worker can read, or a (vertices, triangles) pair of
    numpy arrays (held by tasks, see _hold: they pass through the scheduler
    once). kind: "surface" (svo.voxelize),
    "sdf" (Voxelizer.level_set), "udf" (level_set unsigned=True), "solid" or
    "band" (Voxelizer.band: the voxels nearer than exterior_band to a triangle).
    keywords: those of that call (resolution, voxel_size, grid, backend,
    exterior_band, sign, attributes, closest_triangle, ...); not region.
    With attributes (a surface) or closest_triangle (a level set) the
    result is an svo.Result: every grid of the call joined (the main one,
    "normal"), and the per-voxel arrays (ijk, normal, triangle) of every
    tile as one, rows sorted by (i, j, k) (a single process gives them in
    its octree's order), triangle ids numbered in the whole mesh; report is
    None. Not with output_dir. client: a dask.distributed Client; None starts a
    LocalCluster of one-thread worker processes (one per entry of devices,
    each on its EGL device: see local_cluster) and closes it after. tile:
    voxels per tile side, a multiple of 8, for a lattice of equal tiles
    (default: tiles balanced by the surface they hold, plan_tiles, from a
    lattice of default_tile).
    progress(done, total) is called as tiles finish; a callback that takes a
    third argument also gets the estimated seconds left (None until a tile
    has finished: the time so far over the tiles done, times the tiles left;
    tiles are planned to hold equal surface, so they take about as long).

    partition: for a surface or an unsigned field of arrays, each tile task
    gets only the triangles near its box (cut in parallel on the workers);
    False sends every task the whole mesh. A level set or solid is cut to
    its tiles' z columns (top to bottom, grown by the band) when the whole
    mesh takes parity signs (a task decides that first, as sign="auto"
    would); signed by winding numbers, every task gets the whole mesh. A
    job of one tile (one worker and no tile size) is never cut.

    output_dir: instead of one grid on the client, each worker writes its
    tiles to this folder (one .vdb per tile that holds more than background,
    named by tile_file_name), and the client writes index.json last; returns
    the index (a dict, see write_index). The folder must be one every worker
    and the client can write (a shared file system).

    timeout: seconds any one wait of the job may last (for a first worker,
    for the plan, for the next tile to finish; default an hour); past it the
    job's tasks are cancelled and svo.distributed.JobTimeout (a
    TimeoutError) says what it waited for and the scheduler's view of the
    tiles left. None: no bound. A worker that dies in a task costs that
    task (Dask runs it again); a task whose workers die more often than
    Dask's allowed-failures raises TileError naming the tile.
    """
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    if "region" in keywords:
        raise ValueError("region: svo.distributed plans the regions itself")
    if output_dir is not None and _wants_arrays(kind, keywords):
        raise ValueError("attributes and closest_triangle: their grids and per-voxel arrays are joined on the "
                         "client only; output_dir writes each tile's main grid")
    if kind == "udf" and "unsigned" in keywords:
        raise ValueError("unsigned: kind='udf' sets it")
    if tile is not None and (tile <= 0 or tile % 8):
        raise ValueError(f"tile must be a positive multiple of 8, got {tile}")
    if timeout is not None and not timeout > 0:
        raise ValueError(f"timeout must be a positive number of seconds or None, got {timeout!r}")
    if client is not None and devices is not None:
        raise ValueError("devices: only for the local cluster voxelize starts (client=None); "
                         "on a cluster of your own, start each worker with SVO_EGL_DEVICE set")
    if client is None:
        from dask.system import CPU_COUNT
        from distributed import Client

        # The dashboard on a free port: a second cluster on the machine is no error.
        with local_cluster(workers=CPU_COUNT, devices=devices) as cluster, \
                Client(cluster) as own:
            return _run(own, mesh, kind, tile, progress, output_dir, partition, keywords, timeout)
    return _run(client, mesh, kind, tile, progress, output_dir, partition, keywords, timeout)


class JobTimeout(TimeoutError):
    """A wait of the job ran past its timeout (no worker, no plan, no tile
    finished in time); the message says which wait and what was left."""


def _wait_for_workers(client, timeout):
    """The number of workers, once there is one: a cluster without workers
    would leave every task waiting."""
    from distributed import TimeoutError as DaskTimeout

    try:
        client.wait_for_workers(1, timeout=timeout)
    except (DaskTimeout, TimeoutError) as e:
        raise JobTimeout(f"svo.distributed: no worker joined the cluster in {timeout} s "
                         f"(scheduler {client.scheduler.address})") from e
    return len(client.scheduler_info()["workers"])


def _wait_result(future, timeout, what):
    from distributed import TimeoutError as DaskTimeout

    try:
        return future.result(timeout=timeout)
    except (DaskTimeout, TimeoutError) as e:
        if future.done():  # the task's own TimeoutError, not the wait's
            raise
        future.cancel()
        raise JobTimeout(f"svo.distributed: {what} did not finish in {timeout} s") from e


def _killed_worker():
    try:
        from distributed import KilledWorker
    except ImportError:  # older Dask: only in distributed.scheduler
        from distributed.scheduler import KilledWorker
    return KilledWorker


class _Progress:
    """Calls progress(done, total[, seconds_left]) (see voxelize): the
    estimate is the time since the tiles were submitted over the tiles done,
    times the tiles left. Workers run tiles side by side, so that rate is
    the cluster's, not one worker's."""

    def __init__(self, callback, total):
        self.callback, self.total, self.start = callback, total, time.monotonic()
        self.with_time = callback is not None and _takes_three(callback)

    def __call__(self, done):
        if self.callback is None:
            return
        if not self.with_time:
            self.callback(done, self.total)
            return
        elapsed = time.monotonic() - self.start
        left = elapsed / done * (self.total - done) if done else None
        self.callback(done, self.total, left)


def _takes_three(callback):
    """Whether callback takes a third positional argument."""
    try:
        parameters = inspect.signature(callback).parameters.values()
    except (TypeError, ValueError):  # a builtin without a signature: the documented two
        return False
    positional = [p for p in parameters if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return len(positional) >= 3 or any(p.kind == p.VAR_POSITIONAL for p in parameters)


def _run(client, mesh, kind, tile, progress, output_dir, partition, keywords, timeout=None):
    import queue

    workers = _wait_for_workers(client, timeout)
    place = _placement(client)
    metadata = None
    plan = None
    # One tile (one worker, no tile size): the whole mesh, held; cutting it
    # into parts would only cost time.
    one_tile = tile is None and workers <= 1
    partition = partition and not one_tile
    if not isinstance(mesh, (str, os.PathLike)) and kind in PARTITIONED_KINDS and partition and _metadata_settable():
        sign = None
        if kind in SIGNED_KINDS:
            # The whole mesh decides the sign method; winding numbers need all
            # of it, so its tiles then get the whole mesh, held.
            held = _submit_held(client, place, tuple(mesh))
            sign = _wait_result(_submit(client, place, _sign_task, held, kind, keywords), timeout,
                                "the plan (the sign method)")
        if sign is None or sign.startswith("parity"):
            if sign is not None:
                held.release()  # the tiles get their parts instead
            plan = _partitioned(client, *mesh, kind, tile, workers, keywords, place, timeout, sign)
        else:
            mesh = held
    if plan is not None:
        boxes, box, grids, meshes, metadata, keywords = plan
    else:
        if isinstance(mesh, (str, os.PathLike)):
            mesh = os.fspath(mesh)
        elif not _is_future(mesh):
            mesh = _submit_held(client, place, tuple(mesh))
        if one_tile and output_dir is None:
            # One task, the whole grid: no plan, no region, nothing to join
            # (the 1-worker job's overhead, bench/results/.../distributed_overhead.md).
            boxes, box, grids = [None], None, {}
        else:
            # On a worker: a path is read where the tiles will read it (svo's reader
            # errors name the file), and the client needs no GL context.
            boxes, box, grids = _wait_result(_submit(client, place, _plan_task, mesh, kind, keywords, tile, workers),
                                             timeout, "the plan")
        meshes = [mesh] * len(boxes)
    grid = next(iter(grids.values()), None)
    arrays = [] if _wants_arrays(kind, keywords) else None
    if output_dir is not None:
        output_dir = os.path.abspath(os.fspath(output_dir))
        os.makedirs(output_dir, exist_ok=True)
        # An index left by an earlier job would name files this one replaces:
        # until this job's index is written, the folder holds no index.
        index_path = os.path.join(output_dir, INDEX_NAME)
        if os.path.exists(index_path):
            os.remove(index_path)
    futures = [_submit(client, place, _tile_task, m, kind, keywords, b, output_dir, metadata)
               for m, b in zip(meshes, boxes)]
    box_of = {f.key: b for f, b in zip(futures, boxes)}
    # Finished tiles arrive on a queue (Dask calls back from its own thread),
    # so that the wait for the next one is bounded.
    finished = queue.Queue()
    for f in futures:
        f.add_done_callback(finished.put)
    entries = []
    done = 0
    report = _Progress(progress, len(boxes))
    report(done)
    try:
        # Joined as they arrive, so the client holds one tile's grid at a time
        # besides the result.
        while done < len(futures):
            try:
                future = finished.get(timeout=timeout)
            except queue.Empty:
                raise JobTimeout(_stalled(client, futures, box_of, timeout)) from None
            b = box_of[future.key]
            where = "the whole grid" if b is None else f"tile {b[0]}..{b[1]}"
            try:
                # Done, but a result lost with its worker before it came is made again.
                result = _wait_result(future, timeout, f"{where} (made again: its result was lost)")
            except _killed_worker() as e:
                # Dask's allowed-failures: the task was on a worker that died that many times.
                raise TileError(f"{where}: a worker died while it held the task, more times than "
                                f"Dask's distributed.scheduler.allowed-failures "
                                f"({getattr(e, 'allowed_failures', '?')}) allows") from e
            if output_dir is not None:
                entries.append(result)
            elif arrays is None:
                grid = _joined(grid, _grid_from_bytes(result))
            else:
                parts, tile_arrays = result
                # Each tile's grids joined into the plan's empty ones (attributes included).
                for name, part in parts.items():
                    grids[name] = _joined(grids.get(name), _grid_from_bytes(part))
                if len(tile_arrays.get("ijk", ())):
                    arrays.append(tile_arrays)
            del result
            future.release()
            done += 1
            report(done)
    except BaseException:
        # One call for all: a failed tile (or Ctrl-C) stops the tiles still queued.
        client.cancel(futures)
        raise
    if output_dir is None and arrays is None:
        return grid
    if output_dir is None:
        joined = _joined_arrays(arrays) if arrays else {}
        grid = next(iter(grids.values()))  # the main grid first, as svo.Result's grids
        return svo.Result(grid=grid, grids=grids, **{name: joined.get(name) for name in ARRAYS})
    # A worker killed while svo's writer wrote a tile leaves its temporary
    # file (the tile's own name + ".tmp-" + 8 hex digits); the task ran again.
    for name in os.listdir(output_dir):
        if name.startswith("tile_") and ".vdb.tmp-" in name:
            os.remove(os.path.join(output_dir, name))
    return write_index(output_dir, grid, kind, box, entries)


def _stalled(client, futures, box_of, timeout):
    """The message of a job no tile of which finished in `timeout` seconds:
    the tiles still out and the scheduler's view of them."""
    left = [f for f in futures if not f.done()]
    try:
        states = client.run_on_scheduler(_task_states, [f.key for f in left])
    except Exception as e:  # the scheduler itself may be what is stuck
        states = f"(the scheduler did not answer: {type(e).__name__}: {e})"
    first = box_of[left[0].key] if left else None
    first = "the whole grid" if first is None else f"the first at {first}"
    return (f"svo.distributed: no tile finished in {timeout} s; {len(left)} of {len(futures)} tiles left "
            f"({first}); the scheduler's task states: {states}; "
            f"workers: {len(client.scheduler_info()['workers'])}")


def _task_states(keys, dask_scheduler=None):
    counts = {}
    for key in keys:
        ts = dask_scheduler.tasks.get(key)
        state = ts.state if ts is not None else "forgotten"
        counts[state] = counts.get(state, 0) + 1
    return counts


# --- per-tile output -----------------------------------------------------------

INDEX_NAME = "index.json"
INDEX_FORMAT = "svo.distributed.tiles"


def _transform_matrix(xform):
    """A linear transform's 4x4 matrix in OpenVDB's row-vector convention
    (world = [i j k 1] M), from where it maps the index origin and unit steps."""
    o = xform.indexToWorld((0.0, 0.0, 0.0))
    rows = []
    for axis in range(3):
        p = xform.indexToWorld(tuple(1.0 if a == axis else 0.0 for a in range(3)))
        rows.append([p[a] - o[a] for a in range(3)] + [0.0])
    rows.append(list(o) + [1.0])
    return rows


def _json_value(value):
    if isinstance(value, (bool, int, float, str)) or value is None:
        return value
    if isinstance(value, (tuple, list)):
        return [_json_value(v) for v in value]
    return str(value)


def write_index(output_dir, grid, kind, box, entries):
    """Write output_dir/index.json (a temporary file renamed into place, after
    every tile's file): what a reader needs to put the tiles together.

    Keys: format ("svo.distributed.tiles"), format_version (1), svo_version,
    kind, box (the planned box [lo, hi) in index space), grids (one entry per
    grid each file holds: name, type, class, background, voxel_size,
    transform as a 4x4 row-vector matrix, metadata), tiles (each tile's box
    [lo, hi), its file relative to the folder, or null where the tile holds
    only background, and its active voxels, in the order of their boxes), and
    active_voxels (the sum). grid: the empty grid of the plan (transform,
    class, name, metadata). Returns the index as a dict.
    """
    if hasattr(grid, "gridClass"):  # pyopenvdb
        kind_of_grid = {"type": grid.valueTypeName, "class": grid.gridClass,
                        "voxel_size": list(grid.transform.voxelSize()),
                        "transform": _transform_matrix(grid.transform)}
    else:  # svo.Grid
        kind_of_grid = {"type": grid.type, "class": grid.grid_class, "voxel_size": list(grid.voxel_size),
                        "transform": [[float(x) for x in row] for row in grid.transform]}
    g = {"name": grid.name, **kind_of_grid, "background": _json_value(grid.background),
         "metadata": {k: _json_value(v) for k, v in dict(grid.metadata).items()}}
    entries = sorted(entries, key=lambda e: (e["box"][0], e["box"][1]))
    index = {
        "format": INDEX_FORMAT,
        "format_version": 1,
        "svo_version": svo.__version__,
        "kind": kind,
        "box": [list(box[0]), list(box[1])],
        "grids": [g],
        "tiles": entries,
        "active_voxels": sum(e["active_voxels"] for e in entries),
    }
    path = os.path.join(output_dir, INDEX_NAME)
    tmp = f"{path}.tmp-{os.getpid()}"
    try:
        with open(tmp, "w") as f:
            json.dump(index, f, indent=1)
            f.write("\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return index


class TilesError(ValueError):
    """A folder that is not one finished job's tiles; the message names the
    folder and the problem."""


def read_tiles(path):
    """The grid of a tile folder (voxelize(output_dir=...), --tiles-dir), as
    voxelize without output_dir returns it: the tiles joined
    (svo._svo._join_region) after the index is checked: its format and
    format_version (1), one grid, every tile's box of whole leaves and no
    two overlapping, every named file there, each file one grid of the
    index's name, type, class and voxel size whose active voxels, as many
    as the index says, lie in its box. The files' own statistics (file_*,
    which OpenVDB's reader adds) are not kept. Needs pyopenvdb.
    @throw TilesError naming the folder and what is wrong."""
    import pyopenvdb

    path = os.fspath(path)

    def bad(problem):
        raise TilesError(f"{path}: {problem}")

    try:
        with open(os.path.join(path, INDEX_NAME)) as f:
            index = json.load(f)
    except FileNotFoundError:
        bad(f"no {INDEX_NAME} (not a tile folder, or its job has not finished)")
    except (OSError, ValueError) as e:
        bad(f"{INDEX_NAME} cannot be read: {e}")
    if not isinstance(index, dict) or index.get("format") != INDEX_FORMAT:
        bad(f"{INDEX_NAME} is not an {INDEX_FORMAT} index")
    if index.get("format_version") != 1:
        bad(f"{INDEX_NAME} has format_version {index.get('format_version')!r}; this svo "
            f"({svo.__version__}) reads 1")
    if len(index.get("grids", [])) != 1:
        bad(f"{INDEX_NAME} names {len(index.get('grids', []))} grids per file; svo.distributed writes 1")
    g, tiles = index["grids"][0], index.get("tiles", [])
    lo = np.array([t["box"][0] for t in tiles], dtype=np.int64).reshape(-1, 3)
    hi = np.array([t["box"][1] for t in tiles], dtype=np.int64).reshape(-1, 3)
    for i in np.flatnonzero(np.any(lo % 8, axis=1) | np.any(hi % 8, axis=1) | np.any(hi <= lo, axis=1)):
        bad(f"tile box {tiles[i]['box']} is not a box of whole leaves")
    for i in range(len(tiles)):  # pairwise, vectorised per tile
        meets = np.all((lo[i] < hi[i + 1:]) & (lo[i + 1:] < hi[i]), axis=1)
        if meets.any():
            bad(f"tile boxes {tiles[i]['box']} and {tiles[i + 1 + int(np.argmax(meets))]['box']} overlap")
    missing = [t["file"] for t in tiles if t["file"] and not os.path.isfile(os.path.join(path, t["file"]))]
    if missing:
        bad(f"{len(missing)} tile files named in {INDEX_NAME} are missing, e.g. {missing[0]}")
    grid = None
    for t, box_lo, box_hi in zip(tiles, lo, hi):
        if not t["file"]:
            continue
        file = os.path.join(path, t["file"])
        grids, _ = pyopenvdb.readAll(file)
        part = grids[0] if len(grids) == 1 else None
        if part is None or (part.name, part.valueTypeName, part.gridClass) != (g["name"], g["type"], g["class"]) \
                or list(part.transform.voxelSize()) != g["voxel_size"]:
            bad(f"{t['file']} is not one grid {g['name']!r} ({g['type']}, {g['class']}, voxel size "
                f"{g['voxel_size']}) as {INDEX_NAME} says")
        if part.activeVoxelCount() != t["active_voxels"]:
            bad(f"{t['file']} has {part.activeVoxelCount()} active voxels, {INDEX_NAME} {t['active_voxels']}")
        if part.activeVoxelCount():
            v_lo, v_hi = part.evalActiveVoxelBoundingBox()
            if np.any(np.array(v_lo) < box_lo) or np.any(np.array(v_hi) >= box_hi):
                bad(f"{t['file']} has active voxels outside its box {t['box']}")
        if grid is None:
            grid = part
            for key in [k for k in dict(grid.metadata) if k.startswith("file_")]:
                del grid[key]
        else:
            _join_region(grid, part)
    if grid is None:
        bad("no tile has a file: the grid holds only background")
    if grid.activeVoxelCount() != index.get("active_voxels"):
        bad(f"the tiles hold {grid.activeVoxelCount()} active voxels, {INDEX_NAME} {index.get('active_voxels')}")
    return grid


# --- command line ------------------------------------------------------------


def _main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m svo.distributed",
                                     description="Voxelize a mesh on a Dask cluster, in tiles.")
    commands = parser.add_subparsers(dest="command", required=True)
    p = commands.add_parser("voxelize", help="a mesh file to one .vdb grid")
    p.add_argument("mesh", help="OBJ, PLY, STL, OFF or glTF (.gltf, .glb); every worker must be able to "
                   "read this path")
    size = p.add_mutually_exclusive_group()
    size.add_argument("-r", "--resolution", type=int, help="voxels along the longest side of the mesh's box")
    size.add_argument("--voxel-size", type=float, help="world units per voxel")
    kind = p.add_mutually_exclusive_group()
    kind.add_argument("--sdf", action="store_true", help="a signed distance level set")
    kind.add_argument("--udf", action="store_true", help="an unsigned distance field")
    kind.add_argument("--fill", choices=("solid", "band"),
                      help="solid: the voxels inside the mesh too; band: the voxels nearer than --band to a triangle")
    p.add_argument("--grid", choices=("bool", "fog"), help="a surface's grid type (default bool)")
    p.add_argument("--band", type=float, help="level set half width in voxels, both sides (default 3)")
    p.add_argument("--backend", help="svo's backend (auto, raster, compute, cpu)")
    p.add_argument("--tile", type=int, help="voxels per tile side, a multiple of 8 (default: ~4 tiles per worker)")
    p.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT,
                   help=f"seconds any one wait may last: for a worker, the plan, the next tile (default "
                        f"{DEFAULT_TIMEOUT}); past it the job stops with an error")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=2, help="local cluster worker processes (default 2)")
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--devices", help="a local cluster of one worker per EGL device, e.g. 0,1,2,3 "
                       "(each worker's SVO_EGL_DEVICE)")
    out = p.add_mutually_exclusive_group(required=True)
    out.add_argument("-o", "--output", help="the .vdb file (written atomically)")
    out.add_argument("--tiles-dir", help="a folder every worker can write: one .vdb per tile, written by the "
                     "workers, and index.json naming them, written last")
    args = parser.parse_args(argv)

    kind = "sdf" if args.sdf else "udf" if args.udf else args.fill if args.fill else "surface"
    keywords = {}
    if args.resolution is not None:
        keywords["resolution"] = args.resolution
    if args.voxel_size is not None:
        keywords["voxel_size"] = args.voxel_size
    if args.grid:
        keywords["grid"] = args.grid
    if args.band is not None:
        keywords["exterior_band"] = args.band
        if kind != "band":
            keywords["interior_band"] = args.band
    if args.backend:
        keywords["backend"] = args.backend

    tty = sys.stderr.isatty()

    def report(done, total, left):
        # A terminal gets one line rewritten; a log gets a line per update.
        line = f"tiles {done}/{total}" + (f", about {left:.0f} s left" if left is not None and done < total else "")
        print(f"\r{line}\033[K" if tty else line, end="" if tty else "\n", file=sys.stderr, flush=True)

    from distributed import Client

    try:
        if args.scheduler:
            with Client(args.scheduler) as client:
                grid = voxelize(args.mesh, client=client, tile=args.tile, kind=kind, progress=report,
                                output_dir=args.tiles_dir, timeout=args.timeout, **keywords)
        else:
            devices = args.devices.split(",") if args.devices else None
            with local_cluster(workers=args.workers, devices=devices) as cluster, Client(cluster) as client:
                print(f"dashboard: {client.dashboard_link}", file=sys.stderr, flush=True)
                grid = voxelize(args.mesh, client=client, tile=args.tile, kind=kind, progress=report,
                                output_dir=args.tiles_dir, timeout=args.timeout, **keywords)
    except Exception as e:
        if tty:
            print(file=sys.stderr)
        print(f"svo.distributed: {e}", file=sys.stderr)
        return 1
    if tty:
        print(file=sys.stderr)
    if args.tiles_dir:
        return 0  # the workers wrote the tiles, voxelize the index
    # svo's writer: a temporary file beside the output, then a rename (an
    # interrupted run leaves no partial file); pyopenvdb grids or svo.Grid.
    svo.write(args.output, [grid])
    return 0


if __name__ == "__main__":
    # Run from the imported module, not __main__: Dask then sends the tasks'
    # functions by name (as svo.distributed's), not pickled by value with
    # their globals (some of which, svo._svo's functions, do not pickle).
    from svo.distributed import _main as main

    sys.exit(main())
