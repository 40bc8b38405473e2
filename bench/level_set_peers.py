#!/usr/bin/env python3
"""Level sets end to end against vdb_tool, in one run.

For every mesh and resolution it runs, one cold process each, mesh file to
.vdb file:
  svo voxelize MESH -r N --sdf --band W -o out.vdb --json stats.json
  vdb_tool -read MESH -mesh2ls voxel=V width=W -write out.vdb
(V: svo's voxel size for -r N, since vdb_tool's dim=N would count the band's
padding in N) and records wall ms and peak RSS of both, svo's sign method and its active
voxels, and vdb_tool's active voxels as vdb_print reports them. Writes a
Markdown table (--md) with the ratio vdb_tool / svo per row.

  python3 bench/level_set_peers.py --svo build/bin/svo --res 128 256 512 \\
      --md bench/results/cpu-2core-llvmpipe/level_set_peers.md MESH.obj ...
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time


def run_measured(cmd, timeout):
    """(returncode, wall ms, last line of stderr) of one child process; returncode None on timeout."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        return None, timeout * 1000.0, "timeout"
    lines = err.strip().splitlines()
    return proc.returncode, (time.perf_counter() - t0) * 1000, lines[-1] if lines else ""


def active_voxels(vdb_print, path):
    """Active voxels of the file's first grid, as vdb_print rounds them (e.g. 77.5K)."""
    out = subprocess.run([vdb_print, path], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    m = re.search(r"([\d.]+)([KMG]?)Vox", out)
    if not m:
        return None
    return float(m.group(1)) * {"": 1, "K": 1e3, "M": 1e6, "G": 1e9}[m.group(2)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--vdb-tool", default="vdb_tool")
    ap.add_argument("--vdb-print", default="vdb_print")
    ap.add_argument("--res", type=int, nargs="+", default=[128, 256, 512])
    ap.add_argument("--band", type=float, default=3.0)
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--md", help="Markdown table to write")
    ap.add_argument("--title", default="")
    a = ap.parse_args()

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes:
            name = os.path.splitext(os.path.basename(mesh))[0]
            for res in a.res:
                out_svo, out_peer = os.path.join(tmp, "svo.vdb"), os.path.join(tmp, "peer.vdb")
                stats = os.path.join(tmp, "svo.json")
                svo_cmd = [a.svo, "voxelize", mesh, "-r", str(res), "--sdf", "--band", str(a.band), "-o", out_svo,
                           "--json", stats]
                rc, svo_ms, svo_err = run_measured(svo_cmd, a.timeout)
                info = json.load(open(stats)) if rc == 0 else {}
                # vdb_tool's dim counts the band's padding too: give it svo's voxel size instead.
                size = f"voxel={info['voxel_size']!r}" if info else f"dim={res}"
                peer_cmd = [a.vdb_tool, "-read", mesh, "-mesh2ls", size, f"width={a.band:g}", "-write", out_peer]
                rc2, peer_ms, peer_err = run_measured(peer_cmd, a.timeout)
                peer_active = active_voxels(a.vdb_print, out_peer) if rc2 == 0 else None
                row = {
                    "mesh": name, "res": res, "triangles": info.get("triangles"),
                    "sign": (info.get("sign") or "").split(":")[0],
                    "svo_ms": svo_ms if rc == 0 else None, "svo_error": "" if rc == 0 else svo_err,
                    "svo_active": info.get("active_voxels"),
                    "gpu_ms": sum(s.get("gpu_ms") or 0 for s in info.get("stages", []) if (s.get("gpu_ms") or 0) > 0),
                    "peer_ms": peer_ms if rc2 == 0 else None, "peer_error": "" if rc2 == 0 else peer_err,
                    "peer_active": peer_active,
                    # svo's three longest stages by wall time: where its time went
                    "stages": sorted(((st.get("wall_ms") or 0, st["name"]) for st in info.get("stages", [])),
                                     reverse=True)[:3],
                }
                rows.append(row)
                fmt = lambda v: "–" if v is None else f"{v:.0f}"
                print(f"{name} {res}: svo {fmt(row['svo_ms'])} ms ({row['sign']}, {row['svo_active']} active), "
                      f"vdb_tool {fmt(row['peer_ms'])} ms ({peer_active} active) {row['svo_error']} {row['peer_error']}",
                      flush=True)
                for p in (out_svo, out_peer, stats):
                    if os.path.exists(p):
                        os.remove(p)

    if a.md:
        lines = [a.title or "Level sets end to end (mesh file to .vdb), one cold process each", "",
                 f"Band half width {a.band:g} voxels on both sides. `svo voxelize MESH -r N --sdf --band {a.band:g}` "
                 f"against `vdb_tool -read MESH -mesh2ls voxel=V width={a.band:g} -write out.vdb` with svo's voxel size V; "
                 "wall ms of the "
                 "whole process (start-up, reading, the work, writing). vdb_tool's active voxels are as vdb_print "
                 "rounds them.", "",
                 "| mesh | triangles | grid | svo sign | svo active voxels | vdb_tool active voxels | svo GPU ms "
                 "(all passes) | svo's longest stages, wall ms | svo wall ms | vdb_tool wall ms | vdb_tool / svo |",
                 "|---|---|---|---|---|---|---|---|---|---|---|"]
        def num(v, spec):
            return "–" if v is None else format(v, spec)

        for r in rows:
            ratio = num(r["peer_ms"] / r["svo_ms"] if r["svo_ms"] and r["peer_ms"] else None, ".2f")
            lines.append(f"| {r['mesh']} | {num(r['triangles'], ',')} | {r['res']}³ | {r['sign'] or '–'} | "
                         f"{num(r['svo_active'], ',')} | {num(r['peer_active'], ',.0f')} | {r['gpu_ms']:.1f} | "
                         f"{', '.join(f'{n} {ms:.0f}' for ms, n in r['stages']) or '–'} | "
                         f"{num(r['svo_ms'], '.0f')} | {num(r['peer_ms'], '.0f')} | {ratio} |")
        with open(a.md, "w") as f:
            f.write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
