#!/usr/bin/env python3
"""Random cross-checks of svo's outputs against each other, voxel by voxel
(values and active states, inactive values too) over each grid's box and a
margin: the .vdb against the .nvdb of the same call, a --region call against
the whole grid cut to the region, a --gpu-memory call against the whole
grid (and its .nvdb against the whole grid's, byte for byte), and a GPU
field (--sdf, --udf) against the CPU backend's. Surfaces and solids are not
compared across backends: their sets may differ within the validation's
allowed boundary band (docs/validation.md).

Not a test (it runs for minutes and its cases are random): a hunt for
defects the suites' scenes miss. It found the parity region's lost inside
bricks (Regions.AParityRegionSignsBandBricksWithNoVoxelInTheBand).

  /usr/bin/python3 scripts/cross_check.py --svo build/bin/svo \\
      --meshes build/tests/cgal_data/data/meshes --cases 100 --seed 1

Needs python3-openvdb (pyopenvdb) and numpy; a .nvdb is read through
`svo convert x.nvdb -o x.vdb`. Prints one line per case and exits 1 when any
case differs."""
import argparse
import glob
import os
import random
import subprocess
import sys
import tempfile

import numpy as np
import pyopenvdb

MESHES = ["elephant.off", "elephant-with-holes.off", "bunny00.off", "fandisk.off", "cube-ouvert.off", "knot1.off",
          "hedra_open.off", "cow.off", "P.off", "3torus.off", "armadillo.off", "camel.off", "dino.off", "bull.off"]
KINDS = [["--sdf"], ["--udf"], ["--sdf", "--closest-triangle"], ["--udf", "--closest-triangle"], ["--fill", "solid"],
         [], ["--fog"], ["--attributes", "normal", "triangle"],
         ["--sdf", "--sign", "winding"], ["--sdf", "--exterior-band", "2", "--interior-band", "5"],
         ["--udf", "--band", "1.5"], ["--mode", "thin"], ["--fill", "solid", "--sign", "winding"]]


def grids(paths):
    """Every grid of the files by name (python3-openvdb reads no Int32Grid or MaskGrid: those are left out)."""
    out = {}
    for path in paths:
        try:
            names = [m.name for m in pyopenvdb.readAllGridMetadata(path)]
        except TypeError:  # a grid type it cannot read: try svo's grid names one by one
            names = ["surface", "distance", "solid", "density", "normal", "color"]
        for name in names:
            try:
                out[name] = pyopenvdb.read(path, name)
            except (TypeError, ValueError, KeyError, RuntimeError):
                pass
    return out


def dense(grid, lo, hi):
    vector = (3,) if isinstance(grid, pyopenvdb.Vec3SGrid) else ()
    dtype = bool if isinstance(grid, pyopenvdb.BoolGrid) else np.float32
    values = np.zeros(tuple(h - l for l, h in zip(lo, hi)) + vector, dtype=dtype)
    grid.copyToArray(values, ijk=lo)
    active = np.zeros(values.shape[:3], dtype=bool)
    for item in grid.citerOnValues():
        a, b = item["min"], item["max"]
        if any(b[k] < lo[k] or a[k] >= hi[k] for k in range(3)):
            continue
        s = tuple(slice(max(a[k], lo[k]) - lo[k], min(b[k] + 1, hi[k]) - lo[k]) for k in range(3))
        active[s] = True
    return values, active


