"""svo.distributed against the single-process call: the tiles joined are the
whole grid, voxel for voxel and value for value (inactive values too)."""
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pyopenvdb
import pytest

distributed = pytest.importorskip("distributed")  # CI installs python3-distributed (scripts/setup.sh)
import dask  # noqa: E402  (comes with distributed)

import svo  # noqa: E402
import svo.distributed  # noqa: E402
from scenes import icosphere  # noqa: E402

SVO_EXE = os.environ.get("SVO_EXE", "")
RESOLUTION = 40
TILE = 16


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def voxelizer():
    return svo.Voxelizer()


def open_sphere():
    """The sphere without its top cap: a hole whose inside signs depend on triangles far away."""
    v, t = icosphere()
    return v, t[v[t].mean(axis=1)[:, 2] < 0.6]


@pytest.fixture(scope="module")
def city(tmp_path_factory):
    if not SVO_EXE or not os.path.exists(SVO_EXE):
        pytest.skip("the svo binary is not built (SVO_EXE)")
    path = tmp_path_factory.mktemp("city") / "city.obj"
    subprocess.run([SVO_EXE, "scene", "city", "--triangles", "5000", "-o", str(path)], check=True,
                   capture_output=True)
    return str(path)


def single(voxelizer, mesh, kind):
    v, t = svo.read_mesh(mesh) if isinstance(mesh, str) else mesh
    if kind == "surface":
        return voxelizer.voxelize(v, t, resolution=RESOLUTION).grid
    if kind == "sdf":
        return voxelizer.level_set(v, t, resolution=RESOLUTION).grid
    if kind == "udf":
        return voxelizer.level_set(v, t, resolution=RESOLUTION, unsigned=True).grid
    if kind == "band":
        return voxelizer.band(v, t, resolution=RESOLUTION).grid
    return voxelizer.solid(v, t, resolution=RESOLUTION).grid


def active_mask(grid):
    return set(map(tuple, svo.active_voxels(grid).tolist()))


def values(grid, lo, hi):
    dtype = bool if isinstance(grid, pyopenvdb.BoolGrid) else np.float32
    vector = (3,) if isinstance(grid, pyopenvdb.Vec3SGrid) else ()
    a = np.empty(tuple(h - l for l, h in zip(lo, hi)) + vector, dtype=dtype)
    grid.copyToArray(a, ijk=lo)
    return a


def assert_same_grid(got, want):
    assert type(got) is type(want)
    assert (got.name, got.gridClass, got.background) == (want.name, want.gridClass, want.background)
    assert got.transform.indexToWorld((1, 2, 3)) == want.transform.indexToWorld((1, 2, 3))
    assert got.transform.voxelSize() == want.transform.voxelSize()
    # pyopenvdb.write adds file_* statistics to what it writes; the grid's own metadata must be the same.
    def own(grid):
        return {k: v for k, v in dict(grid.metadata).items() if not k.startswith("file_")}

    assert own(got) == own(want)
    assert got.activeVoxelCount() == want.activeVoxelCount() > 0
    assert active_mask(got) == active_mask(want)
    assert got.evalLeafBoundingBox() == want.evalLeafBoundingBox()
    # Every value of the grid's box and a margin, active or not: the interior
    # tiles of level sets and solids are inactive values that must survive.
    lo, hi = want.evalLeafBoundingBox()
    lo, hi = tuple(c - 24 for c in lo), tuple(c + 25 for c in hi)
    assert np.array_equal(values(got, lo, hi), values(want, lo, hi))


KINDS = ("surface", "sdf", "udf", "solid", "band")


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("shape", ["closed", "open"])
def test_tiles_joined_are_the_single_process_grid(client, voxelizer, shape, kind):
    mesh = icosphere() if shape == "closed" else open_sphere()
    calls = []
    got = svo.distributed.voxelize(mesh, client=client, tile=TILE, kind=kind, resolution=RESOLUTION,
                                   progress=lambda done, total: calls.append((done, total)))
    total = calls[-1][1]
    assert total >= 8 and calls[0] == (0, total) and calls[-1] == (total, total)
    assert [d for d, _ in calls] == list(range(total + 1))
    assert_same_grid(got, single(voxelizer, mesh, kind))


