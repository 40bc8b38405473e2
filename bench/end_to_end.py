#!/usr/bin/env python3
"""End to end, mesh file to output file, in one run with the peers.

For every scene and resolution: `svo voxelize MESH -r N -o out.vdb` as new
processes (median wall of --runs, each with --json for its stage table), the
same with every --variant's extra arguments, `vdb_tool -read MESH -mesh2ls
dim=N width=1 -write out.vdb` (median of --runs), and, when given,
cuda_voxelizer (`-f MESH -s N -o morton`: its kernel and total as it prints
them, and its process wall; median of --runs). Ratios are peer / svo: above 1
means svo is faster. Writes end_to_end.json and end_to_end.md into --out.

  python3 bench/end_to_end.py --machine cpu-2core-llvmpipe --res 64 128 256 512
  python3 bench/end_to_end.py --machine nvidia-h100 --res 1024 2048 --cuda-voxelizer cvb/cuda_voxelizer \\
      --scenes bunny.obj icosphere --variant "128M tiles=--gpu-memory 128M"
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def timed(cmd, cwd=None):
    """(return code, wall ms, stdout + stderr) of one new process."""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=cwd)
    return p.returncode, (time.perf_counter() - t0) * 1000, p.stdout


def scenes(a, tmp):
    """(name, path for every tool, svo's own path) per scene."""
    out = []
    for name in a.scenes:
        if name in ("cornell", "spheres", "icosphere"):
            path = os.path.join(tmp, name + ".obj")  # vdb_tool reads OBJ, not OFF
            extra = ["--level", "8"] if name == "icosphere" else []
            subprocess.run([a.svo, "scene", name, "-o", path] + extra, check=True, stdout=subprocess.DEVNULL)
            out.append((name, path))
            if name == "icosphere" and a.icosphere_off:
                off = os.path.join(tmp, name + ".off")
                subprocess.run([a.svo, "scene", name, "-o", off] + extra, check=True, stdout=subprocess.DEVNULL)
                out.append((name + " (OFF)", off))
        elif os.path.exists(name):
            out.append((os.path.splitext(os.path.basename(name))[0], os.path.abspath(name)))
        else:
            print(f"end_to_end: skipping {name}: no such file", file=sys.stderr)
    return out


def svo_cell(a, path, res, extra, tmp):
    runs = []
    for _ in range(a.runs):
        js = os.path.join(tmp, "svo.json")
        if os.path.exists(js):
            os.remove(js)
        spawned = time.time()
        rc, ms, out = timed([a.svo, "voxelize", path, "-r", str(res), "-o", os.path.join(tmp, "svo.vdb"),
                             "--json", js] + extra)
        if rc != 0:
            return {"error": (out.strip().splitlines() or ["?"])[-1]}
        with open(js) as f:
            report = json.load(f)
        # The report is written last: its time splits what svo's total leaves out into the
        # process's start (loading libraries, parsing arguments) and its exit (destructors, driver).
        written = os.stat(js).st_mtime_ns / 1e6 - spawned * 1000
        report["start_ms"] = written - report.get("total_wall_ms", 0)
        report["exit_ms"] = ms - written
        runs.append((ms, report))
    runs.sort(key=lambda r: r[0])
    ms, report = runs[len(runs) // 2]
    stages = [{"name": s["name"], "wall_ms": s["wall_ms"], "gpu_ms": s.get("gpu_ms")} for s in report["stages"]]
    startup = report.get("startup", {})
    stages = [{"name": "EGL set-up", "wall_ms": startup.get("egl_ms", 0)},
              {"name": "programs", "wall_ms": startup.get("program_ms", 0)}] + stages
    inside = report.get("total_wall_ms", 0)
    return {"ms": ms, "all_ms": [r[0] for r in runs], "voxels": report.get("voxels"), "backend": report.get("backend"),
            "tiles": report.get("tiles", 1), "gpu_bytes": report.get("gpu_bytes"), "stages": stages,
            "inside_ms": inside, "outside_ms": ms - inside, "start_ms": report["start_ms"],
            "exit_ms": report["exit_ms"], "peak_rss_mb": report.get("peak_rss_mb")}


def vdb_tool_cell(a, path, res, tmp):
    times = []
    for _ in range(a.runs):
        rc, ms, out = timed([a.vdb_tool, "-read", path, "-mesh2ls", f"dim={res}", "width=1", "-write",
                             os.path.join(tmp, "peer.vdb")])
        if rc != 0:
            return {"error": (out.strip().splitlines() or ["?"])[-1]}
        times.append(ms)
    return {"ms": statistics.median(times), "all_ms": times}


def cuda_cell(a, path, res, tmp):
    kernels, totals, walls = [], [], []
    for _ in range(a.runs):
        rc, ms, out = timed([a.cuda_voxelizer, "-f", path, "-s", str(res), "-o", "morton"], cwd=tmp)
        k = re.search(r"Voxelization GPU time:\s*([\d.]+)", out)
        t = re.search(r"Total runtime:\s*([\d.]+)", out)
        if rc != 0 or not k or not t:
            return {"error": (out.strip().splitlines() or ["?"])[-1]}
        kernels.append(float(k.group(1)))
        totals.append(float(t.group(1)))
        walls.append(ms)
    return {"kernel_ms": statistics.median(kernels), "total_ms": statistics.median(totals),
            "ms": statistics.median(walls)}


def longest(cell, n=3):
    stages = sorted(cell["stages"], key=lambda s: -s["wall_ms"])[:n]
    return ", ".join(f"{s['name']} {s['wall_ms']:.0f}" for s in stages)


def table(results):
    variants = results["variants"]
    has_cuda = any("cuda_voxelizer" in r for r in results["rows"])
    head = ["scene", "grid"] + [f"svo{' ' + v if v else ''} ms" for v in variants] + ["vdb_tool ms", "vdb_tool / svo"]
    if has_cuda:
        head += ["cuda_voxelizer kernel / total / process ms", "its total / svo", "its process / svo"]
    head += ["svo: longest stages (wall ms)", "svo: process start / exit ms"]
    lines = [f"End to end (mesh file to .vdb, new processes, median of {results['runs']}) on {results['device']}; "
             f"{results['svo_version']}. Ratios: peer / svo's best; above 1, svo is faster.", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in results["rows"]:
        cells = [r["scene"], f"{r['res']}³"]
        best = None
        for v in variants:
            c = r["svo"][v]
            if "error" in c:
                cells.append("error: " + c["error"])
                continue
            cells.append(f"{c['ms']:.0f}" + (f" ({c['tiles']} tiles)" if c["tiles"] > 1 else ""))
            if best is None or c["ms"] < best["ms"]:
                best = c
        p = r.get("vdb_tool", {})
        cells.append(f"{p['ms']:.0f}" if "ms" in p else "–")
        cells.append(f"{p['ms'] / best['ms']:.2f}" if "ms" in p and best else "–")
        if has_cuda:
            c = r.get("cuda_voxelizer", {})
            if "ms" in c and best:
                cells += [f"{c['kernel_ms']:.1f} / {c['total_ms']:.0f} / {c['ms']:.0f}",
                          f"{c['total_ms'] / best['ms']:.2f}", f"{c['ms'] / best['ms']:.2f}"]
            else:
                cells += ["–", "–", "–"]
        cells.append(longest(best) if best else "–")
        cells.append(f"{best['start_ms']:.0f} / {best['exit_ms']:.0f}" if best else "–")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--svo", default=os.path.join(HERE, "..", "build", "bin", "svo"))
    ap.add_argument("--vdb-tool", default=shutil.which("vdb_tool"))
    ap.add_argument("--cuda-voxelizer", default=None)
    ap.add_argument("--machine", required=True, help="results folder name: name the machine and GPU")
    ap.add_argument("--scenes", nargs="+", default=["cornell", "spheres", "icosphere"],
                    help="cornell, spheres, icosphere (generated) or mesh files")
    ap.add_argument("--icosphere-off", action="store_true", help="also run svo on the icosphere as OFF")
    ap.add_argument("--res", nargs="+", type=int, default=[64, 128, 256, 512])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--variant", action="append", default=[],
                    help="'NAME=ARGS': svo again with extra arguments, e.g. '128M tiles=--gpu-memory 128M'")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out_dir = a.out or os.path.join(HERE, "results", a.machine)
    os.makedirs(out_dir, exist_ok=True)
    variants = {"": []}
    for v in a.variant:
        name, _, args = v.partition("=")
        variants[name] = args.split()
    glinfo = subprocess.run([a.svo, "glinfo"], stdout=subprocess.PIPE, text=True).stdout
    renderer = next((l.split(None, 1)[1] for l in glinfo.splitlines() if l.startswith("renderer")), "?")
    results = {"machine": a.machine, "device": renderer.strip(), "runs": a.runs, "variants": list(variants),
               "svo_version": subprocess.run([a.svo, "--version"], stdout=subprocess.PIPE, text=True).stdout.strip(),
               "nproc": os.cpu_count(), "rows": []}
    with tempfile.TemporaryDirectory() as tmp:
        for scene, path in scenes(a, tmp):
            for res in a.res:
                row = {"scene": scene, "res": res, "svo": {}}
                for name, extra in variants.items():
                    row["svo"][name] = svo_cell(a, path, res, extra, tmp)
                peer_path = path[:-4] + ".obj" if path.endswith(".off") and scene.endswith("(OFF)") else path
                if a.vdb_tool and not scene.endswith("(OFF)"):
                    row["vdb_tool"] = vdb_tool_cell(a, peer_path, res, tmp)
                if a.cuda_voxelizer and not scene.endswith("(OFF)"):
                    row["cuda_voxelizer"] = cuda_cell(a, peer_path, res, tmp)
                results["rows"].append(row)
                c = row["svo"][""]
                print(f"{scene:18} {res:5} svo {c.get('ms', float('nan')):8.0f} ms  "
                      f"vdb_tool {row.get('vdb_tool', {}).get('ms', float('nan')):8.0f} ms  "
                      f"cuda_voxelizer {row.get('cuda_voxelizer', {}).get('ms', float('nan')):8.0f} ms",
                      file=sys.stderr, flush=True)
    with open(os.path.join(out_dir, "end_to_end.json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(out_dir, "end_to_end.md"), "w") as f:
        f.write(table(results))
    print(table(results))


if __name__ == "__main__":
    main()
