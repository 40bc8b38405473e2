"""The Python module against independent references: the svo CLI's .vdb read
back by pyopenvdb, pyopenvdb's own reader, and exact identities."""
import base64
import json
import os
import subprocess
import threading

import numpy as np
import pyopenvdb
import pytest

import svo

MESHES = os.environ.get("SVO_CGAL_MESHES", "")
SVO_EXE = os.environ.get("SVO_EXE", "")


def as_set(ijk):
    return set(map(tuple, np.asarray(ijk).tolist()))


def tetrahedron():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
    return v, t


@pytest.fixture(scope="module")
def voxelizer():
    return svo.Voxelizer()


@pytest.fixture(scope="module")
def elephant():
    path = os.path.join(MESHES, "elephant.off")
    if not os.path.exists(path):
        pytest.skip("libcgal-demo meshes not extracted (SVO_CGAL_MESHES)")
    return path


def test_equals_the_cli_voxels_and_transform(voxelizer, elephant, tmp_path):
    out = tmp_path / "cli.vdb"
    # The CLI's default output: it must open in pyopenvdb.
    subprocess.run([SVO_EXE, "voxelize", elephant, "-r", "64", "-o", str(out)], check=True, capture_output=True)
    cli = pyopenvdb.read(str(out), "surface")
    vertices, triangles = svo.read_mesh(elephant)
    grid = voxelizer.voxelize(vertices, triangles, resolution=64).grid
    assert isinstance(grid, pyopenvdb.BoolGrid)
    assert grid.activeVoxelCount() == cli.activeVoxelCount() > 1000
    # The metadata the CLI writes (the source: its file name there, "mesh" for arrays).
    for key in ("svo:triangles", "svo:grid", "svo:voxel_size", "svo:epsilon", "svo:version", "svo:backend",
                "svo:mode"):
        assert grid[key] == cli[key], key
    assert grid["svo:version"] == svo.__version__ and grid["svo:source"] == "mesh"
    assert as_set(svo.active_voxels(grid)) == as_set(svo.active_voxels(cli))
    assert grid.transform.voxelSize() == cli.transform.voxelSize()
    for ijk in [(0, 0, 0), (5, -3, 7)]:
        assert grid.transform.indexToWorld(ijk) == cli.transform.indexToWorld(ijk)


def write_off(path, vertices, triangles):
    lines = ["OFF", f"{len(vertices)} {len(triangles)} 0"]
    lines += [" ".join(repr(float(x)) for x in p) for p in vertices]
    lines += ["3 " + " ".join(str(int(i)) for i in t) for t in triangles]
    path.write_text("\n".join(lines) + "\n")
    return path


def svo_metadata(grid):
    return {k: v for k, v in grid.metadata.items() if k.startswith("svo:")}


CALLS = {
    "surface": ([], lambda vz, v, t, **kw: vz.voxelize(v, t, **kw)),
    "sdf": (["--sdf"], lambda vz, v, t, **kw: vz.level_set(v, t, **kw)),
    "udf": (["--udf"], lambda vz, v, t, **kw: vz.level_set(v, t, unsigned=True, **kw)),
    "solid": (["--fill", "solid"], lambda vz, v, t, **kw: vz.solid(v, t, **kw)),
}


@pytest.mark.parametrize("kind", sorted(CALLS))
@pytest.mark.parametrize("grid_flags, grid_kw", [(["-r", "24"], {"resolution": 24}),
                                                 (["--voxel-size", "0.0625"], {"voxel_size": 0.0625})])
def test_the_cli_and_python_tag_the_same_result_alike(voxelizer, tmp_path, kind, grid_flags, grid_kw):
    # Both front ends call svo::resultMetadata: every svo:* key and value is the
    # same but svo:source, the mesh file's path there and "mesh" for arrays.
    flags, call = CALLS[kind]
    v, t = tetrahedron()
    mesh = write_off(tmp_path / "tet.off", v, t)
    out = tmp_path / "cli.vdb"
    subprocess.run([SVO_EXE, "voxelize", str(mesh), *grid_flags, *flags, "-o", str(out)], check=True,
                   capture_output=True)
    grids, _ = pyopenvdb.readAll(str(out))
    assert len(grids) == 1
    cli = svo_metadata(grids[0])
    ours = svo_metadata(call(voxelizer, *svo.read_mesh(mesh), **grid_kw).grid)
    assert cli.pop("svo:source") == str(mesh) and ours.pop("svo:source") == "mesh"
    assert ours == cli
    # What each says: the request, the voxel size as given, the mesh's triangles.
    assert cli["svo:grid"] == ("resolution 24" if "resolution" in grid_kw else "voxel size 0.0625")
    assert float(cli["svo:voxel_size"]) == (0.0625 if "voxel_size" in grid_kw else 1 / 24)
    assert cli["svo:triangles"] == "4" and cli["svo:version"] == svo.__version__
    assert ("svo:epsilon" in cli) == (kind == "surface")  # a guard band decides surface voxels only


def test_read_mesh_names_and_reads_every_format_svo_reads(tmp_path):
    for ext in (".obj", ".ply", ".stl", ".off", ".gltf", ".glb"):
        assert ext in svo.read_mesh.__doc__
    # A glTF file (positions float32, indices uint16, one embedded buffer) reads
    # as the same triangles as its OFF.
    v, t = tetrahedron()
    data = v.astype("<f4").tobytes() + t.astype("<u2").tobytes()
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
    }
    (tmp_path / "tet.gltf").write_text(json.dumps(gltf))
    gv, gt = svo.read_mesh(tmp_path / "tet.gltf")
    ov, ot = svo.read_mesh(write_off(tmp_path / "tet.off", v, t))
    assert np.array_equal(gv[gt], ov[ot]) and len(gt) == 4


def test_trimesh_style_inputs_and_precisions_agree(voxelizer):
    v, t = tetrahedron()
    want = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=24).grid))
    # float32 vertices exactly representable, uint32/int32 faces, lists, non-contiguous views
    assert as_set(svo.active_voxels(voxelizer.voxelize(v.astype(np.float32), t.astype(np.uint32), resolution=24).grid)) == want
    assert as_set(svo.active_voxels(voxelizer.voxelize(v.tolist(), t.tolist(), resolution=24).grid)) == want
    wide = np.zeros((4, 6))
    wide[:, ::2] = v
    assert not wide[:, ::2].flags.c_contiguous
    assert as_set(svo.active_voxels(voxelizer.voxelize(wide[:, ::2], t, resolution=24).grid)) == want


def test_transform_matrix_equals_pyopenvdb_transform(voxelizer):
    v, t = tetrahedron()
    h = 0.05
    xform = pyopenvdb.createLinearTransform(voxelSize=h)
    m = np.diag([h, h, h, 1.0])
    a = voxelizer.voxelize(v, t, transform=xform).grid
    b = voxelizer.voxelize(v, t, transform=m).grid
    assert as_set(svo.active_voxels(a)) == as_set(svo.active_voxels(b))
    # voxel_size h gives the same lattice
    c = voxelizer.voxelize(v, t, voxel_size=h).grid
    assert as_set(svo.active_voxels(c)) == as_set(svo.active_voxels(a))