def test_a_level_set_of_a_real_mesh_is_the_single_process_grid(client, voxelizer):
    """CGAL's fandisk at 96: its band holds bricks wholly inside with no voxel
    in the band, which a tile signs without a flood fill."""
    path = os.path.join(os.environ.get("SVO_CGAL_MESHES", ""), "fandisk.off")
    if not os.path.exists(path):
        pytest.skip("libcgal-demo meshes not extracted (SVO_CGAL_MESHES)")
    v, t = svo.read_mesh(path)
    got = svo.distributed.voxelize((v, t), client=client, tile=32, kind="sdf", resolution=96)
    assert_same_grid(got, voxelizer.level_set(v, t, resolution=96).grid)


def rows_by_ijk(result):
    """The result's per-voxel arrays, rows sorted by (i, j, k)."""
    order = np.lexsort((result.ijk[:, 2], result.ijk[:, 1], result.ijk[:, 0]))
    return {name: getattr(result, name)[order] for name in ("ijk", "normal", "color", "triangle")
            if getattr(result, name) is not None}


@pytest.mark.parametrize("kind, keywords", [("surface", {"attributes": ["normal", "triangle"]}),
                                            ("surface", {"attributes": ["triangle"], "grid": "fog", "mode": "thin"}),
                                            ("sdf", {"closest_triangle": True}),
                                            ("udf", {"closest_triangle": True})])
def test_attributes_and_closest_triangles_are_joined(client, voxelizer, kind, keywords):
    # The open sphere: a surface and a UDF of arrays are partitioned, so each
    # tile's triangle ids are its part's, numbered back in the whole mesh.
    v, t = open_sphere()
    got = svo.distributed.voxelize((v, t), client=client, tile=TILE, kind=kind, resolution=RESOLUTION, **keywords)
    if kind == "surface":
        want = voxelizer.voxelize(v, t, resolution=RESOLUTION, **keywords)
    else:
        want = voxelizer.level_set(v, t, resolution=RESOLUTION, unsigned=kind == "udf", **keywords)
    assert_same_result(got, want, len(t))


def assert_same_result(got, want, triangles):
    """svo.distributed's svo.Result with arrays against one process's."""
    assert isinstance(got, svo.Result) and got.report is None
    assert list(got.grids) == list(want.grids) and got.grid is got.grids[list(want.grids)[0]]
    for name, grid in want.grids.items():
        assert_same_grid(got.grids[name], grid)
    got_rows, want_rows = rows_by_ijk(got), rows_by_ijk(want)
    assert list(got_rows) == list(want_rows) and len(want_rows["ijk"]) > 0
    for name, rows in want_rows.items():
        assert got_rows[name].dtype == rows.dtype
        np.testing.assert_array_equal(getattr(got, name), rows, err_msg=name)  # the distributed rows come sorted
    assert want_rows["triangle"].min() >= 0 and want_rows["triangle"].max() < triangles


@pytest.mark.parametrize("kind, keywords", [("surface", {}), ("sdf", {}), ("solid", {}),
                                            ("surface", {"attributes": ["normal", "triangle"]}),
                                            ("udf", {"closest_triangle": True})])
def test_one_worker_runs_the_whole_grid_in_one_task(voxelizer, kind, keywords):
    # One worker and no tile size: one task, the whole grid without a region,
    # no plan and no join; the single-process result all the same.
    v, t = open_sphere()
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
        with distributed.get_task_stream(c) as tasks:
            got = svo.distributed.voxelize((v, t), client=c, kind=kind, resolution=RESOLUTION, **keywords)
    names = sorted(str(task["key"]).split("-")[0] for task in tasks.data)
    assert names.count("_tile_task") == 1 and "_plan_task" not in names, names
    if keywords:
        want = (voxelizer.voxelize(v, t, resolution=RESOLUTION, **keywords) if kind == "surface" else
                voxelizer.level_set(v, t, resolution=RESOLUTION, unsigned=True, **keywords))
        assert_same_result(got, want, len(t))
    else:
        assert_same_grid(got, single(voxelizer, (v, t), kind))


def test_progress_with_a_third_argument_gets_the_time_left(client):
    calls = []
    svo.distributed.voxelize(icosphere(), client=client, tile=TILE, kind="udf", resolution=RESOLUTION,
                             progress=lambda done, total, left: calls.append((done, total, left)))
    total = calls[-1][1]
    assert total >= 8 and [c[:2] for c in calls] == [(done, total) for done in range(total + 1)]
    # None before any tile is done (nothing to estimate from), then the
    # seconds left, none once all are done.
    assert calls[0][2] is None and calls[-1][2] == 0.0
    assert all(isinstance(left, float) and left >= 0.0 for _, _, left in calls[1:])


