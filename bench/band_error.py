#!/usr/bin/env python3
"""Level sets: error against GPU time over the band width.

For each mesh, resolution and band W (voxels, both sides), runs
  svo voxelize MESH -r R --sdf --band W --repeat N --json   (GPU ms: medians of N warm runs)
  svo validate MESH -r R --sdf --band W --json              (error against CGAL, and OpenVDB's)
and writes a Markdown table, with the GPU memory the level set held at its
peak (gpu_bytes), to show it follows the band, not the volume. --no-validate
skips the error columns (memory and time only, for grids CGAL is slow on).
  bench/band_error.py --svo build/bin/svo --res 256 512 --band 1 2 3 5 8 --md out.md MESH...
"""
import argparse
import json
import os
import subprocess
import tempfile


def run_json(cmd, path):
    subprocess.run(cmd + ["--json", path], check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--res", type=int, nargs="+", default=[256, 512])
    ap.add_argument("--band", type=float, nargs="+", default=[1, 2, 3, 5, 8])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--md", required=True)
    ap.add_argument("--no-validate", action="store_true", help="memory and time only")
    a = ap.parse_args()
    rows = []
    renderer = ""
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes:
            for r in a.res:
                for w in a.band:
                    base = [a.svo, "voxelize", mesh, "-r", str(r), "--sdf", "--band", str(w)]
                    v = run_json(base + ["--repeat", str(a.repeat), "-o", os.path.join(tmp, "ls.vdb")],
                                 os.path.join(tmp, "v.json"))
                    renderer = v["renderer"]
                    gpu = sum(s["gpu_ms"] for s in v["stages"] if (s.get("gpu_ms") or 0) > 0)
                    memory = f"{v['gpu_bytes'] / 1e6:.1f} | {v['gpu_bytes'] / max(v['active_voxels'], 1):.1f}"
                    if a.no_validate:
                        rows.append(f"| {v['scene']} | {r}³ | {w:g} | {v['sign'].split(':')[0]} | {v['active_voxels']:,} | "
                                    f"{gpu:.2f} | {memory} | – | – | – | – | – |")
                        print(rows[-1], flush=True)
                        continue
                    c = run_json([a.svo, "validate", mesh, "-r", str(r), "--sdf", "--band", str(w)],
                                 os.path.join(tmp, "c.json"))
                    o = c["openvdb"]
                    rows.append(f"| {v['scene']} | {r}³ | {w:g} | {v['sign'].split(':')[0]} | {c['voxels']:,} | "
                                f"{gpu:.2f} | {memory} | {c['max_error']:.2e} | {c['rms_error']:.2e} | "
                                f"{c['missing']} / {c['extra']} | "
                                f"{c['sign_disagreements'] if c['sign_checked'] else 'not checked (open)'} | "
                                f"{o['max_error_openvdb']:.3f} |")
                    print(rows[-1], flush=True)
    head = (f"Level sets over the band width, on {renderer}. GPU ms: the sum of the stages' GPU times, medians of "
            f"{a.repeat} warm runs of `svo voxelize --sdf`. Errors from `svo validate --sdf` against CGAL's exact "
            "distance (voxels); the last column is OpenVDB's meshToLevelSet on the same voxels, for scale.\n\n"
            "GPU MB: the most GPU memory the call held (buffers svo allocated), and that per band voxel.\n\n"
            "| mesh | grid | band | sign | band voxels | GPU ms | GPU MB | GPU bytes / voxel | max error | RMS error | "
            "missing / extra | sign errors | OpenVDB max error |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    with open(a.md + ".tmp", "w") as f:
        f.write(head + "\n".join(rows) + "\n")
    os.replace(a.md + ".tmp", a.md)


if __name__ == "__main__":
    main()