def test_rotated_transform_covers_every_vertex(voxelizer):
    v, t = tetrahedron()
    c, s = np.cos(0.4), np.sin(0.4)
    m = np.array([[c * 0.04, s * 0.04, 0, 0], [-s * 0.05, c * 0.05, 0, 0], [0, 0, 0.03, 0], [0.1, -0.2, 0.3, 1]])
    grid = voxelizer.voxelize(v, t, transform=m).grid
    voxels = as_set(svo.active_voxels(grid))
    # Each vertex lies in (the closed cube of) the voxel nearest to its index-space position.
    inv = np.linalg.inv(m)
    for p in v:
        idx = (np.append(p, 1.0) @ inv)[:3]
        assert tuple(int(x) for x in np.round(idx)) in voxels


def test_round_trip_through_pyopenvdb(voxelizer, tmp_path):
    v, t = tetrahedron()
    grid = voxelizer.voxelize(v, t, resolution=32).grid
    fog = voxelizer.voxelize(v, t, resolution=32, grid="fog").grid
    assert isinstance(fog, pyopenvdb.FloatGrid)
    assert fog.gridClass == "fog volume"
    path = str(tmp_path / "out.vdb")
    pyopenvdb.write(path, [grid, fog])
    back = pyopenvdb.read(path, "surface")
    assert as_set(svo.active_voxels(back)) == as_set(svo.active_voxels(grid))
    assert as_set(svo.active_voxels(pyopenvdb.read(path, "density"))) == as_set(svo.active_voxels(grid))


def test_attribute_channels_come_as_grids_and_arrays(voxelizer):
    v, t = tetrahedron()
    out = voxelizer.voxelize(v, t, resolution=16, attributes=("normal", "triangle"))
    ijk = out.ijk
    assert out.grid is out.grids["surface"] and sorted(out.grids) == ["normal", "surface"]
    assert as_set(ijk) == as_set(svo.active_voxels(out.grid))
    assert isinstance(out.grids["normal"], pyopenvdb.Vec3SGrid)
    assert out.triangle.shape == (len(ijk),) and out.normal.shape == (len(ijk), 3)
    assert out.color is None and out.report is None  # not asked for
    # Pairing: each voxel's values are the normal grid's value there, and its
    # smallest triangle really touches it (the voxel lies within half a voxel
    # diagonal of that triangle's plane).
    normals = out.grids["normal"].getConstAccessor()
    xform = out.grid.transform
    for k in range(0, len(ijk), max(1, len(ijk) // 50)):
        c = tuple(int(x) for x in ijk[k])
        assert np.allclose(normals.getValue(c), out.normal[k])
        a, b, d = v[t[out.triangle[k]]]
        n = np.cross(b - a, d - a)
        n /= np.linalg.norm(n)
        centre = np.array(xform.indexToWorld(c))
        assert abs(np.dot(centre - a, n)) <= 0.5 * np.sqrt(3) * xform.voxelSize()[0] + 1e-9


@pytest.mark.parametrize("vertices, triangles, kwargs, message", [
    (np.zeros((4, 2)), [[0, 1, 2]], {}, "vertices: expected shape (N, 3)"),
    (np.zeros((0, 3)), [[0, 1, 2]], {}, "vertices: the array is empty"),
    ([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]], [[0, 1, 2]], {}, "not finite"),
    ([[0, 0, 0], [1, 0, 0], [0, np.inf, 0]], [[0, 1, 2]], {}, "not finite"),
    (np.eye(3), [[0, 1, 5]], {}, "refers to vertex 5"),
    (np.eye(3), [[0, -1, 2]], {}, "refers to vertex -1"),
    (np.eye(3), [[0.0, 1.0, 2.0]], {}, "expected integers"),
    (np.eye(3), np.zeros((0, 3), int), {}, "triangles: the array is empty"),
    (np.eye(3), [[0, 1]], {}, "triangles: expected shape"),
    (np.eye(3), [[0, 1, 2]], {"resolution": 0}, "resolution"),
    (np.eye(3), [[0, 1, 2]], {"resolution": 2.5}, "resolution"),
    (np.eye(3), [[0, 1, 2]], {"voxel_size": -1.0}, "voxel_size"),
    (np.eye(3), [[0, 1, 2]], {"transform": np.ones((4, 4))}, "not affine"),
    (np.eye(3), [[0, 1, 2]], {"transform": np.eye(3)}, "4x4"),
    (np.eye(3), [[0, 1, 2]], {"resolution": 8, "voxel_size": 0.1}, "give one of"),
    (np.eye(3), [[0, 1, 2]], {"grid": "mask"}, "grid:"),
    (np.eye(3), [[0, 1, 2]], {"backend": "vulkan"}, "backend:"),
    (np.eye(3), [[0, 1, 2]], {"attributes": ("curvature",)}, "attributes:"),
    (np.eye(3), [[0, 1, 2]], {"mode": "thick"}, "mode:"),
    (np.eye(3), [[0, 1, 2]], {"gpu_memory": 0}, "gpu_memory:"),
])
def test_bad_input_raises_value_error_and_leaves_it_usable(voxelizer, vertices, triangles, kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        voxelizer.voxelize(vertices, triangles, **kwargs)
    v, t = tetrahedron()
    assert voxelizer.voxelize(v, t, resolution=8).grid.activeVoxelCount() > 0


def test_read_mesh_errors_are_os_errors(tmp_path):
    with pytest.raises(OSError, match="no such file"):
        svo.read_mesh(str(tmp_path / "missing.off"))
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(OSError, match="bad.off"):
        svo.read_mesh(str(bad))


def test_library_errors_become_python_errors_by_their_type(voxelizer, tmp_path):
    v, t = tetrahedron()
    # A bad option (svo::InvalidInput), named by its keyword: ValueError.
    with pytest.raises(ValueError, match="exterior_band 0.5: a band is a number of voxels from 1 to 1000"):
        voxelizer.level_set(v, t, resolution=8, exterior_band=0.5)
    # A missing or damaged file (svo::IoError): OSError, naming the file.
    with pytest.raises(OSError, match="missing.svo: cannot open the file"):
        svo.load(str(tmp_path / "missing.svo"))
    damaged = tmp_path / "damaged.svo"
    damaged.write_bytes(b"SVOCTREE" + bytes(40))
    with pytest.raises(OSError, match="damaged.svo: not a valid .svo file"):
        svo.load(str(damaged))
    faceless = tmp_path / "faceless.obj"  # a file of no mesh: damaged, not a bad argument
    faceless.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    with pytest.raises(OSError, match="faceless.obj"):
        svo.read_mesh(str(faceless))
    # The GPU budget exhausted (svo::OutOfMemory): MemoryError, and a RuntimeError as before.
    with pytest.raises(MemoryError, match="cannot hold the mesh") as caught:
        voxelizer.voxelize(v, t, resolution=16, gpu_memory=1024)
    assert isinstance(caught.value, RuntimeError) and isinstance(caught.value, svo.OutOfMemoryError)
    # A budget asked of the CPU backend, which allocates no GPU memory: refused, not ignored.
    for call in (voxelizer.voxelize, voxelizer.level_set, voxelizer.solid):
        with pytest.raises(ValueError, match="^gpu_memory applies to the GPU backends, not to backend cpu$"):
            call(v, t, resolution=16, backend="cpu", gpu_memory=1 << 30)
    # An option the mesh cannot take (svo::InvalidInput): ValueError.
    with pytest.raises(ValueError, match="parity signs need a mesh without holes"):
        voxelizer.level_set(v, t[:3], resolution=8, sign="parity")
    # A request svo has no method for (svo::Unsupported): NotImplementedError, a RuntimeError.
    rotated = np.array([[0, 0.1, 0, 0], [-0.1, 0, 0, 0], [0, 0, 0.2, 0], [0, 0, 0, 1]])
    with pytest.raises(NotImplementedError, match="uniform scale") as caught:
        voxelizer.level_set(v, t, transform=rotated)
    assert isinstance(caught.value, RuntimeError)
    # No usable device (svo::DeviceError): RuntimeError.
    with pytest.raises(RuntimeError, match="no EGL device matches 'no-such-device'"):
        svo.Voxelizer(device="no-such-device", program_cache="off").voxelize(v, t, resolution=8)
    # KeyboardInterrupt (svo::Interrupted): test_ctrl_c_cancels_a_long_call_and_leaves_it_usable.
    assert voxelizer.voxelize(v, t, resolution=8).grid.activeVoxelCount() > 0


def test_two_threads_with_two_voxelizers():
    v, t = tetrahedron()
    want = {r: as_set(svo.active_voxels(svo.voxelize(v, t, resolution=r).grid)) for r in (40, 56)}
    got = {}

    def work(r):
        local = svo.Voxelizer()
        for _ in range(3):
            got[r] = as_set(svo.active_voxels(local.voxelize(v, t, resolution=r).grid))

    threads = [threading.Thread(target=work, args=(r,)) for r in want]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert got == want


def test_cpu_backend_is_the_reference_within_the_guard_band(voxelizer):
    v, t = tetrahedron()
    gpu = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48).grid))
    cpu = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48, backend="cpu").grid))
    assert cpu <= gpu  # the GPU's guard band only adds voxels within about 1e-4 voxel of a triangle
    assert len(gpu - cpu) <= len(cpu) // 100