@pytest.mark.parametrize("kind", KINDS)
def test_a_mesh_file_every_worker_reads(client, voxelizer, city, kind):
    got = svo.distributed.voxelize(city, client=client, tile=24, kind=kind, resolution=RESOLUTION)
    assert_same_grid(got, single(voxelizer, city, kind))


def run_cli(*args):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    return subprocess.run([sys.executable, "-m", "svo.distributed", *args], capture_output=True, text=True,
                          env=env, timeout=120)


def test_the_command_line_writes_the_same_grid(voxelizer, tmp_path):
    v, t = icosphere()
    mesh = tmp_path / "sphere.obj"
    with open(mesh, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t.tolist())
    out = tmp_path / "sphere.vdb"
    r = run_cli("voxelize", str(mesh), "-r", str(RESOLUTION), "--sdf", "--tile", "24", "--workers", "1",
                "-o", str(out))
    assert r.returncode == 0, r.stderr
    lines = [line for line in r.stderr.splitlines() if line.startswith("tiles ")]
    total = int(lines[0].split("/")[1])
    assert total >= 8 and len(lines) == total + 1  # not a tty: a line each
    for done, line in enumerate(lines):  # the time left from the first tile done until the last
        pattern = rf"tiles {done}/{total}" + (r", about \d+ s left" if 0 < done < total else "")
        assert re.fullmatch(pattern, line), line
    grids, _ = pyopenvdb.readAll(str(out))
    assert len(grids) == 1
    written = grids[0]
    assert_same_grid(written, single(voxelizer, str(mesh), "sdf"))
    assert [p.name for p in tmp_path.iterdir() if ".tmp-" in p.name] == []  # no temporary left


def test_a_bad_mesh_path_fails_clearly(client, tmp_path):
    missing = str(tmp_path / "no-such-mesh.obj")
    with pytest.raises(OSError, match="no-such-mesh.obj"):
        svo.distributed.voxelize(missing, client=client, resolution=RESOLUTION)
    r = run_cli("voxelize", missing, "-r", "16", "--workers", "1", "-o", str(tmp_path / "x.vdb"))
    assert r.returncode == 1 and "no-such-mesh.obj" in r.stderr and not (tmp_path / "x.vdb").exists()


def test_a_failing_tile_names_its_box(client):
    # A tile's call that fails (a band the level set refuses) raises, through
    # Dask, an error naming the tile's box and the call's error.
    v, t = icosphere()
    box = ((0, 0, 0), (16, 16, 16))
    future = client.submit(svo.distributed._tile_task, (v, t), "sdf",
                           {"resolution": RESOLUTION, "exterior_band": 0.5}, box)
    with pytest.raises(svo.distributed.TileError, match=r"tile \(0, 0, 0\)\.\.\(16, 16, 16\): ValueError: "):
        future.result()


def test_bad_arguments_fail_before_any_work(client):
    v, t = icosphere()
    with pytest.raises(ValueError, match="kind"):
        svo.distributed.voxelize((v, t), client=client, kind="fog")
    with pytest.raises(ValueError, match="multiple of 8"):
        svo.distributed.voxelize((v, t), client=client, tile=12)
    with pytest.raises(ValueError, match="joined on the client only"):
        svo.distributed.voxelize((v, t), client=client, output_dir="tiles", attributes=["normal"])


def test_tiles_cover_the_box_once_in_whole_leaves():
    box = ((-40, -16, 8), (40, 72, 24))
    parts = svo.distributed.tiles(box, 24)
    covered = np.zeros((80, 88, 16), dtype=int)
    for lo, hi in parts:
        assert all(c % 8 == 0 for c in lo + hi)
        covered[lo[0] + 40:hi[0] + 40, lo[1] + 16:hi[1] + 16, lo[2] - 8:hi[2] - 8] += 1
    assert (covered == 1).all()
    # Tiles of a multiple of 128: cut at multiples of 128 (internal nodes), few of them.
    box = ((-200, 8, 0), (312, 136, 64))
    parts = svo.distributed.tiles(box, 256)
    assert sorted({lo[0] for lo, _ in parts}) == [-200, 0, 256]
    assert all(hi[0] in (0, 256, 312) and lo[1:] == (8, 0) and hi[1:] == (136, 64) for lo, hi in parts)
    # About 4 tiles per worker; from 128 up, whole OpenVDB internal nodes.
    assert svo.distributed.default_tile(((0, 0, 0), (64, 64, 64)), 2) == 32  # 8 tiles of 32³
    assert svo.distributed.default_tile(((0, 0, 0), (2048, 2048, 2048)), 4) == 896  # 812 rounded up to 128s


