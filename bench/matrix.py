#!/usr/bin/env python3
"""The benchmark matrix: scenes x resolutions x methods, with peers in the same run.

For every cell it runs `svo voxelize SCENE -r N --conservative M --repeat R --json`
(GPU ms per stage from timer queries, medians after a warm-up; wall ms; voxels;
overflows; GPU bytes; peak RSS), `svo validate` for the error against CGAL
(missed and extra voxels, up to --validate-max), and the peers on the same mesh
and grid: OpenVDB's meshToUnsignedDistanceField through the library
(svo-mesh-to-volume) and `vdb_tool -read MESH -mesh2ls dim=N width=1 -write out.vdb`.
Writes matrix.json and matrix.md (and PNG plots when matplotlib is present,
or later with --plot-only) under bench/results/<machine>/.

  python3 bench/matrix.py --machine cpu-2core-llvmpipe --res 64 128 256 512
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def run(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def run_measured(cmd):
    """(returncode, wall ms, peak RSS MB) of one child process."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, (time.perf_counter() - t0) * 1000, usage.ru_maxrss / 1024.0


def stage(cell, name, key="gpu_ms"):
    for s in cell["stages"]:
        if s["name"] == name:
            return s[key]
    return None


def scenes(args, tmp):
    """(name, path) for each scene; generated ones are written by `svo scene`."""
    out = []
    for name in args.scenes:
        if name in ("cornell", "spheres", "icosphere"):
            path = os.path.join(tmp, name + ".obj")  # vdb_tool reads OBJ, not OFF
            run([args.svo, "scene", name, "-o", path] + (["--level", "8"] if name == "icosphere" else []), check=True)
            out.append((name, path))
        else:
            path = os.path.join(args.meshes, name)
            if os.path.exists(path):
                out.append((os.path.splitext(name)[0], path))
            else:
                print(f"matrix: skipping {name}: not in {args.meshes}", file=sys.stderr)
    return out


def plot(results, out_dir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matrix: matplotlib not found; run again with --plot-only where it is", file=sys.stderr)
        return
    cells = [c for c in results["cells"] if "error" not in c]
    # Error against run time: one point per method and resolution (all scenes summed).
    fig, ax = plt.subplots(figsize=(7, 5))
    for method in sorted({c["method"] for c in cells}):
        xs, ys, labels = [], [], []
        for res in sorted({c["resolution"] for c in cells}):
            sel = [c for c in cells if c["method"] == method and c["resolution"] == res and c.get("missed") is not None]
            if not sel:
                continue
            xs.append(sum(c["wall_ms"] for c in sel))
            ys.append(sum(c["missed"] + c["extra"] for c in sel) / max(sum(c["voxels"] for c in sel), 1))
            labels.append(res)
        ax.plot(xs, [max(y, 1e-7) for y in ys], "o-", label=method)
        for x, y, r in zip(xs, ys, labels):
            ax.annotate(str(r), (x, max(y, 1e-7)), fontsize=7)
    ax.set_xscale("log"); ax.set_yscale("log")
    ax.set_xlabel("voxelize wall ms (all scenes)"); ax.set_ylabel("(missed + extra) / voxels  (0 drawn at 1e-7)")
    ax.set_title(f"Error against run time, {results['machine']}", fontsize=9); ax.legend(); fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "error_vs_time.png"), dpi=110); plt.close(fig)
    # Time against resolution per scene: svo (best exact method, GPU total) and peers.
    fig, ax = plt.subplots(figsize=(7, 5))
    for scene in sorted({c["scene"] for c in cells}):
        sel = sorted([c for c in cells if c["scene"] == scene and c["method"] in ("hardware", "shader")],
                     key=lambda c: c["resolution"])
        best = {}
        for c in sel:
            best[c["resolution"]] = min(best.get(c["resolution"], 1e30), c["end_to_end_ms"])
        ax.plot(list(best), list(best.values()), "o-", label=f"svo {scene}")
        peers = sorted([p for p in results["peers"] if p["scene"] == scene and p.get("vdb_tool_ms")],
                       key=lambda p: p["resolution"])
        if peers:
            ax.plot([p["resolution"] for p in peers], [p["vdb_tool_ms"] for p in peers], "x--", label=f"vdb_tool {scene}")
    ax.set_xscale("log", base=2); ax.set_yscale("log")
    ax.set_xlabel("resolution"); ax.set_ylabel("end-to-end ms (mesh file to .vdb)")
    ax.set_title(f"Time against resolution, {results['machine']}", fontsize=9); ax.legend(fontsize=7); fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "time_vs_resolution.png"), dpi=110); plt.close(fig)
    # Bytes per voxel of the octree.
    fig, ax = plt.subplots(figsize=(7, 5))
    for scene in sorted({c["scene"] for c in cells}):
        sel = sorted([c for c in cells if c["scene"] == scene and c["method"] == cells[0]["method"]],
                     key=lambda c: c["resolution"])
        ax.plot([c["resolution"] for c in sel], [c["octree_bytes"] / max(c["voxels"], 1) for c in sel], "o-", label=scene)
    ax.set_xscale("log", base=2); ax.set_xlabel("resolution"); ax.set_ylabel("octree bytes per voxel")
    ax.set_title(f"Octree size, {results['machine']}", fontsize=9); ax.legend(); fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "bytes_per_voxel.png"), dpi=110); plt.close(fig)