def test_compute_backend_gives_the_raster_voxels(voxelizer):
    v, t = tetrahedron()
    raster = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48, backend="raster").grid))
    compute = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48, backend="compute").grid))
    assert compute == raster and len(raster) > 1000


def test_a_small_gpu_memory_budget_tiles_to_the_same_voxels(voxelizer):
    v, t = tetrahedron()
    whole = voxelizer.voxelize(v, t, resolution=160, attributes=("normal", "triangle"))
    tiled = voxelizer.voxelize(v, t, resolution=160, attributes=("normal", "triangle"), gpu_memory=1 << 20)
    assert as_set(tiled.ijk) == as_set(whole.ijk) and len(whole.ijk) > 10000

    # The GPU lays bricks out in the order it allocates them, the merge in
    # canonical order: compare the channels voxel by voxel.
    def by_voxel(result, key):
        return {tuple(p): repr(v) for p, v in zip(result.ijk.tolist(), getattr(result, key).tolist())}

    assert by_voxel(tiled, "triangle") == by_voxel(whole, "triangle")
    assert by_voxel(tiled, "normal") == by_voxel(whole, "normal")
    with pytest.raises(RuntimeError, match="cannot hold the mesh"):
        voxelizer.voxelize(v, t, resolution=160, gpu_memory=1024)


def test_fields_and_solids_within_a_gpu_memory_budget_are_the_whole_grids(voxelizer, tmp_path):
    v, t = tetrahedron()

    def dense(grid):
        a = np.empty((120, 120, 120), dtype=bool if isinstance(grid, pyopenvdb.BoolGrid) else np.float32)
        grid.copyToArray(a, ijk=(-10, -10, -10))  # the grid and its band, inactive values too
        return a

    for call in (voxelizer.level_set, voxelizer.solid):
        whole = call(v, t, resolution=96, backend="compute", report=True)
        tiled = call(v, t, resolution=96, backend="compute", gpu_memory=1 << 20, report=True)
        assert whole.report["tiles"] == 1 and tiled.report["tiles"] >= 2
        assert np.array_equal(dense(tiled.grid), dense(whole.grid))
    voxelizer.write_nanovdb(tmp_path / "whole.nvdb", v, t, kind="sdf", resolution=96, backend="compute")
    voxelizer.write_nanovdb(tmp_path / "tiled.nvdb", v, t, kind="sdf", resolution=96, backend="compute",
                            gpu_memory=1 << 20)
    assert (tmp_path / "tiled.nvdb").read_bytes() == (tmp_path / "whole.nvdb").read_bytes()
    with pytest.raises(MemoryError, match="raise the budget"):
        voxelizer.level_set(v, t, resolution=96, backend="compute", gpu_memory=1024)


def test_a_region_is_the_whole_grid_cut_to_its_box(voxelizer):
    v, t = tetrahedron()
    whole = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48).grid))
    box = ((8, 0, 8), (32, 24, 48))
    part = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48, region=box).grid))
    inside = {p for p in whole if all(box[0][a] <= p[a] < box[1][a] for a in range(3))}
    assert part == inside and 0 < len(inside) < len(whole)
    sdf = voxelizer.level_set(v, t, resolution=48).grid
    sdf_part = voxelizer.level_set(v, t, resolution=48, region=box).grid
    expected = {p for p in as_set(svo.active_voxels(sdf)) if all(box[0][a] <= p[a] < box[1][a] for a in range(3))}
    assert as_set(svo.active_voxels(sdf_part)) == expected
    acc, part_acc = sdf.getConstAccessor(), sdf_part.getConstAccessor()
    assert all(acc.getValue(p) == part_acc.getValue(p) for p in expected)
    # A region no triangle reaches has the same grids and arrays, empty.
    nowhere = ((1024, 1024, 1024), (1032, 1032, 1032))
    full = voxelizer.voxelize(v, t, resolution=48, region=box, attributes=("normal", "triangle"))
    empty = voxelizer.voxelize(v, t, resolution=48, region=nowhere, attributes=("normal", "triangle"))
    assert sorted(empty.grids) == sorted(full.grids) and "normal" in full.grids
    assert empty.ijk.shape == (0, 3) and empty.normal.shape == (0, 3) and empty.triangle.shape == (0,)
    with pytest.raises(ValueError, match="region .*multiple of 8"):
        voxelizer.voxelize(v, t, resolution=48, region=((0, 0, 0), (8, 8, 12)))
    with pytest.raises(TypeError):
        voxelizer.voxelize(v, t, resolution=48, region=(0, 0, 0, 8, 8, 8))


