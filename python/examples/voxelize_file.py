"""Voxelize a mesh file and write a .vdb that any OpenVDB tool opens (or a
.nvdb for NanoVDB readers). Runs with or without pyopenvdb.

    PYTHONPATH=build/python python3 python/examples/voxelize_file.py mesh.obj out.vdb 256
"""
import sys

import svo

mesh, out = sys.argv[1], sys.argv[2]
resolution = int(sys.argv[3]) if len(sys.argv) > 3 else 256
vertices, triangles = svo.read_mesh(mesh)
result = svo.Voxelizer().voxelize(vertices, triangles, resolution=resolution, report=True)
svo.write(out, [result.grid])  # svo's writer: atomic, with the svo:* metadata on the grid
print(f"{mesh}: {len(triangles)} triangles -> {result.report['active_voxels']} voxels in {out}")
