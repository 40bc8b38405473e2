"""ParaView opens what `svo vtk` writes, with every voxel in it (ctest paraview_reads).

    python3 paraview_reads.py --svo SVO --pvbatch PVBATCH --mesh OFF --work FOLDER

Voxelizes a mesh from Debian's libcgal-demo to a .vdb (the reference count of
voxels, read by python3-openvdb) and a .svo, has `svo vtk` write the .svo as a
hyper tree grid (.htg), voxel cells (.vtu) and octree outlines (.vtp), then
opens the three in ParaView's pvbatch (this same file, run with --read) and
checks that ParaView sees each voxel: the .vtu's cells and the .htg's unmasked
leaves are the .vdb's active voxels, the .vtu spans the .vdb's voxels exactly,
the .htg's root cube holds them, and the .vtp has outlines.
"""
import argparse
import json
import os
import subprocess
import sys

RESOLUTION = "48"


def read_in_paraview(paths):
    """In pvbatch: what ParaView's readers make of svo's files, as JSON."""
    from paraview import servermanager
    from paraview.simple import OpenDataFile
    from vtkmodules.vtkCommonDataModel import vtkHyperTreeGridNonOrientedCursor

    def visible_leaves(htg):
        """The leaves a reader shows: unmasked, walked from each tree's root."""

        def walk(cursor):
            if cursor.IsMasked():
                return 0
            if cursor.IsLeaf():
                return 1
            count = 0
            for child in range(cursor.GetNumberOfChildren()):
                cursor.ToChild(child)
                count += walk(cursor)
                cursor.ToParent()
            return count

        cursor = vtkHyperTreeGridNonOrientedCursor()
        count = 0
        for tree in range(htg.GetMaxNumberOfTrees()):
            if htg.GetTree(tree) is not None:
                htg.InitializeNonOrientedCursor(cursor, tree)
                count += walk(cursor)
        return count

    out = {}
    for path in paths:
        reader = OpenDataFile(path)
        if reader is None:
            raise SystemExit(f"{path}: ParaView has no reader for it")
        reader.UpdatePipeline()
        data = servermanager.Fetch(reader)
        entry = {"class": data.GetClassName(), "cells": data.GetNumberOfCells(), "bounds": list(data.GetBounds())}
        if path.endswith(".htg"):
            entry["visible_leaves"] = visible_leaves(data)
        out[os.path.basename(path)] = entry
    print("PARAVIEW " + json.dumps(out))


def run(cmd):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited {done.returncode}:\n{done.stdout}{done.stderr}")
    return done.stdout


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--svo")
    parser.add_argument("--pvbatch")
    parser.add_argument("--mesh")
    parser.add_argument("--work")
    parser.add_argument("--read", nargs="*")
    args = parser.parse_args()
    if args.read is not None:
        read_in_paraview(args.read)
        return

    import pyopenvdb

    os.makedirs(args.work, exist_ok=True)
    path = lambda name: os.path.join(args.work, name)
    run([args.svo, "voxelize", args.mesh, "-r", RESOLUTION, "-q", "-o", path("mesh.vdb")])
    run([args.svo, "voxelize", args.mesh, "-r", RESOLUTION, "-q", "-o", path("mesh.svo")])
    grid = pyopenvdb.read(path("mesh.vdb"), "surface")
    voxels = grid.activeVoxelCount()
    (lo, hi) = grid.evalActiveVoxelBoundingBox()
    files = [path("mesh.htg"), path("mesh.vtu"), path("mesh.vtp")]
    for f in files:
        run([args.svo, "vtk", path("mesh.svo"), "-o", f])
    done = subprocess.run([args.pvbatch, os.path.abspath(__file__), "--read", *files], capture_output=True, text=True)
    lines = [l for l in done.stdout.splitlines() if l.startswith("PARAVIEW ")]
    if done.returncode != 0 or not lines:
        raise SystemExit(f"pvbatch exited {done.returncode}:\n{done.stdout}{done.stderr}")
    seen = json.loads(lines[-1][len("PARAVIEW "):])
    print(json.dumps(seen, indent=1))

    failures = []
    if seen["mesh.vtu"]["cells"] != voxels:
        failures.append(f"mesh.vtu: ParaView reads {seen['mesh.vtu']['cells']} cells, the .vdb has {voxels} voxels")
    if seen["mesh.htg"]["visible_leaves"] != voxels:
        failures.append(f"mesh.htg: ParaView sees {seen['mesh.htg']['visible_leaves']} unmasked leaves, "
                        f"the .vdb has {voxels} voxels")
    if seen["mesh.vtp"]["cells"] == 0:
        failures.append("mesh.vtp: ParaView reads no outline cells")
    # OpenVDB's voxel (i, j, k) is centred on (i, j, k) times the voxel size.
    size = grid.transform.voxelSize()[0]
    want = [(lo[0] - 0.5) * size, (hi[0] + 0.5) * size, (lo[1] - 0.5) * size, (hi[1] + 0.5) * size,
            (lo[2] - 0.5) * size, (hi[2] + 0.5) * size]
    close = lambda g, w: abs(g - w) <= 1e-9 * max(1.0, abs(w))
    got = seen["mesh.vtu"]["bounds"]
    if not all(close(g, w) for g, w in zip(got, want)):
        failures.append(f"mesh.vtu: ParaView's bounds {got}, the .vdb's voxels span {want}")
    # The hyper tree grid spans the octree's root cube, which holds the voxels.
    got = seen["mesh.htg"]["bounds"]
    if not all(got[2 * a] <= want[2 * a] + 1e-9 and got[2 * a + 1] >= want[2 * a + 1] - 1e-9 for a in range(3)):
        failures.append(f"mesh.htg: ParaView's bounds {got} do not hold the .vdb's voxels {want}")
    if failures:
        sys.exit("\n".join(failures))
    print(f"ParaView sees all {voxels} voxels in the .htg and the .vtu")


if __name__ == "__main__":
    main()