def test_thin_mode_is_inside_conservative_and_equal_on_every_backend(voxelizer):
    v, t = tetrahedron()
    conservative = as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48).grid))
    thin = {b: as_set(svo.active_voxels(voxelizer.voxelize(v, t, resolution=48, backend=b, mode="thin").grid))
            for b in ("raster", "compute", "cpu")}
    assert thin["compute"] == thin["raster"]
    assert thin["cpu"] <= thin["raster"]  # the GPU's guard band only adds voxels within about 1e-4 voxel
    assert len(thin["raster"] - thin["cpu"]) <= len(thin["cpu"]) // 100
    assert thin["raster"] <= conservative and len(thin["raster"]) < len(conservative)
    octree = voxelizer.octree(v, t, resolution=48, mode="thin")
    assert as_set(octree.voxels()) == thin["raster"]


def test_thin_plane_keeps_one_voxel_per_column(voxelizer):
    # z = x/2 + 0.3 over [0.1, 11.9] x [0.1, 7.9], voxel size 1: a voxel's z
    # segment meets it in columns 1..11 x 1..7 at k = (i+1)//2 (0.2 or 0.3
    # away); x segments meet it only in those voxels, y segments never.
    v = np.array([[0.1, 0.1, 0.35], [11.9, 0.1, 6.25], [11.9, 7.9, 6.25], [0.1, 7.9, 0.35]])
    t = np.array([[0, 1, 2], [0, 2, 3]])
    got = as_set(svo.active_voxels(voxelizer.voxelize(v, t, voxel_size=1.0, mode="thin").grid))
    assert got == {(i, j, (i + 1) // 2) for i in range(1, 12) for j in range(1, 8)}


def test_octree_views_files_and_grids(voxelizer, tmp_path):
    v, t = tetrahedron()
    octree = voxelizer.octree(v, t, resolution=40)
    grid = voxelizer.voxelize(v, t, resolution=40).grid
    assert octree.voxel_count == grid.activeVoxelCount()
    assert as_set(octree.voxels()) == as_set(svo.active_voxels(grid))
    assert as_set(svo.active_voxels(octree.to_grid())) == as_set(svo.active_voxels(grid))
    nodes, bricks = octree.nodes, octree.bricks
    assert nodes.dtype == np.uint32 and nodes.shape[1] == 2 and bricks.dtype == np.uint64 and bricks.shape[1] == 8
    assert not nodes.flags.owndata and not bricks.flags.owndata  # views, no copies
    assert len(octree.level_start) == octree.levels + 1 and octree.level_start[-1] == len(nodes)
    # Every voxel is one set bit: the bricks' popcount is the voxel count.
    assert sum(bin(int(w)).count("1") for w in bricks.ravel()) == octree.voxel_count
    # The root's mask says which of its 8 children are occupied; a leaf-level node points into bricks.
    assert nodes[0, 1] != 0
    path = str(tmp_path / "t.svo")
    octree.save(path)
    loaded = svo.load(path)
    assert np.array_equal(loaded.nodes, nodes) and np.array_equal(loaded.bricks, bricks)
    again = svo.Octree.from_grid(grid)
    assert as_set(again.voxels()) == as_set(octree.voxels())
    with pytest.raises(OSError):
        svo.load(str(tmp_path / "missing.svo"))


def test_views_stay_valid_while_the_octree_lives(voxelizer):
    v, t = tetrahedron()
    bricks = voxelizer.octree(v, t, resolution=24).bricks  # the octree object is gone; the view keeps it
    import gc
    gc.collect()
    copy = np.array(bricks)
    voxelizer.octree(v, t, resolution=48)  # allocations that would reuse freed memory
    assert np.array_equal(bricks, copy)
    assert sum(bin(int(w)).count("1") for w in bricks.ravel()) > 0


def test_validate_gives_the_numbers_of_the_cli(elephant, tmp_path):
    out = tmp_path / "v.json"
    subprocess.run([SVO_EXE, "validate", elephant, "-r", "48", "--json", str(out)], check=True, capture_output=True)
    import json
    cli = json.loads(out.read_text())
    vertices, triangles = svo.read_mesh(elephant)
    report = svo.validate(vertices, triangles, resolution=48)
    for key in ("voxels", "required", "exact", "allowed", "missed", "missed_exact", "boundary", "extra", "epsilon", "passed", "octree_consistent"):
        assert report[key] == cli[key], key
    assert report["missed"] == 0 and report["missed_exact"] == 0 and report["holes"]["applies"] and not report["holes"]["leak"]
    assert report["passed"]


def test_validate_thin_uses_segments_and_a_6_connected_fill(elephant, tmp_path):
    out = tmp_path / "v.json"
    subprocess.run([SVO_EXE, "validate", elephant, "-r", "48", "--mode", "thin", "--json", str(out)], check=True,
                   capture_output=True)
    import json
    cli = json.loads(out.read_text())
    vertices, triangles = svo.read_mesh(elephant)
    report = svo.validate(vertices, triangles, resolution=48, mode="thin")
    conservative = svo.validate(vertices, triangles, resolution=48)
    for key in ("mode", "voxels", "required", "exact", "allowed", "missed", "missed_exact", "extra", "passed"):
        assert report[key] == cli[key], key
    assert report["mode"] == "thin" and conservative["mode"] == "conservative"
    assert report["passed"] and report["holes"]["applies"] and report["holes"]["connectivity"] == 6
    assert not report["holes"]["leak"]
    assert report["exact"] < conservative["exact"]


def test_validate_level_set_gives_the_numbers_of_the_cli(elephant, tmp_path):
    out = tmp_path / "v.json"
    subprocess.run([SVO_EXE, "validate", elephant, "-r", "48", "--sdf", "--band", "2", "--json", str(out)],
                   check=True, capture_output=True)
    import json
    cli = json.loads(out.read_text())
    vertices, triangles = svo.read_mesh(elephant)
    report = svo.validate_level_set(vertices, triangles, resolution=48, exterior_band=2, interior_band=2)
    for key in ("voxels", "candidates", "max_error", "rms_error", "sign_checked", "sign_disagreements", "missing",
                "extra", "sign", "passed"):
        assert report[key] == cli[key], key
    for key in ("active", "common", "only_svo", "only_openvdb", "sign_disagreements"):
        assert report["openvdb"][key] == cli["openvdb"][key], key
    assert report["passed"] and report["sign_checked"] and report["max_error"] <= 1e-4
    assert report["missing"] == 0 and report["extra"] == 0 and report["sign_disagreements"] == 0
    assert report["openvdb"]["svo_farther"] == 0
    alone = svo.validate_level_set(vertices, triangles, resolution=48, exterior_band=2, interior_band=2, openvdb=False)
    assert alone["openvdb"] is None and alone["max_error"] == report["max_error"]


def test_validate_level_set_of_an_open_mesh_checks_no_signs():
    v, t = tetrahedron()
    open_t = np.asarray(t)[:-1]  # one face gone: no inside
    report = svo.validate_level_set(v, open_t, resolution=24)
    assert not report["sign_checked"] and "open" in report["sign_reason"]
    assert report["sign"].startswith("winding")
    assert report["passed"] and report["missing"] == 0 and report["extra"] == 0


def test_ctrl_c_cancels_a_long_call_and_leaves_it_usable(voxelizer):
    import signal
    import time
    v, t = tetrahedron()
    start = time.monotonic()
    full = voxelizer.voxelize(v, t, resolution=1536).grid.activeVoxelCount()
    whole = time.monotonic() - start
    timer = threading.Timer(whole * 0.1, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        voxelizer.voxelize(v, t, resolution=1536)
        time.sleep(whole)  # only reached if the call ignored the signal
    timer.join()
    assert time.monotonic() - start < 0.6 * whole, "the call ran on after Ctrl-C"
    assert voxelizer.voxelize(v, t, resolution=1536).grid.activeVoxelCount() == full


@pytest.mark.parametrize("script, args", [
    ("voxelize_file.py", ["{mesh}", "{tmp}/out.vdb", "64"]),
    ("numpy_points.py", []),
    ("validate_mesh.py", ["{mesh}", "48"]),
])
def test_examples_run(elephant, tmp_path, script, args):
    import sys
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.join(here, "..", "examples", script)
    argv = [a.format(mesh=elephant, tmp=tmp_path) for a in args]
    done = subprocess.run([sys.executable, path, *argv], capture_output=True, text=True, env=os.environ)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip()
    if script == "voxelize_file.py":
        assert pyopenvdb.read(str(tmp_path / "out.vdb"), "surface").activeVoxelCount() > 1000
    if script == "validate_mesh.py":
        assert "passed" in done.stdout


def sphere_inside(ijk, centre_index, radius_index):
    return np.linalg.norm(ijk - centre_index, axis=1) < radius_index


def test_level_set_of_a_tetrahedron_matches_the_analytic_distance(voxelizer):
    # The tetrahedron is convex: inside, the distance is the nearest face
    # plane's, and the sign follows the four planes.
    v, t = tetrahedron()
    h = 0.05
    grid = voxelizer.level_set(v, t, voxel_size=h, exterior_band=2, interior_band=4).grid
    assert grid.gridClass == pyopenvdb.GridClass.LEVEL_SET and grid.name == "level_set"
    assert abs(grid.background - 2 * h) < 1e-7
    vertices = np.asarray(v, dtype=float)
    normals, offsets = [], []
    for f in np.asarray(t):
        a, b, c = vertices[f]
        n = np.cross(b - a, c - a)
        n /= np.linalg.norm(n)
        normals.append(n)
        offsets.append(np.dot(n, a))
    normals, offsets = np.array(normals), np.array(offsets)
    ijk = svo.active_voxels(grid)
    values = np.array([grid.getConstAccessor().getValue(tuple(int(c) for c in p)) for p in ijk])
    world = ijk * h
    plane = world @ normals.T - offsets  # signed distance to each face's plane (outward normals)
    inside = (plane < 0).all(axis=1)
    # Inside a convex solid the distance is the nearest plane's.
    deep = inside & (-plane.max(axis=1) > 1e-6)
    assert deep.sum() > 100
    assert np.all(values[deep] < 0)
    assert np.allclose(-values[deep], -plane[deep].max(axis=1), atol=1e-6)
    assert np.all(values[~inside & (plane.max(axis=1) > 1e-6)] > 0)
    unsigned = voxelizer.level_set(v, t, voxel_size=h, unsigned=True).grid
    assert unsigned.name == "distance" and unsigned.activeVoxelCount() > 0


def test_level_set_says_its_sign_and_gives_closest_triangles(voxelizer):
    # Two squares, one at z = 0 (triangles 0, 1) and one at z = 1 (2, 3): a
    # band of 2 voxels of 0.05 around each, so every band voxel's closest
    # triangle is on its own square, and its distance is its height above it.
    v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    t = [(0, 1, 2), (0, 2, 3), (4, 5, 6), (4, 6, 7)]
    h = 0.05
    result = voxelizer.level_set(v, t, voxel_size=h, exterior_band=2, unsigned=True, closest_triangle=True)
    grid, ijk, ids = result.grid, result.ijk, result.triangle
    assert ijk.shape == (grid.activeVoxelCount(), 3) and ids.shape == (len(ijk),)
    assert as_set(ijk) == as_set(svo.active_voxels(grid))
    z = ijk[:, 2] * h
    assert np.all(np.isin(ids[z < 0.5], [0, 1])) and np.all(np.isin(ids[z > 0.5], [2, 3]))
    over = (ijk[:, 0] * h > 0.01) & (ijk[:, 0] * h < 0.99) & (ijk[:, 1] * h > 0.01) & (ijk[:, 1] * h < 0.99)
    values = np.array([grid.getConstAccessor().getValue(tuple(int(c) for c in p)) for p in ijk[over]])
    assert over.sum() > 1000
    assert np.allclose(values, np.minimum(np.abs(z[over]), np.abs(z[over] - 1)), atol=1e-6)
    # Which sign method ran, and why, is the grid's metadata.
    tv, tt = tetrahedron()
    assert voxelizer.level_set(tv, tt, resolution=24).grid["svo:sign"].startswith("parity: the mesh is closed")
    assert voxelizer.level_set(tv, tt[:3], resolution=24).grid["svo:sign"] == \
        "winding: the mesh is not closed (3 boundary edges)"
    with pytest.raises(ValueError, match="parity signs need a mesh without holes"):
        voxelizer.level_set(tv, tt[:3], resolution=24, sign="parity")


def test_level_sets_and_solids_on_the_cpu_backend_are_the_default_backends(voxelizer):
    # backend="cpu" runs level sets, unsigned fields and solids on the CPU
    # (no GPU); test_cpu_fields holds them to the GPU path bit for bit.
    v, t = tetrahedron()
    for kwargs in ({}, {"unsigned": True}, {"sign": "winding"}):
        gpu = voxelizer.level_set(v, t, resolution=32, **kwargs).grid
        cpu = voxelizer.level_set(v, t, resolution=32, backend="cpu", **kwargs).grid
        ijk = svo.active_voxels(gpu)
        assert as_set(ijk) == as_set(svo.active_voxels(cpu)) and len(ijk) > 1000
        a, b = gpu.getConstAccessor(), cpu.getConstAccessor()
        assert all(a.getValue(tuple(int(c) for c in p)) == b.getValue(tuple(int(c) for c in p)) for p in ijk)
        if "unsigned" not in kwargs:
            assert cpu["svo:sign"] == gpu["svo:sign"]
    open_t = t[:3]  # winding signs under auto
    assert as_set(svo.active_voxels(voxelizer.solid(v, open_t, resolution=40, backend="cpu").grid)) == \
        as_set(svo.active_voxels(voxelizer.solid(v, open_t, resolution=40).grid))
    assert as_set(svo.active_voxels(voxelizer.solid(v, t, resolution=40, backend="cpu").grid)) == \
        as_set(svo.active_voxels(voxelizer.solid(v, t, resolution=40).grid))


def test_solid_of_a_tetrahedron_is_its_inside_and_surface(voxelizer):
    v, t = tetrahedron()
    solid = voxelizer.solid(v, t, resolution=40).grid
    surface = voxelizer.voxelize(v, t, resolution=40).grid
    filled, shell = as_set(svo.active_voxels(solid)), as_set(svo.active_voxels(surface))
    assert shell < filled and len(filled) > 1.5 * len(shell)
    # Three faces of four: the winding number (auto, for an open mesh) still
    # finds the inside, away from the missing face; parity is refused.
    opened_grid = voxelizer.solid(v, t[:3], resolution=40).grid
    assert opened_grid["svo:sign"] == "winding: the mesh is not closed (3 boundary edges)"
    opened = as_set(svo.active_voxels(opened_grid))
    assert opened <= filled and len(opened) > 0.8 * len(filled)
    with pytest.raises(ValueError, match="parity signs need a mesh without holes"):
        voxelizer.solid(v, t[:3], resolution=40, sign="parity")
    # A bad option, named by its keyword, before any work (it was a RuntimeError from the GPU call).
    with pytest.raises(ValueError, match="winding_accuracy 0: the winding accuracy"):
        voxelizer.solid(v, t[:3], resolution=40, sign="winding", winding_accuracy=0)
    with pytest.raises(ValueError, match="sign"):
        voxelizer.solid(v, t, resolution=40, sign="nearest")


def test_a_band_is_the_unsigned_fields_active_voxels(voxelizer):
    # band(): the voxels nearer than exterior_band to a triangle, exactly
    # level_set(unsigned=True)'s active voxels, on either backend, for an
    # open mesh too; a BoolGrid named 'band'.
    v, t = tetrahedron()
    for tris in (t, t[:3]):
        for backend in ("compute", "cpu"):
            band = voxelizer.band(v, tris, resolution=40, exterior_band=2.5, backend=backend).grid
            field = voxelizer.level_set(v, tris, resolution=40, unsigned=True, exterior_band=2.5).grid
            got = as_set(svo.active_voxels(band))
            assert got == as_set(svo.active_voxels(field)) and len(got) > 1000
            assert band.name == "band" and band.valueTypeName == "bool"
    with pytest.raises(ValueError, match="exterior_band 0.5"):
        voxelizer.band(v, t, resolution=40, exterior_band=0.5)
    with pytest.raises(TypeError, match="sign"):
        voxelizer.band(v, t, resolution=40, sign="winding")


def read_png_rgb(path):
    """An 8-bit RGB PNG as an (H, W, 3) array: the five row filters of the PNG standard."""
    import struct
    import zlib
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 2)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), 3 * width
    out = np.zeros((height, stride), dtype=np.int64)
    prev = np.zeros(stride, dtype=np.int64)
    for y in range(height):
        f, row = raw[y * (stride + 1)], np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int64)
        cur = np.zeros(stride, dtype=np.int64)
        for x in range(stride):
            a = cur[x - 3] if x >= 3 else 0
            b, c = prev[x], (prev[x - 3] if x >= 3 else 0)
            if f == 0: p = 0
            elif f == 1: p = a
            elif f == 2: p = b
            elif f == 3: p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (row[x] + p) & 255
        out[y], prev = cur, cur
    return out.reshape(height, width, 3).astype(np.uint8)


