"""svo where pyopenvdb does not import (another CPython, a venv without system
site packages): grids come as svo.Grid. A child interpreter runs svo with
pyopenvdb hidden; this process checks what it made against analytic answers
and reads its files back with pyopenvdb and NanoVDB's own validator."""
import json
import os
import pathlib
import pickle
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pyopenvdb
import pytest

# Run in the child: the import of pyopenvdb fails there, as in a CPython without it.
HIDE = "import sys; sys.modules['pyopenvdb'] = None\n"

# A square at z = 0.52, x and y from 0.02 to 0.98, voxel size 0.1: world = 0.1 * index
# and voxel i spans [0.1 i - 0.05, 0.1 i + 0.05], so the square meets exactly the
# voxels i, j in 0..10 of layer k = 5 (no edge lies on a voxel face).
CHILD = textwrap.dedent("""
    import json, os, pathlib, pickle, sys
    import numpy as np
    import svo
    out = pathlib.Path(sys.argv[1])
    square = (np.array([[0.02, 0.02, 0.52], [0.98, 0.02, 0.52], [0.98, 0.98, 0.52], [0.02, 0.98, 0.52]]),
              np.array([[0, 1, 2, 3]]))
    tetrahedron = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float),
                   np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    v = svo.Voxelizer()
    surface = v.voxelize(*square, voxel_size=0.1, report=True)
    level_set = v.level_set(*tetrahedron, voxel_size=0.05, exterior_band=2, interior_band=4)
    solid = v.solid(*tetrahedron, resolution=20)
    normals = v.voxelize(*square, voxel_size=0.1, attributes=["normal"])
    surface.grid.write(out / "surface.vdb")                  # a pathlib.Path: os.PathLike
    svo.write(str(out / "both.nvdb"), [surface.grid, level_set.grid])
    np.save(out / "surface_ijk.npy", surface.grid.ijk)
    np.save(out / "surface_values.npy", surface.grid.values)
    np.save(out / "level_set_ijk.npy", level_set.grid.ijk)
    np.save(out / "level_set_values.npy", level_set.grid.values)
    (out / "grid.pickle").write_bytes(pickle.dumps(level_set.grid))
    try:
        surface.grid.to_pyopenvdb()
        converted = "converted"
    except ImportError as e:
        converted = str(e)
    json.dump({
        "types": [type(r.grid).__name__ for r in (surface, level_set, solid)],
        "names": [r.grid.name for r in (surface, level_set, solid)],
        "classes": [r.grid.grid_class for r in (surface, level_set, solid)],
        "transform": surface.grid.transform.tolist(),
        "metadata": surface.grid.metadata,
        "level_set_metadata": level_set.grid.metadata,
        "version": svo.__version__,
        "report_voxels": surface.report["active_voxels"],
        "solid_count": solid.grid.active_voxel_count,
        "solid_ijk": len(solid.grid.ijk),
        "normal_grid": type(normals.grids["normal"]).__name__,
        "normals": normals.normal.tolist(),
        "to_pyopenvdb": converted,
    }, open(out / "child.json", "w"))
""")