def test_without_a_client_a_local_cluster_runs_and_closes(voxelizer):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
    got = svo.distributed.voxelize((v, t), tile=8, kind="solid", resolution=16)
    assert_same_grid(got, voxelizer.solid(v, t, resolution=16).grid)


@pytest.mark.parametrize("kind, keywords", [("surface", {"grid": "fog"}),
                                            ("sdf", {"exterior_band": 6.0, "interior_band": 2.0})])
def test_keywords_pass_through_to_each_tile(client, voxelizer, kind, keywords):
    v, t = open_sphere()
    got = svo.distributed.voxelize((v, t), client=client, tile=TILE, kind=kind, resolution=RESOLUTION, **keywords)
    want = (voxelizer.voxelize if kind == "surface" else voxelizer.level_set)(v, t, resolution=RESOLUTION,
                                                                              **keywords).grid
    assert_same_grid(got, want)


# --- per-tile output (output_dir, --tiles-dir) -------------------------------


def read_one_grid(path):
    grids, _ = pyopenvdb.readAll(str(path))
    assert len(grids) == 1
    return grids[0]


def assert_tiles_are_the_single_grid(folder, index, want):
    """Each tile's file, read by pyopenvdb (and opened by vdb_print where it is
    installed), is the single-process grid cut to the tile's box; a tile
    without a file holds only background; together they hold every voxel."""
    assert index == json.loads((folder / "index.json").read_text())
    assert index["svo_version"] == svo.__version__ and index["format"] == "svo.distributed.tiles"
    (g,) = index["grids"]
    assert (g["name"], g["class"], g["type"]) == (want.name, want.gridClass, want.valueTypeName)
    assert g["background"] == want.background and g["voxel_size"] == list(want.transform.voxelSize())
    world = np.array([1.0, 2.0, 3.0, 1.0]) @ np.array(g["transform"])
    assert np.allclose(world[:3], want.transform.indexToWorld((1, 2, 3)), rtol=0, atol=1e-12)
    files = [t["file"] for t in index["tiles"] if t["file"]]
    assert len(files) >= 2 and len(set(files)) == len(files)
    assert sorted(p.name for p in folder.iterdir()) == sorted(files + ["index.json"])  # no temporary left
    if shutil.which("vdb_print"):
        r = subprocess.run(["vdb_print", *[str(folder / f) for f in files]], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        assert r.stdout.count(want.name) == len(files)
    mask = active_mask(want)
    union = set()
    for t in index["tiles"]:
        lo, hi = tuple(t["box"][0]), tuple(t["box"][1])
        inside = {v for v in mask if all(lo[a] <= v[a] < hi[a] for a in range(3))}
        if t["file"] is None:
            assert not inside and t["active_voxels"] == 0
            assert (values(want, lo, hi) == want.background).all()
            continue
        got = read_one_grid(folder / t["file"])
        assert type(got) is type(want) and (got.name, got.gridClass) == (want.name, want.gridClass)
        assert got.background == want.background
        assert got.transform.indexToWorld((1, 2, 3)) == want.transform.indexToWorld((1, 2, 3))
        tile_mask = active_mask(got)
        assert tile_mask == inside and got.activeVoxelCount() == t["active_voxels"]
        assert np.array_equal(values(got, lo, hi), values(want, lo, hi))
        union |= tile_mask
    assert union == mask and index["active_voxels"] == want.activeVoxelCount()
    # Nothing of the single grid lies outside the tiles' boxes.
    lo, hi = want.evalLeafBoundingBox()
    assert all(index["box"][0][a] <= lo[a] and hi[a] < index["box"][1][a] for a in range(3))


@pytest.mark.parametrize("kind, shape", [("surface", "open"), ("sdf", "closed"), ("sdf", "open"), ("solid", "closed")])
def test_per_tile_files_are_the_single_process_grid(client, voxelizer, tmp_path, kind, shape):
    mesh = icosphere() if shape == "closed" else open_sphere()
    folder = tmp_path / "tiles"
    index = svo.distributed.voxelize(mesh, client=client, tile=TILE, kind=kind, resolution=RESOLUTION,
                                     output_dir=folder)
    assert len(index["tiles"]) >= 8
    want = single(voxelizer, mesh, kind)
    assert_tiles_are_the_single_grid(folder, index, want)
    assert_same_grid(svo.distributed.read_tiles(folder), want)  # the folder read back and joined


def test_a_bad_tile_folder_is_refused(client, tmp_path):
    folder = tmp_path / "tiles"
    svo.distributed.voxelize(open_sphere(), client=client, tile=TILE, kind="sdf", resolution=RESOLUTION,
                             output_dir=folder)
    good = json.loads((folder / "index.json").read_text())

    def refused(index, match):
        (folder / "index.json").write_text(json.dumps(index))
        with pytest.raises(svo.distributed.TilesError, match=match):
            svo.distributed.read_tiles(folder)

    refused(dict(good, format_version=2), "format_version 2")
    tiles = [dict(t) for t in good["tiles"]]
    tiles[1]["box"] = [[c - 8 for c in tiles[1]["box"][0]], tiles[1]["box"][1]]
    refused(dict(good, tiles=tiles), "overlap|whole leaves")
    tiles = [dict(t) for t in good["tiles"]]
    named = next(t for t in tiles if t["file"])
    named["file"] = "tile_gone.vdb"
    refused(dict(good, tiles=tiles), "missing, e.g. tile_gone.vdb")
    (folder / "index.json").unlink()
    with pytest.raises(svo.distributed.TilesError, match="no index.json"):
        svo.distributed.read_tiles(folder)


def test_the_command_line_writes_tiles_and_an_index(voxelizer, tmp_path):
    v, t = open_sphere()
    mesh = tmp_path / "open.obj"
    with open(mesh, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t.tolist())
    folder = tmp_path / "tiles"
    folder.mkdir()
    (folder / "index.json").write_text("{}")  # an earlier job's index: replaced
    r = run_cli("voxelize", str(mesh), "-r", str(RESOLUTION), "--udf", "--tile", "16", "--devices", "software",
                "--tiles-dir", str(folder))
    assert r.returncode == 0, r.stderr
    index = json.loads((folder / "index.json").read_text())
    assert index["kind"] == "udf"
    assert_tiles_are_the_single_grid(folder, index, single(voxelizer, str(mesh), "udf"))


# --- a worker killed in the middle of a task ---------------------------------


# Bounds of the killed-worker test (seconds): the job's waits (svo.distributed's
# timeout), a worker's start, and the whole test (a last resort: faulthandler
# prints every thread's stack to the real stderr and ends the run rather than
# let it hang).
KILL_JOB_TIMEOUT = 120
KILL_WORKER_TIMEOUT = 60
KILL_TEST_LIMIT = 420


def tile_task_killer(marker, once):
    """A worker plugin that kills its worker process (SIGKILL, no clean-up)
    while a tile task is on the worker's thread: the job's first tile task
    only (once), or every one. Each kill appends "key pid" to `marker`. The
    class is made inside this function so that Dask pickles it by value: the
    workers cannot import this file."""

    class KillInTileTask(distributed.WorkerPlugin):
        name = "svo-test-kill"

        def __init__(self, marker, once):
            self.marker, self.once = str(marker), once

        def transition(self, key, start, finish, **kwargs):
            if finish != "executing" or not str(key).startswith("_tile_task"):
                return
            try:  # once: the first tile task of the job, on whichever worker; never again
                fd = os.open(self.marker, os.O_CREAT | os.O_WRONLY | (os.O_EXCL if self.once else os.O_APPEND))
            except FileExistsError:
                return
            import signal
            import threading
            import time

            def kill_in_task():
                deadline = time.monotonic() + 30
                while time.monotonic() < deadline:
                    for frame in sys._current_frames().values():
                        while frame is not None and frame.f_code.co_name != "_tile_task":
                            frame = frame.f_back
                        if frame is not None:  # the task's thread is inside _tile_task
                            os.write(fd, f"{key} {os.getpid()}\n".encode())
                            os.close(fd)
                            os.kill(os.getpid(), signal.SIGKILL)
                    time.sleep(0.001)

            threading.Thread(target=kill_in_task, daemon=True).start()

    return KillInTileTask(marker, once)


@pytest.mark.parametrize("mesh_as, kind, workers", [("arrays", "surface", 2), ("arrays", "sdf", 2), ("file", "sdf", 2),
                                                    ("arrays", "sdf", 1), ("arrays", "surface", 1)])
def test_a_worker_killed_in_a_task_changes_nothing(voxelizer, tmp_path, capsys, mesh_as, kind, workers):
    """The first tile task to run kills its worker process (SIGKILL, no
    clean-up) while the task is on the worker's thread; the scheduler gives
    the lost task to a worker again and the job's result is unchanged: one
    grid from arrays, per-tile files from a mesh file. With one worker the
    mesh's only copy (a task's result) dies with it: Dask must make it again
    (before svo placed its tasks, Dask 2022.12's queue stranded the tiles
    there and the job waited forever: issue 43)."""
    import faulthandler

    marker = tmp_path / "killed"
    mesh = open_sphere()
    if mesh_as == "file":
        path = tmp_path / "open.obj"
        with open(path, "w") as f:
            f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in mesh[0].tolist())
            f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in mesh[1].tolist())
        mesh = str(path)
    folder = tmp_path / "tiles" if mesh_as == "file" else None
    with capsys.disabled():  # pytest captures fd 2: keep a copy of the real one for the stacks
        stderr = os.fdopen(os.dup(2), "w")
    faulthandler.dump_traceback_later(KILL_TEST_LIMIT, exit=True, file=stderr)
    try:
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
            c.wait_for_workers(workers, timeout=KILL_WORKER_TIMEOUT)
            pids = set(c.run(os.getpid).values())
            c.register_worker_plugin(tile_task_killer(marker, once=True))
            # A surface of arrays: tasks get their part of the mesh (chunks the
            # workers cut); a level set: the whole mesh (arrays held by a task, or a file).
            got = svo.distributed.voxelize(mesh, client=c, tile=TILE, kind=kind, resolution=RESOLUTION,
                                           output_dir=folder, timeout=KILL_JOB_TIMEOUT)
            killed_key, killed_pid = marker.read_text().split()
            assert killed_key.startswith("_tile_task") and int(killed_pid) in pids
            c.wait_for_workers(workers, timeout=KILL_WORKER_TIMEOUT)
            assert int(killed_pid) not in set(c.run(os.getpid).values())  # the nanny started a new process
    finally:
        faulthandler.cancel_dump_traceback_later()
        stderr.close()
    want = single(voxelizer, mesh, kind)
    if folder is None:
        assert_same_grid(got, want)
    else:
        assert_tiles_are_the_single_grid(folder, got, want)