def table(results):
    lines = [f"# Benchmark matrix: {results['machine']}", "", f"Renderer: {results.get('renderer', '-')}. "
             f"GPU ms are medians of {results['repeat']} runs after a warm-up (GL timestamp queries); "
             "wall and end-to-end ms are one run of `svo voxelize MESH -r N -o out.vdb` (mesh file to .vdb file, "
             "context creation and loading included). Error: `svo validate` against CGAL "
             f"(cells above {results['validate_max']}³ not validated: '–').", "",
             "| scene | tris | res | method | voxels | upload | voxelize | octree | readback | GPU total | "
             "vdb build+write | end-to-end | missed | extra | retries | GPU MB | RSS MB |",
             "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    fmt = lambda v, d=2: "–" if v is None else f"{v:.{d}f}"
    for c in results["cells"]:
        if "error" in c:
            lines.append(f"| {c['scene']} | | {c['resolution']} | {c['method']} | error: {c['error']} |" + " |" * 12)
            continue
        gpu = sum(s["gpu_ms"] or 0 for s in c["stages"] if s["gpu_ms"] is not None)
        vdb = (stage(c, "vdb build (cpu)", "wall_ms") or 0) + (stage(c, "vdb write", "wall_ms") or 0)
        oct_ms = stage(c, "octree build") if stage(c, "octree build") is not None else stage(c, "octree build (cpu)", "wall_ms")
        lines.append(f"| {c['scene']} | {c['triangles']:,} | {c['resolution']} | {c['method']} | {c['voxels']:,} | "
                     f"{fmt(stage(c, 'upload'), 3)} | {fmt(stage(c, 'voxelize') if c['method'] != 'cpu' else stage(c, 'voxelize (cpu)', 'wall_ms'))} | "
                     f"{fmt(oct_ms)} | {fmt(stage(c, 'readback'))} | {fmt(gpu)} | {fmt(vdb)} | {fmt(c['end_to_end_ms'], 0)} | "
                     f"{'–' if c.get('missed') is None else c['missed']} | {'–' if c.get('extra') is None else c['extra']} | "
                     f"{c['overflow_retries']} | {c['gpu_bytes'] / 1e6:.1f} | {c['peak_rss_mb']:.0f} |")
    lines += ["", "## Peers, same mesh and grid, same run", "",
              "Ratios are peer time / svo end-to-end time (best exact method); above 1 means svo is faster.", "",
              "| scene | res | svo e2e ms | svo voxels | vdb_tool ms | vdb_tool RSS MB | ratio | meshToUDF ms (library) | "
              "UDF surface voxels | ratio |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for p in results["peers"]:
        r1 = p["vdb_tool_ms"] / p["svo_ms"] if p.get("vdb_tool_ms") else None
        r2 = p["udf_ms"] / p["svo_ms"] if p.get("udf_ms") else None
        lines.append(f"| {p['scene']} | {p['resolution']} | {p['svo_ms']:.0f} | {p['svo_voxels']:,} | {fmt(p.get('vdb_tool_ms'), 0)} | "
                     f"{fmt(p.get('vdb_tool_rss_mb'), 0)} | {fmt(r1)} | {fmt(p.get('udf_ms'), 0)} | "
                     f"{p.get('udf_surface_voxels', '–')} | {fmt(r2)} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--peer", default=None, help="svo-mesh-to-volume (default: next to --svo)")
    ap.add_argument("--vdb-tool", default=shutil.which("vdb_tool"))
    ap.add_argument("--machine", required=True, help="results folder name: name the machine and GPU")
    ap.add_argument("--meshes", default=os.path.join(HERE, "..", "..", "shared", "meshes"))
    ap.add_argument("--scenes", nargs="+", default=["cornell", "spheres", "stanford-bunny.obj", "icosphere"])
    ap.add_argument("--res", nargs="+", type=int, default=[64, 128, 256, 512])
    ap.add_argument("--methods", nargs="+", default=["hardware", "shader", "centroid", "cpu"])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--validate-max", type=int, default=512, help="largest resolution checked against CGAL")
    ap.add_argument("--cpu-max", type=int, default=512, help="largest resolution for the CPU reference method")
    ap.add_argument("--out", default=None)
    ap.add_argument("--plot-only", action="store_true")
    a = ap.parse_args()
    out_dir = a.out or os.path.join(HERE, "results", a.machine)
    os.makedirs(out_dir, exist_ok=True)
    if a.plot_only:
        with open(os.path.join(out_dir, "matrix.json")) as f:
            plot(json.load(f), out_dir)
        return
    peer = a.peer or os.path.join(os.path.dirname(a.svo), "svo-mesh-to-volume")
    glinfo = run([a.svo, "glinfo"]).stdout
    has_nv = any(line.split()[:2] == ["GL_NV_conservative_raster", "yes"] for line in glinfo.splitlines())
    results = {"machine": a.machine, "repeat": a.repeat, "validate_max": a.validate_max, "cells": [], "peers": [],
               "glinfo": glinfo}
    with tempfile.TemporaryDirectory() as tmp:
        for scene, path in scenes(a, tmp):
            for res in a.res:
                best = None
                for method in a.methods:
                    if method == "hardware" and not has_nv:
                        continue
                    if method == "cpu" and res > a.cpu_max:
                        continue
                    js, vdb = os.path.join(tmp, "cell.json"), os.path.join(tmp, "out.vdb")
                    backend = ["--backend", "cpu"] if method == "cpu" else ["--conservative", method]
                    # One timed end-to-end run, then the repeated run for stage medians.
                    t0 = time.perf_counter()
                    p = run([a.svo, "voxelize", path, "-r", str(res), "-o", vdb] + backend)
                    e2e = (time.perf_counter() - t0) * 1000
                    if p.returncode != 0:
                        results["cells"].append({"scene": scene, "resolution": res, "method": method,
                                                 "error": (p.stderr.strip().splitlines() or ["?"])[-1]})
                        continue
                    p = run([a.svo, "voxelize", path, "-r", str(res), "-o", vdb, "--repeat", str(a.repeat),
                             "--json", js] + backend, check=True)
                    with open(js) as f:
                        cell = json.load(f)
                    cell.update({"scene": scene, "method": method, "end_to_end_ms": e2e,
                                 "wall_ms": sum(s["wall_ms"] for s in cell["stages"])})
                    if res <= a.validate_max:
                        vj = os.path.join(tmp, "v.json")
                        if os.path.exists(vj):
                            os.remove(vj)
                        q = run([a.svo, "validate", path, "-r", str(res), "--no-holes", "--json", vj] + backend)
                        if q.returncode in (0, 3):  # 3: validation failed, which is data here
                            with open(vj) as f:
                                v = json.load(f)
                            cell.update({"missed": v["missed"], "extra": v["extra"], "boundary": v["boundary"]})
                    results["cells"].append(cell)
                    results["renderer"] = cell["renderer"] if method != "cpu" else results.get("renderer", "-")
                    if method in ("hardware", "shader") and (best is None or e2e < best["svo_ms"]):
                        best = {"svo_ms": e2e, "svo_voxels": cell["voxels"]}
                    print(f"{scene:16} {res:5} {method:9} voxels {cell['voxels']:>11,} e2e {e2e:9.1f} ms "
                          f"missed {cell.get('missed', '-')}", file=sys.stderr, flush=True)
                if best is None:
                    continue
                peer_row = {"scene": scene, "resolution": res, **best}
                if a.vdb_tool:
                    rc, ms, rss = run_measured([a.vdb_tool, "-read", path, "-mesh2ls", f"dim={res}", "width=1",
                                                "-write", os.path.join(tmp, "peer.vdb")])
                    if rc == 0:
                        peer_row.update({"vdb_tool_ms": ms, "vdb_tool_rss_mb": rss})
                if os.path.exists(peer):
                    q = run([peer, path, "-r", str(res)])
                    if q.returncode == 0:
                        u = json.loads(q.stdout)
                        peer_row.update({"udf_ms": u["ms"], "udf_surface_voxels": u["surface_voxels"]})
                results["peers"].append(peer_row)
    with open(os.path.join(out_dir, "matrix.json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(out_dir, "matrix.md"), "w") as f:
        f.write(table(results))
    plot(results, out_dir)
    print(table(results))


if __name__ == "__main__":
    main()