def run_child(python, tmp_path, env=None):
    script = tmp_path / "child.py"
    script.write_text(HIDE + CHILD)
    r = subprocess.run([python, str(script), str(tmp_path)], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr
    return json.loads((tmp_path / "child.json").read_text())


def check_child(tmp_path, got):
    # Every result is an svo.Grid, with its kind's own name and class.
    assert got["types"] == ["Grid", "Grid", "Grid"]
    assert got["names"] == ["surface", "level_set", "solid"]
    assert got["classes"] == ["unknown", "level set", "unknown"]
    assert got["normal_grid"] == "Grid"
    # The square's voxels, exactly.
    want = {(i, j, 5) for i in range(11) for j in range(11)}
    ijk = np.load(tmp_path / "surface_ijk.npy")
    assert ijk.dtype == np.int32 and set(map(tuple, ijk.tolist())) == want
    assert np.load(tmp_path / "surface_values.npy").all() and got["report_voxels"] == len(want)
    assert np.allclose(got["transform"], np.diag([0.1, 0.1, 0.1, 1.0]))
    # The square's normal is +z or -z on each voxel.
    assert np.allclose(np.abs(np.array(got["normals"])), [0, 0, 1])
    # The metadata `svo voxelize` writes.
    meta = got["metadata"]
    assert meta["svo:version"] == got["version"] and meta["svo:source"] == "mesh"
    assert meta["svo:triangles"] == "2" and meta["svo:grid"] == "voxel size 0.1" and float(meta["svo:voxel_size"]) == 0.1
    assert "svo:epsilon" in meta and "svo:backend" in meta
    assert got["level_set_metadata"]["svo:sign"].startswith("parity")
    # The level set inside the tetrahedron (convex): minus the nearest face plane's distance.
    lijk, values = np.load(tmp_path / "level_set_ijk.npy"), np.load(tmp_path / "level_set_values.npy")
    assert values.dtype == np.float32 and len(values) == len(lijk)
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    normals = np.array([np.cross(v[b] - v[a], v[c] - v[a]) for a, b, c in faces])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    offsets = np.array([normals[f] @ v[a] for f, (a, _, _) in enumerate(faces)])
    plane = (lijk * 0.05) @ normals.T - offsets
    deep = (plane < -1e-6).all(axis=1)
    assert deep.sum() > 100
    assert np.allclose(values[deep], plane[deep].max(axis=1), atol=1e-6)
    # A solid tetrahedron at resolution 20 holds more voxels than its surface, tiles expanded in ijk.
    assert got["solid_count"] == got["solid_ijk"] > 500
    # Without pyopenvdb, to_pyopenvdb says so and names the interpreter.
    assert "pyopenvdb does not import" in got["to_pyopenvdb"]

    # The .vdb read back by OpenVDB's own reader (pyopenvdb, in this process).
    back = pyopenvdb.read(str(tmp_path / "surface.vdb"), "surface")
    assert isinstance(back, pyopenvdb.BoolGrid) and back.activeVoxelCount() == len(want)
    assert back.metadata["svo:version"] == got["version"]
    assert all(back.getConstAccessor().isValueOn(c) for c in want)
    # The .nvdb checked by NanoVDB's own validator, when installed (libnanovdb-tools).
    validate = shutil.which("nanovdb_validate")
    if validate:
        r = subprocess.run([validate, "-v", str(tmp_path / "both.nvdb")], capture_output=True, text=True)
        assert r.returncode == 0 and "fail" not in r.stdout.lower(), r.stdout + r.stderr
    # A pickled svo.Grid converts to pyopenvdb where it imports (here).
    import svo
    grid = pickle.loads((tmp_path / "grid.pickle").read_bytes())
    assert isinstance(grid, svo.Grid)
    converted = grid.to_pyopenvdb()
    assert isinstance(converted, pyopenvdb.FloatGrid) and converted.name == "level_set"
    assert converted.activeVoxelCount() == len(lijk) and converted.gridClass == pyopenvdb.GridClass.LEVEL_SET
    assert converted.getConstAccessor().getValue(tuple(int(x) for x in lijk[0])) == values[0]


def test_debians_python_with_pyopenvdb_hidden(tmp_path):
    check_child(tmp_path, run_child(sys.executable, tmp_path))


# Another CPython 3.11 (pyenv's, where this machine has one): its own site,
# no pyopenvdb at all, numpy from PyPI in a venv the test makes (SVO_OTHER_PYTHON
# names the interpreter; the svo package comes from PYTHONPATH, as here).
OTHER = os.environ.get("SVO_OTHER_PYTHON", os.path.expanduser("~/.pyenv/versions/3.11.7/bin/python3.11"))


@pytest.mark.skipif(not os.path.exists(OTHER), reason="no second CPython 3.11 on this machine (SVO_OTHER_PYTHON)")
def test_another_cpython_without_pyopenvdb(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([OTHER, "-m", "venv", str(venv)], check=True)
    python = str(venv / "bin" / "python")
    if subprocess.run([python, "-c", "import numpy"], capture_output=True).returncode:
        r = subprocess.run([python, "-m", "pip", "install", "-q", "numpy<2"], capture_output=True, text=True)
        if r.returncode:
            pytest.skip(f"numpy cannot be installed for {OTHER}: {r.stderr.strip()[-200:]}")
    work = tmp_path / "work"
    work.mkdir()
    check_child(work, run_child(python, work))