def test_a_tile_whose_workers_keep_dying_fails_the_job_naming_it(tmp_path):
    """Every tile task kills its worker: past Dask's allowed-failures (1
    here) the job stops with a TileError naming a tile, in bounded time, and
    writes no output."""
    v, t = open_sphere()
    path = tmp_path / "open.obj"
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t.tolist())
    marker, folder = tmp_path / "killed", tmp_path / "tiles"
    with dask.config.set({"distributed.scheduler.allowed-failures": 1}), \
            distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                     dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
        c.wait_for_workers(1, timeout=KILL_WORKER_TIMEOUT)
        c.register_worker_plugin(tile_task_killer(marker, once=False))
        with pytest.raises(svo.distributed.TileError,
                           match=r"tile \(.*\)\.\.\(.*\): a worker died while it held the task, more times than "
                                 r"Dask's distributed\.scheduler\.allowed-failures \(1\) allows"):
            svo.distributed.voxelize(str(path), client=c, tile=TILE, kind="udf", resolution=RESOLUTION,
                                     output_dir=folder, timeout=KILL_JOB_TIMEOUT)
    kills = marker.read_text().split("\n")[:-1]
    assert len(kills) >= 2 and all(k.startswith("_tile_task") for k in kills)  # the task ran twice, died twice
    assert not (folder / "index.json").exists()


