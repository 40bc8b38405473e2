"""Voxelize a mesh file and write a .vdb that any OpenVDB tool opens.

    PYTHONPATH=build/python python3 python/examples/voxelize_file.py mesh.obj out.vdb 256
"""
import sys

import pyopenvdb

import svo

mesh, out = sys.argv[1], sys.argv[2]
resolution = int(sys.argv[3]) if len(sys.argv) > 3 else 256
vertices, triangles = svo.read_mesh(mesh)
grid = svo.Voxelizer().voxelize(vertices, triangles, resolution=resolution)
pyopenvdb.write(out, [grid])
print(f"{mesh}: {len(triangles)} triangles -> {grid.activeVoxelCount()} voxels in {out}")
