"""Check a voxelization against CGAL's exact reference, as `svo validate` does.

    PYTHONPATH=build/python python3 python/examples/validate_mesh.py mesh.off 128
"""
import sys

import svo

vertices, triangles = svo.read_mesh(sys.argv[1])
report = svo.validate(vertices, triangles, resolution=int(sys.argv[2]) if len(sys.argv) > 2 else 128)
print(f"{report['voxels']} voxels: {report['missed']} missed, {report['extra']} extra, "
      f"holes: {'leak' if report['holes']['leak'] else report['holes']['reason'] or 'none'}, "
      f"{'passed' if report['passed'] else 'FAILED: ' + report['reason']}")