def test_a_cluster_without_workers_fails_in_time():
    # Every task would wait for a worker forever: the job's first wait is bounded.
    with distributed.LocalCluster(n_workers=0, processes=True, dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as c:
        with pytest.raises(svo.distributed.JobTimeout, match="no worker joined the cluster in 2 s"):
            svo.distributed.voxelize(icosphere(), client=c, resolution=RESOLUTION, timeout=2)
    with pytest.raises(ValueError, match="timeout"):
        svo.distributed.voxelize(icosphere(), client=c, timeout=0)


# --- tiles balanced by the surface they hold ---------------------------------


def test_balanced_tiles_split_where_the_surface_is():
    box = ((-64, -64, 0), (64, 72, 128))
    rng = np.random.default_rng(7)
    # A dense cluster of surface in one corner leaf block, a thin spread elsewhere.
    dense = rng.integers(0, 4, size=(200, 3)) * 8
    sparse = rng.integers(-8, 8, size=(40, 3)) * 8 + np.array([0, 0, 64])
    leaves = np.concatenate([dense, sparse])
    weights = np.concatenate([np.full(200, 10.0), np.ones(40)])
    keep = np.all((leaves >= box[0]) & (leaves < box[1]), axis=1)
    leaves, weights = leaves[keep], weights[keep]
    parts = svo.distributed.plan_tiles(box, 64, leaves, weights, parts=16)
    covered = np.zeros((128, 136, 128), dtype=int)
    target = weights.sum() / 16
    for lo, hi in parts:
        assert all(c % 8 == 0 for c in lo + hi)
        assert all(lo[a] // 64 == (hi[a] - 1) // 64 for a in range(3))  # inside one cell of the lattice
        covered[lo[0] + 64:hi[0] + 64, lo[1] + 64:hi[1] + 64, lo[2]:hi[2]] += 1
        held = weights[np.all((leaves >= lo) & (leaves < hi), axis=1)].sum()
        side = max(hi[a] - lo[a] for a in range(3))
        assert held <= target or side <= 8  # split three times from 64: 8
    assert (covered == 1).all()
    sides = {lo: max(hi[a] - lo[a] for a in range(3)) for lo, hi in parts}
    assert sides[(0, 0, 0)] == 8 and max(sides.values()) == 64  # small at the cluster, whole cells elsewhere
    # No surface: the lattice itself.
    assert svo.distributed.plan_tiles(box, 64, np.zeros((0, 3)), np.zeros(0), parts=16) == \
        sorted(svo.distributed.tiles(box, 64))


def test_surface_weights_put_triangles_in_their_leaves():
    v = np.array([[0.5, 0.5, 0.5], [2, 0.5, 0.5], [0.5, 2, 0.5], [20, 20, 20], [21, 20, 20], [20, 21, 20]])
    t = np.array([[0, 1, 2], [3, 4, 5], [3, 5, 4]])
    m = np.diag([0.25, 0.25, 0.25, 1.0])  # 4 voxels per unit
    m[3, :3] = (-1.0, 0.0, 0.0)
    leaves, weights = svo.distributed.surface_weights(v, t, m)
    # Index = ((x + 1) * 4, y * 4, z * 4): the first triangle (6,2,2) (12,2,2) (6,8,2), centroid (8,4,2),
    # legs of 6; the other two (84,80,80) (88,80,80) (84,84,80), centroid (85.3,81.3,80), legs of 4.
    assert leaves.tolist() == [[8, 0, 0], [80, 80, 80]]
    assert np.allclose(weights, [1 + 0.5 * 6 * 6, 2 * (1 + 0.5 * 4 * 4)])


def two_spheres():
    """A fine small sphere inside the box of a coarse big one, apart: most of the surface in one corner."""
    big_v, big_t = icosphere(1)
    small_v, small_t = icosphere(3)
    v = np.concatenate([big_v, small_v * 0.3 + 1.4])
    return v, np.concatenate([big_t, small_t + len(big_v)])


@pytest.mark.parametrize("kind", ["surface", "sdf"])
def test_balanced_tiles_give_the_single_process_grid(client, voxelizer, kind):
    mesh = two_spheres()
    boxes, box, _ = client.submit(svo.distributed._plan_task, mesh, kind, {"resolution": RESOLUTION}, None, 2,
                                  pure=False).result()
    sides = [max(hi[a] - lo[a] for a in range(3)) for lo, hi in boxes]
    assert min(sides) < max(sides)  # not a lattice
    got = svo.distributed.voxelize(mesh, client=client, kind=kind, resolution=RESOLUTION)
    assert_same_grid(got, single(voxelizer, mesh, kind))


# --- one EGL device per worker -----------------------------------------------


def test_each_worker_of_a_local_cluster_has_its_own_device(voxelizer):
    # CI has one (software) EGL device; a device no machine has proves that
    # the worker's Voxelizer reads the device its worker was given.
    with svo.distributed.local_cluster(devices=["software", "99"]) as cluster, distributed.Client(cluster) as c:
        c.wait_for_workers(2)
        given = c.run(lambda: os.environ.get("SVO_EGL_DEVICE"))
        assert sorted(given.values()) == ["99", "software"]
        good = next(w for w, d in given.items() if d == "software")
        bad = next(w for w, d in given.items() if d == "99")
        assert "software" in c.submit(lambda: svo.Voxelizer().device(), workers=[good], pure=False).result()
        v, t = icosphere()
        with pytest.raises(svo.distributed.TileError, match="no EGL device matches '99'"):
            c.submit(svo.distributed._tile_task, (v, t), "surface", {"resolution": 16, "backend": "raster"},
                     ((0, 0, 0), (8, 8, 8)), workers=[bad], pure=False).result()
        got = c.submit(svo.distributed._tile_task, (v, t), "surface", {"resolution": RESOLUTION, "backend": "raster"},
                       ((16, -8, -8), (24, 8, 8)), workers=[good], pure=False).result()
        got = svo._svo._grid_from_bytes(got)  # a tile's grid comes back as bytes
    want = voxelizer.voxelize(v, t, resolution=RESOLUTION, backend="raster", region=((16, -8, -8), (24, 8, 8))).grid
    assert active_mask(got) == active_mask(want) and got.activeVoxelCount() > 0


def test_a_level_set_signed_by_winding_numbers_is_not_partitioned(client):
    v, t = open_sphere()
    sign = svo.distributed._sign_task((v, t), "sdf", {"resolution": RESOLUTION})
    assert sign.startswith("winding")
    with pytest.raises(ValueError, match="only when signed by parity"):
        svo.distributed._partitioned(client, v, t, "sdf", TILE, 2, {"resolution": RESOLUTION}, sign=sign)


def test_devices_only_for_the_local_cluster(client):
    with pytest.raises(ValueError, match="SVO_EGL_DEVICE"):
        svo.distributed.voxelize(icosphere(), client=client, devices=[0])


# --- the mesh partitioned to tiles -------------------------------------------


PARITY = "parity: the mesh is closed and consistently oriented"


@pytest.mark.parametrize("kind", ["surface", "udf", "sdf", "solid"])
def test_each_tile_task_gets_only_the_triangles_near_it(client, voxelizer, kind):
    v, t = icosphere(3)
    signed = kind in ("sdf", "solid")
    # A closed mesh: a level set or solid takes parity signs, and a tile its z columns' triangles.
    if signed:
        assert svo.distributed._sign_task((v, t), kind, {"resolution": RESOLUTION}) == PARITY
    boxes, _, _, meshes, metadata, keywords = svo.distributed._partitioned(
        client, v, t, kind, TILE, 2, {"resolution": RESOLUTION}, sign=PARITY if signed else None)
    assert metadata == {"svo:triangles": str(len(t)), **({"svo:sign": PARITY} if signed else {})}
    assert keywords == {"resolution": RESOLUTION, **({"part_of_closed_mesh": True} if signed else {})}
    counts, seen = [], set()
    for m in meshes:
        pieces = [p for p in client.gather(m["pieces"]) if p is not None]
        index = set(np.concatenate([i for i, _ in pieces]).tolist()) if pieces else set()
        counts.append(len(index))
        seen |= index
        for i, corners in pieces:  # each piece is the mesh's own triangles
            assert np.array_equal(corners, v[t[i]])
    assert seen == set(range(len(t)))  # every triangle reaches a tile
    assert max(counts) < len(t) / (4 if kind == "surface" else 2) and len(boxes) >= 8
    if signed:  # tiles of one column share their triangles, whatever their height
        by_column = {}
        for (lo, hi), m in zip(boxes, meshes):
            pieces = [p for p in client.gather(m["pieces"]) if p is not None]
            index = frozenset(np.concatenate([i for i, _ in pieces]).tolist()) if pieces else frozenset()
            by_column.setdefault((lo[:2], hi[:2]), set()).add(index)
        assert all(len(parts) == 1 for parts in by_column.values()) and len(by_column) < len(boxes)
    # And the parts give the whole grid (the bounding triangles fix its box).
    got = svo.distributed.voxelize((v, t), client=client, tile=TILE, kind=kind, resolution=RESOLUTION)
    assert_same_grid(got, single(voxelizer, (v, t), kind))
    whole = svo.distributed.voxelize((v, t), client=client, tile=TILE, kind=kind, resolution=RESOLUTION,
                                     partition=False)
    assert_same_grid(whole, got)
