"""Voxelizer.write_nanovdb: the NanoVDB file `svo voxelize -o x.nvdb` writes,
byte for byte, for every kind, on the CPU layout and (backend="compute") on
the GPU builder's path; NanoVDB's own validator passes it."""
import os
import shutil
import subprocess

import numpy as np
import pytest

import svo
from scenes import icosphere

SVO_EXE = os.environ.get("SVO_EXE")
VALIDATE = shutil.which("nanovdb_validate")


def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist())
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles.tolist())


def sphere(subdivisions=3):
    """A closed sphere, consistently oriented (parity signs), off the origin."""
    v, t = icosphere(subdivisions)
    return v * 0.8 + (0.1, -0.2, 0.05), t


KINDS = [
    ("surface", ["--topology", "mask"], {}),  # the command line's default is bool, the library's mask
    ("surface", ["--fog", "--attributes", "normal"], {"fog": True, "attributes": ["normal"], "topology": "bool"}),
    ("sdf", ["--sdf", "--band", "2", "--closest-triangle"], {"exterior_band": 2.0, "interior_band": 2.0,
                                                             "closest_triangle": True}),
    ("udf", ["--udf"], {}),
    ("solid", ["--fill", "solid", "--topology", "mask"], {}),
    ("band", ["--fill", "band", "--band", "2.5", "--topology", "mask"], {"exterior_band": 2.5}),
]


@pytest.mark.skipif(not SVO_EXE or not os.path.exists(SVO_EXE), reason="the svo binary is not built (SVO_EXE)")
@pytest.mark.parametrize("backend", ["cpu", "compute"])
@pytest.mark.parametrize("kind, flags, keywords", KINDS)
@pytest.mark.parametrize("shape", ["closed", "open"])
def test_the_file_is_the_command_lines(tmp_path, shape, kind, flags, keywords, backend):
    v, t = sphere()
    if shape == "open":  # without its last faces: winding numbers sign it
        t = t[:-16]
    mesh = tmp_path / "mesh.obj"
    write_obj(mesh, v, t)
    v, t = svo.read_mesh(str(mesh))  # the arrays the command line reads
    cli, py = tmp_path / "cli.nvdb", tmp_path / "py.nvdb"
    subprocess.run([SVO_EXE, "voxelize", str(mesh), "-r", "40", "--backend", backend, *flags, "-o", str(cli)],
                   check=True, capture_output=True)
    size = svo.Voxelizer().write_nanovdb(py, v, t, kind=kind, resolution=40, backend=backend, **keywords)
    assert size == py.stat().st_size > 1000
    assert py.read_bytes() == cli.read_bytes()
    if VALIDATE:
        subprocess.run([VALIDATE, str(py)], check=True, capture_output=True)
    assert not [p for p in tmp_path.iterdir() if ".tmp" in p.name]  # written through a temporary, renamed


def test_bad_arguments_are_refused(tmp_path):
    v, t = sphere(1)
    vx = svo.Voxelizer()
    with pytest.raises(ValueError, match="kind: expected"):
        vx.write_nanovdb(tmp_path / "x.nvdb", v, t, kind="fog")
    with pytest.raises(ValueError, match="writes .nvdb files"):
        vx.write_nanovdb(tmp_path / "x.vdb", v, t, kind="sdf")
    with pytest.raises(ValueError, match="transform: write_nanovdb takes resolution or voxel_size"):
        vx.write_nanovdb(tmp_path / "x.nvdb", v, t, transform=np.eye(4))
    with pytest.raises(ValueError, match="codec"):
        vx.write_nanovdb(tmp_path / "x.nvdb", v, t, codec="lz77")
    assert not list(tmp_path.iterdir())