@pytest.mark.skipif(not SVO_EXE, reason="SVO_EXE is not set")
def test_octree_render_draws_what_svo_view_draws(voxelizer, tmp_path):
    v, t = tetrahedron()
    octree = voxelizer.octree(v, t, resolution=24, attributes=["normal"])
    path = str(tmp_path / "t.svo")
    octree.save(path)
    for view, color in (("+z", "flat"), ("front", "normal")):
        image = octree.render(size=(64, 48), view=view, layers=["voxels", "outlines"], levels=(1, 2), color=color)
        assert image.shape == (48, 64, 4) and image.dtype == np.uint8
        png = str(tmp_path / f"{view}.png")
        subprocess.run([SVO_EXE, "view", path, "--screenshot", png, "--size", "64x48", "--view", view,
                        "--layers", "voxels,outlines", "--levels", "1:2", "--color", color],
                       check=True, capture_output=True)
        assert np.array_equal(image[:, :, :3], read_png_rgb(png))
        green = (image[:, :, 1].astype(int) > image[:, :, 0].astype(int) + 50).sum()
        assert 0 < green < 64 * 48  # voxels drawn, background left
    # Ambient occlusion alone, grey: the same picture as svo view --render ao.
    image = octree.render(size=(64, 48), view="front", layers=["voxels"], ao_only=True)
    png = str(tmp_path / "ao.png")
    subprocess.run([SVO_EXE, "view", path, "--screenshot", png, "--size", "64x48", "--view", "front",
                    "--layers", "voxels", "--render", "ao"], check=True, capture_output=True)
    assert np.array_equal(image[:, :, :3], read_png_rgb(png))
    grey = (image[:, :, 0] == image[:, :, 1]) & (image[:, :, 1] == image[:, :, 2])
    assert 0 < grey.sum() < 64 * 48
    octree_ao = octree.render(size=(64, 48), view="front", layers=["voxels"], ao_only=True, ao_source="octree")
    subprocess.run([SVO_EXE, "view", path, "--screenshot", png, "--size", "64x48", "--view", "front",
                    "--layers", "voxels", "--render", "ao", "--ao-source", "octree"], check=True, capture_output=True)
    assert np.array_equal(octree_ao[:, :, :3], read_png_rgb(png))
    assert not np.array_equal(octree_ao, image)  # two opacity sources, two pictures
    with pytest.raises(ValueError, match="ao"):
        octree.render(ao=17)
    with pytest.raises(ValueError, match="ao_source"):
        octree.render(ao_source="mesh")
    # Lit voxels: the same pictures as svo view --render direct|gi with the same lights.
    for lighting in ("direct", "gi"):
        image = octree.render(size=(64, 48), view="front", lighting=lighting,
                              lights=[("sun", (0.3, -1, 0.2), 2.0), ("point", (0.2, 0.9, 0.3), (1, 1, 0.5))],
                              specular=0.2 if lighting == "gi" else None)
        png = str(tmp_path / f"{lighting}.png")
        subprocess.run([SVO_EXE, "view", path, "--screenshot", png, "--size", "64x48", "--view", "front",
                        "--render", lighting, "--light", "sun:0.3,-1,0.2:2", "--light", "point:0.2,0.9,0.3:1,1,0.5"]
                       + (["--specular", "0.2"] if lighting == "gi" else []), check=True, capture_output=True)
        assert np.array_equal(image[:, :, :3], read_png_rgb(png))
        assert image[:, :, 1].max() > 0
    # Six-way radiance and cones clear of voxels, as svo view --gi-emission directional --gi-clearance.
    clear = octree.render(size=(64, 48), view="front", lighting="gi", gi_emission="directional", gi_clearance=True)
    png = str(tmp_path / "clear.png")
    subprocess.run([SVO_EXE, "view", path, "--screenshot", png, "--size", "64x48", "--view", "front",
                    "--render", "gi", "--gi-emission", "directional", "--gi-clearance"], check=True, capture_output=True)
    assert np.array_equal(clear[:, :, :3], read_png_rgb(png))
    assert not np.array_equal(clear, octree.render(size=(64, 48), view="front", lighting="gi"))
    # The cones' shape, as svo view's options of the same names: the same bytes, and not the defaults' picture.
    shaped = octree.render(size=(64, 48), view="front", lighting="gi", ao=3, gi_cones=9, gi_aperture=40,
                           gi_offset=0.75, gi_step=0.3, gi_distance=12, ao_aperture=90, ao_offset=1, ao_step=0.25,
                           ao_distance=8, light_volume=32)
    subprocess.run([SVO_EXE, "view", path, "--screenshot", png, "--size", "64x48", "--view", "front",
                    "--render", "gi", "--ao", "3", "--gi-cones", "9", "--gi-aperture", "40", "--gi-offset", "0.75",
                    "--gi-step", "0.3", "--gi-distance", "12", "--ao-aperture", "90", "--ao-offset", "1",
                    "--ao-step", "0.25", "--ao-distance", "8", "--light-volume", "32"], check=True, capture_output=True)
    assert np.array_equal(shaped[:, :, :3], read_png_rgb(png))
    assert not np.array_equal(shaped, octree.render(size=(64, 48), view="front", lighting="gi", ao=3))
    for bad in (dict(gi_cones=17), dict(gi_step=0), dict(gi_aperture=180), dict(ao_step=1.5),
                dict(ao_distance=0), dict(light_volume=48)):
        with pytest.raises(ValueError, match="cone|ambient occlusion|volume resolution"):
            octree.render(lighting="gi", **bad)
    with pytest.raises(ValueError, match="gi_cones"):
        octree.render(gi_cones=3)  # without lighting
    with pytest.raises(ValueError, match="gi_emission"):
        octree.render(lighting="gi", gi_emission="sideways")
    with pytest.raises(ValueError, match="gi_clearance"):
        octree.render(gi_clearance=True)  # without lighting
    # The mesh's own triangles (surface "auto" with a mesh, as svo view --render ao
    # of the mesh file shades them): the same picture as svo view draws.
    obj = tmp_path / "t.obj"
    obj.write_text("".join(f"v {a} {b} {c}\n" for a, b, c in v) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t))
    smooth = octree.render(size=(64, 48), view="front", layers=["voxels"], ao_only=True, mesh=(v, t))
    png = str(tmp_path / "smooth.png")
    subprocess.run([SVO_EXE, "view", str(obj), "-r", "24", "--screenshot", png, "--size", "64x48", "--view", "front",
                    "--layers", "voxels", "--render", "ao"], check=True, capture_output=True)
    assert np.array_equal(smooth[:, :, :3], read_png_rgb(png))
    blocks = octree.render(size=(64, 48), view="front", layers=["voxels"], ao_only=True)
    assert not np.array_equal(smooth, blocks)  # triangles, not voxels
    assert np.array_equal(octree.render(size=(64, 48), view="front", layers=["voxels"], ao_only=True, mesh=(v, t),
                                        surface="voxels"), blocks)
    with pytest.raises(ValueError, match="mesh"):
        octree.render(ao_only=True, surface="mesh")  # no mesh given
    with pytest.raises(ValueError, match="mesh"):
        octree.render(ao_only=True, mesh=(v,))
    with pytest.raises(ValueError, match="surface"):
        octree.render(ao_only=True, mesh=(v, t), surface="smooth")
    with pytest.raises(ValueError, match="lighting"):
        octree.render(lighting="bright")
    with pytest.raises(ValueError, match="lights"):
        octree.render(lighting="direct", lights=[("lamp", (1, 2, 3))])
    with pytest.raises(ValueError, match="lights"):
        octree.render(lights=[("sun", (0, -1, 0))])  # lights without lighting
    with pytest.raises(ValueError, match="albedo"):
        octree.render(lighting="direct", albedo=2.0)
    plain = voxelizer.octree(v, t, resolution=24)
    with pytest.raises(ValueError, match="normal channel"):
        plain.render(lighting="gi")
    with pytest.raises(ValueError, match="no 'triangle' channel"):
        octree.render(color="triangle")
    with pytest.raises(ValueError, match="sideways"):
        octree.render(view="sideways")
    with pytest.raises(ValueError, match="layers"):
        octree.render(layers=["mesh"])


