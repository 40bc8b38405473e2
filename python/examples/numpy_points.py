"""Voxelize a mesh made on the spot with numpy, and turn the voxels into a
point cloud of voxel centres in world units. Runs with or without pyopenvdb.

    PYTHONPATH=build/python python3 python/examples/numpy_points.py
"""
import numpy as np

import svo

# An octahedron: 6 vertices, 8 triangles.
vertices = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.float64)
triangles = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
h = 0.05
result = svo.voxelize(vertices, triangles, voxel_size=h)
ijk = svo.active_voxels(result.grid)
points = ijk * h  # a voxel-size-only transform: world = h * index
print(f"{len(points)} voxel centres, from {points.min(axis=0)} to {points.max(axis=0)}")