def differ(a_paths, b_paths, box=None):
    """Names of the grids that differ (or are missing) between two sets of files."""
    a, b = grids(a_paths), grids(b_paths)
    bad = sorted(set(a) ^ set(b))
    for name in sorted(set(a) & set(b)):
        if box:
            lo, hi = box
        else:
            boxes = [g.evalActiveVoxelBoundingBox() for g in (a[name], b[name]) if g.activeVoxelCount()]
            if not boxes:
                continue
            lo = tuple(min(x[0][k] for x in boxes) - 9 for k in range(3))
            hi = tuple(max(x[1][k] for x in boxes) + 10 for k in range(3))
        va, ma = dense(a[name], lo, hi)
        vb, mb = dense(b[name], lo, hi)
        if not (np.array_equal(va, vb) and np.array_equal(ma, mb)):
            bad.append(f"{name}: {int(np.count_nonzero(ma != mb))} active states, values differ")
    return bad


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--svo", required=True)
    p.add_argument("--meshes", required=True, help="libcgal-demo's data/meshes folder")
    p.add_argument("--cases", type=int, default=50)
    p.add_argument("--seed", type=int, default=1)
    a = p.parse_args()
    rng = random.Random(a.seed)
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        def run(args, stem, ext):
            for f in glob.glob(os.path.join(tmp, stem + ".*")):
                os.remove(f)
            out = os.path.join(tmp, stem + ext)
            r = subprocess.run(args + ["-q", "-o", out], capture_output=True, text=True)
            return r, sorted(glob.glob(os.path.join(tmp, stem + ".*vdb")))

        def as_vdb(nvdb, stem):
            """The .nvdb's grids as a .vdb (svo convert), or the error it gave."""
            path = os.path.join(tmp, stem + ".vdb")
            r = subprocess.run([a.svo, "convert", nvdb, "-q", "-o", path], capture_output=True, text=True)
            return ([path], "") if r.returncode == 0 else ([], r.stderr.strip())

        for case in range(a.cases):
            kind = rng.choice(KINDS)
            res = rng.choice([64, 97, 128, 160, 200])
            backend = rng.choice(["cpu", "raster", "compute"])
            if kind[:1] in (["--sdf"], ["--udf"]) and backend == "raster":
                backend = "compute"  # fields run compute passes
            base = [a.svo, "voxelize", os.path.join(a.meshes, rng.choice(MESHES)), "-r", str(res),
                    "--backend", backend] + kind
            extra, box = [], None
            if rng.random() < 0.5:
                lo = [(rng.randrange(-4, res // 8 + 2) - res // 16) * 8 for _ in range(3)]
                hi = [x + rng.randrange(1, 12) * 8 for x in lo]
                extra.append("--region=" + ",".join(map(str, lo + hi)))
                box = (tuple(lo), tuple(hi))
            if rng.random() < 0.5 and backend != "cpu":
                extra += ["--gpu-memory", rng.choice(["1M", "2M", "4M", "8M"])]
            what = " ".join(base[2:] + extra)
            whole, whole_vdb = run(base, "whole", ".vdb")
            part, part_vdb = run(base + extra, "part", ".vdb")
            nano, _ = run(base + extra, "nanopart", ".nvdb")
            if whole.returncode or part.returncode or nano.returncode:
                ok = part.returncode == nano.returncode  # refused alike: a bad combination or a budget too small
                print(("refused " if ok else "DIFFERS (exit codes) ") + what, flush=True)
                failed += not ok
                continue
            nano_vdb, error = as_vdb(os.path.join(tmp, "nanopart.nvdb"), "nano")
            bad = [f"svo convert of the .nvdb: {error}"] if error else []
            bad += [f"vdb/nvdb {d}" for d in differ(part_vdb, nano_vdb)] if nano_vdb else []
            if extra:
                bad += [f"vs whole {d}" for d in differ(part_vdb, whole_vdb, box)]
            if extra and not box:  # a budget: the whole grid's .nvdb, byte for byte
                run(base, "wn", ".nvdb")
                with open(os.path.join(tmp, "nanopart.nvdb"), "rb") as x, open(os.path.join(tmp, "wn.nvdb"), "rb") as y:
                    if x.read() != y.read():
                        bad.append("budget .nvdb bytes")
            if backend != "cpu" and kind[:1] in (["--sdf"], ["--udf"]) and "--gpu-memory" not in extra:
                cpu, cpu_vdb = run([x if x != backend else "cpu" for x in base] + extra, "cpu", ".vdb")
                if not cpu.returncode:
                    bad += [f"vs cpu {d}" for d in differ(part_vdb, cpu_vdb)]
            print(("DIFFERS " + "; ".join(bad) + ": " if bad else "same ") + what, flush=True)
            failed += bool(bad)
    print(f"{failed} of {a.cases} cases differ")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