def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        for p in np.asarray(vertices, dtype=np.float64):
            f.write("v %r %r %r\n" % tuple(float(c) for c in p))
        for t in np.asarray(triangles):
            f.write("f %d %d %d\n" % tuple(int(i) + 1 for i in t))


@pytest.mark.parametrize("kwargs, cli_args", [
    ({"resolution": 16}, ["-r", "16"]),
    ({"voxel_size": 625000.0}, ["--voxel-size", "625000"]),
])
def test_a_mesh_beyond_unit_voxels_voxelizes_as_the_cli_does(voxelizer, tmp_path, kwargs, cli_args):
    # 1e7 voxels a side at voxel size 1: the binding once prepared the mesh on
    # that lattice and refused it; the CLI never did.
    v, t = np.eye(3) * 1e7, [[0, 1, 2]]
    mesh = tmp_path / "big.obj"
    write_obj(mesh, v, t)
    out = tmp_path / "cli.vdb"
    subprocess.run([SVO_EXE, "voxelize", str(mesh), *cli_args, "-o", str(out)], check=True, capture_output=True)
    cli = pyopenvdb.read(str(out), "surface")
    grid = voxelizer.voxelize(v, t, **kwargs).grid
    assert grid.activeVoxelCount() == cli.activeVoxelCount() > 16
    assert as_set(svo.active_voxels(grid)) == as_set(svo.active_voxels(cli))
    assert grid.transform.voxelSize() == cli.transform.voxelSize()
    assert grid.transform.indexToWorld((3, 2, 1)) == cli.transform.indexToWorld((3, 2, 1))
    assert svo.voxelize(v, t, **kwargs).grid.activeVoxelCount() == grid.activeVoxelCount()
    assert as_set(voxelizer.octree(v, t, **kwargs).voxels()) == as_set(svo.active_voxels(cli))
    closed = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]) * 1e7
    assert voxelizer.level_set(closed, tetrahedron()[1], **kwargs).grid.activeVoxelCount() > 0


