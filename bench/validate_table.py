#!/usr/bin/env python3
"""`svo validate` over every libcgal-demo mesh with at most 200 K triangles.

Writes a markdown table (mesh, triangles, resolution, voxels, missed,
boundary, extra, leak, validation seconds, GPU ms) and the raw JSON.

  python3 bench/validate_table.py --meshes build/tests/cgal_data/data/meshes \
      --out docs/validation_table.md --json bench/results/<machine>/validation.json [--mode thin]
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile


def off_triangles(path):
    """Triangle count from an OFF header (polygons with n vertices count n - 2)."""
    with open(path, "rb") as f:
        words = []
        for raw in f:
            line = raw.split(b"#")[0].strip()
            if not line:
                continue
            words += line.split()
            if len(words) >= 4:
                break
    if not words or not words[0].endswith(b"OFF"):
        return None
    first = 1 if words[0] in (b"OFF", b"COFF", b"NOFF", b"CNOFF") else None
    if first is None:
        return None
    try:
        return int(words[first + 1])  # faces; triangulated faces count more, checked by svo itself
    except (ValueError, IndexError):
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--meshes", required=True)
    ap.add_argument("--res", nargs="+", type=int, default=[64, 128, 256])
    ap.add_argument("--max-triangles", type=int, default=200000)
    ap.add_argument("--out", required=True)
    ap.add_argument("--json", required=True)
    ap.add_argument("--mode", default="conservative", choices=["conservative", "thin"])
    a = ap.parse_args()
    rows = []
    meshes = sorted(glob.glob(os.path.join(a.meshes, "*.off")))
    with tempfile.TemporaryDirectory() as tmp:
        for path in meshes:
            faces = off_triangles(path)
            name = os.path.basename(path)
            if faces is None or faces > a.max_triangles:
                continue
            for res in a.res:
                js = os.path.join(tmp, "v.json")
                if os.path.exists(js):
                    os.remove(js)
                p = subprocess.run([a.svo, "validate", path, "-r", str(res), "--mode", a.mode, "--json", js],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                row = {"mesh": name, "resolution": res, "exit": p.returncode}
                if os.path.exists(js):
                    with open(js) as f:
                        row.update(json.load(f))
                else:
                    row["error"] = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "no report"
                rows.append(row)
                print(f"{name:32} {res:4} exit {p.returncode} "
                      f"{row.get('missed', '-')} missed {row.get('error', '')}", file=sys.stderr, flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.json)), exist_ok=True)
    with open(a.json, "w") as f:
        json.dump(rows, f, indent=1)
    ok = [r for r in rows if "missed" in r]
    lines = ["| mesh | triangles | res | voxels | missed | boundary | extra | leak | validation s | GPU ms |",
             "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
    for r in rows:
        if "missed" not in r:
            lines.append(f"| {r['mesh']} | | {r['resolution']} | | | | | | | error: {r['error']} |")
            continue
        h = r["holes"]
        leak = ("**LEAK**" if h["leak"] else "none") if h["applies"] else "n/a (" + (
            "open" if "open" in h["reason"] else "non-manifold" if "manifold" in h["reason"] else h["reason"]) + ")"
        lines.append(f"| {r['mesh']} | {r['triangles']:,} | {r['resolution']} | {r['voxels']:,} | {r['missed']} | "
                     f"{r['boundary']:,} | {r['extra']} | {leak} | {r['validation_seconds']:.2f} | {r['gpu_ms']:.2f} |")
    summary = (f"{a.mode} mode, {len(ok)} runs over {len({r['mesh'] for r in rows})} meshes: "
               f"{sum(r['missed'] for r in ok)} voxels missed ({sum(r['missed_exact'] for r in ok)} of the exact "
               f"set), {sum(r['extra'] for r in ok)} extra, "
               f"{sum(1 for r in ok if r['holes']['leak'])} leaks, "
               f"{sum(1 for r in ok if r['holes']['applies'])} runs hole-checked, "
               f"{len(rows) - len(ok)} runs ended in an input error.")
    with open(a.out, "w") as f:
        f.write(summary + "\n\n" + "\n".join(lines) + "\n")
    print(summary)


if __name__ == "__main__":
    main()
