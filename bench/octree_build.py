#!/usr/bin/env python3
"""Octree build time and bytes per voxel against the voxel count.

Runs `svo voxelize MESH -r N -o out.svo --repeat R --json ...` for every mesh
and resolution, and writes bench/results/<machine>/octree_build.{json,md}.
GPU times are medians of R runs after a warm-up (GL timestamp queries).

  python3 bench/octree_build.py --machine cpu-2core-llvmpipe --meshes DIR [--res 128 256 512]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile


def stage(run, name):
    for s in run["stages"]:
        if s["name"] == name:
            return s
    return {"gpu_ms": None, "wall_ms": None}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--machine", required=True, help="folder name under bench/results, naming machine and GPU")
    ap.add_argument("--meshes", required=True, help="folder holding the meshes named by --mesh")
    ap.add_argument("--mesh", nargs="+", default=["stanford-bunny.obj", "ogre.obj", "elephant.off", "knot1.off"])
    ap.add_argument("--res", nargs="+", type=int, default=[128, 256, 512])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=None, help="results folder (default bench/results/<machine>)")
    a = ap.parse_args()
    out_dir = a.out or os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", a.machine)
    os.makedirs(out_dir, exist_ok=True)
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.mesh:
            path = os.path.join(a.meshes, mesh)
            if not os.path.exists(path):
                print(f"skipping {mesh}: not in {a.meshes}", file=sys.stderr)
                continue
            for res in a.res:
                js = os.path.join(tmp, "run.json")
                cmd = [a.svo, "voxelize", path, "-r", str(res), "-o", os.path.join(tmp, "out.svo"),
                       "--repeat", str(a.repeat), "--json", js]
                subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
                with open(js) as f:
                    run = json.load(f)
                run["mesh"] = mesh
                runs.append(run)
                b = stage(run, "octree build")
                print(f"{mesh:24} {res:5} voxels {run['voxels']:>10,} build GPU {b['gpu_ms']} ms", file=sys.stderr)
    with open(os.path.join(out_dir, "octree_build.json"), "w") as f:
        json.dump(runs, f, indent=1)
    lines = [f"# Octree build on {a.machine}", "",
             f"Renderer: {runs[0]['renderer'] if runs else '-'}. `svo voxelize MESH -r N -o out.svo --repeat {a.repeat}`: "
             "GPU ms are medians of the runs after a warm-up, from GL timestamp queries.", "",
             "| mesh | res | voxels | list entries | bricks | nodes | levels | octree build GPU ms | build ns/entry | "
             "voxelize GPU ms | readback GPU ms | bytes/voxel | brick fill | retries |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in runs:
        b, v, rb = stage(r, "octree build"), stage(r, "voxelize"), stage(r, "readback")
        ns = (b["gpu_ms"] or 0) * 1e6 / max(r["list_entries"], 1)
        fill = r["voxels"] / (512.0 * max(r["bricks"], 1))
        lines.append(f"| {r['mesh']} | {r['resolution']} | {r['voxels']:,} | {r['list_entries']:,} | {r['bricks']:,} | "
                     f"{r['nodes']:,} | {len(r['nodes_per_level'])} | {b['gpu_ms']:.3f} | {ns:.1f} | {v['gpu_ms']:.3f} | "
                     f"{rb['gpu_ms']:.3f} | {r['octree_bytes'] / max(r['voxels'], 1):.3f} | {fill:.3f} | "
                     f"{r['overflow_retries']} |")
    with open(os.path.join(out_dir, "octree_build.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