def test_a_unit_triangle_1e12_away_gives_the_voxels_at_the_origin_shifted(voxelizer):
    v, t = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float64), [[0, 1, 2]]
    offset = 1e12  # a multiple of the voxel size 1/16: the same lattice, moved

    def world_centres(grid):
        return {tuple(c) for c in (np.array([grid.transform.indexToWorld(tuple(int(x) for x in ijk))
                                             for ijk in svo.active_voxels(grid)]))}

    near = voxelizer.voxelize(v, t, resolution=16).grid
    far = voxelizer.voxelize(v + offset, t, resolution=16).grid
    assert far.activeVoxelCount() == near.activeVoxelCount() > 100
    assert {tuple(c - offset for c in p) for p in world_centres(far)} == world_centres(near)


@pytest.mark.parametrize("call, kwargs, message", [
    ("level_set", {"exterior_band": float("nan")}, "exterior_band nan: a band is a number of voxels from 1 to 1000"),
    ("level_set", {"interior_band": float("nan")}, "interior_band nan"),
    ("level_set", {"exterior_band": 0.5}, "exterior_band 0.5"),
    ("level_set", {"unsigned": True, "exterior_band": float("nan")}, "exterior_band nan"),
    ("level_set", {"winding_accuracy": float("inf")}, "winding_accuracy inf: the winding accuracy is a positive"),
    ("level_set", {"winding_accuracy": float("nan")}, "winding_accuracy nan"),
    ("level_set", {"winding_accuracy": 0}, "winding_accuracy 0:"),
    ("solid", {"winding_accuracy": float("inf")}, "winding_accuracy inf"),
])
def test_nan_and_inf_options_are_value_errors_naming_the_keyword(voxelizer, call, kwargs, message):
    v, t = tetrahedron()
    with pytest.raises(ValueError, match=message):
        getattr(voxelizer, call)(v, t, resolution=8, **kwargs)


def test_validate_refuses_a_negative_worst():
    if not hasattr(svo, "validate"):
        pytest.skip("built without SVO_WITH_VALIDATE")
    v, t = tetrahedron()
    with pytest.raises(ValueError, match="worst -1: the worst cases listed of each kind are 0 to 1000000"):
        svo.validate(v, t, resolution=8, worst=-1)
    with pytest.raises(ValueError, match="worst -1"):
        svo.validate_level_set(v, t, resolution=8, worst=-1)
    with pytest.raises(ValueError, match="exterior_band nan"):
        svo.validate_level_set(v, t, resolution=8, exterior_band=float("nan"))


def test_face_messages_name_the_shape_and_the_index_as_given(voxelizer):
    with pytest.raises(ValueError, match=r"expected shape \(M, 3\) or \(M, 4\), got \(1, 2\)"):
        voxelizer.voxelize(np.eye(3), np.array([[0, 1]]), resolution=8)
    with pytest.raises(ValueError, match=r"got \(3,\)"):
        voxelizer.voxelize(np.eye(3), np.array([0, 1, 2]), resolution=8)
    big = np.array([[0, 1, 2 ** 63]], dtype=np.uint64)
    with pytest.raises(ValueError, match="refers to vertex 9223372036854775808, but there are 3 vertices"):
        voxelizer.voxelize(np.eye(3), big, resolution=8)
    ok = np.array([[0, 1, 2]], dtype=np.uint64)
    assert voxelizer.voxelize(np.eye(3), ok, resolution=8).grid.activeVoxelCount() > 0


def test_paths_may_be_path_like_and_kinds_have_their_own_names(voxelizer, tmp_path):
    v, t = tetrahedron()
    mesh = tmp_path / "tetrahedron.obj"
    write_obj(mesh, v, t)
    vertices, triangles = svo.read_mesh(mesh)  # a pathlib.Path
    assert np.array_equal(vertices, v) and np.array_equal(triangles, t)
    octree = voxelizer.octree(vertices, triangles, resolution=16)
    octree.save(tmp_path / "t.svo")
    assert svo.load(tmp_path / "t.svo").voxel_count == octree.voxel_count
    # One file holds the surface, the level set and the solid: three names.
    results = [voxelizer.voxelize(v, t, resolution=16), voxelizer.level_set(v, t, resolution=16),
               voxelizer.solid(v, t, resolution=16)]
    svo.write(tmp_path / "all.vdb", [r.grid for r in results])
    grids, _ = pyopenvdb.readAll(str(tmp_path / "all.vdb"))
    by_name = {g.name: g for g in grids}
    assert sorted(by_name) == ["level_set", "solid", "surface"]
    for r in results:
        got = by_name[r.grid.name]
        assert got.activeVoxelCount() == r.grid.activeVoxelCount() > 0
        assert got["svo:version"] == svo.__version__
    with pytest.raises(OSError, match="all.txt"):
        svo.write(tmp_path / "all.txt", [results[0].grid])
    # .nvdb with each of NanoVDB's codecs: its own validator passes every file,
    # and the compressed ones are smaller than the plain one.
    sizes = {}
    for codec in ("none", "zip", "blosc"):
        path = tmp_path / f"all_{codec}.nvdb"
        svo.write(path, [r.grid for r in results], codec=codec)
        sizes[codec] = path.stat().st_size
        r = subprocess.run(["nanovdb_validate", "-v", str(path)], capture_output=True, text=True)
        assert r.returncode == 0 and "fail" not in r.stdout.lower(), r.stdout + r.stderr
    assert sizes["zip"] < sizes["none"] and sizes["blosc"] < sizes["none"]
    with pytest.raises(ValueError, match="codec: expected 'none', 'zip' or 'blosc', got 'lz4'"):
        svo.write(tmp_path / "x.nvdb", [results[0].grid], codec="lz4")
    with pytest.raises(ValueError, match="codec applies to .nvdb"):
        svo.write(tmp_path / "x.vdb", [results[0].grid], codec="zip")


def test_every_call_returns_a_result_and_a_report_when_asked(voxelizer):
    v, t = tetrahedron()
    for result in (voxelizer.voxelize(v, t, resolution=16, report=True),
                   voxelizer.level_set(v, t, resolution=16, report=True),
                   voxelizer.solid(v, t, resolution=16, report=True)):
        assert isinstance(result, svo.Result)
        assert result.ijk is None and result.normal is None and result.triangle is None
        assert result.grids == {result.grid.name: result.grid}
        assert result.report["active_voxels"] == result.grid.activeVoxelCount() > 0
        assert result.report["backend"] in ("raster", "compute", "cpu") and result.report["stages"]
    assert voxelizer.voxelize(v, t, resolution=16).report is None
    assert voxelizer.level_set(v, t, resolution=16, report=True).report["sign"].startswith("parity")
